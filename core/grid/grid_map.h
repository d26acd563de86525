// The grid baseline's map (architecture §9): an OctoMap occupancy octree at 0.5 m built from
// SLAM points. Each update inserts the frame's points as one scan from the estimated camera
// position, with the reference's range rules:
//   - a point within max_range_m marks its cell occupied;
//   - every ray clears the cells it crosses as free, up to the point or free_ray_length_m,
//     whichever is closer (a point beyond max_range_m therefore gives free space only);
//   - a cell hit by some point in the scan is not also cleared by another ray of the scan.
// Insertion is our own loop over OctoMap's ray keys in sorted key order (not insertPointCloud),
// so the result never depends on threads or hash-set order.
//
// insertion = confidence_weighted (Buck et al., "fuzzy" voxel map updates; docs/baseline.md):
// every point's occupied and free updates are its log-odds scaled by a weight in [0, 1], the
// product of the extrinsic quality of its two views (Eq. 3-9: the look directions A of the
// anchor camera and B of the current camera and their baseline D; Q = min(max(cos AB, 0),
// sin AD, sin BD)) and a depth confidence max(1 - a·2σ_depth/100, 0) (Eq. 10 with the spread of
// the depth estimate taken as ±σ). OctoMap accepts a log-odds value per update, so the weight
// scales it directly: the continuous limit of the paper's α-cut workaround (inserting a point
// once per confidence threshold it passes, N_t thresholds, each with l/N_t).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <octomap/OcTree.h>

#include "core/common/aabb.h"
#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/explorer/snapshot.h"

namespace msb {

/// Grid map settings (reference values).
struct GridMapConfig {
  double resolution_m = 0.5;        ///< leaf size
  double max_range_m = 20.0;        ///< points farther give no occupied cell
  double free_ray_length_m = 15.0;  ///< rays clear free space up to this far
  // The sensor model of the reference's mapper, mrs_octomap_server (its config/default.yaml, which
  // the reference's grid session does not override): a hit saturates a cell at once, a miss takes
  // a fifth of that away. OctoMap's own defaults are 0.7 / 0.4 / 0.1192 / 0.971.
  double prob_hit = 0.95;   ///< occupancy update of a point's cell
  double prob_miss = 0.45;  ///< free update of a cell a ray crosses
  double clamp_min = 0.3;   ///< clamping of the occupancy probability
  double clamp_max = 0.7;
  std::string insertion = "standard";        ///< standard | confidence_weighted
  double confidence_depth_gain_per_m = 5.0;  ///< a of Eq. 10 (confidence 0 at 2σ = 100/a m)
  /// Prune the octree as it updates (OctoMap's non-lazy update: eight equal sibling leaves become
  /// one cell twice the size), as the reference's mapper keeps its map; msbench's default keeps
  /// every 0.5 m leaf.
  bool prune = false;

  /// True for confidence-weighted insertion.
  bool weighted() const { return insertion == "confidence_weighted"; }
  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("resolution_m", s.resolution_m, Limits::range(0.05, 5.0));
    v.key("max_range_m", s.max_range_m, Limits::positive());
    v.key("free_ray_length_m", s.free_ray_length_m, Limits::positive());
    v.key("prob_hit", s.prob_hit, Limits::range(0.5, 1.0));
    v.key("prob_miss", s.prob_miss, Limits::range(0.0, 0.5));
    v.key("clamp_min", s.clamp_min, Limits::range(0.0, 0.5));
    v.key("clamp_max", s.clamp_max, Limits::range(0.5, 1.0));
    v.key("insertion", s.insertion, Choices{"standard", "confidence_weighted"});
    v.key("confidence_depth_gain_per_m", s.confidence_depth_gain_per_m, Limits::nonNegative());
    v.key("prune", s.prune);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A free or occupied leaf of the octree (after pruning: any size ≥ the resolution).
struct GridLeaf {
  Vec3 centre;
  double size_m;
  uint64_t id;  ///< packed key and depth, stable while the leaf exists
};

/// An update a scan made to a watched cell (GridMap::watch): which ray (the point's index in the
/// scan) set it hit or missed. Misses of a cell that the same scan hit are not made, so not listed.
struct WatchedUpdate {
  uint64_t key = 0;  ///< packed OcTreeKey of the cell
  int point = 0;     ///< index of the point whose ray made the update
  bool hit = false;  ///< true: the point's own cell (occupied update); false: crossed by its ray (free update)
};

/// Counts of one map update.
struct GridUpdateStats {
  int points = 0, occupied_cells = 0, free_cells = 0;
  double weight_sum = 0;  ///< sum of the points' weights (= points for standard insertion)
};

/// Extrinsic quality of two views (Buck et al. Eq. 3-9): look directions a and b of the two
/// cameras, baseline d between them. 1 = aligned views moved sideways; 0 = views apart by 90°
/// or more, or moved along a look direction.
double extrinsicQuality(const Vec3& a, const Vec3& b, const Vec3& d);

/// A SLAM point's insertion weight in [0, 1]: extrinsic quality of its anchor view and the
/// current view (optical axes, baseline between the camera centres) times the depth confidence
/// max(1 - gain·2σ/100, 0).
double confidenceWeight(const SlamPoint& p, const Pose& T_W_C, double depth_gain_per_m);

/// OctoMap occupancy grid.
class GridMap {
 public:
  /// Throws ConfigError.
  explicit GridMap(const GridMapConfig& config);

  /// Inserts one frame of SLAM points as a scan from the frame's estimated camera position.
  GridUpdateStats insert(const SlamPointsFrame& frame);
  /// Inserts points as a scan from `origin`; `weights` (empty = all 1) scale each point's
  /// log-odds updates (a cell touched by several rays takes the largest weight).
  GridUpdateStats insertScan(const Vec3& origin, const std::vector<Vec3>& points,
                             const std::vector<double>& weights = {});

  /// Occupancy of the cell containing p: +1 occupied, 0 free, −1 unknown.
  int occupancy(const Vec3& p) const;
  /// True if some occupied cell comes within r of p (distance to the cell's box).
  bool occupiedWithin(const Vec3& p, double r) const;
  /// Free / occupied leaves (iteration order of the octree: deterministic).
  std::vector<GridLeaf> leaves(bool occupied) const;
  /// The octree as liboctomap's binary format (.bt: free/occupied, the tree as it is, unpruned
  /// and unchanged).
  std::string binary() const;
  /// The octree (read-only).
  const octomap::OcTree& tree() const { return *tree_; }
  /// The configuration.
  const GridMapConfig& config() const { return config_; }

  /// Cells whose updates each scan lists in lastWatched() (an analysis aid: the collision audit of
  /// the grid baseline; empty by default, then insertion does no extra work).
  void watch(std::vector<uint64_t> keys);
  /// The updates the last scan made to watched cells, in ray order.
  const std::vector<WatchedUpdate>& lastWatched() const { return last_watched_; }
  /// The packed key of the cell containing p (nullopt outside the tree's range).
  std::optional<uint64_t> keyOf(const Vec3& p) const;
  /// The centre of the cell of a packed key.
  Vec3 centreOf(uint64_t key) const;
  /// The occupancy probability of the cell of a packed key (nullopt: unknown).
  std::optional<double> probabilityOf(uint64_t key) const;

 private:
  friend struct GridMapTestSeam;  // hand-built maps in tests (grid_map_test_seam.h)

  // Records the updates of watched keys of one ray (misses of keys hit in the scan dropped later).
  void noteWatched(const octomap::KeyRay& ray, size_t point, const std::optional<uint64_t>& hit_key);

  GridMapConfig config_;
  std::unique_ptr<octomap::OcTree> tree_;
  std::vector<uint64_t> watched_;  ///< sorted
  std::vector<WatchedUpdate> last_watched_;
};

/// The grid methods' predicted-path check: true if the first `ahead_m` of the polyline
/// from -> path[1] -> ... (path[0] is where it was sent from) come within `clearance_m` of an
/// occupied cell, sampled every 0.25 m.
bool pathNearOccupied(const GridMap& map, const std::vector<Vec3>& path, const Vec3& from, double ahead_m,
                      double clearance_m);

/// The free leaves as free-space elements (id, centre, half the leaf size, square footprint:
/// their real size after pruning) for the coverage metric and pictures.
std::vector<FreeSpaceElement> freeLeaves(const GridMap& map);

/// A grid method's snapshot: the free leaves (freeLeaves), the occupied leaves' centres as
/// obstacle points, the goal (if any) and the last path.
ExplorerSnapshot gridSnapshot(const GridMap& map, const std::optional<Vec3>& goal, const std::vector<Vec3>& path);

/// The waypoints of a grid path (its points after the first, the vehicle's own cell), each
/// flown facing the direction of travel.
std::vector<Waypoint> pathWaypoints(const std::vector<Vec3>& points);

}  // namespace msb
