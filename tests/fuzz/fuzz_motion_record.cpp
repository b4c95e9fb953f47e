// Fuzzes the ground-motion readers (motion/readers.hpp: PEER .AT2, ESM ASCII, plain text) through parse_record.
// The first byte picks the file name (its extension steers the format detection), the --units and --dt options and a
// forced format; the rest is the file's text. A record that is returned must pass Record::validate().

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string_view>

#include "blockdem/core/error.hpp"
#include "blockdem/motion/readers.hpp"

namespace {

using blockdem::motion::AccelerationUnit;
using blockdem::motion::ReadOptions;
using blockdem::motion::RecordFormat;

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_motion_record: %s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);

  static constexpr const char* names[] = {"fuzz.AT2", "fuzz.asc", "fuzz.txt", "fuzz.at2"};
  const char* name = names[mode & 3];
  ReadOptions options;
  switch ((mode >> 2) & 3) {
    case 1: options.units = AccelerationUnit::g; break;
    case 2: options.units = AccelerationUnit::m_s2; break;
    case 3: options.units = AccelerationUnit::cm_s2; break;
    default: break;  // from the file
  }
  switch ((mode >> 4) & 3) {
    case 1: options.dt = 0.01; break;
    case 2: options.dt = 0.005; break;
    case 3: options.dt = (mode & 1) ? std::numeric_limits<double>::quiet_NaN() : 0.0; break;  // refused
    default: break;  // from the file
  }
  static constexpr RecordFormat formats[] = {RecordFormat::automatic, RecordFormat::peer_at2, RecordFormat::esm_ascii,
                                             RecordFormat::plain_text};
  // Detected from the name and the text, or forced as with ReadOptions::format.
  options.format = formats[(mode >> 6) & 3];

  try {
    const auto record = blockdem::motion::parse_record(text, name, options);
    try {
      record.validate("fuzzed record");
    } catch (const blockdem::InvalidArgument& e) {
      finding("the reader returned a record that does not validate", e.what());
    }
  } catch (const blockdem::InvalidArgument&) {
  } catch (const blockdem::InputError&) {
  }
  return 0;
}
