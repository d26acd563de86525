// A method's map as plain data (estimate frame): what pictures, map.ply and the determinism
// hash need, whatever the method's own representation (spheres, voxels, ...).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// Map contents for drawing and hashing, in the estimate frame.
struct ExplorerSnapshot {
  struct Disk { uint64_t id; Vec3 centre; double radius; };
  struct Pose2 { Vec3 position; double yaw_rad; };
  std::vector<Disk> free_space;         ///< spheres (or free cells as their inscribed spheres)
  std::vector<Vec3> obstacles;          ///< obstacle points / occupied cells
  std::vector<Vec3> frontiers;
  std::vector<Pose2> viewpoints;        ///< current candidate goals
  std::vector<Pose2> visited;           ///< VPB markers
  std::optional<Pose2> goal;            ///< the active goal
  std::vector<Vec3> path;               ///< the last path sent (vehicle first)
};

}  // namespace msb
