// Stack hold part (stack_hold.hpp; docs/solver.md (S15)-(S16)).
#include <patchspin/parts/stack_hold.hpp>

namespace patchspin::parts {

void linkStackedPatches(const std::vector<StackPatchView>& patches, int numBodies,
                        const std::vector<char>& otherRows, std::vector<StackLinks>& links,
                        std::vector<StackHold>& holds) {
  links.assign(patches.size(), StackLinks());
  // by body id (a patch's body a is dynamic, so its id is its own):
  // own: the body's single patch (kNone: none, kSeveral: more than one);
  // above: how many patches stand on the body
  constexpr int kNone = -2, kSeveral = -1;
  std::vector<int> own(std::size_t(numBodies), kNone), above(std::size_t(numBodies), 0);
  for (int i = 0; i < int(patches.size()); ++i) {
    int& o = own[std::size_t(patches[std::size_t(i)].bodyA)];
    o = o == kNone ? i : kSeveral;
  }
  for (const StackPatchView& pc : patches)
    if (pc.b->dynamic) ++above[std::size_t(pc.bodyB)];
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const StackPatchView& pc = patches[p];
    if (!pc.b->dynamic || above[std::size_t(pc.bodyB)] != 1 || own[std::size_t(pc.bodyA)] < 0 ||
        otherRows[std::size_t(pc.bodyB)])
      continue;
    const int support = own[std::size_t(pc.bodyB)];
    if (support < 0) continue;
    const StackPatchView& sp = patches[std::size_t(support)];
    if (std::size_t(support) == p || sp.bodyA != pc.bodyB) continue;
    // K_PS = -J_{P,b} M_L^-1 J_{S,a}^T (the lower body L is P's b, S's a)
    const Mat6 JPb = patchBodyRows(*pc.b, *pc.F, pc.rho), JSa = patchBodyRows(*sp.a, *sp.F, sp.rho);
    Mat6 MinvJSaT;
    MinvJSaT.topRows<3>() = pc.b->invM.asDiagonal() * JSa.leftCols<3>().transpose();
    MinvJSaT.bottomRows<3>() = pc.b->invI * JSa.rightCols<3>().transpose();
    const Mat6 Kps = -JPb * MinvJSaT;
    // fold the held DOFs (the support's first n) into P's blocks
    const Mat6 K6p = patchEffectiveMass(*pc.a, *pc.b, *pc.F, pc.rho);
    const Mat6 K6s = patchEffectiveMass(*sp.a, *sp.b, *sp.F, sp.rho);
    StackHold sh;
    foldHeldDofs<6>(K6p, K6s, Kps.leftCols<6>(), sh.all);
    foldHeldDofs<3>(K6p, K6s, Kps.leftCols<3>(), sh.normal);
    sh.coupling = Kps;
    sh.heldK = K6s;
    if (!sh.all.valid && !sh.normal.valid) continue;
    links[p].support = support;
    links[p].hold = int(holds.size());
    holds.push_back(sh);
    // and the other way round: a support on a static body (the bottom of the
    // stack) is solved with its load P held, K_S - K_SP K_P^-1 K_PS, so the
    // floor feels the heavy body's inertia
    if (sp.b->dynamic || links[std::size_t(support)].load >= 0 || otherRows[std::size_t(pc.bodyA)])
      continue;
    StackHold lh;
    foldHeldDofs<6>(K6s, K6p, Kps.topRows<6>().transpose(), lh.all);
    foldHeldDofs<3>(K6s, K6p, Kps.topRows<3>().transpose(), lh.normal);
    lh.coupling = Kps.transpose();
    lh.heldK = K6p;
    if (!lh.all.valid && !lh.normal.valid) continue;
    links[std::size_t(support)].load = int(p);
    links[std::size_t(support)].loadHold = int(holds.size());
    holds.push_back(lh);
  }
}

}  // namespace patchspin::parts
