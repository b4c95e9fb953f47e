#pragma once
// One include for all of blockdem.

#include "blockdem/core/constexpr_math.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/damping/mass_proportional.hpp"
#include "blockdem/damping/maxwell.hpp"
#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/damping/rayleigh.hpp"
#include "blockdem/damping/stiffness_proportional.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/motion/acceleration_unit.hpp"
#include "blockdem/motion/arias.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/record.hpp"
#include "blockdem/motion/writers.hpp"
#include "blockdem/solve/levenberg_marquardt.hpp"
