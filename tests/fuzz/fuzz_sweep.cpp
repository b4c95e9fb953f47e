// Fuzzes the sweep description reader (analysis/sweep_file.hpp) as the cross_vault sweep command uses it: parse_sweep
// on the file's text, then expand_sweep of what it read over the default study options (the ranges of the values,
// the names and the ids of the cases).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "blockdem/analysis/sweep.hpp"
#include "blockdem/analysis/sweep_file.hpp"
#include "blockdem/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const blockdem::analysis::VaultStudyOptions base;
  try {
    const auto spec = blockdem::analysis::parse_sweep(text, "sweeps/fuzz.json", "sweeps");
    (void)blockdem::analysis::expand_sweep(spec, base);
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
