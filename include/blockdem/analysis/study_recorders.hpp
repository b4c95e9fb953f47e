#pragma once
// What a study records during a level: the monitor points' histories (displacement relative to the table,
// acceleration from centred differences of the velocity, paper Sect. 5.3), streamed to CSV so that the file is
// readable while the run goes on (as <file>.part, renamed when the level ends or the run guard stops it: a history
// under its own name is whole, a .part one belongs to a run killed or interrupted in that level), with their
// peaks; and the census of damaged joints per group (the vault's components, Sect. 5.2).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/model/monitor_point.hpp"

namespace blockdem::analysis {

/// Peaks of one channel over a level.
struct ChannelPeaks {
  std::string name;  // <point>_<ux|uy|uz|ax|ay|az>
  double max = -std::numeric_limits<double>::infinity();
  double min = std::numeric_limits<double>::infinity();

  void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
  void load_state(io::CheckpointReader& r) { visit_state(*this, r); }

 private:
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar("channel name", s.name);
    ar("channel maximum", s.max);
    ar("channel minimum", s.min);
  }
};

/// Histories of the monitor points over one level. Columns: time (s from the start of the level), then per point
/// <name>_ux, _uy, _uz (m, relative to the table and to the point's position at the start of the level) and
/// <name>_ax, _ay, _az (m/s^2, absolute: centred differences of the recorded velocities, one-sided at the ends).
/// A point on a rigid block moves with the block; a point on a deformable block follows its nearest node. Without a
/// table block (a structure on fixed supports) the displacements are absolute.
class MonitorHistory {
 public:
  MonitorHistory(const model::Model& model, const std::vector<model::MonitorPoint>& points, std::optional<std::size_t> table_block)
      : table_(table_block) {
    const auto& b = model.bodies;
    for (const auto& p : points) {
      names_.push_back(p.name);
      block_.push_back(p.block);
      body_point_.push_back(b.rotation[p.block].transpose() * (p.position - b.position[p.block]));
      node_.push_back(model.deformable.is_deformable(p.block) ? static_cast<std::int64_t>(model.nearest_node(p.block, p.position)) : -1);
    }
  }

  std::size_t points() const { return names_.size(); }
  const std::vector<std::string>& names() const { return names_; }

  /// Starts a level: the reference positions are the current ones; `path` (may be empty) receives the CSV, written
  /// as io::partial_path(path) until end_level().
  void begin_level(const model::Model& model, double time0, const std::string& path) {
    time0_ = time0;
    reference_.clear();
    for (std::size_t p = 0; p < points(); ++p) reference_.push_back(world(model, p));
    table_reference_ = table_position(model);
    samples_.clear();
    written_ = 0;
    bytes_ = 0;
    peaks_.clear();
    for (const auto& n : names_)
      for (const char* q : {"ux", "uy", "uz", "ax", "ay", "az"}) peaks_.push_back({n + "_" + q});
    out_ = std::ofstream();
    path_ = path;
    if (!path.empty()) {
      out_.open(io::partial_path(path));
      if (!out_) throw InvalidArgument("cannot open '" + io::partial_path(path) + "' for writing");
      std::string header = "time";
      for (const auto& p : peaks_) (header += ',') += p.name;
      header += '\n';
      put(header);
    }
  }

  /// Records the state at simulation time t (s).
  void sample(const model::Model& model, double t) {
    const auto& b = model.bodies;
    Sample s;
    s.time = t - time0_;
    const Vec3 table = table_position(model) - table_reference_;
    for (std::size_t p = 0; p < points(); ++p) {
      s.displacement.push_back(world(model, p) - reference_[p] - table);
      if (node_[p] >= 0) {
        s.velocity.push_back(model.deformable.nodes.velocity[static_cast<std::size_t>(node_[p])]);
      } else {
        const std::size_t i = block_[p];
        s.velocity.push_back(b.velocity[i] + b.angular_velocity[i].cross(b.rotation[i] * body_point_[p]));
      }
    }
    samples_.push_back(std::move(s));
    // Row k needs samples k - 1 and k + 1: write the one before the newest.
    if (samples_.size() >= 2) write_row(samples_.size() - 2);
    if (samples_.size() > 3) samples_.erase(samples_.begin());
  }

  /// Writes the last row, closes the file and gives it its name.
  void end_level() {
    if (!samples_.empty()) write_row(samples_.size() - 1);
    if (!out_.is_open()) return;
    io::close_checked(out_, io::partial_path(path_));
    std::error_code error;
    std::filesystem::rename(io::partial_path(path_), path_, error);
    if (error) throw InvalidArgument("cannot write '" + path_ + "': " + error.message());
  }

  /// The state of the level in progress, for a checkpoint: the references, the last samples, the peaks and how
  /// many bytes of the CSV were written (each row is flushed as it is written).
  void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
  /// The reverse of save_state(); then resume_file() reopens the CSV.
  void load_state(io::CheckpointReader& r) { visit_state(*this, r); }

  /// Continues the level's CSV at `path` (may be empty: none), in io::partial_path(path) (taken back from `path`
  /// if a run that went on after its checkpoint had finished the level): cut back to what the checkpoint had
  /// written, then appended to. Throws InvalidArgument if the file is missing or shorter than that.
  void resume_file(const std::string& path) {
    out_ = std::ofstream();
    path_ = path;
    if (path.empty()) return;
    std::error_code error;
    const std::string part = io::partial_path(path);
    if (!std::filesystem::exists(part, error) && std::filesystem::exists(path, error)) std::filesystem::rename(path, part, error);
    const auto size = std::filesystem::file_size(part, error);
    if (error || size < bytes_)
      throw InvalidArgument("--resume: the history '" + part + "' " +
                            (error ? "cannot be read (" + error.message() + ")"
                                   : "holds " + std::to_string(size) + " bytes, fewer than the " + std::to_string(bytes_) +
                                         " the checkpoint wrote") +
                            "; resume into the output folder of the run that wrote the checkpoint");
    std::filesystem::resize_file(part, bytes_, error);
    if (error) throw InvalidArgument("--resume: cannot cut '" + part + "' back to the checkpoint: " + error.message());
    out_.open(part, std::ios::app);
    if (!out_) throw InvalidArgument("cannot open '" + part + "' for writing");
  }

  const std::vector<ChannelPeaks>& peaks() const { return peaks_; }
  long long rows() const { return written_; }
  /// Displacement relative to the table at the last sample, m.
  Vec3 last_displacement(std::size_t p) const { return samples_.empty() ? Vec3::Zero() : samples_.back().displacement[p]; }

 private:
  struct Sample {
    double time = 0;
    std::vector<Vec3> displacement, velocity;

    void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
    void load_state(io::CheckpointReader& r) { visit_state(*this, r); }
    template <class Self, class Archive>
    static void visit_state(Self& s, Archive& ar) {
      ar("sample time", s.time);
      ar("sample displacements", s.displacement);
      ar("sample velocities", s.velocity);
    }
  };

  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar.check("monitor points", s.names_);
    ar.same_size("monitor points in their blocks", s.body_point_);  // from the settled vault, not the one built anew
    ar.same_size("monitor nodes", s.node_);
    ar("level start", s.time0_);
    ar("reference positions", s.reference_);
    ar("table reference", s.table_reference_);
    ar("last samples", s.samples_);
    ar("peaks", s.peaks_);
    ar("rows written", s.written_);
    ar("bytes written", s.bytes_);
  }

  void put(const std::string& text) {
    out_ << text;
    bytes_ += text.size();
  }

  Vec3 table_position(const model::Model& model) const { return table_ ? model.bodies.position[*table_] : Vec3::Zero(); }

  Vec3 world(const model::Model& model, std::size_t p) const {
    return node_[p] >= 0 ? model.deformable.nodes.position[static_cast<std::size_t>(node_[p])]
                         : model.bodies.to_world(block_[p], body_point_[p]);
  }

  void write_row(std::size_t k) {
    const std::size_t lo = k == 0 ? 0 : k - 1;
    const std::size_t hi = k + 1 < samples_.size() ? k + 1 : k;
    const auto& s = samples_[k];
    const double span = samples_[hi].time - samples_[lo].time;
    char buffer[40];
    std::string row;
    std::snprintf(buffer, sizeof buffer, "%.6f", s.time);
    row += buffer;
    for (std::size_t p = 0; p < points(); ++p) {
      const Vec3 a = span > 0 ? Vec3((samples_[hi].velocity[p] - samples_[lo].velocity[p]) / span) : Vec3::Zero();
      for (int c = 0; c < 6; ++c) {
        const double value = c < 3 ? s.displacement[p][c] : a[c - 3];
        auto& peak = peaks_[6 * p + static_cast<std::size_t>(c)];
        peak.max = std::max(peak.max, value);
        peak.min = std::min(peak.min, value);
        std::snprintf(buffer, sizeof buffer, ",%.9g", value);
        row += buffer;
      }
    }
    row += '\n';
    if (out_.is_open()) {
      put(row);
      if (!out_.flush()) throw InvalidArgument("cannot write '" + io::partial_path(path_) + "' (disk full?)");
    }
    ++written_;
  }

  std::optional<std::size_t> table_;
  std::vector<std::string> names_;
  std::vector<std::size_t> block_;
  std::vector<Vec3> body_point_, reference_;
  std::vector<std::int64_t> node_;  // the node a point on a deformable block follows, -1 on a rigid block
  Vec3 table_reference_ = Vec3::Zero();
  double time0_ = 0;
  std::vector<Sample> samples_;
  std::vector<ChannelPeaks> peaks_;
  long long written_ = 0;
  std::uint64_t bytes_ = 0;  // of the CSV
  std::ofstream out_;
  std::string path_;
};

/// Damaged contact points, counted for each group a CP touches (a CP between vault and infill counts for both).
struct DamageCensus {
  struct Counts {
    long long contact_points = 0;
    long long cracked = 0;   // opened beyond the tensile strength (secant unloading)
    long long crushed = 0;   // closed beyond the compressive hardening limit
    long long slipped = 0;   // damaged or failed in shear only (Mohr-Coulomb: failed or at the Coulomb limit)
    long long damaged = 0;   // any damage > 0 or failure
    long long new_contacts = 0;  // appeared during the run, never bonded (contact::never_bonded): not counted as damage
    double max_damage = 0;
  };
  std::vector<Counts> by_group;  // by joint tag (a structure's groups, the vault's components)
  Counts total;
  long long loose_blocks = 0;  // free blocks without any contact point: fallen out of the structure, or in flight

  void save_state(io::CheckpointWriter& w) const { visit_state(*this, w); }
  void load_state(io::CheckpointReader& r) { visit_state(*this, r); }

 private:
  template <class Self, class Archive>
  static void visit_state(Self& s, Archive& ar) {
    ar("damage by group", s.by_group);
    ar("damage in all", s.total);
    ar("loose blocks", s.loose_blocks);
  }
};

/// The census of a simulation whose joint tags are `groups` groups, over the contact points of rigid and deformable
/// blocks alike.
template <class Simulation>
DamageCensus damage_census(const Simulation& sim, const model::Model& model, std::size_t groups) {
  DamageCensus census;
  census.by_group.resize(groups);
  std::vector<char> touched(model.bodies.size(), 0);
  sim.visit_contact_histories([&]<class Law>(std::size_t a, std::size_t b, std::type_identity<Law>, const auto& h) {
    touched[a] = touched[b] = 1;
    bool cracked = false, crushed = false, slipped = false;
    double damage = 0;
    const bool appeared = Law::never_bonded(h);
    if (!appeared) damage = Law::damage(h);  // a contact made during the run: its failed start is no damage
    // How the masonry is damaged, by the laws that say it: elasto-softening (cracked, crushed), Mohr-Coulomb (slip).
    if (appeared) {
    } else if constexpr (requires { h.tension_secant; }) {
      cracked = h.tension_secant < 1;
      crushed = h.compression_secant < 1;
      slipped = damage > 0 && !cracked && !crushed;
    } else if constexpr (requires { h.slipping; }) {
      slipped = h.failed || h.slipping;
    }
    const bool damaged = cracked || crushed || slipped || damage > 0;
    auto count = [&](DamageCensus::Counts& c) {
      ++c.contact_points;
      c.cracked += cracked;
      c.crushed += crushed;
      c.slipped += slipped;
      c.damaged += damaged;
      c.new_contacts += appeared;
      c.max_damage = std::max(c.max_damage, damage);
    };
    const auto ta = static_cast<std::size_t>(model.bodies.joint_tag[a]), tb = static_cast<std::size_t>(model.bodies.joint_tag[b]);
    count(census.total);
    count(census.by_group.at(ta));
    if (tb != ta) count(census.by_group.at(tb));
  });
  for (std::size_t i = 0; i < touched.size(); ++i) census.loose_blocks += model.bodies.motion[i] == model::Motion::free && !touched[i];
  return census;
}

}  // namespace blockdem::analysis
