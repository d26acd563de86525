// The MonoSpheres map (paper §III, docs/architecture.md §7): free-space spheres connected where they overlap,
// plus obstacle points, all in the VIO world frame. One update per SLAM-points frame:
//   0. optional (off by default): points with a depth σ above max_point_depth_std_m are left
//      out of every step (experiment of issue 13: far, uncertain points inside tunnels)
//   1. input: SLAM points in front of the camera (≤ max_view_angle_deg off-axis; ≥ min_points,
//      else skip); all points of the frame, also side points, limit radii in step 6/7
//   2./4. free-space polyhedron P_f from the points (FreeSpacePolyhedron)
//   3. OVDE (switch `ovde`): active virtual points outside the real points' hull extend P_f
//      for the sphere steps; DBOF keeps using the real-points P_f (virtual points never delete)
//   5. DBOF: an obstacle point x inside P_f is deleted iff |x − c| < α·d_min(x), otherwise it
//      is protected (it constrains spheres); dbof = false means α = 0 (nothing deleted). With
//      dbof_age_per_m = β > 0 (off by default) d_min is read as d_min + β·(path flown since the
//      point was measured): in a drifting frame an old point's position error grows with the
//      flight, not only with its measuring distance, and the point ages out of protection.
//   6. sphere update near P_f:
//        r ← min( c ∈ P_f ? max(r, d(c, ∂P_f)) : r,  d(c, X_in ∪ X_p),  r_max )
//      (X_in: all of this frame's points, X_p: protected points); spheres with r < r_min are deleted
//   7. new spheres: new_sphere_samples samples along fisheye rays inside P_f's cone (drawn
//      over the image until that many fall inside), uniform from the camera to the depth
//      surface (≤ 20 m); radius by the same rule with r = 0, kept if r ≥ r_min
//   8. graph: edge iff spheres overlap; sparsify updated/new spheres smallest first: remove i if
//      a neighbour j has |c_i − c_j| < 0.9·(r_i + r_j)/2 and i's neighbours stay connected
//   9. obstacle points: SLAM points within range, spacing ρ; the closer measurement wins
//  10. frontiers: candidates on P_f's faces (area-weighted, jittered) and in the shells
//      [r + 0.48, r + 2.72] of spheres within 20 m; kept if ≥ 1.5 m from other frontiers and
//      from every obstacle point, outside all spheres, inside the shell of some sphere it can
//      see (no obstacle point on the segment towards it: not behind a wall), with free
//      space on one side (normal = mean direction to the nearby centres) and a normal that
//      does not put the unknown straight above (n_z ≥ −0.5). After each update the frontiers
//      near anything that changed (spheres created, resized or removed; obstacle points
//      inserted, deleted or replaced) are re-validated. Validity depends on the spheres whose
//      shell may hold the frontier (within r + shell_max_m) and on obstacle points up to
//      frontierObstacleReach() away (the gap and the line-of-sight segments); every change to
//      either marks that neighbourhood.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/common/rng.h"
#include "core/methods/monospheres/map/open_area_depth.h"
#include "core/methods/monospheres/map/point_grid.h"

namespace msb {

class FreeSpacePolyhedron;

/// Mapper parameters (docs/architecture.md §7 defaults).
struct SphereMapConfig {
  bool ovde = true;                 ///< open-area virtual depth
  OpenAreaDepthConfig ovde_params;  ///< its parameters
  bool dbof = true;                 ///< distance-based obstacle filtering
  /// New spheres' sample rays through the pinhole K (method.reference_code.pinhole_rays; not a
  /// key of its own): the published code's ±58.8° × ±46.5° instead of the fisheye's ±90°.
  bool pinhole_sample_rays = false;
  /// The published pruning test (method.reference_code.worked_mask_scalar; not a key of its
  /// own): when the youngest sphere of an update's worked set ends below r_min, the worked
  /// spheres keep their edges and no sphere of the set is pruned.
  bool published_worked_mask = false;
  /// The published early return (method.reference_code.early_return_stale; not a key of its
  /// own): an update without a new sphere inserts no obstacle points and draws no frontiers.
  bool published_early_return = false;
  /// DBOF on the OVDE-extended P_f (method.reference_code.dbof_on_ovde_polyhedron; not a key of
  /// its own): old points inside it are deleted or protected, not only those inside the real P_f.
  bool published_dbof_on_ovde_pf = false;
  /// OVDE's activation as published (method.reference_code.ovde_parallax_frames; not a key of its
  /// own): OpenAreaDepth::updatePublished instead of the paper's rule.
  bool published_ovde_activation = false;
  /// DBOF's triangulation test with the pinhole K (method.reference_code.dbof_pinhole_projection;
  /// not a key of its own): an old point counts only if its pinhole image falls inside P_f's
  /// fisheye image.
  bool published_dbof_pinhole = false;
  double dbof_alpha = 1.1;       ///< deletion factor α
  double dbof_age_per_m = 0.0;   ///< DBOF counts a point as measured this much farther per metre flown since (0 = off)
  double r_max_m = 10.0;         ///< sphere radius cap
  double r_min_m = 1.4;          ///< spheres below are deleted / not created (paper: 1.6; docs/deviations.md)
  int new_sphere_samples = 150;  ///< samples per update
  double max_sample_range_m = 20.0;      ///< sampling along rays is capped here
  double max_point_range_m = 20.0;       ///< SLAM points farther are not inserted as obstacles
  double obstacle_spacing_m = 0.3;       ///< ρ
  double sparsify_factor = 0.9;          ///< removal when |c_i − c_j| < factor·(r_i + r_j)/2
  int min_points = 4;                    ///< fewer input points: the update is skipped
  double max_point_depth_std_m = 1e9;    ///< points with a larger 1σ depth uncertainty are ignored (off by default)
  double max_view_angle_deg = 80.0;      ///< points farther off-axis are not triangulated
  int frontier_surface_samples = 150;    ///< candidates on P_f's faces per update
  int frontier_shell_samples = 150;      ///< candidates in sphere shells per update
  double frontier_jitter_m = 0.96;       ///< Gaussian jitter of surface candidates
  double shell_min_m = 0.48;             ///< shell inner offset from the sphere surface
  double shell_max_m = 2.72;             ///< shell outer offset
  double frontier_spacing_m = 1.5;       ///< between frontiers
  double frontier_obstacle_gap_m = 1.5;  ///< from every obstacle point
  double frontier_range_m = 20.0;        ///< shell sampling around spheres within this range
  double frontier_min_normal_z = -0.5;   ///< reject normals pointing down harder than this
  double frontier_min_balance = 0.3;     ///< |mean direction| needed for a one-sided frontier

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("ovde_params", s.ovde_params);
    v.key("dbof_alpha", s.dbof_alpha, Limits::range(0.0, 10.0));
    v.key("dbof_age_per_m", s.dbof_age_per_m, Limits::range(0.0, 10.0));
    v.key("r_max_m", s.r_max_m, Limits::positive());
    v.key("max_point_depth_std_m", s.max_point_depth_std_m, Limits::positive());
    v.key("r_min_m", s.r_min_m, Limits::positive());
    v.key("new_sphere_samples", s.new_sphere_samples, Limits::range(0, 100000));
    v.key("max_sample_range_m", s.max_sample_range_m, Limits::positive());
    v.key("max_point_range_m", s.max_point_range_m, Limits::positive());
    v.key("obstacle_spacing_m", s.obstacle_spacing_m, Limits::positive());
    v.key("sparsify_factor", s.sparsify_factor, Limits::range(0.0, 2.0));
    v.key("min_points", s.min_points, Limits::range(3, 100000));
    v.key("max_view_angle_deg", s.max_view_angle_deg, Limits::range(1.0, 89.0));
    v.key("frontier_surface_samples", s.frontier_surface_samples, Limits::range(0, 100000));
    v.key("frontier_shell_samples", s.frontier_shell_samples, Limits::range(0, 100000));
    v.key("frontier_jitter_m", s.frontier_jitter_m, Limits::nonNegative());
    v.key("shell_min_m", s.shell_min_m, Limits::nonNegative());
    v.key("shell_max_m", s.shell_max_m, Limits::positive());
    v.key("frontier_spacing_m", s.frontier_spacing_m, Limits::nonNegative());
    v.key("frontier_obstacle_gap_m", s.frontier_obstacle_gap_m, Limits::nonNegative());
    v.key("frontier_range_m", s.frontier_range_m, Limits::positive());
    v.key("frontier_min_normal_z", s.frontier_min_normal_z, Limits::range(-1.0, 1.0));
    v.key("frontier_min_balance", s.frontier_min_balance, Limits::range(0.0, 1.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A free-space sphere (centre fixed for life, radius updated).
struct Sphere {
  uint64_t id = 0;
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// An obstacle point with the smallest distance it was measured from.
struct ObstaclePoint {
  uint64_t id = 0;
  Vec3 position = Vec3::Zero();
  double d_min = 0.0;
  double flown_at_m = 0.0;  ///< the camera's path length (estimate frame) when it was measured
};

/// A frontier: the boundary of known free space, with the direction towards the free side.
struct Frontier {
  uint64_t id = 0;
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< unit, towards the nearby free-space centres
};

/// Counts and stage times of one update (times are recorded, never used).
struct MapUpdateStats {
  bool skipped = false;
  bool graph_stale = false;     ///< published_worked_mask fired: edges and pruning left as they were
  bool returned_early = false;  ///< published_early_return fired: no obstacle points, no frontiers
  int input_points = 0;
  int virtual_points = 0;  ///< active OVDE points added to P_f
  int deleted_obstacles = 0, protected_obstacles = 0;
  std::vector<uint64_t> dbof_deleted_ids;  ///< the obstacle points DBOF deleted in this update
  int updated_spheres = 0, deleted_spheres = 0, new_spheres = 0, sparsified_spheres = 0;
  int sphere_samples = 0;  ///< step 7 samples that fell inside P_f's cone
  int inserted_obstacles = 0;
  int new_frontiers = 0, dropped_frontiers = 0;
  std::vector<uint64_t> changed_spheres;  ///< ids created or grown in this update (still present)
  double frontiers_ms = 0;
  double polyhedron_ms = 0, dbof_ms = 0, spheres_ms = 0, sampling_ms = 0, graph_ms = 0, obstacles_ms = 0;
};

/// Everything a SphereMap changes as frames arrive, apart from its configuration and camera
/// (as MuJoCo keeps mjData apart from mjModel). A value: copying a SphereMap copies its state,
/// and SphereMap::reset() replaces it with a fresh one.
struct SphereMapState {
  /// An empty map whose sampling stream is seeded from `seed`.
  explicit SphereMapState(uint64_t seed) : rng(seed, "map_sampling") {}

  RngStream rng;                                     ///< the "map_sampling" stream
  OvdePoseBuffer ovde_poses;                         ///< OVDE's past camera poses
  std::vector<bool> ovde_active;                     ///< the published OVDE's kept activation flags
  std::map<uint64_t, Sphere> spheres;                ///< by id
  std::map<uint64_t, std::set<uint64_t>> adjacency;  ///< overlapping spheres, both ways
  std::map<uint64_t, ObstaclePoint> obstacles;       ///< by id
  PointGrid sphere_grid{20.0};                       ///< sphere centres
  PointGrid obstacle_grid{2.0};                      ///< obstacle points
  std::map<uint64_t, Frontier> frontiers;            ///< by id
  std::vector<std::pair<Vec3, double>> dirty;        ///< regions changed since the last re-validation
  PointGrid frontier_grid{8.0};  ///< coarse: frontiers are sparse and queries reach 1.5–13 m (docs/performance.md)
  uint64_t next_sphere = 1, next_obstacle = 1, next_frontier = 1;  ///< the next ids
  double flown_m = 0.0;             ///< camera path length over the updates (estimate frame)
  std::optional<Vec3> last_camera;  ///< the camera position of the last update
};

/// The sphere map. Spheres and points keep their ids for life (planning may hold them).
class SphereMap {
 public:
  /// `seed` seeds the "map_sampling" stream. Throws ConfigError.
  SphereMap(const SphereMapConfig& config, const FisheyeCamera& camera, uint64_t seed);

  /// Integrates one frame of SLAM points (estimated camera pose + points).
  MapUpdateStats update(const SlamPointsFrame& frame);
  /// Forgets every frame: the empty map of the constructor (same configuration and seed).
  void reset() { state_ = SphereMapState(seed_); }
  /// The map's state (spheres, points, frontiers, their indices, the sampling stream).
  const SphereMapState& state() const { return state_; }

  /// Spheres by id.
  const std::map<uint64_t, Sphere>& spheres() const { return state_.spheres; }
  /// Obstacle points by id.
  const std::map<uint64_t, ObstaclePoint>& obstacles() const { return state_.obstacles; }
  /// Neighbours (overlapping spheres) of a sphere, ascending ids.
  const std::set<uint64_t>& neighbours(uint64_t sphere_id) const { return state_.adjacency.at(sphere_id); }
  /// Frontiers by id.
  const std::map<uint64_t, Frontier>& frontiers() const { return state_.frontiers; }
  /// Frontier test for a point: returns the normal if valid (ignoring frontier `self`).
  std::optional<Vec3> frontierNormal(const Vec3& x, uint64_t self = 0) const;
  /// The id the next new frontier will get (ids only grow: a frontier with a smaller id existed
  /// before this call).
  uint64_t nextFrontierId() const { return state_.next_frontier; }
  /// True if every sphere can reach every other through overlaps.
  bool connected() const;
  /// Ids (ascending) of spheres whose ball comes within `reach` of p: |c − p| ≤ r + reach.
  std::vector<uint64_t> spheresNear(const Vec3& p, double reach) const;
  /// Ids (ascending) of obstacle points within distance r of p.
  std::vector<uint64_t> obstaclesNear(const Vec3& p, double r) const;
  /// Ids (ascending) of frontiers within distance r of p.
  std::vector<uint64_t> frontiersNear(const Vec3& p, double r) const;
  /// Calls `f(id, frontier)` for every frontier within r of p, in no particular order (for
  /// results that do not depend on it; frontiersNear() gives them sorted).
  template <class F>
  void forEachFrontierNear(const Vec3& p, double r, F f) const {
    state_.frontier_grid.forEachNear(p, r, [&](uint64_t id, const Vec3& q) {
      if ((q - p).norm() <= r) f(id, state_.frontiers.at(id));
    });
  }
  /// True if some obstacle point lies within distance r of p.
  bool anyObstacleNear(const Vec3& p, double r) const;
  /// The configuration.
  const SphereMapConfig& config() const { return config_; }

  /// The radius rule (step 6) for a centre, given P_f and the constraining points.
  double ruleRadius(const Vec3& c, double r, const FreeSpacePolyhedron& pf, const std::vector<Vec3>& constraints) const;

  /// How far from a frontier an obstacle point can change its validity (see step 10).
  double frontierObstacleReach() const;

 private:
  friend struct SphereMapTestSeam;  // hand-built maps in tests (sphere_map_test_seam.h)
  /// Adds a frontier at x if it passes the frontier test; returns its id (step 10; the seam).
  std::optional<uint64_t> tryAddFrontier(const Vec3& x);
  /// Drops frontiers that are no longer valid; returns how many (the seam).
  int revalidateFrontiers();
  /// Re-validates the frontiers near everything changed since the last update (step 10 does
  /// this itself; tests editing the map by hand call it through the seam); returns how many dropped.
  int revalidateChangedFrontiers() { return revalidateDirtyFrontiers(); }
  /// Adds a sphere directly (the test seam); returns its id. Links it into the graph.
  uint64_t addSphere(const Vec3& centre, double radius);
  /// Adds an obstacle point directly with its measurement distance; returns its id.
  uint64_t addObstacle(const Vec3& p, double d_min);
  /// Removes sphere i if a close neighbour makes it redundant and its neighbours stay
  /// connected without it (step 8); returns true if removed.
  bool sparsify(uint64_t id);
  /// Inserts a measured point under the spacing rule (step 9); returns true if kept.
  bool insertObstacle(const Vec3& p, double distance_from_camera);
  /// Removes an obstacle point (as DBOF does); frontiers it may have affected are re-checked
  /// at the next update.
  void eraseObstacle(uint64_t id);

  void removeSphere(uint64_t id);
  void markDirty(const Vec3& centre, double reach) { state_.dirty.emplace_back(centre, reach); }
  int revalidateDirtyFrontiers();
  int revalidate(const std::vector<uint64_t>& ids);  // re-checks ids (ascending), drops failures
  void sampleFrontiers(const FreeSpacePolyhedron& pf, const Vec3& cam, MapUpdateStats& st);
  void setRadius(uint64_t id, double r);
  void relink(uint64_t id);  // recomputes a sphere's edges from the current radii
  // The published worked-set rule (published_worked_mask): radii set, edges and pruning left
  // alone when the youngest worked sphere ends below r_min; true if it fired.
  bool publishedStaleGraph(const std::vector<uint64_t>& worked, const std::vector<double>& radii, MapUpdateStats& st);
  // The steps of update() (numbered as there).
  std::vector<Vec3> pointsInView(const SlamPointsFrame& frame) const;  // 1
  // DBOF's published pinhole test (published_dbof_pinhole) on a point in the camera frame.
  bool pinholeImageInside(const FreeSpacePolyhedron& pf, const Pose& T_W_C, const Vec3& p_C) const;
  std::vector<Vec3> applyDbof(const SlamPointsFrame& frame, const FreeSpacePolyhedron& real_pf,  // 5
                              MapUpdateStats& st);
  void updateSpheresNear(const FreeSpacePolyhedron& pf, const std::vector<Vec3>& constraints,  // 6
                         std::vector<uint64_t>& touched, MapUpdateStats& st);
  void sampleNewSpheres(const SlamPointsFrame& frame, const FreeSpacePolyhedron& pf,  // 7
                        const std::vector<Vec3>& constraints, std::vector<uint64_t>& touched, MapUpdateStats& st);
  Vec3 pinholeRay(const Vec2& px) const;  // the published code's back-projection (camera frame)
  void sparsifyTouched(std::vector<uint64_t>& touched, MapUpdateStats& st);     // 8
  void insertFrameObstacles(const SlamPointsFrame& frame, MapUpdateStats& st);  // 9

  // Configuration (fixed for the map's life) ...
  SphereMapConfig config_;
  FisheyeCamera camera_;
  OpenAreaDepth ovde_;
  uint64_t seed_;
  // ... and state.
  SphereMapState state_;
};

}  // namespace msb
