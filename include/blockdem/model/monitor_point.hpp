#pragma once
// A named point whose motion a study records: on a rigid block it moves with the block, on a deformable one it
// follows the block's node nearest to it.

#include <cstddef>
#include <string>

#include "blockdem/core/types.hpp"

namespace blockdem::model {

struct MonitorPoint {
  std::string name;
  Vec3 position = Vec3::Zero();  // m, world, in the model as built
  std::size_t block = 0;         // the block it is attached to
};

}  // namespace blockdem::model
