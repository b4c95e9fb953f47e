#pragma once
// blockdem.Simulation's C++ side: a structure's simulation stepped from Python, whatever its damping policy. The
// explicit integrator is specialized at compile time for each policy (analysis::StudySimulation<D>); Stepper is the
// one virtual seam between those specializations and Python, crossed once per call (a run of many steps, a state
// read), never per step. The settling simulation is compiled in sim_settle.cpp, the dynamic ones in sim_viscous.cpp
// and sim_maxwell.cpp, so that the module's translation units compile in parallel.

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "bindings.hpp"

#include "blockdem/analysis/study.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/analysis/study_report.hpp"
#include "blockdem/integrate/contact_view.hpp"
#include "blockdem/integrate/energy.hpp"
#include "blockdem/integrate/frequency_bound.hpp"
#include "blockdem/integrate/run.hpp"

namespace blockdem::python {

/// A simulation as Python steps it.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Steps until the time reaches t_end (run_until's rule), calling poll about every 1024 steps; stops early, with
  /// interrupted set, when blockdem::interrupted() (Python's Ctrl-C, seen by poll).
  virtual RunSummary run_until(double t_end, const std::function<void()>& poll, bool progress) = 0;
  virtual double time() const = 0;
  virtual double timestep() const = 0;
  virtual double critical_timestep() const = 0;
  virtual long long steps() const = 0;
  virtual EnergyReport energy() const = 0;
  virtual double unbalanced_force_ratio() const = 0;
  virtual std::size_t contact_points() const = 0;
  virtual void visit_contacts(const std::function<void(const ContactView&)>& f) const = 0;
};

/// Stepper over a simulation of type Sim.
template <class Sim>
class StepperOf : public Stepper {
 public:
  template <class... Args>
  explicit StepperOf(Args&&... args) : sim(std::forward<Args>(args)...) {}

  RunSummary run_until(double t_end, const std::function<void()>& poll, bool progress) override {
    long long n = 0;
    RunOptions o;
    o.progress = progress;
    o.label = "simulation";
    return blockdem::run_until(sim, t_end, [&] {
      if ((++n & 1023) == 0 && poll) poll();
    }, o);
  }
  double time() const override { return sim.time(); }
  double timestep() const override { return sim.timestep(); }
  double critical_timestep() const override { return sim.critical_timestep(); }
  long long steps() const override { return sim.steps(); }
  EnergyReport energy() const override { return sim.energy(); }
  double unbalanced_force_ratio() const override { return sim.unbalanced_force_ratio(); }
  std::size_t contact_points() const override { return sim.contact_points(); }
  void visit_contacts(const std::function<void(const ContactView&)>& f) const override { sim.visit_contacts(f); }

  Sim sim;
};

/// The structure's simulation under local damping, for settling (bind_simulation.cpp compiles it).
class Settling final : public StepperOf<analysis::StudySimulation<damping::Local>> {
 public:
  using StepperOf::StepperOf;
};

/// What the study chooses for the dynamic run before settling (analysis::with_settled_structure): the damping policy,
/// its timestep and the factory of the dynamic simulation, continued from the settling one.
struct DynamicPlan {
  double unscaled_dt = 0;  // s, the policy's timestep without density scaling
  double target_dt = 0;    // s, the timestep it runs at
  std::function<std::unique_ptr<Stepper>(Settling&, const analysis::Structure&, analysis::StudyResult&)> make;
};

/// The plan of the options' damping: maxwell (sim_maxwell.cpp) or the others (sim_viscous.cpp). `r` receives the
/// damping's description and the timestep's factor and unscaled value, as the study fills them.
DynamicPlan plan_maxwell(Settling& settle, const FrequencyBound& bound, const analysis::StudyOptions& o, analysis::StudyResult& r);
DynamicPlan plan_viscous(Settling& settle, const FrequencyBound& bound, const analysis::StudyOptions& o, analysis::StudyResult& r);

/// The plan of damping policy D (the study's steps, analysis/study.hpp): its timestep now, its simulation later.
template <class D>
DynamicPlan plan_for(Settling& settle, const FrequencyBound& bound, D policy, const analysis::StudyOptions& o, analysis::StudyResult& r) {
  r.damping.scheme = analysis::name(o.damping);
  if constexpr (damping::damps_velocities<D>()) r.damping.frame = damping::name(o.damping_frame);
  const auto t = analysis::choose_dynamic_timestep(settle.sim, bound, policy, o, r.model.free_mass, r.timestep);
  DynamicPlan plan;
  plan.unscaled_dt = t.unscaled;
  plan.target_dt = t.target;
  plan.make = [policy, target = t.target, frame = o.damping_frame](Settling& from, const analysis::Structure& s, analysis::StudyResult& result) {
    auto dynamic = std::make_unique<StepperOf<analysis::StudySimulation<D>>>(from.sim, policy);
    dynamic->sim.set_damping_frame(frame);
    analysis::set_dynamic_timestep(dynamic->sim, target, s, result.timestep);
    return std::unique_ptr<Stepper>(std::move(dynamic));
  };
  return plan;
}

template <class D>
inline constexpr bool is_maxwell = false;
template <int N>
inline constexpr bool is_maxwell<damping::Maxwell<N>> = true;

/// The plan of the options' damping if it is of the kind this translation unit compiles (Maxwell or not): the others'
/// simulations are not instantiated here.
template <bool maxwell>
DynamicPlan plan_of_kind(Settling& settle, const FrequencyBound& bound, const analysis::StudyOptions& o, analysis::StudyResult& r) {
  std::string description;
  DynamicPlan plan = analysis::with_damping_policy(o, description, [&]<class D>(D policy) -> DynamicPlan {
    if constexpr (is_maxwell<D> == maxwell)
      return plan_for(settle, bound, policy, o, r);
    else
      throw std::logic_error(maxwell ? "plan_maxwell: not a Maxwell scheme" : "plan_viscous: a Maxwell scheme");
  });
  r.damping.description = description;
  return plan;
}

}  // namespace blockdem::python
