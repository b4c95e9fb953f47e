#pragma once
// What the translation units of the module `blockdem._core` share: their entry points (one per part of the library,
// each compiled on its own so that the module builds in parallel), the conversions between Python and blockdem's
// types, and running C++ with the GIL released while Ctrl-C still stops it.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/integrate/run.hpp"
#include "blockdem/motion/record.hpp"

namespace blockdem::python {

namespace py = pybind11;

void bind_damping(py::module_& m);
void bind_motion(py::module_& m);
void bind_model(py::module_& m);
void bind_study(py::module_& m);
void bind_simulation(py::module_& m);
void bind_sweep(py::module_& m);

/// A copy of `v` as a one-dimensional numpy array.
inline py::array_t<double> to_array(const std::vector<double>& v) { return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data()); }

/// The doubles of a sequence or numpy array (any shape, read flat), named `what` in the error.
inline std::vector<double> to_vector(const py::handle& values, const char* what) {
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  auto refuse = [&] {
    return py::type_error(std::string(what) + ": expected numbers (a list or a numpy array), got " + std::string(py::str(py::type::of(values))));
  };
  if (py::isinstance<py::str>(values)) throw refuse();
  const Array a = Array::ensure(values);
  if (!a) throw refuse();
  return {a.data(), a.data() + a.size()};
}

/// The value of `name` in `allowed` (pairs of Python spelling and C++ value), or a ValueError that lists them.
template <class T>
T choice(const std::string& value, const char* name, const std::vector<std::pair<std::string, T>>& allowed) {
  std::string list;
  for (const auto& [text, v] : allowed) {
    if (text == value) return v;
    list += (list.empty() ? "" : ", ") + ("'" + text + "'");
  }
  throw py::value_error(std::string(name) + " must be one of " + list + ", got '" + value + "'");
}

/// A message of blockdem's option checks with each program option ("--mass-increase") spelt as the Python keyword
/// that sets it ("mass_increase").
inline std::string python_option_names(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "--") == 0 && i + 2 < text.size() && text[i + 2] >= 'a' && text[i + 2] <= 'z') {
      i += 2;
      for (; i < text.size() && ((text[i] >= 'a' && text[i] <= 'z') || text[i] == '-'); ++i) out += text[i] == '-' ? '_' : text[i];
      --i;
      continue;
    }
    out += text[i];
  }
  return out;
}

/// Runs `f` with the GIL released, passing it a poll function for the run to call now and then (every 1024 steps):
/// it takes the GIL back for a moment to let Python handle its signals. Ctrl-C in Python then asks the run to stop
/// as SIGINT asks the programs (blockdem::interrupted(): it stops cleanly, writing its checkpoint), and is raised as
/// KeyboardInterrupt once `f` returns. Another thread's Python code runs meanwhile.
template <class F>
auto run_without_gil(F&& f) {
  struct Pending {
    std::optional<py::error_already_set> error;
  } pending;
  auto poll = [&pending] {
    py::gil_scoped_acquire gil;
    if (!pending.error && PyErr_CheckSignals() != 0) {
      pending.error.emplace();  // takes the KeyboardInterrupt (or a signal handler's exception) out of Python's hands
      detail::interrupt_flag().store(true);
    }
  };
  auto finish = [&pending] {
    detail::interrupt_flag().store(false);
    if (pending.error) {
      pending.error->restore();
      throw py::error_already_set();
    }
  };
  try {
    auto result = [&] {
      py::gil_scoped_release released;
      return f(std::function<void()>(poll));
    }();
    finish();
    return result;
  } catch (...) {
    detail::interrupt_flag().store(false);
    throw;
  }
}

/// A record from Python: a blockdem Record, or None for the built-in synthetic stand-in.
motion::Record record_from(const py::handle& record);

/// Applies Python keyword options to a study's options (the names of `blockdem run`'s options in snake_case); an
/// unknown one is a TypeError naming the allowed ones. The options given are remembered, for messages that say
/// which value was a default.
void apply_study_options(analysis::StudyOptions& o, const py::dict& options);

}  // namespace blockdem::python
