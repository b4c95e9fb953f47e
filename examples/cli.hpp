#pragma once
// What the blockdem programs share: command-line parsing with exit status 0 for --help and 2 for bad input.

#include <optional>

#include <CLI/CLI.hpp>

namespace blockdem::programs {

inline constexpr int exit_bad_input = 2;

/// Parses the command line. Returns the exit status if the program should stop now (help printed: 0; bad input,
/// with CLI11's message naming the option: 2), nothing if it should go on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
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

}  // namespace blockdem::programs
