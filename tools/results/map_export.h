// A run's map (map.ply, msbench's ASCII map: free-space spheres or cells with their radius,
// obstacle points, frontiers) as binary PLYs that name their frame, coloured by kind: one in
// the VIO frame the method mapped in (ROS odom), one moved into the world frame (ROS map) by
// the estimate → truth correction at the end of the run (docs/interop.md).
#pragma once

#include <optional>
#include <string>

#include "core/common/types.h"

namespace msb {

/// The two PLY texts of one map.ply and what they hold.
struct MapPlys {
  std::string odom;   ///< as mapped, VIO frame
  std::string world;  ///< moved by T_true_est; "" when no correction is known
  int free_space = 0, obstacles = 0, frontiers = 0;
};

/// The PLYs of `ply` (a map.ply msbench wrote; `where` names it in errors), the world-frame one
/// moved by `T_true_est` when given. Throws InputFileError (exit 2) naming the file and line
/// for a header msbench does not write, a short file or a cell that is not a finite number.
MapPlys mapPlysFromMapPly(const std::string& ply, const std::string& where, const std::optional<Pose>& T_true_est);

}  // namespace msb
