// Grid A* for the baseline (architecture §9): a dense traversability grid over the exploration
// box, aligned with the OctoMap cells, rebuilt from the map before planning. A cell is blocked
// when its centre lies within `clearance_m` of an occupied cell's centre; with
// `unknown_is_occupied` (the default; the paper: "the same distance from obstacles and unknown
// space as MonoSpheres") also when it is unknown or within `unknown_clearance_m` (by default
// `clearance_m`) of an unknown cell.
// With it off, unknown space is traversable (what our design notes record of the reference
// code; measured to crash into unseen walls and ceilings within a minute, docs/baseline.md). A* (26-neighbour moves,
// Euclidean heuristic, ties broken by cell index) searches from the vehicle's cell; when the goal cannot be reached it
// returns the path to the reached cell closest to the goal. A vehicle that finds itself in blocked cells (new points
// appeared close to it) may leave through blocked cells within `escape_radius_m` of its start, but never through cells
// within `escape_clearance_m` of an occupied cell (nor unknown ones when unknown is occupied). The path is shortened by
// line-of-sight shortcuts over traversable cells.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/aabb.h"
#include "core/common/config_fields.h"
#include "core/grid/grid_map.h"

namespace msb {

/// Grid planner settings.
struct GridPlannerConfig {
  double clearance_m = 1.5;           ///< distance kept from occupied cells
  bool unknown_is_occupied = true;    ///< unknown cells and their clearance blocked (the paper; false: traversable)
  double unknown_clearance_m = -1.0;  ///< distance kept from unknown cells when they are blocked (< 0: clearance_m;
                                      ///< 0: only known free cells, star discovery's rule)
  double escape_radius_m = 2.0;       ///< from a blocked start, blocked cells this close are passable ...
  double escape_clearance_m = 0.75;   ///< ... unless this close to an occupied cell
  int max_expansions = 500000;        ///< A* node budget per search
  /// > 0: plan on mrs_octomap_planner's planning tree of this leaf size instead of the map's
  /// cells (astar_planner.cpp createPlanningTree, 428-466): the map's leaves within
  /// kPlanningTreeSubmapM of the start, each keyed by its centre in a tree of this resolution at
  /// its own depth, then expanded. A cell no leaf landed in is unknown. 0: the map's cells.
  double planning_tree_resolution_m = 0.0;
  /// > 0: mrs_octomap_planner's `timeout_threshold` (astar_planner.cpp findPath, 95-190): the
  /// clock starts before the planning tree is built, and the search stops when this much time
  /// has passed, ending at its best node so far. The time is modelled, never measured: the
  /// planning tree's work and each expansion cost what they cost liboctomap and dynamicEDT3D on
  /// msbench's reference machine (kGridBudgetCosts, results/grid_budget/). 0: no time budget.
  double time_budget_s = 0.0;
  /// The reference's A* rules (astar_planner.cpp findPath, 150-260): a cell's cost is fixed when
  /// it is first reached (no re-opening), and a search that does not reach the goal ends at the
  /// lowest-f cell reached, or, when that is the start, at the reached cell closest to the goal
  /// (reached: generated, not only expanded). false: msbench's A* (cells re-opened when a
  /// cheaper way is found; the expanded cell closest to the goal).
  bool reference_search = false;

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("clearance_m", s.clearance_m, Limits::nonNegative());
    v.key("unknown_is_occupied", s.unknown_is_occupied);
    v.key("escape_radius_m", s.escape_radius_m, Limits::nonNegative());
    v.key("escape_clearance_m", s.escape_clearance_m, Limits::nonNegative());
    v.key("unknown_clearance_m", s.unknown_clearance_m, Limits::range(-1.0, std::numeric_limits<double>::infinity()));
    v.key("max_expansions", s.max_expansions, Limits::range(1000, 100000000));
    v.key("planning_tree_resolution_m", s.planning_tree_resolution_m, Limits::range(0.0, 10.0));
    v.key("time_budget_s", s.time_budget_s, Limits::range(0.0, 60.0));
    v.key("reference_search", s.reference_search);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The planning tree's reach from the start (mrs_octomap_planner `distance_transform/submap_distance`), m.
inline constexpr double kPlanningTreeSubmapM = 20.0;

/// What mrs_octomap_planner's work costs on msbench's reference machine (the 2-core VM of
/// docs/compute.md), measured with liboctomap and Debian's dynamicEDT3D doing the reference's
/// steps (results/grid_budget/measure.cc, output.txt): the time budget charges these.
struct GridBudgetCosts {
  double per_leaf_s = 0.25e-6;  ///< a map leaf keyed into the planning tree (both walks)
  double per_cell_s = 1.2e-6;  ///< a cell of the expanded tree: expanded, in the distance field, set in the binary tree
  double per_edt_cell_s = 2e-9;     ///< a cell of the distance field's box (the tree's extent, map origin included)
  double per_expansion_s = 4.5e-6;  ///< an A* expansion (26 `search` calls, hash sets, heap)
};
/// The costs the time budget charges.
inline constexpr GridBudgetCosts kGridBudgetCosts{};

/// The planning tree's work at its last rebuild (the time budget charges it).
struct PlanningTreeWork {
  long leaves = 0;         ///< map leaves keyed into it
  long cells = 0;          ///< its cells after expansion
  double edt_cells = 0.0;  ///< cells of the distance field's box
  /// Its modelled time on the reference machine, s.
  double seconds(const GridBudgetCosts& c = kGridBudgetCosts) const {
    return c.per_leaf_s * double(leaves) + c.per_cell_s * double(cells) + c.per_edt_cell_s * edt_cells;
  }
};

/// A planned grid path.
struct GridPath {
  std::vector<Vec3> points;   ///< start position first, cell centres after
  bool reaches_goal = false;  ///< false: ends at the reachable cell closest to the goal
  int expansions = 0;
};

/// A* on a traversability grid over a box.
class GridPathPlanner {
 public:
  /// Throws ConfigError. The box is cut into cells of the map's resolution.
  GridPathPlanner(const GridPlannerConfig& config, const Aabb& box, double resolution_m);

  /// Recomputes the blocked cells from the map (with a planning tree: from its leaves within
  /// kPlanningTreeSubmapM of `start`, which must then be given).
  void rebuild(const GridMap& map, const std::optional<Vec3>& start = std::nullopt);
  /// True if this planner plans on a planning tree (rebuilt for every start).
  bool usesPlanningTree() const { return config_.planning_tree_resolution_m > 0; }
  /// Plans from start to goal (both clamped into the box); none if the start is outside
  /// the box by more than a cell. `max_expansions` >= 0 caps this search below the config's.
  std::optional<GridPath> plan(const Vec3& start, const Vec3& goal, int max_expansions = -1) const;
  /// The planning tree's work at the last rebuild (zero without a planning tree).
  const PlanningTreeWork& treeWork() const { return tree_work_; }
  /// True if the cell containing p is inside the box and not blocked.
  bool traversable(const Vec3& p) const;
  /// Number of blocked cells (for counters).
  long blockedCells() const;

 private:
  int64_t index(int i, int j, int k) const { return (int64_t(k) * ny_ + j) * nx_ + i; }
  bool cellOf(const Vec3& p, int* i, int* j, int* k) const;  // false if outside the box
  Vec3 centre(int i, int j, int k) const;
  Vec3 centre(int64_t cell) const {
    return centre(int(cell % nx_), int((cell / nx_) % ny_), int(cell / (int64_t(nx_) * ny_)));
  }
  // Where a plan may go: free cells, and for a vehicle already in blocked cells, the soft
  // blocked ones within the escape radius of its start.
  struct Passability {
    bool start_blocked = false;
    Vec3 start_c = Vec3::Zero();
    double escape2 = 0.0;
  };
  bool passable(int i, int j, int k, const Passability& p) const;
  // The steps of rebuild(): neighbourhood offsets within a clearance (with their flags), the
  // occupied cells' neighbourhoods, the cells the map knows, unknown space blocked.
  std::vector<std::array<int, 4>> offsetsWithin(double clearance_m) const;
  void blockAroundOccupied(const GridMap& map);
  void blockAroundCell(int ci, int cj, int ck, const std::vector<std::array<int, 4>>& offsets);
  std::vector<uint8_t> knownCells(const GridMap& map) const;
  void blockUnknown(const std::vector<uint8_t>& known);
  // The planning tree's cells: known and occupied flags per cell, from the map's leaves near
  // the start (createPlanningTree's resampling), then blocked as the map's cells are.
  void rebuildFromPlanningTree(const GridMap& map, const Vec3& start);
  // A* over cells from `start` towards `goal`: the reached cell closest to the goal (the goal
  // itself when reached), the parent of every reached cell, the expansions.
  // Cells are indexed within the search window (the whole box, or the planning tree's extent).
  struct Search {
    int64_t best = -1;
    int expansions = 0;
    std::vector<int64_t> parent;  // by window index, global cell indices
  };
  Search search(int64_t start, int64_t goal, const Passability& p, int max_expansions) const;
  int64_t windowIndex(int i, int j, int k) const {
    return (int64_t(k - win_lo_[2]) * (win_hi_[1] - win_lo_[1]) + (j - win_lo_[1])) * (win_hi_[0] - win_lo_[0]) +
           (i - win_lo_[0]);
  }
  int64_t windowIndexOf(int64_t cell) const {
    return windowIndex(int(cell % nx_), int((cell / nx_) % ny_), int(cell / (int64_t(nx_) * ny_)));
  }
  bool inWindow(int i, int j, int k) const {
    return i >= win_lo_[0] && j >= win_lo_[1] && k >= win_lo_[2] && i < win_hi_[0] && j < win_hi_[1] && k < win_hi_[2];
  }
  void setWindow(const std::array<int, 3>& lo, const std::array<int, 3>& hi);
  // True if every cell the segment a–b passes through is passable (3D DDA; at an edge or a
  // corner the cells beside it count too).
  bool segmentClear(const Vec3& a, const Vec3& b, const Passability& p) const;

  GridPlannerConfig config_;
  Aabb box_;
  double res_;
  Vec3 origin_;  // min corner of cell (0, 0, 0), on the OctoMap grid
  int nx_ = 0, ny_ = 0, nz_ = 0;
  static constexpr uint8_t kBlocked = 1, kHard = 2;  // cell flags
  std::vector<uint8_t> blocked_;
  // Cells outside [win_lo_, win_hi_) are blocked: the whole box, or, with a planning tree whose
  // unknown cells are blocked, the extent of its known cells (nothing outside can be passed).
  std::array<int, 3> win_lo_{0, 0, 0}, win_hi_{0, 0, 0};
  PlanningTreeWork tree_work_;
};

}  // namespace msb
