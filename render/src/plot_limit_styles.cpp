// Limit-direction styles of the plots (plot_limit_styles.hpp).
#include "plot_limit_styles.hpp"

#include "plot_script.hpp"

namespace patchspin::render::plotting {

int pointType(LimitKind k) {
  switch (k) {
    case LimitKind::Dominant:
      return 7;  // filled circle
    case LimitKind::Isolated:
      return 6;  // open circle
    case LimitKind::Saddle:
      return 9;  // filled triangle
    case LimitKind::Nonhyperbolic:
      return 12;  // open diamond
  }
  return 7;
}
const char* kindName(LimitKind k) {
  switch (k) {
    case LimitKind::Dominant:
      return "dominant";
    case LimitKind::Isolated:
      return "isolated";
    case LimitKind::Saddle:
      return "saddle";
    case LimitKind::Nonhyperbolic:
      return "nonhyperbolic";
  }
  return "";
}
const char* kindShort(LimitKind k) {
  switch (k) {
    case LimitKind::Dominant:
      return "dom";
    case LimitKind::Isolated:
      return "iso";
    case LimitKind::Saddle:
      return "sad";
    case LimitKind::Nonhyperbolic:
      return "nonhyp";
  }
  return "";
}
const char* stabilityName(Stability s) {
  return s == Stability::Attracting ? "attracting" : "repelling";
}
const char* stabilityColour(Stability s, bool pale) {
  if (s == Stability::Attracting) return pale ? kAttractingPale : kAttracting;
  return pale ? kRepellingPale : kRepelling;
}
int styleIndex(Stability s, LimitKind k) {
  return (s == Stability::Attracting ? 0 : kKinds) + static_cast<int>(k);
}
Stability styleStability(int i) {
  return i < kKinds ? Stability::Attracting : Stability::Repelling;
}
LimitKind styleKind(int i) {
  return static_cast<LimitKind>(i % kKinds);
}

std::string limitKeyEntries(const std::set<int>& styles) {
  std::string s;
  for (int i : styles) {
    s += ", keyentry with points pt " + std::to_string(pointType(styleKind(i))) +
         " ps 1.8 lw 2 lc rgb " + gpString(stabilityColour(styleStability(i))) + " title " +
         gpString(std::string(stabilityName(styleStability(i))) + " " + kindName(styleKind(i)));
  }
  return s;
}

}  // namespace patchspin::render::plotting
