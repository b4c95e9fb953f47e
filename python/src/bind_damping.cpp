// blockdem.fit_maxwell and blockdem.damping_ratio: the Maxwell fit (paper eq. 21-25) and the damping-ratio curve of
// every scheme (eq. 10, 19), as the study builds them (analysis::with_damping_policy).

#include <cmath>

#include "bindings.hpp"

#include "blockdem/analysis/study.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell_fit.hpp"

namespace blockdem::python {

namespace {

/// A fit and what Python reads of it.
struct MaxwellFit {
  damping::MaxwellFitResult r;
  damping::MaxwellFitOptions o;

  std::vector<double> each(double damping::MaxwellBranch::*field) const {
    std::vector<double> v;
    for (const auto& b : r.active()) v.push_back(b.*field);
    return v;
  }
  py::array_t<double> damping_ratio(const py::handle& frequencies_hz) const {
    std::vector<double> f = to_vector(frequencies_hz, "frequencies_hz");
    for (double& x : f) x = damping::damping_ratio(r.active(), angular_frequency(x));
    return to_array(f);
  }
};

analysis::StudyOptions scheme_options(const std::string& scheme, std::optional<double> zeta, double frequency, std::pair<double, double> band,
                                      int branches) {
  analysis::StudyOptions o;
  o.context = "damping_ratio";
  o.damping = choice<analysis::DampingScheme>(scheme, "scheme",
                                              {{"none", analysis::DampingScheme::none},
                                               {"mass", analysis::DampingScheme::mass},
                                               {"stiffness", analysis::DampingScheme::stiffness},
                                               {"rayleigh", analysis::DampingScheme::rayleigh},
                                               {"maxwell", analysis::DampingScheme::maxwell}});
  if (zeta) {
    if (!(*zeta > 0 && *zeta < 0.5)) throw py::value_error("zeta must be in (0, 0.5), got " + num(*zeta));
    o.zeta = *zeta;
  }
  o.frequency_hz = frequency;
  o.lower_hz = band.first;
  o.upper_hz = band.second;
  o.branches = branches;
  try {
    o.validate();
  } catch (const InvalidArgument& e) {
    throw py::value_error(python_option_names(e.what()));
  }
  return o;
}

}  // namespace

void bind_damping(py::module_& m) {
  py::class_<MaxwellFit>(m, "MaxwellFit", R"(The Maxwell branches fitted to a flat damping ratio over a band (paper eq. 21-25).

Attributes: alpha (stiffness fractions of the branches), tau (their relaxation times, s), peak_hz (the frequency of
each branch's peak damping, Hz), zeta (the target), zeta_min and zeta_max over the band, max_rel_error
(max |zeta - target| / target over the band), dt_factor (1 / sqrt(1 + sum alpha), eq. 20: the timestep's factor),
converged, iterations.)")
      .def_property_readonly("alpha", [](const MaxwellFit& f) { return to_array(f.each(&damping::MaxwellBranch::alpha)); })
      .def_property_readonly("tau", [](const MaxwellFit& f) { return to_array(f.each(&damping::MaxwellBranch::tau)); })
      .def_property_readonly("peak_hz", [](const MaxwellFit& f) {
        std::vector<double> v;
        for (int i = 0; i < f.r.branches; ++i) v.push_back(f.r.peak_hz(i));
        return to_array(v);
      })
      .def_property_readonly("branches", [](const MaxwellFit& f) { return f.r.branches; })
      .def_property_readonly("zeta", [](const MaxwellFit& f) { return f.r.target; })
      .def_property_readonly("band", [](const MaxwellFit& f) { return std::pair(f.o.lower_hz, f.o.upper_hz); })
      .def_property_readonly("zeta_min", [](const MaxwellFit& f) { return f.r.zeta_min; })
      .def_property_readonly("zeta_max", [](const MaxwellFit& f) { return f.r.zeta_max; })
      .def_property_readonly("rel_error_min", [](const MaxwellFit& f) { return f.r.rel_error_min; })
      .def_property_readonly("rel_error_max", [](const MaxwellFit& f) { return f.r.rel_error_max; })
      .def_property_readonly("max_rel_error", [](const MaxwellFit& f) { return f.r.max_rel_error; })
      .def_property_readonly("dt_factor", [](const MaxwellFit& f) { return f.r.dt_factor; })
      .def_property_readonly("converged", [](const MaxwellFit& f) { return f.r.converged; })
      .def_property_readonly("iterations", [](const MaxwellFit& f) { return f.r.total_iterations; })
      .def("damping_ratio", &MaxwellFit::damping_ratio, py::arg("frequencies_hz"),
           "The damping ratio of the fitted branches at these frequencies (Hz), eq. 19: an array of their shape, flattened.")
      .def("__repr__", [](const MaxwellFit& f) {
        std::string s = "MaxwellFit(zeta=" + num(f.r.target) + ", band=(" + num(f.o.lower_hz) + ", " + num(f.o.upper_hz) + "), alpha=[";
        for (int i = 0; i < f.r.branches; ++i) s += (i ? ", " : "") + num(f.r.branch[static_cast<std::size_t>(i)].alpha);
        s += "], tau=[";
        for (int i = 0; i < f.r.branches; ++i) s += (i ? ", " : "") + num(f.r.branch[static_cast<std::size_t>(i)].tau);
        return s + "], max_rel_error=" + num(f.r.max_rel_error) + ")";
      });

  m.def(
      "fit_maxwell",
      [](double zeta, std::pair<double, double> band, int branches, int points) {
        MaxwellFit f;
        f.o.damping_ratio = zeta;
        f.o.lower_hz = band.first;
        f.o.upper_hz = band.second;
        f.o.branches = branches;
        f.o.points = points;
        f.r = damping::fit_maxwell(f.o);
        return f;
      },
      py::arg("zeta") = 0.03, py::arg("band") = std::pair(1.0, 40.0), py::arg("branches") = 3, py::arg("points") = 500,
      R"(Fits N Maxwell branches to a flat damping ratio zeta over band = (f_lb, f_ub) in Hz (paper eq. 21-25), by
Levenberg-Marquardt on `points` log-spaced frequencies. Returns a MaxwellFit (alpha, tau in s, the band error).
zeta in (0, 0.5); branches 1..8 (the study compiles 1..4).)");

  m.def(
      "damping_ratio",
      [](const std::string& scheme, const py::handle& frequencies_hz, std::optional<double> zeta, double frequency,
         std::pair<double, double> band, int branches) {
        const auto o = scheme_options(scheme, zeta, frequency, band, branches);
        std::vector<double> f = to_vector(frequencies_hz, "frequencies_hz");
        std::string description;
        analysis::with_damping_policy(o, description, [&](const auto& policy) {
          for (double& x : f) {
            if constexpr (requires { policy.damping_ratio(1.0); })
              x = policy.damping_ratio(angular_frequency(x));
            else
              x = 0;  // none
          }
        });
        return to_array(f);
      },
      py::arg("scheme"), py::arg("frequencies_hz"), py::arg("zeta") = py::none(), py::arg("frequency") = 7.5,
      py::arg("band") = std::pair(1.0, 40.0), py::arg("branches") = 3,
      R"(The damping ratio of a viscous damping scheme at these frequencies (Hz), with the study's parameters:
scheme 'none', 'mass' (zeta at `frequency`, eq. 10), 'stiffness' (zeta at `frequency`), 'rayleigh' (zeta at both
ends of `band`) or 'maxwell' (zeta over `band` with `branches` branches, eq. 19). zeta defaults as in the study:
0.04 for mass, 0.03 otherwise.)");
}

}  // namespace blockdem::python
