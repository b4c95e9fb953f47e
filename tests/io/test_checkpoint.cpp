// Checkpoints (io/checkpoint.hpp, Simulation::save_state/load_state): a simulation restored from a checkpoint and
// stepped on is bitwise the uninterrupted one (every block and node, every CP's history, Maxwell state, energy
// term); and every kind of bad file is refused with a message that says what is wrong.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/frame.hpp"
#include "blockdem/damping/local.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/none.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/motion/base_motion.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_checkpoint {

namespace {

std::string temporary_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("blockdem_test_checkpoint_" + name + ".ckpt")).string();
}

// ---- bitwise comparison of two simulations ----

/// The names of the fields in which two simulations differ (bit for bit), with the first index.
class Differences {
 public:
  template <class T>
  void values(const std::string& what, const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) {
      found_.push_back(what + ": sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size()));
      return;
    }
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same(a[i], b[i])) {
        found_.push_back(what + " [" + std::to_string(i) + "]");
        return;
      }
  }
  template <class T>
  void value(const std::string& what, const T& a, const T& b) {
    if (!same(a, b)) found_.push_back(what);
  }
  /// Law histories field by field (their padding is no state).
  template <class H>
  void histories(const std::string& what, const std::vector<H>& a, const std::vector<H>& b) {
    std::vector<std::vector<double>> wa, wb;
    for (const auto& h : a) wa.push_back(history_fields(h));
    for (const auto& h : b) wb.push_back(history_fields(h));
    values(what, wa, wb);
  }
  const std::vector<std::string>& found() const { return found_; }

 private:
  template <class T>
  static bool same(const T& a, const T& b) {
    if constexpr (std::is_same_v<T, damping::NoState> || std::is_same_v<T, std::array<damping::NoState, 3>> ||
                  std::is_same_v<T, std::array<damping::NoState, 7>>) {
      return true;
    } else if constexpr (requires { a.size(); a[0]; } && !io::plain_checkpoint_value<T>) {
      if (a.size() != b.size()) return false;
      for (std::size_t i = 0; i < a.size(); ++i)
        if (!same(a[i], b[i])) return false;
      return true;
    } else {
      static_assert(std::has_unique_object_representations_v<T> || std::is_floating_point_v<T> ||
                        io::plain_checkpoint_value<T>,
                    "compared as bytes: no padding");
      return std::memcmp(&a, &b, sizeof(T)) == 0;
    }
  }
  template <class H>
  static std::vector<double> history_fields(const H& h) {
    std::vector<double> f{h.gap, h.shear[0], h.shear[1]};
    if constexpr (requires { h.normal; }) f.push_back(h.normal);
    if constexpr (requires { h.damage; }) f.insert(f.end(), {h.damage, h.tension_secant, h.compression_secant, h.max_closure});
    if constexpr (requires { h.failed; }) f.push_back(h.failed);
    if constexpr (requires { h.slipping; }) f.push_back(h.slipping);
    if constexpr (requires { h.inelastic; }) f.push_back(h.inelastic);
    return f;
  }
  std::vector<std::string> found_;
};

template <class G>
void compare_contact_group(Differences& d, const std::string& law, const G& a, const G& b) {
  d.values(law + " body_a", a.body_a, b.body_a);
  d.values(law + " body_b", a.body_b, b.body_b);
  d.values(law + " property", a.property, b.property);
  d.values(law + " origin_a", a.origin_a, b.origin_a);
  d.values(law + " normal_a", a.normal_a, b.normal_a);
  d.values(law + " tangent_a", a.tangent_a, b.tangent_a);
  d.values(law + " first_point", a.first_point, b.first_point);
  d.values(law + " force", a.force, b.force);
  d.values(law + " moment", a.moment, b.moment);
  d.values(law + " s1", a.s1, b.s1);
  d.values(law + " s2", a.s2, b.s2);
  d.values(law + " area", a.area, b.area);
  d.histories(law + " history", a.history, b.history);
  d.values(law + " spring_state", a.spring_state, b.spring_state);
  d.values(law + " slip_dissipation", a.slip_dissipation, b.slip_dissipation);
  d.values(law + " viscous_dissipation", a.viscous_dissipation, b.viscous_dissipation);
  d.values(law + " field_form", a.field_form, b.field_form);
  if constexpr (G::has_field) d.values(law + " field", a.field, b.field);
  d.values(law + " first", a.first, b.first);
  d.values(law + " entry", a.entry, b.entry);
}

template <class G>
void compare_node_group(Differences& d, const G& a, const G& b) {
  d.values("node contact node", a.node, b.node);
  d.values("node contact face_block", a.face_block, b.face_block);
  d.values("node contact area", a.area, b.area);
  d.values("node contact point_local", a.point_local, b.point_local);
  d.values("node contact triangle", a.triangle, b.triangle);
  d.values("node contact weight", a.weight, b.weight);
  d.histories("node contact history", a.history, b.history);
  d.values("node contact spring_state", a.spring_state, b.spring_state);
  d.values("node contact traction", a.traction, b.traction);
  d.values("node contact force", a.force, b.force);
  d.values("node contact moment", a.moment, b.moment);
  d.values("node contact slip_dissipation", a.slip_dissipation, b.slip_dissipation);
  d.values("node contact viscous_dissipation", a.viscous_dissipation, b.viscous_dissipation);
}

template <class Law, class Sim>
void compare_law(Differences& d, const Sim& a, const Sim& b) {
  compare_contact_group(d, std::to_string(sizeof(typename Law::History)) + "-byte-history law", a.template group<Law>(),
                        b.template group<Law>());
}

template <class Damping, class... Laws>
std::vector<std::string> differences(const Simulation<Damping, Laws...>& a, const Simulation<Damping, Laws...>& b) {
  Differences d;
  const auto& ba = a.model().bodies;
  const auto& bb = b.model().bodies;
  d.values("block position", ba.position, bb.position);
  d.values("block orientation", ba.orientation, bb.orientation);
  d.values("block rotation", ba.rotation, bb.rotation);
  d.values("block velocity", ba.velocity, bb.velocity);
  d.values("block angular velocity", ba.angular_velocity, bb.angular_velocity);
  d.values("block mass", ba.mass, bb.mass);
  d.values("block inertia", ba.principal_inertia, bb.principal_inertia);
  d.values("block force", ba.force, bb.force);
  d.values("block moment", ba.moment, bb.moment);
  const auto& na = a.model().deformable.nodes;
  const auto& nb = b.model().deformable.nodes;
  d.values("node position", na.position, nb.position);
  d.values("node velocity", na.velocity, nb.velocity);
  d.values("node force", na.force, nb.force);
  d.values("node mass", na.mass, nb.mass);
  d.values("tetrahedron stress", a.model().deformable.tetrahedra.stress, b.model().deformable.tetrahedra.stress);
  (compare_law<Laws>(d, a, b), ...);
  const auto& da = a.deformable_state();
  const auto& db = b.deformable_state();
  d.values("element state", da.element_state, db.element_state);
  d.values("element force", da.element_force, db.element_force);
  d.values("element viscous", da.element_viscous, db.element_viscous);
  d.values("truss force", da.truss_force, db.truss_force);
  d.values("node kinetic", da.node_kinetic, db.node_kinetic);
  d.values("node viscous", da.node_viscous, db.node_viscous);
  d.values("node gravity work", da.node_gravity_work, db.node_gravity_work);
  std::apply([&](const auto&... ga) {
    std::apply([&](const auto&... gb) { (compare_node_group(d, ga, gb), ...); }, db.groups);
  }, da.groups);
  const EnergyReport ea = a.energy(), eb = b.energy();
  d.value("kinetic energy", ea.kinetic, eb.kinetic);
  d.value("elastic energy", ea.elastic, eb.elastic);
  d.value("gravity work", ea.gravity_work, eb.gravity_work);
  d.value("base work", ea.base_work, eb.base_work);
  d.value("viscous energy", ea.viscous, eb.viscous);
  d.value("slip energy", ea.slip, eb.slip);
  d.value("contact update energy", ea.contact_update, eb.contact_update);
  d.value("balance error", ea.balance_error, eb.balance_error);
  d.value("time", a.time(), b.time());
  d.value("steps", a.steps(), b.steps());
  d.value("timestep", a.timestep(), b.timestep());
  d.value("detections", a.detections(), b.detections());
  return d.found();
}

template <class Sim>
void check_identical(const Sim& a, const Sim& b) {
  const auto found = differences(a, b);
  for (const auto& f : found) MESSAGE("differs: " << f);
  CHECK(found.empty());
}

// ---- (a) an arch of rigid voussoirs on shaking supports ----

struct ArchOptions {
  int voussoirs = 9;
  double radius = 1.0, thickness = 0.15, depth = 0.5;  // m
  double lateral = 0.5;                                // lateral gravity, g
};

model::Model arch_model(const ArchOptions& o) {
  model::Model m;
  for (const auto& b : geometry::semicircular_arch(o.voussoirs, o.radius, o.thickness, o.depth))
    m.add_block(b.shape, 2000.0, b.name, b.support ? 1 : 0, b.support ? model::Motion::base : model::Motion::free);
  m.gravity = Vec3(o.lateral * 9.81, 0, -9.81);
  // Moving from the start: the energy reference (taken at the first step) is not zero.
  for (std::size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies.motion[i] == model::Motion::free) m.bodies.velocity[i] = Vec3(0.01, 0, 0.002);
  // 4 Hz along x and 7 Hz along z for 10 s (the runs last well under 1 s).
  m.base_motion = motion::BaseMotion(motion::SineVelocity{0.05, 1.0 / 4.0, 40, Vec3::UnitX()}) +
                  motion::BaseMotion(motion::SineVelocity{0.01, 1.0 / 7.0, 70, Vec3::UnitZ()});
  return m;
}

std::uint64_t arch_hash(const ArchOptions& o, const std::string& policy) {
  return io::Hasher().add("arch").add(o.voussoirs).add(o.radius).add(o.thickness).add(o.depth).add(o.lateral).add(policy).value();
}

/// Voussoir joints dry (Mohr-Coulomb), springings mortared (elasto-softening).
std::variant<contact::MohrCoulomb::Parameters, contact::ElastoSoftening::Parameters> arch_joint(int ta, int tb) {
  if (ta == 1 || tb == 1) return contact::ElastoSoftening::Parameters::from_material();
  return contact::MohrCoulomb::Parameters(1e9, 0.5e9, 0, 0, 0.6);
}

model::ContactSettings arch_settings() {
  model::ContactSettings s;
  s.tolerance = 1e-4;
  // Checks every 60 steps for a move of 10 um: at the checkpoint (step 500) 20 steps have passed since the last
  // check, and blocks have moved by more since the last detection: both are state.
  s.redetection_distance = 1e-5;
  s.redetection_check_interval = 60;
  return s;
}

template <class Damping>
using ArchSimulation = Simulation<Damping, contact::MohrCoulomb, contact::ElastoSoftening>;

/// The 500 steps after the checkpoint, with an explicit redetection among them (automatic ones happen too).
template <class Sim>
void continue_run(Sim& sim) {
  for (int k = 0; k < 500; ++k) {
    if (k == 250) sim.redetect();
    sim.step();
  }
}

template <class Damping>
void check_arch_continuation(const Damping& damping, const std::string& policy, bool density_scaling) {
  const ArchOptions o;
  const std::uint64_t hash = arch_hash(o, policy);
  const std::string path = temporary_path("arch_" + policy);
  model::Model original_model = arch_model(o);
  ArchSimulation<Damping> original(original_model, damping, arch_joint, arch_settings());
  if (density_scaling) CHECK(original.scale_density_to(2.0 * original.timestep()).scaled_blocks > 0);
  const auto start = original_model.bodies.position;
  for (int k = 0; k < 500; ++k) original.step();
  const int detections_at_save = original.detections();
  io::save_checkpoint(path, hash, "arch, " + policy + ", step 500", [&](io::CheckpointWriter& w) { original.save_state(w); });
  CHECK_FALSE(std::filesystem::exists(path + ".part"));
  continue_run(original);

  model::Model restored_model = arch_model(o);
  ArchSimulation<Damping> restored(restored_model, damping, arch_joint, arch_settings());
  io::load_checkpoint(path, hash, [&](io::CheckpointReader& r) { restored.load_state(r); });
  CHECK(restored.steps() == 500);
  continue_run(restored);
  check_identical(original, restored);

  // Not a comparison of two runs that did nothing: the blocks moved, contacts were detected again after the
  // checkpoint (the explicit one and automatic ones), and energy was dissipated.
  double moved = 0;
  for (std::size_t i = 0; i < start.size(); ++i) moved = std::max(moved, (original_model.bodies.position[i] - start[i]).norm());
  MESSAGE(policy << ": largest displacement " << moved << " m, detections " << detections_at_save << " at the checkpoint, "
                 << original.detections() << " at the end; slip " << original.energy().slip << " J, viscous "
                 << original.energy().viscous << " J");
  CHECK(moved > 1e-3);
  CHECK(original.detections() > detections_at_save + 1);
  CHECK(original.energy().slip > 0);
  std::filesystem::remove(path);
}

// ---- (b) a deformable block under a deformable block hanging from a truss ----

model::Model deformable_model() {
  model::Model m;
  m.add_block(geometry::make_box(Vec3(-1, -1, -0.3), Vec3(1, 1, 0)), 2000, "base", 1, model::Motion::base);
  const auto lower = m.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0), Vec3(0.2, 0.2, 0.4)), 2000, "lower");
  const auto upper = m.add_block(geometry::make_box(Vec3(-0.15, -0.15, 0.4), Vec3(0.15, 0.15, 0.6)), 2000, "upper");
  const auto support = m.add_block(geometry::make_box(Vec3(0.8, -0.1, 1.0), Vec3(1.0, 0.1, 1.2)), 2000, "support", 1,
                                   model::Motion::fixed);
  m.make_deformable(lower, 0.2, model::IsotropicElastic(1e9, 0.2));
  m.make_deformable(upper, 0.15, model::IsotropicElastic(2e9, 0.25));
  const auto tied = m.nearest_node(upper, Vec3(0.15, 0, 0.6));
  m.add_truss(m.block_end(support, Vec3(0.8, 0, 1.1)), m.node_end(tied), 1e-4, 2e10, 7800, 500.0, "tie");
  m.gravity = Vec3(2.0, 0, -9.81);
  m.base_motion = motion::BaseMotion(motion::SineVelocity{0.1, 1.0 / 5.0, 50, Vec3::UnitX()}) +
                  motion::BaseMotion(motion::SineVelocity{0.05, 1.0 / 3.0, 30, Vec3::UnitY()});
  return m;
}

contact::MohrCoulomb::Parameters deformable_joint(int, int) { return contact::MohrCoulomb::Parameters(5e9, 2.5e9, 0, 0, 0.5); }

template <class Damping>
void check_deformable_continuation(const Damping& damping, const std::string& policy) {
  const std::uint64_t hash = io::Hasher().add("two deformable blocks and a tie").add(policy).value();
  const std::string path = temporary_path("deformable_" + policy);
  model::Model original_model = deformable_model();
  Simulation<Damping, contact::MohrCoulomb> original(original_model, damping, deformable_joint);
  // Density scaling: node masses, the timestep and the damping constants differ from a fresh simulation's.
  const auto scaling = original.scale_density_to(3.0 * original.timestep());
  CHECK(scaling.scaled_nodes > 0);
  const auto start = original_model.deformable.nodes.position;
  for (int k = 0; k < 500; ++k) original.step();
  io::save_checkpoint(path, hash, "deformable, " + policy, [&](io::CheckpointWriter& w) { original.save_state(w); });
  continue_run(original);

  model::Model restored_model = deformable_model();
  Simulation<Damping, contact::MohrCoulomb> restored(restored_model, damping, deformable_joint);
  CHECK(restored.timestep() != original.timestep());
  io::load_checkpoint(path, hash, [&](io::CheckpointReader& r) { restored.load_state(r); });
  continue_run(restored);
  check_identical(original, restored);

  double moved = 0;
  for (std::size_t i = 0; i < start.size(); ++i)
    moved = std::max(moved, (original_model.deformable.nodes.position[i] - start[i]).norm());
  MESSAGE(policy << ": " << original_model.deformable.tetrahedra.size() << " tetrahedra, "
                 << original.deformable_state().contact_points() << " node CPs, largest node displacement " << moved << " m");
  CHECK(original.deformable_state().contact_points() > 0);
  CHECK(moved > 1e-6);
  std::filesystem::remove(path);
}

damping::Maxwell<3> maxwell_policy() {
  // 3 % at 2, 8 and 30 Hz (eq. 17 inverted, as 3DEC's `maxwell z f` pairs).
  return damping::Maxwell<3>({damping::MaxwellBranch::from_peak(0.03, two_pi * 2.0),
                              damping::MaxwellBranch::from_peak(0.03, two_pi * 8.0),
                              damping::MaxwellBranch::from_peak(0.03, two_pi * 30.0)});
}

// ---- (c) a small checkpoint to spoil ----

struct SmallRun {
  model::Model blocks;
  std::unique_ptr<Simulation<damping::None, contact::Elastic>> sim;
  explicit SmallRun(int count = 2) {
    blocks.add_block(geometry::make_box(Vec3(-1, -1, -0.5), Vec3(1, 1, 0)), 2000, "base", 0, model::Motion::fixed);
    for (int i = 1; i < count; ++i)
      blocks.add_block(geometry::make_box(Vec3(-0.5, -0.5, i - 1.0), Vec3(0.5, 0.5, i)), 2000, "block " + std::to_string(i));
    sim = std::make_unique<Simulation<damping::None, contact::Elastic>>(
        blocks, damping::None{}, [](int, int) { return contact::Elastic::Parameters(1e9, 1e9); });
  }
};

constexpr std::uint64_t small_hash = 0x1234abcd;

std::string save_small(const std::string& name) {
  SmallRun run;
  for (int k = 0; k < 20; ++k) run.sim->step();
  const std::string path = temporary_path(name);
  io::save_checkpoint(path, small_hash, "a block on a base", [&](io::CheckpointWriter& w) { run.sim->save_state(w); });
  return path;
}

void load_small(const std::string& path, std::uint64_t hash = small_hash) {
  SmallRun run;
  io::load_checkpoint(path, hash, [&](io::CheckpointReader& r) { run.sim->load_state(r); });
}

void overwrite(const std::string& path, std::uint64_t offset, const void* bytes, std::size_t size) {
  std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
  f.seekp(static_cast<std::streamoff>(offset));
  f.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
}

}  // namespace

TEST_CASE("checkpoint: an arch restored at step 500 continues bitwise as the uninterrupted run (None)") {
  check_arch_continuation(damping::None{}, "none", false);
}

TEST_CASE("checkpoint: an arch restored at step 500 continues bitwise as the uninterrupted run (MassProportional)") {
  check_arch_continuation(damping::MassProportional::from_damping_ratio(0.05, 5.0), "mass_proportional", false);
}

TEST_CASE("checkpoint: an arch restored at step 500 continues bitwise as the uninterrupted run (Maxwell<3>)") {
  check_arch_continuation(maxwell_policy(), "maxwell3", false);
}

TEST_CASE("checkpoint: a density-scaled rigid arch (the mixed step switched on) continues bitwise (Maxwell<3>)") {
  check_arch_continuation(maxwell_policy(), "maxwell3_scaled", true);
}

TEST_CASE("checkpoint: deformable blocks and a truss continue bitwise (Maxwell<3>, tensor form)") {
  check_deformable_continuation(maxwell_policy(), "maxwell3");
}

TEST_CASE("checkpoint: deformable blocks and a truss continue bitwise (Rayleigh, spring form)") {
  check_deformable_continuation(damping::Rayleigh::from_two_frequencies(0.02, 2.0, 0.02, 20.0), "rayleigh");
}

TEST_CASE("checkpoint: a fresh simulation that does not load the checkpoint ends elsewhere (the comparison sees state)") {
  const ArchOptions o;
  model::Model m1 = arch_model(o), m2 = arch_model(o);
  ArchSimulation<damping::None> a(m1, damping::None{}, arch_joint, arch_settings());
  ArchSimulation<damping::None> b(m2, damping::None{}, arch_joint, arch_settings());
  for (int k = 0; k < 500; ++k) a.step();
  continue_run(a);
  continue_run(b);
  CHECK_FALSE(differences(a, b).empty());
}

TEST_CASE("checkpoint: writer and reader round trip values, vectors, nested vectors and strings, counts are bounded") {
  std::stringstream buffer;
  io::CheckpointWriter w(buffer);
  const std::vector<std::vector<std::uint32_t>> nested{{1, 2, 3}, {}, {4}};
  const std::vector<Vec3> points{Vec3(1, -0.0, 3), Vec3(std::nextafter(1.0, 2.0), 5, 6)};
  const std::array<std::vector<double>, 2> pair{std::vector<double>{0.5}, std::vector<double>{}};
  w.write(std::uint32_t{7});
  w.write(-0.0);
  w.write(nested);
  w.write(points);
  w.write(std::string("description"));
  w.write(pair);
  const auto size = w.bytes();
  io::CheckpointReader r(buffer, "memory", size);
  CHECK(r.read_value<std::uint32_t>() == 7);
  CHECK(std::signbit(r.read_value<double>()));
  CHECK(r.read_value<std::vector<std::vector<std::uint32_t>>>() == nested);
  CHECK(r.read_value<std::vector<Vec3>>() == points);
  CHECK(r.read_value<std::string>() == "description");
  CHECK(r.read_value<std::array<std::vector<double>, 2>>() == pair);
  CHECK(r.remaining() == 0);
  CHECK_THROWS_WITH_AS(r.read_value<double>("the next number"),
                       doctest::Contains("checkpoint 'memory': truncated: 8 bytes needed, 0 left (reading the next number)"),
                       InvalidArgument);

  // A count that the bytes left cannot hold is refused before anything is allocated.
  std::stringstream huge;
  io::CheckpointWriter(huge).write(std::uint64_t{1} << 50);
  io::CheckpointReader hr(huge, "memory", 8);
  std::vector<double> v;
  CHECK_THROWS_WITH_AS(hr.read(v, "block masses"), doctest::Contains("more than the 0 bytes left can hold (reading block masses)"),
                       InvalidArgument);

  // The hash helper: FNV-1a 64 of "a" is af63dc4c8601ec8c (the published test vector).
  CHECK(io::hash_bytes("a") == 0xaf63dc4c8601ec8cull);
  CHECK(io::Hasher().add("ab").add("c").value() != io::Hasher().add("a").add("bc").value());
}

TEST_CASE("checkpoint: a stored bool or enumerator that is no value of its type is refused by name, not read") {
  // The checksum guards a file; a payload read without one (or a checksum that collides) must still never give a bool
  // that is neither false nor true (undefined behaviour wherever it is read) or an enumerator out of range.
  std::stringstream buffer;
  io::CheckpointWriter w(buffer);
  const unsigned char flag48 = 48, flag1 = 1, motion7 = 7;
  w.write_bytes(&flag1, 1);  // a valid flag
  w.write_bytes(&flag48, 1);  // the byte a fuzzer found in place of the simulation's "mixed step"
  damping::Local local;
  w.write(local);
  w.write(std::vector<model::Motion>{model::Motion::free, model::Motion::base});
  w.write(std::uint64_t{2});  // a vector of two motions, the second out of range
  w.write_bytes(&flag1, 1);
  w.write_bytes(&motion7, 1);
  w.write(int{5});  // damping::Frame has two enumerators
  io::CheckpointReader r(buffer, "memory", w.bytes());
  CHECK(r.read_value<bool>("a flag"));
  CHECK_THROWS_WITH_AS(r.read_value<bool>("mixed step"),
                       doctest::Contains("checkpoint 'memory': a flag stored as 48, not 0 or 1 (reading mixed step)"),
                       InvalidArgument);
  CHECK_NOTHROW(r.read_value<damping::Local>("damping policy"));
  CHECK(r.read_value<std::vector<model::Motion>>("block motions") ==
        std::vector<model::Motion>{model::Motion::free, model::Motion::base});
  CHECK_THROWS_WITH_AS(r.read_value<std::vector<model::Motion>>("block motions"),
                       doctest::Contains("an enumerator out of range (stored 7) (reading block motions)"), InvalidArgument);
  CHECK_THROWS_WITH_AS(r.read_value<damping::Frame>("damping frame"),
                       doctest::Contains("an enumerator out of range (stored 5) (reading damping frame)"), InvalidArgument);

  // A bool member of a plain class (listed in its checkpoint_flags()) is checked as well.
  std::stringstream policy;
  io::CheckpointWriter pw(policy);
  pw.write(local);
  std::string bytes = policy.str();
  const auto at = static_cast<std::size_t>(reinterpret_cast<const char*>(&local.split_rigid_motion) -
                                           reinterpret_cast<const char*>(&local));
  bytes[at] = 2;
  std::istringstream spoiled(bytes);
  io::CheckpointReader pr(spoiled, "memory", bytes.size());
  CHECK_THROWS_WITH_AS(pr.read_value<damping::Local>("damping policy"),
                       doctest::Contains("a flag stored as 2, not 0 or 1 (reading damping policy)"), InvalidArgument);
}

TEST_CASE("checkpoint: refusals name the file and the problem") {
  const std::string path = save_small("refusals");
  const std::string spoiled = temporary_path("refusals_spoiled");
  const auto header = io::read_checkpoint_header(path);
  CHECK(header.description == "a block on a base");
  CHECK(header.model_hash == small_hash);
  const auto fresh_copy = [&] { std::filesystem::copy_file(path, spoiled, std::filesystem::copy_options::overwrite_existing); };

  CHECK_NOTHROW(load_small(path));

  SUBCASE("missing file") {
    CHECK_THROWS_WITH_AS(load_small(temporary_path("no_such")), doctest::Contains("no such file"), InvalidArgument);
  }
  SUBCASE("truncated in the payload") {
    fresh_copy();
    std::filesystem::resize_file(spoiled, std::filesystem::file_size(spoiled) - 100);
    const std::string expected = "checkpoint '" + spoiled + "': truncated";
    CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains(expected.c_str()), InvalidArgument);
  }
  SUBCASE("truncated in the header") {
    fresh_copy();
    std::filesystem::resize_file(spoiled, 20);
    CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains("truncated"), InvalidArgument);
  }
  SUBCASE("a flipped byte in the payload") {
    fresh_copy();
    const std::uint64_t at = header.payload_offset + header.payload_size / 2;
    std::ifstream in(spoiled, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(at));
    char c = 0;
    in.get(c);
    in.close();
    c = static_cast<char>(c ^ 0x10);
    overwrite(spoiled, at, &c, 1);
    CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains("corrupted payload (checksum mismatch"), InvalidArgument);
  }
  SUBCASE("wrong magic") {
    fresh_copy();
    overwrite(spoiled, 0, "X", 1);
    CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains("not a blockdem checkpoint (bad magic bytes"), InvalidArgument);
    std::ofstream(spoiled, std::ios::trunc) << "hello";  // shorter than the magic
    CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains("not a blockdem checkpoint"), InvalidArgument);
  }
  SUBCASE("another format version") {
    fresh_copy();
    // A later build's, and earlier builds' (version 1 held no contact_update, 2 no timestep hold: read on, they
    // would be out of step).
    for (const std::uint32_t version : {99u, 1u, 2u}) {
      overwrite(spoiled, io::checkpoint_magic.size(), &version, sizeof version);
      const std::string message = "written by format version " + std::to_string(version) + ", this build reads " +
                                  std::to_string(io::checkpoint_format_version);
      CHECK_THROWS_WITH_AS(load_small(spoiled), doctest::Contains(message.c_str()), InvalidArgument);
    }
  }
  SUBCASE("another model hash") {
    CHECK_THROWS_WITH_AS(load_small(path, small_hash + 1),
                         doctest::Contains("the checkpoint is of another model or other options (it holds 'a block on a base'"),
                         InvalidArgument);
  }
  SUBCASE("the same hash given for a model with another number of blocks") {
    SmallRun three(3);
    CHECK_THROWS_WITH_AS(
        io::load_checkpoint(path, small_hash, [&](io::CheckpointReader& r) { three.sim->load_state(r); }),
        doctest::Contains("another model: 2 stored, this model has 3 (reading block positions)"),
        InvalidArgument);
  }
  SUBCASE("the same hash given for a simulation with another damping policy") {
    model::Model m = SmallRun().blocks;
    Simulation<damping::MassProportional, contact::Elastic> other(m, damping::MassProportional{1.0}, [](int, int) {
      return contact::Elastic::Parameters(1e9, 1e9);
    });
    CHECK_THROWS_WITH_AS(io::load_checkpoint(path, small_hash, [&](io::CheckpointReader& r) { other.load_state(r); }),
                         doctest::Contains("stored 'blockdem::Simulation<blockdem::damping::None, blockdem::contact::Elastic>', "
                                           "this simulation has 'blockdem::Simulation<blockdem::damping::MassProportional, "
                                           "blockdem::contact::Elastic>' (reading the simulation type"),
                         InvalidArgument);
  }
  SUBCASE("a payload not read to its end") {
    CHECK_THROWS_WITH_AS(io::load_checkpoint(path, small_hash, [](io::CheckpointReader& r) { r.read_value<std::uint64_t>(); }),
                         doctest::Contains("bytes of the payload were left unread"), InvalidArgument);
  }
  SUBCASE("a failed save leaves the previous checkpoint") {
    fresh_copy();
    const auto before = std::filesystem::file_size(spoiled);
    CHECK_THROWS_AS(io::save_checkpoint(spoiled, small_hash, "broken", [](io::CheckpointWriter& w) {
                      w.write(1.0);
                      throw InvalidArgument("stopped");
                    }),
                    InvalidArgument);
    CHECK(std::filesystem::file_size(spoiled) == before);
    CHECK_FALSE(std::filesystem::exists(spoiled + ".part"));
    CHECK_NOTHROW(load_small(spoiled));
  }
  std::filesystem::remove(spoiled);
  std::filesystem::remove(path);
}

}  // namespace test_checkpoint
