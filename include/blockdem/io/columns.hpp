#pragma once
// Two-column numeric text (time, value), separated by spaces, tabs or commas; '#' starts a comment; a header line
// of words is skipped. Errors name the file and the line.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"

namespace blockdem::io {

struct TwoColumns {
  std::vector<double> x;
  std::vector<double> y;
};

inline TwoColumns read_two_columns(const std::string& path) {
  if (std::filesystem::is_directory(path)) throw InputError(path + ": is a directory, not a file of two columns");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  TwoColumns data;
  std::string line;
  int number = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream fields(line);
    std::string a, b, extra;
    if (!(fields >> a)) continue;
    if (!(fields >> b) || (fields >> extra))
      throw InputError(path + ":" + std::to_string(number) + ": expected two columns (time, value)");
    std::size_t used_a = 0, used_b = 0;
    double va = 0, vb = 0;
    try {
      va = std::stod(a, &used_a);
      vb = std::stod(b, &used_b);
    } catch (const std::exception&) {
      used_a = 0;
    }
    if (used_a != a.size() || used_b != b.size()) {
      if (header_allowed) {
        header_allowed = false;
        continue;
      }
      throw InputError(path + ":" + std::to_string(number) + ": expected two numbers, found '" + a + " " + b + "'");
    }
    header_allowed = false;
    if (!std::isfinite(va) || !std::isfinite(vb)) throw InputError(path + ":" + std::to_string(number) + ": not a finite number");
    if (!data.x.empty() && !(va > data.x.back()))
      throw InputError(path + ":" + std::to_string(number) + ": the first column must increase (" + a + " after " + std::to_string(data.x.back()) + ")");
    data.x.push_back(va);
    data.y.push_back(vb);
  }
  if (data.x.size() < 2) throw InputError(path + ": fewer than two data lines");
  return data;
}

}  // namespace blockdem::io
