#pragma once
// Errors at the library boundary (files, options, builders) and assertions for the hot loops.

#include <stdexcept>
#include <string>

namespace blockdem {

/// Thrown when an input value (an option, a field of a file, a builder argument) is outside its allowed range.
/// The message names the field and the allowed range, for example
/// "maxwell fit: branches = 9 is outside 1..8".
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Thrown when an input file cannot be read or is malformed; the message names the file and the line.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Thrown when a run leaves every physical bound (a state that is not finite, a monitor point farther from where
/// it settled than any collapse could take it): the run diverged, or a block fell off the model. The message names
/// the time, the point and the bound.
class RunawayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace blockdem

// Checks that hold by construction inside the hot loops: compiled out unless BLOCKDEM_ENABLE_ASSERTS is defined
// (tests define it), so release builds pay nothing for them.
#if defined(BLOCKDEM_ENABLE_ASSERTS)
#include <cstdio>
#include <cstdlib>
#define BLOCKDEM_ASSERT(condition)                                                                     \
  do {                                                                                                 \
    if (!(condition)) {                                                                                \
      std::fprintf(stderr, "blockdem: assertion failed: %s (%s:%d)\n", #condition, __FILE__, __LINE__); \
      std::abort();                                                                                    \
    }                                                                                                  \
  } while (false)
#else
#define BLOCKDEM_ASSERT(condition) static_cast<void>(0)
#endif
