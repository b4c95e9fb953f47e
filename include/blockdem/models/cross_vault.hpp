#pragma once
// The full-scale brick cross vault of the LNEC shake-table test (paper Sect. 2 and 3.2, Fig. 1, 6; Tables 1-2) as a
// parametric generator: the four webs of two intersecting barrel vaults in brick courses trimmed at the groins, the
// corner infill, piers, tie anchors, slab and steel frame, each block tagged with its component; materials, the
// joint law of every component pair, the steel ties and the monitor points of the test. A plain description that
// build_rigid_model() turns into a model::Model and check_assembly() checks (overlaps, contacts, masses).
//
// Frame: origin at the centre of the plan on the slab's top face, x east-west (transverse), y north-south (the
// excitation direction, paper Sect. 2), z up. Barrel A has its axis along y and forms the north and south webs,
// barrel B has its axis along x and forms the east and west webs; they intersect on the diagonal planes x = +-y.
//
// One header per job: the description (components, materials, joints, options, monitor points), the geometry of the
// barrels and courses, the generator, and the checks.

#include "blockdem/models/cross_vault_check.hpp"
#include "blockdem/models/cross_vault_description.hpp"
#include "blockdem/models/cross_vault_generator.hpp"
#include "blockdem/models/cross_vault_geometry.hpp"
