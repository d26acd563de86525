// A method's map as plain data (estimate frame): what the coverage metric, pictures, map.ply and
// the determinism hash need, whatever the method's own representation (spheres, voxels, ...).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// One element of a method's free space, as the coverage metric reads it (estimate frame): its
/// xy footprint marks the columns whose nodes it covers — a sphere's disk, or a free cell's
/// axis-aligned square.
struct FreeSpaceElement {
  enum class Footprint { kDisk, kSquare };
  uint64_t id = 0;  ///< stable while the element lives (true-frame coverage)
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;  ///< the disk's radius, or half the square's side
  Footprint footprint = Footprint::kDisk;
};

/// Map contents for drawing and hashing, in the estimate frame.
struct ExplorerSnapshot {
  using Disk = FreeSpaceElement;
  struct Pose2 {
    Vec3 position;
    double yaw_rad;
  };
  std::vector<FreeSpaceElement> free_space;  ///< spheres, or free cells (square footprints)
  std::vector<Vec3> obstacles;               ///< obstacle points / occupied cells
  std::vector<Vec3> frontiers;
  std::vector<Pose2> viewpoints;  ///< current candidate goals
  std::vector<Pose2> visited;     ///< VPB markers
  std::optional<Pose2> goal;      ///< the active goal
  std::vector<Vec3> path;         ///< the last path sent (vehicle first)
};

}  // namespace msb
