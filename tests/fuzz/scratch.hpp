// Scratch files for the fuzz harnesses whose reader takes a path, not bytes: one file or folder per harness process,
// in memory where possible, removed when the fuzzer exits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace blockdem::fuzz {

/// $TMPDIR, else /dev/shm (memory: a disk-backed /tmp costs more than the reader), else /tmp.
inline std::string scratch_dir() {
  if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp) return tmp;
  std::error_code error;
  return std::filesystem::is_directory("/dev/shm", error) ? "/dev/shm" : "/tmp";
}

/// A file or folder under scratch_dir() named `stem` and this process's id (then `suffix`), removed on exit.
struct Scratch {
  std::string path;
  Scratch(const std::string& stem, const std::string& suffix = "")
      : path(scratch_dir() + "/" + stem + std::to_string(getpid()) + suffix) {}
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() {
    std::error_code error;
    std::filesystem::remove_all(path, error);
  }
};

/// Writes `size` bytes to `file` (truncating it) and returns its path.
inline const std::string& write_scratch(const Scratch& file, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(file.path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file.path;
}

}  // namespace blockdem::fuzz
