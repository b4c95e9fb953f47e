// blockdem.run and blockdem.pushover: a model file's study as `blockdem run` runs it (settling, then the levels of
// its record; or the equivalent-static pushover), with the GIL released, Ctrl-C, checkpoints and resume. The
// compiled study is the programs' own (examples/study_runs.cpp).

#include <map>

#include "bindings.hpp"

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/study.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/motion/acceleration_unit.hpp"
#include "study_runs.hpp"

namespace blockdem::python {

namespace {

double number(const py::handle& v, const std::string& key) {
  try {
    return v.cast<double>();
  } catch (const py::cast_error&) {
    throw py::type_error(key + ": expected a number, got " + std::string(py::str(py::type::of(v))));
  }
}

std::pair<double, double> number_pair(const py::handle& v, const std::string& key) {
  const auto x = to_vector(v, key.c_str());
  if (x.size() != 2) throw py::value_error(key + ": expected two numbers (low, high), got " + std::to_string(x.size()));
  return {x[0], x[1]};
}

std::string text(const py::handle& v, const std::string& key) {
  if (!py::isinstance<py::str>(v)) throw py::type_error(key + ": expected a string, got " + std::string(py::str(py::type::of(v))));
  return v.cast<std::string>();
}

bool flag(const py::handle& v) { return PyObject_IsTrue(v.ptr()) == 1; }

long long whole(const py::handle& v, const std::string& key) {
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    throw py::type_error(key + ": expected an integer, got " + std::string(py::str(py::type::of(v))));
  return v.cast<long long>();
}

/// The program option that a Python keyword stands for ("mass_increase" -> "--mass-increase").
std::string program_option(const std::string& key) {
  std::string o = "--" + key;
  for (char& c : o)
    if (c == '_') c = '-';
  return o;
}

using Setter = void (*)(analysis::StudyOptions&, const py::handle&, const std::string&);

const std::map<std::string, Setter>& setters() {
  using O = analysis::StudyOptions;
  static const std::map<std::string, Setter> table{
      {"out", [](O& o, const py::handle& v, const std::string& k) { o.out_dir = text(v, k); }},
      {"record",
       [](O& o, const py::handle& v, const std::string& k) {
         if (py::isinstance<py::str>(v)) {
           o.record_path = text(v, k);
           o.record.reset();
         } else {
           o.record = record_from(v);
           o.record_path.clear();
         }
       }},
      {"units",
       [](O& o, const py::handle& v, const std::string& k) {
         const auto u = motion::parse_acceleration_unit(text(v, k));
         if (!u) throw py::value_error("units must be 'g', 'm/s2' or 'cm/s2', got '" + text(v, k) + "'");
         o.read.units = *u;
       }},
      {"axis", [](O& o, const py::handle& v, const std::string& k) {
         o.axis = choice<char>(text(v, k), "axis", {{"x", 'x'}, {"y", 'y'}, {"z", 'z'}});
       }},
      {"record_level", [](O& o, const py::handle& v, const std::string& k) { o.record_level = number(v, k); }},
      {"levels", [](O& o, const py::handle& v, const std::string& k) { o.levels = to_vector(v, k.c_str()); }},
      {"truncate",
       [](O& o, const py::handle& v, const std::string& k) {
         o.truncation = choice<analysis::Truncation>(text(v, k), "truncate",
                                                     {{"window", analysis::Truncation::window}, {"wavelet", analysis::Truncation::wavelet}});
       }},
      {"window",
       [](O& o, const py::handle& v, const std::string& k) {
         std::tie(o.window_start, o.window_end) = number_pair(v, k);
         o.window_default = false;
       }},
      {"baseline", [](O& o, const py::handle& v, const std::string& k) { o.baseline = text(v, k); }},
      {"rest", [](O& o, const py::handle& v, const std::string& k) { o.rest = number(v, k); }},
      {"damping",
       [](O& o, const py::handle& v, const std::string& k) {
         o.damping = choice<analysis::DampingScheme>(text(v, k), "damping",
                                                     {{"none", analysis::DampingScheme::none},
                                                      {"mass", analysis::DampingScheme::mass},
                                                      {"stiffness", analysis::DampingScheme::stiffness},
                                                      {"rayleigh", analysis::DampingScheme::rayleigh},
                                                      {"maxwell", analysis::DampingScheme::maxwell}});
       }},
      {"zeta", [](O& o, const py::handle& v, const std::string& k) { o.zeta = number(v, k); }},
      {"frequency", [](O& o, const py::handle& v, const std::string& k) { o.frequency_hz = number(v, k); }},
      {"band", [](O& o, const py::handle& v, const std::string& k) { std::tie(o.lower_hz, o.upper_hz) = number_pair(v, k); }},
      {"branches", [](O& o, const py::handle& v, const std::string& k) { o.branches = static_cast<int>(whole(v, k)); }},
      {"damping_frame",
       [](O& o, const py::handle& v, const std::string& k) {
         o.damping_frame = choice<damping::Frame>(text(v, k), "damping_frame",
                                                  {{"table", damping::Frame::table}, {"absolute", damping::Frame::absolute}});
       }},
      {"target_dt", [](O& o, const py::handle& v, const std::string& k) { o.target_dt = number(v, k); }},
      {"mass_increase", [](O& o, const py::handle& v, const std::string& k) { o.default_mass_increase_percent = number(v, k); }},
      {"max_mass_increase", [](O& o, const py::handle& v, const std::string& k) { o.max_mass_increase_percent = number(v, k); }},
      {"settling",
       [](O& o, const py::handle& v, const std::string& k) {
         o.settling = choice<analysis::Settling>(text(v, k), "settling", {{"auto", analysis::Settling::automatic},
                                                                          {"inertial", analysis::Settling::inertial},
                                                                          {"local", analysis::Settling::local}});
       }},
      {"settle_tolerance", [](O& o, const py::handle& v, const std::string& k) { o.settle_tolerance = number(v, k); }},
      {"settle_steps", [](O& o, const py::handle& v, const std::string& k) { o.settle_max_steps = whole(v, k); }},
      {"contacts",
       [](O& o, const py::handle& v, const std::string& k) {
         o.contacts = choice<model::ContactKinds>(text(v, k), "contacts",
                                                  {{"faces", model::ContactKinds::faces}, {"general", model::ContactKinds::general}});
       }},
      {"collapse_displacement", [](O& o, const py::handle& v, const std::string& k) { o.collapse_displacement = number(v, k); }},
      {"runaway_displacement", [](O& o, const py::handle& v, const std::string& k) { o.runaway_displacement = number(v, k); }},
      {"max_speed", [](O& o, const py::handle& v, const std::string& k) { o.max_speed = number(v, k); }},
      {"history_dt", [](O& o, const py::handle& v, const std::string& k) { o.history_dt = number(v, k); }},
      {"snapshots_every", [](O& o, const py::handle& v, const std::string& k) { o.snapshots_every = number(v, k); }},
      {"free_vibration", [](O& o, const py::handle& v, const std::string&) { o.free_vibration = flag(v); }},
      {"checkpoint_minutes", [](O& o, const py::handle& v, const std::string& k) { o.checkpoint_minutes = number(v, k); }},
      {"resume", [](O& o, const py::handle& v, const std::string& k) { o.resume = text(v, k); }},
      {"stop_after_steps", [](O& o, const py::handle& v, const std::string& k) { o.stop_after_steps = whole(v, k); }},
      {"progress", [](O& o, const py::handle& v, const std::string&) { o.progress = flag(v); }},
  };
  return table;
}

/// The study's options with the Python keywords applied, checked; `source` names the model in messages.
analysis::StudyOptions study_options(const analysis::ModelFile& file, const py::dict& options) {
  analysis::StudyOptions o = file.study;
  o.program = "blockdem (Python)";
  apply_study_options(o, options);
  if (!o.resume.empty() && !options.contains("out")) {
    const auto folder = std::filesystem::path(o.resume).parent_path();
    o.out_dir = folder.empty() ? std::string(".") : folder.string();
  }
  try {
    o.validate();
  } catch (const InvalidArgument& e) {
    throw py::value_error(python_option_names(e.what()));
  }
  return o;
}

py::dict pushover_dict(const analysis::PushoverResult& r, const std::string& out_dir) {
  std::vector<double> lambda, displacement, ratio, steps, seconds, stands;
  for (const auto& t : r.trials) {
    lambda.push_back(t.lambda);
    stands.push_back(t.stands ? 1 : 0);
    displacement.push_back(t.max_displacement);
    ratio.push_back(t.unbalanced_ratio);
    steps.push_back(static_cast<double>(t.steps));
    seconds.push_back(t.wall_seconds);
  }
  py::dict trials;
  trials["lambda"] = to_array(lambda);
  trials["stands"] = to_array(stands).attr("astype")("bool");
  trials["max_displacement"] = to_array(displacement);
  trials["unbalanced_force_ratio"] = to_array(ratio);
  trials["steps"] = to_array(steps).attr("astype")("int64");
  trials["wall_seconds"] = to_array(seconds);
  py::dict d;
  d["analysis"] = "pushover";
  d["collapse_multiplier"] = r.collapse_multiplier;
  d["lower"] = r.lower;
  d["upper"] = r.upper;
  d["stands_at_upper"] = r.stands_at_upper;
  d["falls_under_weight"] = r.falls_under_weight;
  d["collapse_displacement"] = r.collapse_displacement;
  d["wall_seconds"] = r.wall_seconds;
  d["trials"] = trials;
  d["out"] = out_dir;
  return d;
}

}  // namespace

void apply_study_options(analysis::StudyOptions& o, const py::dict& options) {
  const auto& table = setters();
  for (const auto& [key_handle, value] : options) {
    const std::string key = py::str(key_handle);
    const auto it = table.find(key);
    if (it == table.end()) {
      std::string allowed;
      for (const auto& [name, setter] : table) allowed += (allowed.empty() ? "" : ", ") + name;
      throw py::type_error("unknown study option '" + key + "' (allowed: " + allowed + ")");
    }
    if (value.is_none()) continue;  // None: the model file's value, or the default
    it->second(o, value, key);
    o.given.insert(program_option(key));
  }
  o.given_known = true;
}

void bind_study(py::module_& m) {
  m.def(
      "run_model",
      [](const analysis::ModelFile& file, const std::string& source, const py::dict& options) -> py::dict {
        analysis::StudyOptions o = study_options(file, options);
        py::list warnings;
        for (const auto& w : analysis::refuse_unusable(file.structure, file.geometry_issues, file.block_origin, source)) warnings.append(w);
        if (file.pushover) {
          auto p = *file.pushover;
          p.out_dir = o.out_dir;
          p.progress = o.progress;
          const bool general = o.contacts == model::ContactKinds::general;
          const auto r = run_without_gil([&](std::function<void()> poll) {
            p.poll = std::move(poll);
            return programs::run_pushover(file.structure, p, general);
          });
          py::dict d = pushover_dict(r, o.out_dir);
          d["warnings"] = warnings;
          return d;
        }
        if (file.scale.kind != analysis::RecordScale::Kind::record_level && !options.contains("record_level"))
          o.record_level = analysis::record_level_for(file.scale, o, source);
        const auto r = run_without_gil([&](std::function<void()> poll) {
          o.poll = std::move(poll);
          return programs::run_study(file.structure, o);
        });
        py::dict d;
        d["analysis"] = "levels";
        d["report"] = analysis::detail::report_json(r);
        d["table4"] = analysis::table4(r);
        d["interrupted"] = r.interrupted;
        d["out"] = o.out_dir;
        d["warnings"] = warnings;
        return d;
      },
      py::arg("file"), py::arg("source"), py::arg("options"),
      "Runs a model file's study (internal: blockdem.run calls it). Returns a dict with report.json's text.");
  m.def(
      "study_option_names", [] {
        std::vector<std::string> names;
        for (const auto& [name, setter] : setters()) names.push_back(name);
        return names;
      },
      "The keyword options of blockdem.run.");
}

}  // namespace blockdem::python
