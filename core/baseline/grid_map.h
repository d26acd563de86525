// The grid baseline's map (architecture §9): an OctoMap occupancy octree at 0.5 m built from
// SLAM points. Each update inserts the frame's points as one scan from the estimated camera
// position, with the reference's range rules:
//   - a point within max_range_m marks its cell occupied;
//   - every ray clears the cells it crosses as free, up to the point or free_ray_length_m,
//     whichever is closer (a point beyond max_range_m therefore gives free space only);
//   - a cell hit by some point in the scan is not also cleared by another ray of the scan.
// Insertion is our own loop over OctoMap's ray keys in sorted key order (not insertPointCloud),
// so the result never depends on threads or hash-set order.
#pragma once

#include <memory>
#include <vector>

#include <octomap/OcTree.h>

#include "core/common/aabb.h"
#include "core/common/config_check.h"
#include "core/common/messages.h"

namespace msb {

/// Grid map settings (reference values).
struct GridMapConfig {
  double resolution_m = 0.5;          ///< leaf size
  double max_range_m = 20.0;          ///< points farther give no occupied cell
  double free_ray_length_m = 15.0;    ///< rays clear free space up to this far
  double prob_hit = 0.7;              ///< OctoMap sensor model (its defaults)
  double prob_miss = 0.4;
  double clamp_min = 0.1192;
  double clamp_max = 0.971;

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A free or occupied leaf of the octree (after pruning: any size ≥ the resolution).
struct GridLeaf {
  Vec3 centre;
  double size_m;
  uint64_t id;   ///< packed key and depth, stable while the leaf exists
};

/// Counts of one map update.
struct GridUpdateStats {
  int points = 0, occupied_cells = 0, free_cells = 0;
};

/// OctoMap occupancy grid.
class GridMap {
 public:
  /// Throws ConfigError.
  explicit GridMap(const GridMapConfig& config);

  /// Inserts one frame of SLAM points as a scan from the frame's estimated camera position.
  GridUpdateStats insert(const SlamPointsFrame& frame);
  /// Inserts points as a scan from `origin` (tests).
  GridUpdateStats insertScan(const Vec3& origin, const std::vector<Vec3>& points);

  /// Occupancy of the cell containing p: +1 occupied, 0 free, −1 unknown.
  int occupancy(const Vec3& p) const;
  /// True if some occupied cell comes within r of p (distance to the cell's box).
  bool occupiedWithin(const Vec3& p, double r) const;
  /// Free / occupied leaves (iteration order of the octree: deterministic).
  std::vector<GridLeaf> leaves(bool occupied) const;
  /// The octree (read-only).
  const octomap::OcTree& tree() const { return *tree_; }
  /// The octree for hand-built maps (tests).
  octomap::OcTree& mutableTree() { return *tree_; }
  /// The configuration.
  const GridMapConfig& config() const { return config_; }

 private:
  GridMapConfig config_;
  std::unique_ptr<octomap::OcTree> tree_;
};

}  // namespace msb
