// blockdem.Record and the ground-motion toolkit (paper Sect. 2, 6.1.2): record readers, baseline correction, Arias
// intensity, response spectra, window and wavelet truncation. Accelerations are in m/s^2, times in s.

#include "bindings.hpp"

#include "blockdem/motion/acceleration_unit.hpp"
#include "blockdem/motion/arias.hpp"
#include "blockdem/motion/baseline.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/processing.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/spectrum.hpp"
#include "blockdem/motion/synthetic.hpp"
#include "blockdem/motion/truncation.hpp"
#include "blockdem/motion/wavelet_truncation.hpp"

namespace blockdem::python {

motion::Record record_from(const py::handle& record) {
  if (record.is_none()) return motion::synthetic_aqa75();
  try {
    return record.cast<motion::Record>();
  } catch (const py::cast_error&) {
    throw py::type_error("record: expected a blockdem.Record (blockdem.read_record(path)) or None (the built-in stand-in), got " +
                         std::string(py::str(py::type::of(record))));
  }
}

namespace {

motion::AccelerationUnit unit_named(const std::string& text) {
  if (const auto u = motion::parse_acceleration_unit(text)) return *u;
  throw py::value_error("units must be 'g', 'm/s2' or 'cm/s2', got '" + text + "'");
}

py::dict peaks_dict(const motion::Record& r) {
  const auto p = motion::peak_values(r);
  py::dict d;
  d["pga"] = p.pga;
  d["pgv"] = p.pgv;
  d["pgd"] = p.pgd;
  return d;
}

py::dict truncation_dict(const motion::Truncation& t) {
  py::dict d;
  d["record"] = t.record;
  d["start"] = t.start;
  d["end"] = t.end;
  d["arias_fraction"] = t.arias_fraction;
  return d;
}

}  // namespace

void bind_motion(py::module_& m) {
  py::class_<motion::Record>(m, "Record", R"(A ground-acceleration record: uniformly sampled acceleration in m/s^2.

Record(acceleration, dt, start_time=0, name="", units="m/s2") makes one from samples given in `units` ('g', 'm/s2',
'cm/s2'); blockdem.read_record(path) reads PEER .AT2, ESM ASCII and plain-text files. `acceleration` is a numpy view
of the samples (m/s^2, writable), `time` the times of the samples (s).)")
      .def(py::init([](const py::handle& acceleration, double dt, double start_time, const std::string& name, const std::string& units) {
             motion::Record r;
             r.acceleration = to_vector(acceleration, "acceleration");
             r.input_unit = unit_named(units);
             for (double& a : r.acceleration) a *= motion::to_m_s2(r.input_unit);
             r.dt = dt;
             r.start_time = start_time;
             r.name = name.empty() ? "record" : name;
             r.source = "Python";
             r.validate("Record");
             return r;
           }),
           py::arg("acceleration"), py::arg("dt"), py::arg("start_time") = 0.0, py::arg("name") = "", py::arg("units") = "m/s2")
      .def_readwrite("name", &motion::Record::name)
      .def_readonly("source", &motion::Record::source, "the format read (\"PEER NGA .AT2\", ...) or how it was made")
      .def_readonly("dt", &motion::Record::dt, "time step, s")
      .def_readonly("start_time", &motion::Record::start_time, "time of the first sample, s")
      .def_readonly("synthetic", &motion::Record::synthetic)
      .def_property_readonly("units", [](const motion::Record& r) { return motion::to_string(r.input_unit); },
                             "the unit the samples were given in (they are held in m/s^2)")
      .def_readonly("header_pga", &motion::Record::header_pga, "the PGA (m/s^2) the file's header states, if any")
      .def_property_readonly(
          "acceleration",
          [](py::object self) {
            auto& r = self.cast<motion::Record&>();
            return py::array_t<double>(static_cast<py::ssize_t>(r.acceleration.size()), r.acceleration.data(), self);
          },
          "the samples, m/s^2 (a view: writing it changes the record)")
      .def_property_readonly("time", [](const motion::Record& r) {
        std::vector<double> t(r.size());
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = r.time(i);
        return to_array(t);
      }, "the time of each sample, s")
      .def_property_readonly("duration", &motion::Record::duration, "s, first to last sample")
      .def("__len__", &motion::Record::size)
      .def("peaks", &peaks_dict, "{'pga': m/s^2, 'pgv': m/s, 'pgd': m} of the record as it is (integrated without correction)")
      .def("velocity", [](const motion::Record& r) { return to_array(motion::integrate(r).velocity); }, "the integrated velocity, m/s")
      .def("displacement", [](const motion::Record& r) { return to_array(motion::integrate(r).displacement); },
           "the integrated displacement, m")
      .def("scaled", [](const motion::Record& r, double factor) { return motion::scale(r, factor); }, py::arg("factor"),
           "a copy with every sample times `factor`")
      .def("scaled_to_pga", [](const motion::Record& r, double pga) { return motion::scale_to_pga(r, pga); }, py::arg("pga"),
           "a copy scaled to this peak ground acceleration, m/s^2")
      .def("__repr__", [](const motion::Record& r) {
        return "Record('" + r.name + "', " + std::to_string(r.size()) + " samples, dt=" + num(r.dt) + " s, PGA " +
               num(motion::peak_values(r).pga) + " m/s^2)";
      });

  m.def(
      "read_record",
      [](const std::string& path, std::optional<std::string> units, std::optional<double> dt) {
        motion::ReadOptions o;
        if (units) o.units = unit_named(*units);
        o.dt = dt;
        return motion::read_record(path, o);
      },
      py::arg("path"), py::arg("units") = py::none(), py::arg("dt") = py::none(),
      R"(Reads a record file: PEER NGA .AT2, ESM/ITACA ASCII or plain text (one or two columns), detected from its
contents. `units` ('g', 'm/s2', 'cm/s2') overrides the header's; `dt` (s) is needed for one-column text.)");
  m.def("synthetic_aqa75", &motion::synthetic_aqa75,
        "The built-in synthetic stand-in for the AQA record at 75 % (the study's default input; not a recording).");
  m.def(
      "correct_baseline",
      [](const motion::Record& r, const std::string& steps) { return motion::correct_baseline(r, motion::parse_baseline(steps)); },
      py::arg("record"), py::arg("steps") = "mean,highpass:0.1",
      (std::string("The record with its baseline corrected, step by step: ") + motion::baseline_grammar + ".").c_str());
  m.def("arias_intensity", &motion::arias_intensity, py::arg("record"), "The Arias intensity I_A = pi / (2 g) int a^2 dt, m/s.");
  m.def("arias_history", [](const motion::Record& r) { return to_array(motion::arias_intensity_history(r)); }, py::arg("record"),
        "The Arias intensity accumulated up to each sample, m/s.");
  m.def(
      "significant_duration",
      [](const motion::Record& r, double lower, double upper) {
        const auto d = motion::significant_duration(r, lower, upper);
        return py::make_tuple(d.start, d.end);
      },
      py::arg("record"), py::arg("lower") = 0.05, py::arg("upper") = 0.95,
      "(start, end) in s: where the Arias intensity reaches the fractions `lower` and `upper` of its total.");
  m.def(
      "response_spectrum",
      [](const motion::Record& r, const py::object& periods, double damping) {
        const std::vector<double> T = periods.is_none() ? motion::default_periods() : to_vector(periods, "periods");
        const auto s = motion::response_spectrum(r, T, damping);
        py::dict d;
        d["period"] = to_array(s.period);
        d["sd"] = to_array(s.sd);
        d["psv"] = to_array(s.psv);
        d["psa"] = to_array(s.psa);
        return d;
      },
      py::arg("record"), py::arg("periods") = py::none(), py::arg("damping") = 0.05,
      R"(The elastic response spectrum of a record (Nigam-Jennings): a dict of arrays 'period' (s), 'sd' (m), 'psv'
(m/s) and 'psa' (m/s^2). periods: default 100 log-spaced from 0.02 to 10 s; damping: the ratio, default 5 %.)");
  m.def(
      "truncate_window",
      [](const motion::Record& r, double start, double end) { return truncation_dict(motion::truncate_window(r, start, end)); },
      py::arg("record"), py::arg("start"), py::arg("end"),
      "The record cut to [start, end] s: a dict with 'record', 'start', 'end' and 'arias_fraction' (the share of the Arias intensity kept).");
  m.def(
      "wavelet_truncation",
      [](const motion::Record& r, double damping, std::optional<double> period) {
        motion::WaveletTruncationOptions o;
        o.damping_ratio = damping;
        o.period = period;
        const auto w = motion::wavelet_truncation(r, o);
        py::dict d = truncation_dict(w.truncation);
        py::dict pulse;
        pulse["amplitude"] = w.pulse.amplitude;
        pulse["gamma"] = w.pulse.gamma;
        pulse["period"] = w.pulse.period;
        pulse["t0"] = w.pulse.t0;
        pulse["phase"] = w.pulse.phase;
        d["pulse"] = pulse;
        std::vector<double> v(r.size());
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = w.pulse.velocity(r.time(i));
        d["pulse_velocity"] = to_array(v);
        d["correlation"] = w.correlation;
        d["period_from_spectrum"] = w.period_from_spectrum;
        return d;
      },
      py::arg("record"), py::arg("damping") = 0.05, py::arg("period") = py::none(),
      R"(The wavelet truncation of the paper (Sect. 6.1.2): the Mavroeidis-Papageorgiou pulse fitted to the record's
velocity, and the record cut to the pulse's support. Returns a dict: 'record' (the cut), 'start', 'end' (s),
'arias_fraction', 'pulse' (amplitude m/s, gamma, period s, t0 s, phase rad), 'pulse_velocity' (m/s at each sample of
the record), 'correlation'. period: T_p in s (default: the dominant peak of the PSV spectrum at `damping`).)");
}

}  // namespace blockdem::python
