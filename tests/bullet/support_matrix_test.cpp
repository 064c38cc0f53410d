// Which body shape gets a patch on which support: every cell of the table in
// docs/bullet.md ("Shapes") is run here, and the table must list exactly
// the cells run (SupportMatrix.DocumentedTableMatchesEveryCell). A cell is
// "patch" (a patch in every step after the first and nothing left to
// Bullet) or "points: <reason>" (no patch; every step counts the contact
// under that NotPatchedCounts reason: never silent).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <patchspin/scenes/support_matrix.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bullet_scenes.hpp"

namespace patchspin::bullet {
namespace {

using scenes::BodyShape;
using scenes::SupportShape;

// 0.2 s of a body spinning at 5 rad/s and sliding at 5 cm/s on the support
// (the ellipsoidal law): long enough for a patch to form and hold, short of
// stopping.
constexpr int kSteps = 48;

std::string runCell(BodyShape b, SupportShape s) {
  Scene scene(kG);
  scenes::addSupport(scene, s);
  btRigidBody* body = scenes::addBodyOnTop(scene, b);
  scene.solver().enablePatchFriction(body, {Model::Ellipsoidal});
  body->setLinearVelocity(btVector3(0.05f, 0, 0));
  body->setAngularVelocity(btVector3(0, 0, 5));
  int patched = 0;
  std::map<std::string, int> reasons;  // steps counting each reason
  for (int k = 0; k < kSteps; ++k) {
    scene.step(kDt);
    const PatchReport* r = scene.solver().findPatchReport(body);
    if (k > 0 && r) ++patched;
    const NotPatchedCounts* np = scene.solver().notPatchedOf(body);
    if (!np || k == 0) continue;
    const std::pair<const char*, long> all[] = {{"unsupported shape", np->unsupportedShape},
                                                {"side contact", np->sideContact},
                                                {"not flat", np->notFlat},
                                                {"off faces", np->offFaces},
                                                {"tip cooldown", np->tipCooldown},
                                                {"no overlap", np->noOverlap},
                                                {"law refused", np->lawRefused},
                                                {"sliver", np->sliver},
                                                {"singular blocks", np->singularBlocks},
                                                {"crease", np->crease},
                                                {"bad mesh", np->badMesh}};
    for (const auto& [name, count] : all)
      if (count > 0) ++reasons[name];
  }
  if (patched == kSteps - 1 && reasons.empty()) return "patch";
  // points: the reason counted in every step (after the first)
  for (const auto& [name, steps] : reasons)
    if (patched == 0 && steps >= kSteps - 1) return "points: " + name;
  std::ostringstream mixed;
  mixed << "mixed: patched " << patched << "/" << kSteps - 1;
  for (const auto& [name, steps] : reasons) mixed << ", " << name << " " << steps;
  return mixed.str();
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t`*");
  const auto b = s.find_last_not_of(" \t`*");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) out.push_back(trim(cell));
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

// The table after the marker line in docs/bullet.md: header (supports),
// separator, one row per body shape.
std::map<std::pair<std::string, std::string>, std::string> documentedTable() {
  std::ifstream doc(std::string(PATCHSPIN_SOURCE_DIR) + "/docs/bullet.md");
  EXPECT_TRUE(doc.good());
  std::string line;
  while (std::getline(doc, line) && line.find("<!-- support-matrix") == std::string::npos) {
  }
  std::vector<std::string> header;
  std::map<std::pair<std::string, std::string>, std::string> table;
  while (std::getline(doc, line) && !line.empty() && line[0] == '|') {
    const std::vector<std::string> c = cells(line);
    if (header.empty()) {
      header = c;
      continue;
    }
    if (c.empty() || c[0].find("---") != std::string::npos) continue;
    for (size_t i = 1; i < c.size() && i < header.size(); ++i) table[{c[0], header[i]}] = c[i];
  }
  return table;
}

TEST(SupportMatrix, DocumentedTableMatchesEveryCell) {
  const auto table = documentedTable();
  size_t run = 0;
  for (BodyShape b : scenes::allBodyShapes()) {
    for (SupportShape s : scenes::allSupportShapes()) {
      const std::string outcome = runCell(b, s);
      std::printf("  %-12s on %-14s %s\n", toString(b).c_str(), toString(s).c_str(),
                  outcome.c_str());
      const auto it = table.find({toString(b), toString(s)});
      ++run;
      if (it == table.end()) {
        ADD_FAILURE() << "docs/bullet.md has no cell for " << toString(b) << " on " << toString(s);
        continue;
      }
      EXPECT_EQ(it->second, outcome) << toString(b) << " on " << toString(s);
    }
  }
  // and the table has no cell that is not run
  EXPECT_EQ(table.size(), run);
}

}  // namespace
}  // namespace patchspin::bullet
