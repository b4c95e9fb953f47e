#pragma once
// Files that are either complete or absent: written under a temporary name beside the target and renamed when done,
// so that a run stopped mid-write leaves the previous complete file (or none), never a truncated one.

#include <filesystem>
#include <string>
#include <system_error>

#include "blockdem/core/error.hpp"

namespace blockdem::io {

/// Calls write(temporary_path), then renames the temporary file to `path`. Throws InvalidArgument naming `path` if
/// the rename fails; the writer's own errors propagate (and the temporary file is removed).
template <class Write>
void write_atomically(const std::string& path, Write&& write) {
  const std::string part = path + ".part";
  try {
    write(part);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(part, ignored);
    throw;
  }
  std::error_code error;
  std::filesystem::rename(part, path, error);
  if (error) throw InvalidArgument("cannot write '" + path + "': " + error.message());
}

}  // namespace blockdem::io
