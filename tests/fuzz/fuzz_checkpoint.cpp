// Fuzzes the checkpoint reader (io/checkpoint.hpp): the file's header (read_checkpoint_header from an istringstream,
// then load_checkpoint of the same bytes: checksum, model hash, payload) and the payload itself (CheckpointReader and
// every load_state, from an istringstream) as cross_vault --resume reads it. The first byte picks which.
//
// Seeds: BLOCKDEM_FUZZ_WRITE_SEEDS=DIR ./fuzz_checkpoint writes a real small checkpoint and real payloads to DIR.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "blockdem/analysis/damage_memory.hpp"
#include "blockdem/analysis/study_checkpoint.hpp"
#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/geometry/generators.hpp"
#include "blockdem/integrate/simulation.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/motion/base_motion.hpp"

#include "scratch.hpp"

namespace {

using namespace blockdem;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_checkpoint: %s\n", what.c_str());
  std::abort();
}

/// What a cross-vault study checkpoint holds, over a model small enough to build for every input: the study's
/// simulation type (analysis::VaultSimulation with Maxwell damping of 3 branches: the three joint laws) on a shaking
/// base (elasto-softening joint), a rigid block (Mohr-Coulomb) and, unless rigid, a deformable block on it (elastic:
/// node contacts and elements); the result so far, the cursor, the monitor histories, the snapshots and the settled
/// positions.
struct VaultRun {
  // analysis::VaultSimulation<damping::Maxwell<3>> spelled out: vault_study.hpp would compile every study.
  using Sim = Simulation<damping::Maxwell<3>, contact::ElastoSoftening, contact::MohrCoulomb, contact::Elastic>;
  static constexpr std::uint64_t hash = 0x5eedc0ffee;

  model::Model model;
  std::unique_ptr<Sim> sim;
  analysis::StudyResult result;
  analysis::StudyCursor cursor;
  std::unique_ptr<analysis::MonitorHistory> history;
  analysis::SnapshotSeries snapshots{""};
  std::vector<Vec3> settled;
  analysis::DamageMemory memory;

  static Sim::Properties law(int ta, int tb) {
    switch (std::min(ta, tb)) {
      case 0: return contact::ElastoSoftening::Parameters::from_material();
      case 1: return contact::MohrCoulomb::Parameters(1e9, 0.5e9, 0, 0, 0.6);
      default: return contact::Elastic::Parameters(1e9, 1e9);
    }
  }

  explicit VaultRun(bool deformable) {
    const auto base = model.add_block(geometry::make_box(Vec3(-1, -1, -0.3), Vec3(1, 1, 0)), 2000, "base", 0,
                                      model::Motion::base);
    const auto lower = model.add_block(geometry::make_box(Vec3(-0.3, -0.3, 0), Vec3(0.3, 0.3, 0.3)), 2000, "lower", 1);
    const auto upper = model.add_block(geometry::make_box(Vec3(-0.2, -0.2, 0.3), Vec3(0.2, 0.2, 0.5)), 2000, "upper", 2);
    if (deformable) model.make_deformable(upper, 1.0, model::IsotropicElastic(2e9, 0.25));
    model.gravity = Vec3(2.0, 0, -9.81);
    model.base_motion = motion::BaseMotion(motion::SineVelocity{0.05, 1.0 / 5.0, 50, Vec3::UnitX()});
    const damping::Maxwell<3> maxwell({damping::MaxwellBranch::from_peak(0.03, two_pi * 2.0),
                                       damping::MaxwellBranch::from_peak(0.03, two_pi * 8.0),
                                       damping::MaxwellBranch::from_peak(0.03, two_pi * 30.0)});
    sim = std::make_unique<Sim>(model, maxwell, law);
    const std::vector<model::MonitorPoint> points{{"R1", Vec3(0, 0, 0.3), lower}, {"D1", Vec3(0, 0, 0.5), upper}};
    history = std::make_unique<analysis::MonitorHistory>(model, points, base);
    settled = model.bodies.position;
    memory.start(*sim, model);
  }

  /// A level in progress after `steps` steps (for the seeds).
  void run(int steps) {
    history->begin_level(model, sim->time(), "");
    cursor.in_level = true;
    for (int k = 0; k < steps; ++k) {
      sim->step();
      if (k % 10 == 0) history->sample(model, sim->time());
    }
    cursor.level_steps = steps;
    cursor.energy_at_level_start = sim->energy();
    analysis::LevelResult level;
    level.level = 25;
    level.steps = steps;
    level.peaks = history->peaks();
    result.levels.push_back(level);
    result.free_vibration.note = "not measured";
    result.free_vibration.time = {0.0, 0.01};
    result.free_vibration.response = {0.0, 1e-6};
  }

  template <class Archive>
  void study(Archive& ar) {
    analysis::detail::visit_study_state(ar, result, cursor, *sim, *history, snapshots, settled, memory);
  }
};

/// The objects that read the fuzzed bytes, built once: a load sets or checks every field it reads whatever the
/// object held before (a vector takes its stored size, a same_size or check field is compared with the model's), so
/// an input reads the same into them as into fresh ones, and construction does not slow down every input.
VaultRun& reader_of(bool deformable) {
  static VaultRun rigid(false), vault(true);
  return deformable ? vault : rigid;
}

enum Mode : std::uint8_t { checkpoint_file, rigid_simulation, deformable_simulation, study_state, mode_count };

/// Reads a payload as load_checkpoint does once the checksum matched: from a reader bounded by the payload's size,
/// into objects built as the ones that wrote it, every byte read.
void read_payload(Mode mode, const std::string& payload) {
  std::istringstream in(payload);
  io::CheckpointReader reader(in, "fuzz.ckpt", payload.size());
  VaultRun& run = reader_of(mode != rigid_simulation);
  if (mode == study_state) run.study(reader);
  else run.sim->load_state(reader);
  if (reader.remaining() != 0)
    throw InvalidArgument("checkpoint 'fuzz.ckpt': " + std::to_string(reader.remaining()) + " bytes left unread");
}

/// The file: its header from a stream, then the whole load from a file, as cross_vault --resume does.
void read_file(const std::string& bytes) {
  std::istringstream in(bytes);
  const io::CheckpointHeader h = io::detail::read_checkpoint_header(in, "fuzz.ckpt", bytes.size());
  // A header that is accepted describes the file: payload and checksum fill the rest of it exactly.
  if (h.payload_offset > bytes.size() || h.payload_size > bytes.size() ||
      h.payload_offset + h.payload_size + sizeof(std::uint64_t) != bytes.size())
    finding("accepted a header with a payload of " + std::to_string(h.payload_size) + " bytes at offset " +
            std::to_string(h.payload_offset) + " in a file of " + std::to_string(bytes.size()) + " bytes");
  if (static_cast<std::streamoff>(in.tellg()) != static_cast<std::streamoff>(h.payload_offset))
    finding("the header reader left the stream at " + std::to_string(in.tellg()) + ", not at the payload (" +
            std::to_string(h.payload_offset) + ")");

  static const fuzz::Scratch file{"blockdem_fuzz_checkpoint_", ".ckpt"};
  const std::string& path = file.path;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  io::load_checkpoint(path, VaultRun::hash, [](io::CheckpointReader& r) { reader_of(true).study(r); });
}

// ---- seeds ----

std::vector<std::string> written;  // the seeds' paths

void write_seed(const std::string& dir, const std::string& name, Mode mode, const std::string& bytes) {
  written.push_back(dir + "/" + name);
  std::ofstream out(written.back(), std::ios::binary);
  out.put(static_cast<char>(mode));
  out << bytes;
  if (!out) {
    std::fprintf(stderr, "cannot write the seed '%s/%s'\n", dir.c_str(), name.c_str());
    std::exit(1);
  }
}

template <class Write>
std::string payload_of(Write&& write) {
  std::ostringstream out;
  io::CheckpointWriter w(out, "seed");
  write(w);
  return out.str();
}

void write_seeds(const std::string& dir) {
  std::filesystem::create_directories(dir);
  for (const int steps : {0, 100}) {
    const std::string at = "_step" + std::to_string(steps);
    VaultRun rigid(false);
    rigid.run(steps);
    write_seed(dir, "rigid_simulation" + at, rigid_simulation,
               payload_of([&](io::CheckpointWriter& w) { rigid.sim->save_state(w); }));
    VaultRun vault(true);
    vault.run(steps);
    write_seed(dir, "deformable_simulation" + at, deformable_simulation,
               payload_of([&](io::CheckpointWriter& w) { vault.sim->save_state(w); }));
    write_seed(dir, "study_state" + at, study_state, payload_of([&](io::CheckpointWriter& w) { vault.study(w); }));
    // The whole file, as the study writes it.
    const std::string file = dir + "/.checkpoint.tmp";
    io::save_checkpoint(file, VaultRun::hash, "cross vault study, maxwell, in level 25 %, t = 0.1 s",
                        [&](io::CheckpointWriter& w) { vault.study(w); });
    std::ifstream in(file, std::ios::binary);
    write_seed(dir, "checkpoint_file" + at, checkpoint_file,
               std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
    std::filesystem::remove(file);
  }
  // Each seed must read back whole.
  for (const auto& path : written) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes[0] == checkpoint_file) read_file(bytes.substr(1));
    else read_payload(static_cast<Mode>(bytes[0]), bytes.substr(1));
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* dir = std::getenv("BLOCKDEM_FUZZ_WRITE_SEEDS")) {
    write_seeds(dir);
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto mode = static_cast<Mode>(data[0] % mode_count);
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (mode == checkpoint_file) read_file(bytes);
    else read_payload(mode, bytes);
  } catch (const InvalidArgument&) {
  } catch (const InputError&) {
  }
  return 0;
}
