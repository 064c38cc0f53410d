// Patch visits (patch_visit.hpp): the stage-5 helpers that are not
// templates, and the checks of the options and settings.
#include "patch_visit.hpp"

#include <cmath>
#include <string>

namespace patchspin::bullet::internal {

parts::FrictionPartSettings frictionSettings(const PatchSolverSettings& s) {
  parts::FrictionPartSettings f;
  f.pressureRefreshTolerance = s.pressureRefreshTolerance;
  f.pressureLagTolerance = s.pressureLagTolerance;
  f.quickStick = s.quickStick;
  f.deferStickingRefresh = s.deferStickingRefresh;
  f.blockTolerance = kBlockRelTol;
  f.reuseTolerance = kReuseRelTol;
  return f;
}

void checkPatchOptions(const PatchOptions& options) {
  using patchspin::internal::formatDouble;
  if (options.model != Model::Ellipsoidal && options.model != Model::Exact)
    throw Error("PatchOptions::model must be Model::Ellipsoidal or Model::Exact: got " +
                std::to_string(int(options.model)));
  if (options.mu) {
    patchspin::internal::requireFinite(*options.mu, "PatchOptions::mu");
    if (*options.mu < 0.0)
      throw Error("PatchOptions::mu must be >= 0: got " + formatDouble(*options.mu));
  }
  if (options.rho) {
    patchspin::internal::requirePositive(*options.rho, "PatchOptions::rho");
    if (!(*options.rho >= kMinRho && *options.rho <= kMaxRho))
      throw Error("PatchOptions::rho = " + formatDouble(*options.rho) +
                  " m can never make a patch: the lever max|r| / rho must lie in [1e-5, 1e5] "
                  "with max|r| in [1.25e-162, 1e6] m, so rho in [" +
                  formatDouble(kMinRho) + ", " + formatDouble(kMaxRho) + "] m");
  }
  patchspin::internal::requirePositive(options.flatnessTolerance,
                                       "PatchOptions::flatnessTolerance");
  if (options.flatnessTolerance > kMaxFlatnessTolerance)
    throw Error("PatchOptions::flatnessTolerance must be at most pi/8 = " +
                formatDouble(kMaxFlatnessTolerance) +
                " rad (a patch ends at twice it, within "
                "the 45 degrees beyond which a face no longer faces the contact): got " +
                formatDouble(options.flatnessTolerance));
}

void checkSolverSettings(const PatchSolverSettings& settings) {
  using patchspin::internal::formatDouble;
  for (const auto& [value, name] :
       {std::pair{settings.pressureRefreshTolerance, "pressureRefreshTolerance"},
        std::pair{settings.pressureLagTolerance, "pressureLagTolerance"}}) {
    patchspin::internal::requireFinite(value,
                                       (std::string("PatchSolverSettings::") + name).c_str());
    if (value < 0.0)
      throw Error(std::string("PatchSolverSettings::") + name + " must be >= 0: got " +
                  formatDouble(value));
  }
}

// Patches whose normals agree within this angle [rad] share a plane for
// the load sharing (S25): a body on faces of one floor or of boxes of one
// height (both exactly parallel); tilted faces keep their own split.
namespace {
constexpr double kShareParallel = 1e-3;
}  // namespace

// The groups of (S25): per dynamic body, its hard patches on static or
// kinematic supports with no stack hold, parallel to the body's first such
// patch; a body with one such patch has none. (A patch's loads are shared
// only while its impulses leave the support's velocity unchanged.)
// `groupOf`: scratch by solver body id; linear in the patches, and nothing
// allocated for bodies on one patch (a pile of coins).
void groupSharedPatches(const std::vector<PatchConstraint>& patches, int numBodies,
                        std::vector<int>& groupOf, std::vector<std::vector<int>>& groups) {
  groups.clear();
  auto eligible = [](const PatchConstraint& pc) {
    return pc.articulated < 0 && !pc.b.body.dynamic && pc.compliance == 0.0 && pc.stack.hold < 0 &&
           pc.stack.loadHold < 0;
  };
  // pass 1: -1 none, -2 one, -3 several eligible patches
  groupOf.assign(std::size_t(numBodies), -1);
  bool several = false;
  for (const PatchConstraint& pc : patches) {
    if (!eligible(pc)) continue;
    int& g = groupOf[std::size_t(pc.a.id)];
    several = several || g == -2;
    g = g == -1 ? -2 : -3;
  }
  if (!several) return;
  // pass 2: a group per body with several, by index once made
  const double cosParallel = std::cos(kShareParallel);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const PatchConstraint& pc = patches[i];
    if (!eligible(pc)) continue;
    int& g = groupOf[std::size_t(pc.a.id)];
    if (g == -2) continue;
    if (g == -3) {
      g = int(groups.size());
      groups.push_back({int(i)});
    } else if (patches[std::size_t(groups[std::size_t(g)][0])].F.col(2).dot(pc.F.col(2)) >=
               cosParallel) {
      groups[std::size_t(g)].push_back(int(i));
    }
  }
  // (a body whose other patches are not parallel to its first)
  groups.erase(std::remove_if(groups.begin(), groups.end(),
                              [](const std::vector<int>& grp) { return grp.size() < 2; }),
               groups.end());
}

// (S25) for one group, in the frame of its first patch; a patch whose
// loads change is visited again and its friction block re-solved.
void shareGroupLoads(std::vector<PatchConstraint>& patches, const std::vector<int>& group,
                     std::vector<parts::SharedPatch>& buf) {
  const PatchConstraint& ref = patches[std::size_t(group[0])];
  const btVector3& o = ref.state->geometry.origin;
  const Vec3 ex = ref.F.col(0), ey = ref.F.col(1);
  buf.resize(group.size());
  for (std::size_t k = 0; k < group.size(); ++k) {
    const PatchConstraint& pc = patches[std::size_t(group[k])];
    const btVector3 d = pc.state->geometry.origin - o;
    const Vec3 dv(double(d.x()), double(d.y()), double(d.z()));
    parts::SharedPatch& sp = buf[k];
    sp.origin = Vec2(dv.dot(ex), dv.dot(ey));
    sp.R << pc.F.col(0).dot(ex), pc.F.col(1).dot(ex), pc.F.col(0).dot(ey), pc.F.col(1).dot(ey);
    sp.shape = &pc.state->friction->shape();
    sp.lamN = pc.lamN;
  }
  if (!parts::shareLoads(buf)) return;
  for (std::size_t k = 0; k < group.size(); ++k) {
    PatchConstraint& pc = patches[std::size_t(group[k])];
    if (buf[k].lamN == pc.lamN) continue;
    pc.lamN = buf[k].lamN;
    pc.settled = false;
    pc.fb.haveLast = false;
  }
}

}  // namespace patchspin::bullet::internal
