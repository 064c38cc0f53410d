#include "tool_common.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace patchspin::tool {

std::vector<double> parseNumbers(const std::string& text, const char* what, std::size_t count) {
  std::vector<double> out;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || errno == ERANGE) {
      throw UsageError(std::string(what) + ": '" + item + "' is not a number (in '" + text + "')");
    }
    if (!std::isfinite(v))
      throw UsageError(std::string(what) + ": values must be finite, got '" + item + "'");
    out.push_back(v);
  }
  if (count != 0 && out.size() != count) {
    throw UsageError(std::string(what) + " needs " + std::to_string(count) +
                     " comma-separated numbers, got " + std::to_string(out.size()) + " ('" + text +
                     "')");
  }
  return out;
}

PatchShape parsePatch(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    throw UsageError(
        "--patch must be disk:R, rect:LX,LY, poly:x1,y1,x2,y2,..., cut:R,D or lens:R1,R2,D: got '" +
        text + "'");
  }
  const std::string kind = text.substr(0, colon), args = text.substr(colon + 1);
  if (kind == "disk") {
    return PatchShape::disk(parseNumbers(args, "--patch disk:R", 1)[0]);
  }
  if (kind == "rect") {
    const auto v = parseNumbers(args, "--patch rect:LX,LY", 2);
    return PatchShape::rectangle(v[0], v[1]);
  }
  if (kind == "poly") {
    const auto v = parseNumbers(args, "--patch poly:x1,y1,...");
    if (v.size() % 2 != 0)
      throw UsageError("--patch poly: needs x,y pairs, got an odd count of numbers");
    std::vector<Vec2> vertices;
    for (std::size_t i = 0; i < v.size(); i += 2) vertices.emplace_back(v[i], v[i + 1]);
    return PatchShape::polygon(std::move(vertices));
  }
  if (kind == "cut") {
    // the disk (O, R) over the edge x = D of a box that holds x <= D
    const auto v = parseNumbers(args, "--patch cut:R,D", 2);
    const double R = v[0], D = v[1];
    internal::requirePositive(R, "--patch cut:R,D radius R");
    if (!(D > -R)) throw UsageError("--patch cut:R,D: nothing of the disk is left at x <= D");
    const double h = 2.0 * R;  // the box reaches beyond the disk but at x = D
    const std::vector<Vec2> box = {Vec2(-h, -h), Vec2(D, -h), Vec2(D, h), Vec2(-h, h)};
    return PatchShape::arcRegion(diskPolygonIntersection(Vec2::Zero(), R, box));
  }
  if (kind == "lens") {
    const auto v = parseNumbers(args, "--patch lens:R1,R2,D", 3);
    internal::requirePositive(v[0], "--patch lens:R1,R2,D radius R1");
    internal::requirePositive(v[1], "--patch lens:R1,R2,D radius R2");
    const std::vector<BoundaryPiece> lens =
        diskDiskIntersection(Vec2::Zero(), v[0], Vec2(v[2], 0.0), v[1]);
    if (lens.empty()) throw UsageError("--patch lens:R1,R2,D: the disks do not overlap");
    return PatchShape::arcRegion(lens);
  }
  throw UsageError("--patch kind must be disk, rect, poly, cut or lens: got '" + kind + "'");
}

}  // namespace patchspin::tool
