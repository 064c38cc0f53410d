// CSV tables of the plots (plot_csv.hpp).
#include "plot_csv.hpp"

#include <cstdlib>
#include <fstream>

namespace patchspin::render::plotting {
namespace {

// Splits a CSV line; a field in double quotes may hold commas, "" is a quote.
std::vector<std::string> splitComma(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  bool inQuotes = false, wasQuoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (inQuotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        inQuotes = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      inQuotes = true;
      wasQuoted = true;
      cell = trim(cell);  // spaces before the quote do not count
    } else if (c == ',') {
      out.push_back(wasQuoted ? cell : trim(cell));
      cell.clear();
      wasQuoted = false;
    } else if (!(wasQuoted && (c == ' ' || c == '\t' || c == '\r'))) {
      cell += c;
    }
  }
  out.push_back(wasQuoted ? cell : trim(cell));
  return out;
}

}  // namespace

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

Csv readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RenderError("cannot read " + path);
  Csv csv;
  csv.path = path;
  std::string line;
  int lineNo = 0;
  bool haveHeader = false;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> cells = splitComma(t);
    if (!haveHeader) {
      for (std::size_t i = 0; i < cells.size(); ++i) csv.column[cells[i]] = i;
      haveHeader = true;
      continue;
    }
    csv.rows.push_back(std::move(cells));
    csv.lineOf.push_back(lineNo);
  }
  if (!haveHeader) throw RenderError(path + ": empty file (a header row is required)");
  if (csv.rows.empty()) throw RenderError(path + ": no data rows");
  return csv;
}

Stability parseStability(const Csv& csv, std::size_t row) {
  const std::string& s = csv.text(row, "stability");
  if (s == "attracting") return Stability::Attracting;
  if (s == "repelling") return Stability::Repelling;
  throw RenderError(csv.path + ":" + std::to_string(csv.lineOf[row]) +
                    ": stability must be attracting or repelling, got '" + s + "'");
}

LimitKind parseKind(const Csv& csv, std::size_t row) {
  const std::string& s = csv.text(row, "kind");
  if (s == "dominant") return LimitKind::Dominant;
  if (s == "isolated") return LimitKind::Isolated;
  if (s == "saddle") return LimitKind::Saddle;
  if (s == "nonhyperbolic") return LimitKind::Nonhyperbolic;
  throw RenderError(csv.path + ":" + std::to_string(csv.lineOf[row]) +
                    ": kind must be dominant, isolated, saddle or nonhyperbolic, got '" + s + "'");
}

}  // namespace patchspin::render::plotting
