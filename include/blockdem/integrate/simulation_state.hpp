#pragma once
// The checkpoint state of Simulation: the one list of its saved fields (declared and documented in
// integrate/simulation.hpp, which includes this file after the class: include that one).

namespace blockdem {

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
template <class Self, class Archive>
void Simulation<Damping, Laws...>::visit_state(Self& s, Archive& ar) {
  ar.check("the simulation type (damping policy, joint laws)", io::type_name<Simulation>());
  ar("model", *s.model_);
  static_assert(io::plain_checkpoint_value<Damping>, "a checkpoint saves the damping policy as its bytes");
  ar("damping policy", s.damping_);
  ar("mixed step", s.mixed_);
  ar("deformable state", s.deformable_);
  std::apply([&](auto&... g) { (ar("contact group", g), ...); }, s.groups_);
  ar("timestep", s.dt_);
  ar("time", s.time_);
  ar("steps", s.steps_);
  ar("steps since the last detection check", s.steps_since_check_);
  ar("detections", s.detections_);
  ar("pending increment", s.pending_increment_);
  ar("moved since the last detection", s.moved_since_detection_);
  ar("static masses", s.static_masses_);
  auto& blocks = s.blocks_;
  ar.same_size("block kinetic energies", blocks.kinetic);
  ar.same_size("block gravity work", blocks.gravity_work);
  ar.same_size("block base work", blocks.base_work);
  ar.same_size("block viscous work", blocks.viscous);
  ar.same_size("block frame work", blocks.frame_work);
  ar("damping frame", s.damping_frame_);
  ar.same_size("block inverse masses", blocks.inverse_mass);
  ar.same_size("block inverse inertias", blocks.inverse_inertia);
  ar.same_size("block positions at the last detection", blocks.detected_position);
  ar.same_size("block orientations at the last detection", blocks.detected_orientation);
  ar("base displacement", blocks.base_displacement);
  ar("base displacement at the last detection", blocks.detected_base_displacement);
  ar("energy reference", s.energy0_);
  ar("energy reference pending", s.energy_reference_pending_);
  ar("retired slip", s.retired_slip_);
  ar("retired viscous work", s.retired_viscous_);
  ar("energy added by contact updates", s.contact_update_);
  ar("timestep of the last move", s.last_move_dt_);
  ar("density scaling safety factor", s.density_safety_);
  ar("timestep margin", s.timestep_margin_);
  ar("timestep hold", s.hold_);
  ar("closure impulse bound", s.closure_inverse_omega_squared_);
}

}  // namespace blockdem
