// Fuzzes the readers of numeric tables from files: read_csv_table (analysis/error_metrics.hpp: measured channels and
// history_<level>.csv, then compare_tables against a simulated history as `cross_vault compare` does) and
// read_two_columns (io/columns.hpp: the rocking_block history). The first byte picks the reader; the rest is the file.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <system_error>
#include <vector>

#include "blockdem/analysis/error_metrics.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/io/columns.hpp"

#include "scratch.hpp"

namespace {

using namespace blockdem;

/// A simulated history as the vault study writes it: 2 s at 500 Hz, the optical cameras and an accelerometer.
const analysis::Table& simulated() {
  static const analysis::Table table = [] {
    analysis::Table t;
    t.source = "history_25.csv";
    t.columns = {"time", "OC1_ux", "OC1_uy", "OC2_uy", "OC4_uy", "ACC18_ay"};
    t.values.resize(t.columns.size());
    for (int i = 0; i <= 1000; ++i) {
      const double time = 0.002 * i;
      t.values[0].push_back(time);
      for (std::size_t c = 1; c < t.columns.size(); ++c) t.values[c].push_back(1e-3 * c * std::sin(3.0 * c * time));
    }
    return t;
  }();
  return table;
}

const std::string& write_file(const std::uint8_t* data, std::size_t size) {
  static const fuzz::Scratch file{"blockdem_fuzz_table_", ".csv"};
  return fuzz::write_scratch(file, data, size);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t mode = data[0];
  const std::string path = write_file(data + 1, size - 1);
  try {
    if (mode & 1) {
      (void)io::read_two_columns(path);
    } else {
      const analysis::Table table = analysis::read_csv_table(path);
      // As measured, then as the simulated side of the comparison.
      const auto comparisons = (mode & 2) ? analysis::compare_tables(table, simulated())
                                          : analysis::compare_tables(simulated(), table);
      (void)analysis::mean_rmsd_error_percent(comparisons, "_uy");
    }
  } catch (const InvalidArgument&) {
  } catch (const InputError&) {
  }
  return 0;
}
