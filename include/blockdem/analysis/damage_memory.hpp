#pragma once
// The damage memory of a study (DESIGN §11): the contact points of the joints bonded when the dynamic run starts,
// each with the worst state it has reached. The contact detection drops the points of blocks that move apart and
// gives a joint that cracked, opened and closed again new, never-bonded points; the memory keeps the joint as it
// was built, so that a joint that broke stays broken in every output (census, maps, report), whether its blocks
// touch again or fell apart, and a map never hides a damaged joint under a new contact.
//
// A remembered point is found again among the present ones by its block pair and its place on block A (in A's body
// frame): the present bonded points are the original ones or their heirs (a point that takes over a history stays
// within the matching distance of the one it came from). On a deformable block A the place is taken in the frame of
// its rigid entry, which does not move: its nodes' displacements must stay below the matching distance for the
// match to hold (a few millimetres; a deformable block that moves farther keeps its worst state, matched to its
// nearest point).

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "blockdem/analysis/study_recorders.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/integrate/contact_view.hpp"
#include "blockdem/io/checkpoint.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::analysis {

class DamageMemory {
 public:
  // The states a joint reaches (Joint::state bits).
  static constexpr std::uint64_t cracked = 1, crushed = 2, slipped = 4;

  /// One contact point of a bonded joint: 56 bytes, no padding (a checkpoint writes it as it is).
  struct Joint {
    std::uint32_t a = 0, b = 0;  // its blocks
    double local[3] = {0, 0, 0};  // m, its place in A's body frame when the run started
    double area = 0;             // m^2
    double damage = 0;           // the worst reached, 0..1
    std::uint64_t state = 0;     // State bits ever reached
  };
  static_assert(sizeof(Joint) == 56);

  /// Remembers the bonded contact points of `sim` as they are now (at the start of the dynamic run).
  template <class Sim>
  void start(const Sim& sim, const model::Model& m) {
    joints_.clear();
    sim.visit_contacts([&](const ContactView& c) {
      if (c.never_bonded) return;
      Joint j;
      j.a = static_cast<std::uint32_t>(c.block_a);
      j.b = static_cast<std::uint32_t>(c.block_b);
      const Vec3 x = local(m, c.block_a, c.position);
      for (int k = 0; k < 3; ++k) j.local[k] = x[k];
      j.area = c.area;
      joints_.push_back(j);
    });
    index();
    update(sim, m);
  }

  /// Takes the worst of each remembered point and its present heir. Call it before every contact detection (the
  /// simulation's detection observer) and at the end of each level.
  template <class Sim>
  void update(const Sim& sim, const model::Model& m) {
    sim.visit_contacts([&](const ContactView& c) {
      if (c.never_bonded) return;
      Joint* j = find(m, c);
      if (!j) return;
      j->damage = std::max(j->damage, c.damage);
      j->state |= (c.cracked ? cracked : 0) | (c.crushed ? crushed : 0) | (c.slipped ? slipped : 0);
    });
  }

  /// The census of the remembered joints by group (joint tags), with the present simulation's new contact points
  /// and loose blocks: a joint counts as damaged once it has been, whatever became of its blocks.
  template <class Sim>
  DamageCensus census(const Sim& sim, const model::Model& m, std::size_t groups) const {
    DamageCensus census;
    census.by_group.resize(groups);
    auto count = [&](const Joint& j, auto&& add) {
      const auto ta = static_cast<std::size_t>(m.bodies.joint_tag[j.a]), tb = static_cast<std::size_t>(m.bodies.joint_tag[j.b]);
      add(census.total);
      add(census.by_group.at(ta));
      if (tb != ta) add(census.by_group.at(tb));
    };
    for (const auto& j : joints_)
      count(j, [&](DamageCensus::Counts& c) {
        ++c.contact_points;
        c.cracked += (j.state & cracked) != 0;
        c.crushed += (j.state & crushed) != 0;
        const bool cracked_or_crushed = (j.state & (cracked | crushed)) != 0;
        c.slipped += (j.state & slipped) != 0 || (j.damage > 0 && !cracked_or_crushed);
        c.damaged += j.state != 0 || j.damage > 0;
        c.max_damage = std::max(c.max_damage, j.damage);
      });
    std::vector<char> touched(m.bodies.size(), 0);
    sim.visit_contacts([&](const ContactView& v) {
      touched[v.block_a] = touched[v.block_b] = 1;
      if (!v.never_bonded) return;
      Joint j;
      j.a = static_cast<std::uint32_t>(v.block_a);
      j.b = static_cast<std::uint32_t>(v.block_b);
      count(j, [](DamageCensus::Counts& c) { ++c.new_contacts; });
    });
    for (std::size_t i = 0; i < touched.size(); ++i) census.loose_blocks += m.bodies.motion[i] == model::Motion::free && !touched[i];
    return census;
  }

  /// The remembered points where they are now (on A as it has moved), for maps: f(const Joint&, const Vec3& world).
  template <class F>
  void visit(const model::Model& m, F&& f) const {
    for (const auto& j : joints_) f(j, m.bodies.to_world(j.a, Vec3(j.local[0], j.local[1], j.local[2])));
  }

  const std::vector<Joint>& joints() const { return joints_; }
  /// The remembered point a present one is the heir of (nullptr if none: a new contact).
  const Joint* heir_of(const model::Model& m, const ContactView& c) const { return const_cast<DamageMemory*>(this)->find(m, c); }

  void save_state(io::CheckpointWriter& w) const { w.write(joints_); }
  void load_state(io::CheckpointReader& r) {
    r.read(joints_, "damage memory");
    index();
  }

 private:
  static Vec3 local(const model::Model& m, std::size_t block, const Vec3& world) {
    return m.bodies.rotation[block].transpose() * (world - m.bodies.position[block]);
  }
  static std::uint64_t key(std::size_t a, std::size_t b) { return (std::uint64_t{a} << 32) | std::uint64_t{b}; }

  void index() {
    by_pair_.clear();
    for (std::uint32_t k = 0; k < joints_.size(); ++k) by_pair_[key(joints_[k].a, joints_[k].b)].push_back(k);
  }

  Joint* find(const model::Model& m, const ContactView& c) {
    const auto it = by_pair_.find(key(c.block_a, c.block_b));
    if (it == by_pair_.end()) return nullptr;
    const Vec3 x = local(m, c.block_a, c.position);
    Joint* best = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto k : it->second)
      if (const double d = (Vec3(joints_[k].local[0], joints_[k].local[1], joints_[k].local[2]) - x).squaredNorm(); d < nearest) {
        nearest = d;
        best = &joints_[k];
      }
    return best;
  }

  std::vector<Joint> joints_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_pair_;
};

}  // namespace blockdem::analysis
