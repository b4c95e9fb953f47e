// blockdem.Simulation: a model's simulation stepped from Python, for users who write their own loop. It takes the
// steps of the study (analysis/study.hpp) one call at a time: settle under local damping, then the dynamic run
// under the options' damping at the study's timestep, the table moved by a record; the state of blocks, nodes,
// elements and contact points read as numpy arrays (views of blockdem's own storage where its layout allows).

#include <chrono>

#include "simulation.hpp"

#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/io/vtk.hpp"
#include "blockdem/motion/processing.hpp"

namespace blockdem::python {

void apply_study_options(analysis::StudyOptions& o, const py::dict& options);

namespace {

/// A read-only numpy view of the rows of `v`, each `cols` doubles (a Vec3, a quaternion, a stress), kept alive with
/// `owner`: no copy.
template <std::size_t cols, class T>
py::array rows_view(const std::vector<T>& v, const py::object& owner) {
  static_assert(sizeof(T) == cols * sizeof(double), "rows of doubles without padding");
  const auto n = static_cast<py::ssize_t>(v.size());
  py::array a(py::dtype::of<double>(), {n, static_cast<py::ssize_t>(cols)},
              {static_cast<py::ssize_t>(sizeof(T)), static_cast<py::ssize_t>(sizeof(double))},
              reinterpret_cast<const double*>(v.data()), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

class Session {
 public:
  Session(const analysis::ModelFile& file, const std::string& source, const py::dict& options) : file_(file), source_(source) {
    o_ = file_.study;
    o_.program = "blockdem.Simulation";
    o_.context = "Simulation";
    apply_study_options(o_, options);
    if (options.contains("out") || options.contains("resume") || options.contains("levels"))
      throw py::type_error("Simulation: out, resume and levels are options of blockdem.run; a Simulation runs what you step");
    try {
      o_.validate();
    } catch (const InvalidArgument& e) {
      throw py::value_error(python_option_names(e.what()));
    }
    auto& s = file_.structure;
    s.validate();
    for (const auto& w : analysis::refuse_unusable(s, file_.geometry_issues, file_.block_origin, source_)) warnings_.push_back(w);
    if (file_.scale.kind != analysis::RecordScale::Kind::record_level && !options.contains("record_level"))
      o_.record_level = analysis::record_level_for(file_.scale, o_, source_);
    r_.model.name = s.name;
    r_.model.groups = s.groups();
    r_.model.free_mass = s.model.total_mass();
    r_.timestep.added_by_group.assign(s.laws.groups(), {});
    model::ContactSettings contacts = s.contacts;
    contacts.kinds = o_.contacts;
    s.laws.fill(contacts);
    using Sim = analysis::StudySimulation<damping::Local>;
    settle_ = std::make_unique<Settling>(s.model, analysis::detail::settling_damping(o_, s.model), analysis::detail::structure_properties<Sim>(s),
                                         contacts);
    settle_->sim.set_run_guard(RunGuard{o_.max_speed});
    const FrequencyBound bound = settle_->sim.frequency_bound();
    plan_ = o_.damping == analysis::DampingScheme::maxwell ? plan_maxwell(*settle_, bound, o_, r_) : plan_viscous(*settle_, bound, o_, r_);
  }

  // ---- running ----

  py::dict settle() {
    if (dynamic_) throw py::value_error("Simulation.settle: the dynamic run has started; settling comes before it");
    analysis::SettlingResult out;
    run_without_gil([&](std::function<void()> poll) {
      o_.poll = std::move(poll);
      analysis::detail::settle(settle_->sim, std::max(plan_.unscaled_dt, plan_.target_dt), o_, out);
      o_.poll = nullptr;
      return 0;
    });
    r_.settling = out;
    py::dict d;
    d["steps"] = out.steps;
    d["unbalanced_force_ratio"] = out.unbalanced_ratio;
    d["converged"] = out.converged;
    d["wall_seconds"] = out.wall_seconds;
    return d;
  }

  /// Runs for `duration` s of simulated time (the dynamic run: it starts at the first call).
  py::dict run(double duration) {
    if (!(duration >= 0) || !std::isfinite(duration)) throw py::value_error("duration must be >= 0 s, got " + num(duration));
    Stepper& sim = dynamic();
    const double t_end = sim.time() + duration;
    const auto summary = run_without_gil([&](std::function<void()> poll) { return sim.run_until(t_end, poll, o_.progress); });
    py::dict d;
    d["steps"] = summary.steps;
    d["wall_seconds"] = summary.wall_seconds;
    d["steps_per_second"] = summary.wall_seconds > 0 ? static_cast<double>(summary.steps) / summary.wall_seconds : 0.0;
    return d;
  }

  void set_record(const py::object& record, double level, std::optional<std::string> axis) {
    if (!file_.structure.table)
      throw py::value_error("Simulation.set_record: '" + file_.structure.name + "' has no base block for a record to move");
    if (!(level > 0 && level <= 1000)) throw py::value_error("level must be in (0, 1000] %, got " + num(level));
    Stepper& sim = dynamic();
    motion::Record cut;
    double factor = level / 100;
    if (record.is_none()) {
      std::string note;
      cut = analysis::detail::input_record(o_, note);
      factor = level / o_.record_level;
    } else {
      cut = record_from(record);
    }
    const char a = axis ? choice<char>(*axis, "axis", {{"x", 'x'}, {"y", 'y'}, {"z", 'z'}}) : o_.axis;
    const motion::RecordMotion m(motion::scale(cut, factor), {}, analysis::axis_vector(a), sim.time(), table_velocity_);
    file_.structure.model.base_motion = motion::BaseMotion(m);
    table_velocity_ = m.final_velocity();
  }

  // ---- state ----

  Stepper& current() { return dynamic_ ? *dynamic_ : static_cast<Stepper&>(*settle_); }
  const Stepper& current() const { return dynamic_ ? *dynamic_ : static_cast<const Stepper&>(*settle_); }

  Stepper& dynamic() {
    if (!dynamic_) {
      dynamic_ = plan_.make(*settle_, file_.structure, r_);
      settle_.reset();
      auto& m = file_.structure.model;
      monitors_ = std::make_unique<analysis::MonitorHistory>(m, file_.structure.monitors, file_.structure.table);
      monitors_->begin_level(m, dynamic_->time(), "");
    }
    return *dynamic_;
  }

  py::array monitor_displacements() {
    dynamic();
    auto& m = file_.structure.model;
    monitors_->sample(m, dynamic_->time());
    std::vector<double> d;
    for (std::size_t p = 0; p < monitors_->points(); ++p)
      for (int c = 0; c < 3; ++c) d.push_back(monitors_->last_displacement(p)[c]);
    py::array_t<double> a({static_cast<py::ssize_t>(monitors_->points()), py::ssize_t{3}});
    std::copy(d.begin(), d.end(), a.mutable_data());
    return a;
  }

  py::dict contacts() const {
    const auto n = static_cast<py::ssize_t>(current().contact_points());
    py::array_t<double> position({n, py::ssize_t{3}}), normal({n, py::ssize_t{3}}), force({n, py::ssize_t{3}});
    py::array_t<double> area(n), gap(n), normal_stress(n), shear_stress(n), damage(n);
    py::array_t<std::int64_t> block_a(n), block_b(n);
    py::array_t<bool> never_bonded(n), cracked(n), crushed(n), slipped(n);
    double *p = position.mutable_data(), *q = normal.mutable_data(), *f = force.mutable_data();
    double *ar = area.mutable_data(), *g = gap.mutable_data(), *sn = normal_stress.mutable_data(), *ss = shear_stress.mutable_data(),
           *dm = damage.mutable_data();
    std::int64_t *ba = block_a.mutable_data(), *bb = block_b.mutable_data();
    bool *nb = never_bonded.mutable_data(), *cr = cracked.mutable_data(), *cu = crushed.mutable_data(), *sl = slipped.mutable_data();
    py::ssize_t k = 0;
    current().visit_contacts([&](const ContactView& c) {
      if (k >= n) return;
      for (int i = 0; i < 3; ++i) {
        p[3 * k + i] = c.position[i];
        q[3 * k + i] = c.normal[i];
        f[3 * k + i] = c.force[i];
      }
      ar[k] = c.area;
      g[k] = c.gap;
      sn[k] = c.normal_stress;
      ss[k] = c.shear_stress;
      dm[k] = c.damage;
      ba[k] = static_cast<std::int64_t>(c.block_a);
      bb[k] = static_cast<std::int64_t>(c.block_b);
      nb[k] = c.never_bonded;
      cr[k] = c.cracked;
      cu[k] = c.crushed;
      sl[k] = c.slipped;
      ++k;
    });
    py::dict d;
    d["position"] = position;
    d["normal"] = normal;
    d["force"] = force;
    d["area"] = area;
    d["gap"] = gap;
    d["normal_stress"] = normal_stress;
    d["shear_stress"] = shear_stress;
    d["damage"] = damage;
    d["block_a"] = block_a;
    d["block_b"] = block_b;
    d["never_bonded"] = never_bonded;
    d["cracked"] = cracked;
    d["crushed"] = crushed;
    d["slipped"] = slipped;
    return d;
  }

  py::dict energy() const {
    const auto e = current().energy();
    py::dict d;
    d["kinetic"] = e.kinetic;
    d["elastic"] = e.elastic;
    d["gravity_work"] = e.gravity_work;
    d["base_work"] = e.base_work;
    d["viscous"] = e.viscous;
    d["slip"] = e.slip;
    d["contact_update"] = e.contact_update;
    d["balance_error"] = e.balance_error;
    return d;
  }

  py::dict timestep_report() const {
    const auto& t = r_.timestep;
    py::dict d;
    d["dt"] = dynamic_ ? dynamic_->timestep() : plan_.target_dt;
    d["critical_unscaled"] = t.critical_unscaled;
    d["damping_factor"] = t.damping_factor;
    d["density_scaling_mass_increase_percent"] = t.scaling.mass_increase_percent;
    d["density_scaled_blocks"] = t.scaling.scaled_blocks;
    d["density_scaled_nodes"] = t.scaling.scaled_nodes;
    return d;
  }

  void write_vtk(const std::string& path) const {
    const auto& m = file_.structure.model;
    io::write_blocks_vtu(path, m, {});
  }

  analysis::ModelFile file_;
  std::string source_;
  analysis::StudyOptions o_;
  analysis::StudyResult r_;
  std::vector<std::string> warnings_;
  std::unique_ptr<Settling> settle_;
  DynamicPlan plan_;
  std::unique_ptr<Stepper> dynamic_;
  std::unique_ptr<analysis::MonitorHistory> monitors_;
  double table_velocity_ = 0;
};

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<Session>(m, "Simulation", R"(A model's simulation, stepped from Python (the steps of blockdem.run, one call at a time).

Simulation(model, **options): the options of blockdem.run that concern the run (damping, zeta, frequency, band,
branches, damping_frame, target_dt, mass_increase, max_mass_increase, contacts, settling, settle_tolerance,
settle_steps, max_speed, record, units, axis, record_level, truncate, window, baseline, progress). Then settle(), set_record(),
run(duration); read the state at any time. The damping policy is compiled in: choose it here, once.)")
      .def(py::init<const analysis::ModelFile&, const std::string&, const py::dict&>(), py::arg("file"), py::arg("source"),
           py::arg("options"))
      .def("settle", &Session::settle,
           "Static equilibrium under gravity with static mass scaling, by inertial relaxation or local damping (settling), "
           "to settle_tolerance (the unbalanced-force ratio) or settle_steps; as the study settles. Returns {steps, unbalanced_force_ratio, "
           "converged, wall_seconds}.")
      .def("run", &Session::run, py::arg("duration"),
           "Runs the dynamic simulation for `duration` s of simulated time (the first call starts it from the state "
           "reached, settled or not). Without the GIL; Ctrl-C stops it after the current step and raises "
           "KeyboardInterrupt, the state consistent. Returns {steps, wall_seconds, steps_per_second}.")
      .def("set_record", &Session::set_record, py::arg("record") = py::none(), py::arg("level") = 100.0, py::arg("axis") = py::none(),
           "From now on the table (the base blocks) moves by this record (a blockdem.Record, as given) at `level` % of it; "
           "None: the model's own record, cut and corrected as the study does, at `level` % as the study counts levels. "
           "After the record the table keeps its last velocity; a next record starts from it.")
      .def_property_readonly("time", [](const Session& s) { return s.current().time(); }, "simulated time, s")
      .def_property_readonly("dt", [](const Session& s) { return s.current().timestep(); }, "the timestep, s")
      .def_property_readonly("critical_timestep", [](const Session& s) { return s.current().critical_timestep(); }, "s")
      .def_property_readonly("steps", [](const Session& s) { return s.current().steps(); })
      .def_property_readonly("dynamic", [](const Session& s) { return static_cast<bool>(s.dynamic_); },
                             "whether the dynamic run has started (before it: the settling simulation)")
      .def_property_readonly("unbalanced_force_ratio", [](const Session& s) { return s.current().unbalanced_force_ratio(); })
      .def_property_readonly("damping", [](const Session& s) { return s.r_.damping.description; })
      .def_property_readonly("timestep_report", &Session::timestep_report)
      .def_property_readonly("warnings", [](const Session& s) { return s.warnings_; })
      .def("energy", &Session::energy, "The energy books (J): kinetic, elastic, gravity_work, base_work, viscous, slip, contact_update, balance_error.")
      .def("contacts", &Session::contacts,
           R"(The contact points now, as a dict of arrays (one row per point, copied): position, normal (from block_a to
block_b), force (N, on block_b) as (n, 3); area (m^2), gap (m, open positive), normal_stress (Pa, compression
positive), shear_stress (Pa), damage (0 intact .. 1), block_a, block_b (block indices; block_a of a node contact: the
node's block), never_bonded, cracked, crushed, slipped.)")
      .def("monitor_displacements", &Session::monitor_displacements,
           "The displacement of each monitor point (rows in the model's order), relative to the table, since the dynamic "
           "run started (m): an (n, 3) array.")
      .def_property_readonly("monitor_names", [](const Session& s) {
        std::vector<std::string> names;
        for (const auto& p : s.file_.structure.monitors) names.push_back(p.name);
        return names;
      })
      .def_property_readonly("block_names", [](const Session& s) { return s.file_.structure.model.bodies.name; })
      .def_property_readonly("block_positions", [](py::object self) {
        return rows_view<3>(self.cast<Session&>().file_.structure.model.bodies.position, self);
      }, "the blocks' centroids, m: an (n, 3) view (read-only) of blockdem's storage, current as the run goes on")
      .def_property_readonly("block_velocities", [](py::object self) {
        return rows_view<3>(self.cast<Session&>().file_.structure.model.bodies.velocity, self);
      }, "m/s at the half step: an (n, 3) view")
      .def_property_readonly("block_angular_velocities", [](py::object self) {
        return rows_view<3>(self.cast<Session&>().file_.structure.model.bodies.angular_velocity, self);
      }, "rad/s, world frame: an (n, 3) view")
      .def_property_readonly("block_orientations", [](py::object self) {
        return rows_view<4>(self.cast<Session&>().file_.structure.model.bodies.orientation, self);
      }, "unit quaternions (x, y, z, w), body to world: an (n, 4) view")
      .def_property_readonly("block_masses", [](py::object self) {
        const auto& v = self.cast<Session&>().file_.structure.model.bodies.mass;
        return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data(), self);
      }, "kg (after density scaling, the inertia of the run): a view")
      .def_property_readonly("node_positions", [](py::object self) {
        return rows_view<3>(self.cast<Session&>().file_.structure.model.deformable.nodes.position, self);
      }, "the nodes of the deformable blocks, m: an (n, 3) view")
      .def_property_readonly("node_velocities", [](py::object self) {
        return rows_view<3>(self.cast<Session&>().file_.structure.model.deformable.nodes.velocity, self);
      }, "m/s: an (n, 3) view")
      .def_property_readonly("node_blocks", [](py::object self) {
        const auto& v = self.cast<Session&>().file_.structure.model.deformable.nodes.block;
        return py::array_t<std::uint32_t>(static_cast<py::ssize_t>(v.size()), v.data(), self);
      }, "the block of each node: a view")
      .def_property_readonly("tetrahedra", [](py::object self) {
        const auto& v = self.cast<Session&>().file_.structure.model.deformable.tetrahedra.node;
        return py::array_t<std::uint32_t>({static_cast<py::ssize_t>(v.size()), py::ssize_t{4}}, reinterpret_cast<const std::uint32_t*>(v.data()), self);
      }, "the four nodes of each tetrahedron: an (n, 4) view")
      .def_property_readonly("element_stresses", [](py::object self) {
        return rows_view<6>(self.cast<Session&>().file_.structure.model.deformable.tetrahedra.stress, self);
      }, "Pa, xx yy zz xy yz zx, tension positive: an (n, 6) view")
      .def("write_vtk", &Session::write_vtk, py::arg("path"), "The blocks as they are now, as a VTK file for ParaView (.vtu).");
}

}  // namespace blockdem::python
