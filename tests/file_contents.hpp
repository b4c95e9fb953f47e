#pragma once
// The whole of a file the test wrote, byte for byte ("" if it cannot be read).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace blockdem::test {

inline std::string file_contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace blockdem::test
