#pragma once
// What the blockdem programs share: command-line parsing with exit status 0 for --help and 2 for bad input.

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "blockdem/analysis/deformable_options.hpp"

namespace blockdem::programs {

inline constexpr int exit_bad_input = 2;

/// Refuses NaN, infinities and numbers beyond the range of a double (1e400) for every floating-point option of `app`
/// and of its subcommands: CLI11 reads them as numbers, and a range such as x > 0 lets infinity through. The message
/// names the option and repeats its help, which gives the allowed range.
inline void require_finite_numbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name().rfind("FLOAT", 0) != 0) continue;
    const std::string help = option->get_description().empty() ? "" : " (" + option->get_description() + ")";
    option->check(CLI::Validator(
        [help](std::string& text) {
          char* end = nullptr;
          const double value = std::strtod(text.c_str(), &end);
          if (end == text.c_str() || std::isfinite(value)) return std::string();  // a number, or CLI11's to refuse
          return "'" + text + "' is not a finite number" + help;
        },
        ""));
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) require_finite_numbers(*command);
}

/// Parses the command line. Returns the exit status if the program should stop now (help printed: 0; bad input,
/// with CLI11's message naming the option: 2), nothing if it should go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  require_finite_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return exit_bad_input;
  }
  return std::nullopt;
}

/// The flags of a program whose blocks can be deformable: --deformable, --max-edge, --young, --poisson, --target-dt.
/// `what` names the blocks in the help ("the voussoirs", "the block").
inline void add_deformable_options(CLI::App& app, analysis::DeformableOptions& o, const std::string& what) {
  app.add_flag("--deformable", o.deformable, "mesh " + what + " into constant-strain tetrahedra");
  app.add_option("--max-edge", o.max_edge, "maximum tetrahedron edge, m")->capture_default_str();
  app.add_option("--young", o.young, "Young's modulus of " + what + " if deformable, Pa")->capture_default_str();
  app.add_option("--poisson", o.poisson, "Poisson's ratio of " + what + " if deformable, (-1, 0.5)")->capture_default_str();
  app.add_option("--target-dt", o.target_dt, "partial density scaling to this timestep, s (0: none)")->capture_default_str();
}

}  // namespace blockdem::programs
