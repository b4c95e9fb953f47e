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

#include "blockdem/analysis/sweep_run.hpp"
#include "blockdem/core/error.hpp"

#include "scratch.hpp"

namespace {

using namespace blockdem;

const std::string& case_dir() {
  static const fuzz::Scratch dir{"blockdem_fuzz_sweep_run_"};
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
