// The compiled part of the Python module `blockdem` (the package around it: python/blockdem/). blockdem's errors
// arrive in Python with their messages: InvalidArgument as ValueError, InputError (a file that cannot be read) as
// blockdem.InputError, a ValueError too, RunawayError (a run that diverged) as blockdem.RunawayError, a
// RuntimeError.

#include "bindings.hpp"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace blockdem::python;
  m.doc() = "blockdem's compiled part: use the package `blockdem`, which wraps it.";
  py::register_exception<blockdem::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<blockdem::RunawayError>(m, "RunawayError", PyExc_RuntimeError);
  bind_damping(m);
  bind_motion(m);
  bind_model(m);
  bind_study(m);
  bind_simulation(m);
  bind_sweep(m);
}
