// Argument parsing shared by the subcommands of the `patchspin` tool.
#pragma once

#include "command_registry.hpp"

#include <patchspin/geometry.hpp>

#include <string>
#include <vector>

namespace patchspin::tool {

// "1.5,2,-3" -> {1.5, 2, -3}; `what` names the flag in errors. If `count` is
// nonzero the list must have exactly that many numbers.
std::vector<double> parseNumbers(const std::string& text, const char* what, std::size_t count = 0);

// --patch SHAPE: "disk:R", "rect:LX,LY" (centred on O, sides along x and y),
// "poly:x1,y1,x2,y2,..." (counter-clockwise, patch frame), or the exact arc
// regions (PatchShape::arcRegion) "cut:R,D" (the disk of radius R about O,
// the part x <= D: a coin over a box edge) and "lens:R1,R2,D" (the disks
// (O, R1) and ((D, 0), R2) intersected). Throws UsageError /
// patchspin::Error with a one-line message.
PatchShape parsePatch(const std::string& text);

}  // namespace patchspin::tool
