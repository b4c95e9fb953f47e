// Fuzzes what a sweep reads back (analysis/sweep_run.hpp): a case's case.json from an earlier run (read_case_file,
// which must treat anything damaged as "run the case again") and the rows the workers send to the lead (decode).
// The first byte picks which; the rest is the file or the row.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

#include "blockdem/analysis/sweep_run.hpp"
#include "blockdem/core/error.hpp"

namespace {

using namespace blockdem;

/// Where the input is written for a reader that takes a path: $TMPDIR, else /dev/shm (memory: a disk-backed /tmp
/// costs more than the reader), else /tmp.
std::string scratch_dir() {
  if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp) return tmp;
  std::error_code error;
  return std::filesystem::is_directory("/dev/shm", error) ? "/dev/shm" : "/tmp";
}

/// A file or folder of this process under scratch_dir(), removed when the fuzzer exits.
struct Scratch {
  std::string path;
  ~Scratch() {
    std::error_code error;
    std::filesystem::remove_all(path, error);
  }
};

const std::string& case_dir() {
  static const Scratch dir{scratch_dir() + "/blockdem_fuzz_sweep_run_" + std::to_string(getpid())};
  [[maybe_unused]] static const bool created = std::filesystem::create_directories(dir.path);
  return dir.path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (data[0] & 1) {
      (void)analysis::detail::decode(bytes);
    } else {
      {
        std::ofstream out(case_dir() + "/case.json", std::ios::binary | std::ios::trunc);
        out << bytes;
      }
      analysis::SweepCase c;
      c.index = 3;
      c.id = "rigid_aqa75_maxwell_z0.03_b1-40_n3";
      (void)analysis::detail::read_case_file(case_dir(), c);
    }
  } catch (const InvalidArgument&) {
  } catch (const InputError&) {
  }
  return 0;
}
