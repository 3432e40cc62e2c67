// Reads a table of README.md, for the tests that hold text restating a table of the code (the
// integrators, the node's parameters) to that table.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vgtest {

// The body rows of the first Markdown table after the line `heading` (e.g. "### Parameters"),
// each as its cells with surrounding spaces and backticks removed and "\|" read as "|". Empty
// when the heading or the table is missing.
inline std::vector<std::vector<std::string>> readme_table(const std::string& path,
                                                          const std::string& heading) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line != heading) {
  }
  std::vector<std::vector<std::string>> rows;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) != 0) {
      if (in_table) break;
      continue;
    }
    in_table = true;
    if (line.find("---") != std::string::npos) continue;  // the separator row
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
        cell += '|';
        ++i;
      } else if (line[i] == '|') {
        std::string clean;
        for (char c : cell) {
          if (c != '`') clean += c;
        }
        const std::size_t first = clean.find_first_not_of(' ');
        const std::size_t last = clean.find_last_not_of(' ');
        cells.push_back(first == std::string::npos ? "" : clean.substr(first, last - first + 1));
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    rows.push_back(cells);
  }
  if (!rows.empty()) rows.erase(rows.begin());  // the header row
  return rows;
}

}  // namespace vgtest
