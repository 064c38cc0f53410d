// Internal to patchspin::render's plots: the CSV tables they read, with
// messages that name the file, line and column (plot_*.cpp).
#pragma once

#include <patchspin/render/plot.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace patchspin::render::plotting {

struct Csv {
  std::string path;
  std::map<std::string, std::size_t> column;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> lineOf;  // source line of each row, for messages

  std::size_t index(const std::string& name) const {
    auto it = column.find(name);
    if (it == column.end()) throw RenderError(path + ": missing column '" + name + "'");
    return it->second;
  }
  bool has(const std::string& name) const { return column.count(name) > 0; }
  const std::string& text(std::size_t row, const std::string& name) const {
    const std::size_t c = index(name);
    if (c >= rows[row].size()) {
      throw RenderError(path + ":" + std::to_string(lineOf[row]) + ": missing value for '" + name +
                        "'");
    }
    return rows[row][c];
  }
  double number(std::size_t row, const std::string& name) const {
    const std::string& t = text(row, name);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') {
      throw RenderError(path + ":" + std::to_string(lineOf[row]) + ": '" + name +
                        "' is not a number: '" + t + "'");
    }
    return v;
  }
};

// s without leading and trailing blanks
std::string trim(const std::string& s);
// The table at path: '#' lines and blank lines skipped, the first row the
// header; RenderError if it cannot be read or has no data row.
Csv readCsv(const std::string& path);
// The cells "stability" and "kind" of a row; RenderError for another word.
Stability parseStability(const Csv& csv, std::size_t row);
LimitKind parseKind(const Csv& csv, std::size_t row);

}  // namespace patchspin::render::plotting
