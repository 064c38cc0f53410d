// Internal to patchspin::render's plots: how a limit direction is drawn,
// by its stability (colour) and kind (point type) (plot_*.cpp).
#pragma once

#include <patchspin/render/plot.hpp>

#include <set>
#include <string>

namespace patchspin::render::plotting {

int pointType(LimitKind k);
const char* kindName(LimitKind k);
const char* kindShort(LimitKind k);
const char* stabilityName(Stability s);
const char* stabilityColour(Stability s, bool pale = false);
// styles: (stability, kind) pairs numbered attracting first
constexpr int kKinds = 4;
constexpr int kStyles = 2 * kKinds;
int styleIndex(Stability s, LimitKind k);
Stability styleStability(int i);
LimitKind styleKind(int i);
// key entries for the limit-direction styles present
std::string limitKeyEntries(const std::set<int>& styles);

}  // namespace patchspin::render::plotting
