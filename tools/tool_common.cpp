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
    throw UsageError("--patch must be disk:R, rect:LX,LY or poly:x1,y1,x2,y2,...: got '" + text +
                     "'");
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
  throw UsageError("--patch kind must be disk, rect or poly: got '" + kind + "'");
}

}  // namespace patchspin::tool
