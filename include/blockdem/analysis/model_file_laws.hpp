#pragma once
// The joint laws of a model file (docs/model-file.md, "joints"): one entry per pair of groups, with the law and its
// parameters, and the contact-point grid of the pair. Reads one entry into a contact::JointLaw; model_file.hpp
// assembles the table.
//
//   {"between": ["wall", "wall"], "law": "softening", "preset": "paper_table1", "contact_point_spacing": 0.03}
//   {"between": ["wall", "table"], "law": "mohr_coulomb", "normal_stiffness": 1e10, "shear_stiffness": 5e9,
//    "friction_angle_deg": 30}
//   {"between": ["*", "*"], "law": "elastic", "normal_stiffness": 1e10, "shear_stiffness": 5e9}

#include <algorithm>
#include <string>
#include <vector>

#include "blockdem/contact/elastic.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/contact/mohr_coulomb.hpp"
#include "blockdem/contact/softening.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/io/json_fields.hpp"

namespace blockdem::analysis::detail {

inline const io::Range stiffness_range{0, 1e16, true, false, "Pa/m"};
inline const io::Range strength_range{0, 1e10, false, false, "Pa"};

/// An angle given as "<key>_deg" or "<key>_rad" (one of them; rad: exactly as written, for files written by
/// programs), in radians; `fallback` (rad) if neither is given and fallback >= 0, else an error.
inline double angle_field(const io::JsonFields& f, const std::string& key, double fallback, double max_deg) {
  const auto deg = f.find(key + "_deg"), rad = f.find(key + "_rad");
  if (deg && rad) io::field_error(*rad, f.path(key + "_rad"), "give " + key + "_deg or " + key + "_rad, not both");
  if (deg) return io::number_value(*deg, f.path(key + "_deg"), {0, max_deg, false, false, "degrees"}) * pi / 180.0;
  if (rad) return io::number_value(*rad, f.path(key + "_rad"), {0, max_deg * pi / 180.0, false, false, "rad"});
  if (fallback >= 0) return fallback;
  io::field_error(f.object(), f.path(), "\"" + key + "_deg\" is missing (the angle in degrees, [0, " + num(max_deg) + "])");
}

/// The law of a "joints" entry (its "between" and "contact_point_spacing" are read by the caller). Parameters the
/// law refuses are reported at the entry, with the law's own message.
inline contact::JointLaw read_joint_law(const io::JsonFields& f) {
  const std::string law = io::JsonFields::choice_value<std::string>(
      f.required("law", "elastic, mohr_coulomb or softening"), f.path("law"),
      {{"elastic", "elastic"}, {"mohr_coulomb", "mohr_coulomb"}, {"softening", "softening"}});
  auto refused = [&](const InvalidArgument& e) -> contact::JointLaw { io::field_error(f.object(), f.path(), e.what()); };
  // The keys each law takes (besides "between", "law" and "contact_point_spacing").
  const std::vector<std::string> elastic{"normal_stiffness", "shear_stiffness"};
  std::vector<std::string> keys = elastic;
  if (law != "elastic")
    for (const char* k : {"tensile_strength", "cohesion", "friction_angle_deg", "friction_angle_rad", "residual_tensile_strength",
                          "residual_cohesion", "residual_friction_angle_deg", "residual_friction_angle_rad"})
      keys.emplace_back(k);
  if (law == "softening")
    for (const char* k : {"preset", "compressive_strength", "residual_compressive_strength", "fracture_energy_tension",
                          "fracture_energy_shear", "fracture_energy_compression", "cap_shear_factor", "damping_damage_limit",
                          "unit_modulus", "mortar_modulus", "mortar_thickness", "poisson_ratio"})
      keys.emplace_back(k);
  for (const auto& [key, value] : f.object().as_object())
    if (key != "between" && key != "law" && key != "contact_point_spacing" && std::find(keys.begin(), keys.end(), key) == keys.end())
      io::field_error(value, f.path(key), "the law " + law + " takes no \"" + key + "\" (it takes: " + io::join_words(keys) + ")");
  if (law == "elastic") {
    const double kn = f.required_number("normal_stiffness", stiffness_range), ks = f.required_number("shear_stiffness", stiffness_range);
    return contact::Elastic::Parameters(kn, ks);
  }
  if (law == "mohr_coulomb") {
    const double kn = f.required_number("normal_stiffness", stiffness_range), ks = f.required_number("shear_stiffness", stiffness_range);
    const double phi = angle_field(f, "friction_angle", -1, 89);
    const double phi_r = angle_field(f, "residual_friction_angle", phi, 89);
    try {
      return contact::MohrCoulomb::Parameters(kn, ks, f.number("tensile_strength", 0, strength_range), f.number("cohesion", 0, strength_range),
                                              phi, f.number("residual_tensile_strength", 0, strength_range),
                                              f.number("residual_cohesion", 0, strength_range), phi_r);
    } catch (const InvalidArgument& e) {
      return refused(e);
    }
  }
  // Elasto-softening (Fig. 5C). A preset gives every value of the paper's Table 1 (the LNEC vault's mortar joints);
  // without one the strengths are required. Stiffnesses: given, or eq. 7 from the unit and mortar; fracture
  // energies: given, or eq. 4-6 from the strengths.
  contact::MasonryJointProperties m;  // the paper's Table 1
  const bool preset = f.has("preset");
  if (preset) io::JsonFields::choice_value<int>(*f.find("preset"), f.path("preset"), {{"paper_table1", 1}});
  auto strength = [&](const char* key, double table1) {
    return preset ? f.number(key, table1, strength_range) : f.required_number(key, strength_range);
  };
  m.tensile_strength = strength("tensile_strength", m.tensile_strength);
  m.compressive_strength = preset ? f.number("compressive_strength", m.compressive_strength, {0, 1e10, true, false, "Pa"})
                                  : f.required_number("compressive_strength", {0, 1e10, true, false, "Pa"});
  m.cohesion = strength("cohesion", m.cohesion);
  m.friction_angle = angle_field(f, "friction_angle", preset ? m.friction_angle : -1, 89);
  contact::JointStiffness k;
  const bool eq7 = f.has("unit_modulus") || f.has("mortar_modulus") || f.has("mortar_thickness") || f.has("poisson_ratio");
  if (f.has("normal_stiffness") || f.has("shear_stiffness") || (!preset && !eq7)) {
    if (eq7)
      io::field_error(f.object(), f.path(), "give the stiffnesses or the unit and mortar of eq. 7 (unit_modulus, mortar_modulus, "
                                            "mortar_thickness, poisson_ratio), not both");
    k.normal = f.required_number("normal_stiffness", stiffness_range);
    k.shear = f.required_number("shear_stiffness", stiffness_range);
  } else {
    if (!preset)  // eq. 7 without the preset: all four, none taken silently from Table 1
      for (const char* key : {"unit_modulus", "mortar_modulus", "mortar_thickness", "poisson_ratio"})
        (void)f.required(key, "eq. 7 needs unit_modulus, mortar_modulus, mortar_thickness and poisson_ratio");
    m.unit_modulus = f.number("unit_modulus", m.unit_modulus, {0, 1e13, true, false, "Pa"});
    m.mortar_modulus = f.number("mortar_modulus", m.mortar_modulus, {0, 1e13, true, false, "Pa"});
    m.mortar_thickness = f.number("mortar_thickness", m.mortar_thickness, {0, 1, true, false, "m"});
    m.poisson_ratio = f.number("poisson_ratio", m.poisson_ratio, {-1, 0.5, true, true, ""});
    try {
      k = contact::joint_stiffness_from_eq7(m.unit_modulus, m.mortar_modulus, m.mortar_thickness, m.poisson_ratio);
    } catch (const InvalidArgument& e) {
      return refused(e);
    }
  }
  contact::ElastoSoftening::Strengths s;
  s.tensile = m.tensile_strength;
  s.cohesion = m.cohesion;
  s.friction_angle = m.friction_angle;
  s.compressive = m.compressive_strength;
  s.residual_tensile = f.number("residual_tensile_strength", 0, strength_range);
  s.residual_cohesion = f.number("residual_cohesion", 0, strength_range);
  s.residual_friction_angle = angle_field(f, "residual_friction_angle", s.friction_angle, 89);
  s.residual_compressive = f.number("residual_compressive_strength", 0, strength_range);
  const io::Range energy{0, 1e9, true, false, "J/m^2"};
  try {
    // Each default from its equation only if the value is not given (eq. 6 refuses f_c beyond its range).
    const double gf1 = f.has("fracture_energy_tension") ? f.required_number("fracture_energy_tension", energy)
                                                        : contact::fracture_energy_tension_eq4(s.tensile);
    const contact::ElastoSoftening::FractureEnergies g{
        gf1, f.has("fracture_energy_shear") ? f.required_number("fracture_energy_shear", energy) : contact::fracture_energy_shear_eq5(gf1),
        f.has("fracture_energy_compression") ? f.required_number("fracture_energy_compression", energy)
                                             : contact::fracture_energy_compression_eq6(s.compressive)};
    return contact::ElastoSoftening::Parameters(k, s, g, f.number("cap_shear_factor", 9.0, {0, 1e3, false, false, ""}),
                                                f.number("damping_damage_limit", 0.5, {0, 1, true, false, ""}));
  } catch (const InvalidArgument& e) {
    return refused(e);
  }
}

}  // namespace blockdem::analysis::detail
