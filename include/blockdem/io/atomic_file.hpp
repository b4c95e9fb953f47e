#pragma once
// Files that are either complete or absent: written under a temporary name beside the target and renamed when done,
// so that a run stopped mid-write (Ctrl-C, SIGKILL, a crash) leaves the previous complete file, or none, never a
// truncated one; and a write that fails (disk full, no permission) is an error that names the file.

#include <cerrno>
#include <concepts>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <system_error>

#include "blockdem/core/error.hpp"

namespace blockdem::io {

/// The temporary name a file is written under until it is complete.
inline std::string partial_path(const std::string& path) { return path + ".part"; }

/// Throws InvalidArgument naming `path` (and the reason the system gives) if `out` failed; closes it first, so that
/// what was still buffered is written and its failure seen.
inline void close_checked(std::ofstream& out, const std::string& path) {
  int error = out.fail() ? errno : 0;  // why a write of the writer's failed (the last call that set errno)
  if (out.is_open()) {
    errno = 0;
    out.close();
    if (!error && out.fail()) error = errno;
  }
  if (out.fail())
    throw InvalidArgument("cannot write '" + path + "'" + (error ? std::string(": ") + std::strerror(error) : std::string()));
}

/// Calls write(temporary_path), then renames the temporary file to `path`. Throws InvalidArgument naming `path` if
/// the rename fails; the writer's own errors propagate (and the temporary file is removed). The writer must check
/// its stream after closing it (close_checked).
template <class Write>
  requires std::invocable<Write&, const std::string&>
void write_atomically(const std::string& path, Write&& write) {
  const std::string part = partial_path(path);
  try {
    write(part);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(part, ignored);
    throw;
  }
  std::error_code error;
  std::filesystem::rename(part, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(part, ignored);
    throw InvalidArgument("cannot write '" + path + "': " + error.message());
  }
}

/// The same for a writer of a text stream: write(std::ostream&) fills the temporary file, which is then flushed,
/// closed and checked (InvalidArgument naming `path` if anything failed: cannot open, disk full, file too large).
template <class Write>
  requires std::invocable<Write&, std::ostream&>
void write_atomically(const std::string& path, Write&& write) {
  write_atomically(path, [&](const std::string& part) {
    std::ofstream out(part);
    if (!out) throw InvalidArgument("cannot open '" + path + "' for writing (as '" + part + "'): " + std::strerror(errno));
    write(static_cast<std::ostream&>(out));
    close_checked(out, path);
  });
}

}  // namespace blockdem::io
