// Stack links (patch_stacks.hpp).
#include "patch_stacks.hpp"

namespace patchspin::bullet::internal {

void linkPatchStacks(std::vector<PatchConstraint>& patches, int numBodies,
                     std::vector<char>& otherRows, StackScratch& scratch,
                     std::vector<parts::StackHold>& holds) {
  auto mark = [&](int id) {
    if (id >= 0) otherRows[std::size_t(id)] = 1;
  };
  scratch.views.clear();
  scratch.patchOfView.clear();
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const PatchConstraint& pc = patches[i];
    if (pc.articulated >= 0) {
      mark(pc.a.id);
      mark(pc.b.id);
      continue;
    }
    scratch.patchOfView.push_back(int(i));
    scratch.views.push_back({pc.a.id, pc.b.id, &pc.a.body, &pc.b.body, &pc.F, pc.fb.rho});
  }
  parts::linkStackedPatches(scratch.views, numBodies, otherRows, scratch.links, holds);
  auto patchOf = [&](int view) { return view < 0 ? -1 : scratch.patchOfView[std::size_t(view)]; };
  // a soft patch is solved on its own
  for (std::size_t v = 0; v < scratch.links.size(); ++v) {
    parts::StackLinks& l = scratch.links[v];
    if (l.support < 0) continue;
    parts::StackLinks& s = scratch.links[std::size_t(l.support)];
    if (patches[std::size_t(patchOf(int(v)))].compliance == 0.0 &&
        patches[std::size_t(patchOf(l.support))].compliance == 0.0)
      continue;
    if (s.load == int(v)) s.load = s.loadHold = -1;
    l.support = l.hold = -1;
  }
  for (std::size_t v = 0; v < scratch.links.size(); ++v) {
    parts::StackLinks l = scratch.links[v];
    l.support = patchOf(l.support);
    l.load = patchOf(l.load);
    patches[std::size_t(scratch.patchOfView[v])].stack = l;
  }
}

}  // namespace patchspin::bullet::internal
