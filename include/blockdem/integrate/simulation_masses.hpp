#pragma once
// The timestep and the masses: setting the timestep, partial density scaling, static mass scaling, the
// real masses back, and the hold against contacts that appear during a run (eq. 1-3, 11, 20; Sect. 3.2). Members of
// Simulation, declared and documented in integrate/simulation.hpp, which includes this file after the class: include
// that one.

namespace blockdem {

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
template <class Factor>
double Simulation<Damping, Laws...>::density_scaling_mass(double target_dt, Factor timestep_factor) const {
  if (!bounded_frequency()) {  // static masses: the plan follows the estimate, not the bound
    const MassPlan plan = plan_masses(*model_, groups_, deformable(), real_masses(), false, target_dt, safety_factor(),
                                      MassRule::raise_only, timestep_factor);
    return added_mass(plan);
  }
  return density_scaling_mass(target_dt, timestep_factor, frequency_bound());
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
template <class Factor>
double Simulation<Damping, Laws...>::density_scaling_mass(double target_dt, Factor timestep_factor, const FrequencyBound& bound) const {
  const MassPlan plan = plan_masses(*model_, groups_, deformable(), real_masses(), bounded_frequency(), target_dt,
                                    safety_factor(), MassRule::raise_only, timestep_factor, &bound);
  return added_mass(plan);
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
double Simulation<Damping, Laws...>::added_mass(const MassPlan& plan) const {
  double added = 0;
  for (std::size_t i = 0; i < plan.block_mass.size(); ++i) added += plan.block_mass[i] - model_->bodies.mass[i];
  for (std::size_t i = 0; i < plan.node_mass.size(); ++i) added += plan.node_mass[i] - model_->deformable.nodes.mass[i];
  return added;
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
void Simulation<Damping, Laws...>::restore_real_masses() {
  auto& b = model_->bodies;
  auto& nd = model_->deformable.nodes;
  if (mixed_) {  // blocks are scaled only in the mixed step, which keeps their real masses
    b.mass = deformable_.rigid_real_mass;
    b.principal_inertia = deformable_.rigid_real_inertia;
    nd.mass = nd.real_mass;
    for (std::size_t i = 0; i < nd.size(); ++i) deformable_.node_inverse_mass[i] = 1.0 / nd.mass[i];
  }
  blocks_.set_inverse_masses(b);
  static_masses_ = false;
  density_safety_ = 0;
  set_timestep(default_timestep());
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
void Simulation<Damping, Laws...>::set_timestep(double dt, TimestepCheck check) {
  const double critical = critical_timestep();
  if (!(dt > 0) || !std::isfinite(dt))
    throw InvalidArgument("timestep must be > 0 s and finite, got " + std::to_string(dt));
  if (check == TimestepCheck::checked && dt > critical)
    throw InvalidArgument("timestep " + std::to_string(dt) + " s exceeds the critical timestep " +
                          std::to_string(critical) + " s (eq. 1 with the damping factor of eq. 11/20)");
  dt_ = dt;
  timestep_margin_ = check == TimestepCheck::checked && std::isfinite(critical) ? dt / critical : 0.0;
  if constexpr (damping::PreparedDamping<Damping>) damping_.prepare(dt_);
  refresh_closure_bound();
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
double Simulation<Damping, Laws...>::hold_timestep() {
  if (!bounded_frequency()) return 0.0;  // static masses (settling): the estimate's wide margin, and local damping
  if (density_safety_ > 0) {
    ++hold_.checks;
    const MassPlan plan = plan_masses(*model_, groups_, deformable(), real_masses(), bounded_frequency(), dt_, density_safety_,
                                      MassRule::raise_only, [&](double omega) { return damping_.timestep_factor(omega); });
    const MassRaise raised = raise_masses(*model_, plan, deformable_.node_inverse_mass, blocks_);
    if (raised.nodes + raised.blocks == 0) return plan.omega_max;
    ++hold_.raises;
    hold_.raised_nodes += raised.nodes;
    hold_.raised_blocks += raised.blocks;
    hold_.added_mass += raised.added;
    hold_.kinetic_energy += raised.kinetic;
    contact_update_ += raised.kinetic;
    return omega_max();
  }
  const double omega = omega_max();
  if (!(timestep_margin_ > 0)) return omega;
  ++hold_.checks;
  const double critical = critical_timestep(omega);
  if (!(dt_ > timestep_margin_ * critical)) return omega;
  const double margin = timestep_margin_;
  set_timestep(margin * critical);
  timestep_margin_ = margin;
  ++hold_.reductions;
  hold_.smallest_dt = dt_;
  return omega;
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
DensityScaling Simulation<Damping, Laws...>::scale_masses(double target_dt, double safety_factor, MassRule rule) {
  const std::string what = rule == MassRule::raise_only ? "density scaling" : "static mass scaling";
  if (!(target_dt > 0) || !std::isfinite(target_dt))
    throw InvalidArgument(what + ": the target timestep must be > 0 s and finite, got " + std::to_string(target_dt));
  if (!(safety_factor > 0 && safety_factor <= 1))
    throw InvalidArgument(what + ": the safety factor must be in (0, 1], got " + std::to_string(safety_factor));
  DensityScaling r;
  r.target_dt = target_dt;
  r.dt_critical_unscaled = critical_timestep();
  // Static masses: the one frequency without the policy's factor (Local's 1 / sqrt(1 + c) lies inside the
  // estimate's margin: omega dt = 2 safety = 1 < 2 / sqrt(1.8) for a block on its own).
  const MassPlan plan = plan_masses(*model_, groups_, deformable(), real_masses(), bounded_frequency(), target_dt,
                                    safety_factor, rule, [&](double omega) {
                                      return rule == MassRule::exact ? 1.0 : damping_.timestep_factor(omega);
                                    });
  if (!mixed_) {  // the weight correction of scaled rigid blocks runs in the mixed path, which keeps the real masses
    mixed_ = true;
    deformable_.setup(*model_);
  }
  apply_mass_plan(*model_, plan, real_masses(), deformable_.node_inverse_mass, blocks_, r);
  static_masses_ = rule == MassRule::exact;
  density_safety_ = rule == MassRule::raise_only ? safety_factor : 0.0;
  r.dt_critical = critical_timestep();
  set_timestep(target_dt);
  r.dt = dt_;
  return r;
}

}  // namespace blockdem
