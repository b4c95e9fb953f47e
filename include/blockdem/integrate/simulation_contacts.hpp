#pragma once
// Detecting the contacts again during a run and assigning a detection's contacts to the contact groups (rigid pairs)
// and the node groups (pairs with a deformable block). Members of Simulation, declared and documented in
// integrate/simulation.hpp, which includes this file after the class: include that one.

namespace blockdem {

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
template <bool Mixed>
void Simulation<Damping, Laws...>::redetect_and_update() {
  const auto stored = [&] {
    const EnergyReport e = energy_terms();
    return e.elastic + e.viscous + e.slip;
  };
  const double before = stored();
  if (detection_observer_) detection_observer_();
  const auto start = std::chrono::steady_clock::now();
  if constexpr (Mixed) {
    move_proxies(*model_);
    assign_all(model::detect_contacts(model_->bodies, settings_), /*keep_history=*/true);
  } else {
    assign_contacts(model::detect_contacts(model_->bodies, settings_), /*keep_history=*/true);
  }
  detection_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for_each_group([&](auto& g) { contact_pass(g, model_->bodies, damping_, 0.0, closure_inverse_omega_squared()); });
  if constexpr (Mixed) mixed_forces(0.0);
  contact_update_ += stored() - before;
  // One FrequencyBound per re-detection (its 6 x 6 eigenproblems per block are most of a violent run's detection
  // time): the timestep's hold and the closure impulse share it.
  set_closure_bound(hold_timestep());
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
void Simulation<Damping, Laws...>::assign_all(const std::vector<model::ContactCandidate>& candidates, bool keep_history) {
  if (!mixed_) {
    assign_contacts(candidates, keep_history);
    return;
  }
  std::vector<model::ContactCandidate> rigid, deformable;
  for (const auto& c : candidates)
    (model_->deformable.is_deformable(c.a) || model_->deformable.is_deformable(c.b) ? deformable : rigid).push_back(c);
  assign_contacts(rigid, keep_history);
  node_assignment_.assign(deformable_, *model_, deformable, [&](int ta, int tb) { return choose_properties(ta, tb); },
                          settings_, keep_history);
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
void Simulation<Damping, Laws...>::assign_contacts(const std::vector<model::ContactCandidate>& candidates,
                                                    bool keep_history) {
  const auto& b = model_->bodies;
  CarriedDissipation retired{retired_slip_, retired_viscous_};
  assignment_.assign(groups_, b, candidates, properties_, damping_, settings_, keep_history, retired);
  retired_slip_ = retired.slip;
  retired_viscous_ = retired.viscous;
  blocks_.detected_position = b.position;
  blocks_.detected_orientation = b.orientation;
  blocks_.detected_base_displacement = blocks_.base_displacement;
  update_redetection_distances();
  moved_since_detection_ = false;
  ++detections_;
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
auto Simulation<Damping, Laws...>::choose_properties(int ta, int tb) -> Properties {
  auto it = chosen_properties_.find({ta, tb});
  if (it == chosen_properties_.end()) it = chosen_properties_.emplace(std::make_pair(ta, tb), properties_(ta, tb)).first;
  return it->second;
}

template <damping::DampingPolicy Damping, contact::ContactLaw... Laws>
void Simulation<Damping, Laws...>::update_redetection_distances() {
  const auto& d = model_->deformable;
  blocks_.redetection_distance = model::redetection_distances(model_->bodies, blocks_.detected_position,
                                                              blocks_.detected_orientation, settings_,
                                                              [&](std::size_t i) { return d.is_deformable(i); });
}

}  // namespace blockdem
