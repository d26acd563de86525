// Exploration viewpoints and visited-viewpoint blocking (docs/architecture.md §8). Candidates are sampled at
// centres of spheres reachable from the vehicle (fix: the reference sampled any sphere) with a
// random yaw and a level camera; a viewpoint's value is the number of frontiers it would see:
// within range, inside the useful field of view about the optical axis, and facing the camera
// (n · ray < 0). With VPB, passing a viewpoint (within 7 m and 60°) removes it and leaves a
// visited marker at the vehicle's pose; markers block new viewpoints around them.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/rng.h"
#include "core/methods/monospheres/map/sphere_map.h"

namespace msb {

/// The image of a level pinhole camera as tangents of its half-angles about the optical axis.
struct PinholeFrustum {
  bool on = false;
  double left = 0, right = 0, up = 0, down = 0;  ///< cx/fx, (w − cx)/fx, cy/fy, (h − cy)/fy
};

/// Viewpoint sampling, value and blocking parameters.
struct ViewpointConfig {
  int candidates = 300;              ///< samples per planning step
  double frontier_range_m = 10.0;    ///< frontiers farther do not count
  double fov_half_angle_deg = 60.0;  ///< useful field of view about the optical axis
  int min_value = 7;                 ///< viewpoints seeing fewer frontiers are dropped
  int relaxed_min_value = 2;         ///< used instead while the set is empty and the planner idles
  bool vpb = true;                   ///< visited-viewpoint blocking
  bool vpb_new_frontiers = false;    ///< markers block only frontiers older than themselves
  /// > 0: VPB per frontier instead of per pose. A frontier is "seen" from a marker if it passes
  /// the value test at the marker's pose (by position: frontier ids churn as the map changes).
  /// Near a marker only the frontiers it does not see count, and a frontier seen from this many
  /// markers counts nowhere: it survived being looked at that often. 0 = plain VPB (a marker
  /// blocks the poses near it). Default 2: measured better in the cave, not worse elsewhere
  /// (docs/planner.md). Without vpb there are no markers, so it has no effect.
  int frontier_view_limit = 2;
  double block_distance_m = 7.0;       ///< VPB / blocking radius
  double block_angle_deg = 60.0;       ///< VPB / blocking heading difference
  double blacklist_radius_m = 2.0;     ///< failed goals block new viewpoints this close ...
  double blacklist_duration_s = 60.0;  ///< ... for this long
  /// The published code's sampling (method.reference_code.viewpoints_anywhere; not a key of its
  /// own): candidate k is the map's sphere number i, i drawn over every sphere of the map,
  /// reachable or not (still only while the vehicle has a start sphere).
  bool sample_anywhere = false;
  /// The published code's visibility (method.reference_code.pinhole_rays; not a key of its own):
  /// a frontier counts only where the pinhole K projects it inside the image. Off: the cone of
  /// fov_half_angle_deg.
  PinholeFrustum pinhole_view;

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("candidates", s.candidates, Limits::range(1, 100000));
    v.key("frontier_range_m", s.frontier_range_m, Limits::range(0.1, 1000.0));
    v.key("fov_half_angle_deg", s.fov_half_angle_deg, Limits::range(1.0, 100.0));
    v.key("min_value", s.min_value, Limits::range(1, 100000));
    v.key("relaxed_min_value", s.relaxed_min_value, Limits::range(1, 100000));
    v.key("block_distance_m", s.block_distance_m, Limits::nonNegative());
    v.key("block_angle_deg", s.block_angle_deg, Limits::range(0.0, 180.0));
    v.key("blacklist_radius_m", s.blacklist_radius_m, Limits::nonNegative());
    v.key("blacklist_duration_s", s.blacklist_duration_s, Limits::nonNegative());
    v.key("vpb_new_frontiers", s.vpb_new_frontiers);
    v.key("frontier_view_limit", s.frontier_view_limit, Limits::range(0, 1000));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// A candidate goal: a pose and the frontiers it would see.
struct Viewpoint {
  uint64_t id = 0;
  Vec3 position = Vec3::Zero();
  double yaw_rad = 0.0;
  int value = 0;
  uint64_t sphere = 0;  ///< the sphere whose centre it is
};

/// A pose from which a viewpoint was visited (VPB).
struct VisitedMarker {
  Vec3 position = Vec3::Zero();
  double yaw_rad = 0.0;
  uint64_t frontier_watermark = 0;  ///< frontiers with this id or above appeared after the visit
};

/// Why sampled candidates were not kept, counted over the whole run (diagnostics: an idle
/// explorer with frontiers left shows here whether VPB markers, the value threshold or the box
/// kept it from new viewpoints).
struct CandidateRejections {
  long outside = 0;      ///< centre outside the exploration box
  long visited = 0;      ///< near a visited marker (VPB)
  long blocked = 0;      ///< near the active goal or a recently failed goal
  long no_frontier = 0;  ///< sees no frontier
  long low_value = 0;    ///< sees some frontiers, fewer than the minimum value
  long dominated = 0;    ///< a nearby viewpoint with at least its value exists
};

/// True if pose (p, yaw) is within `distance` and `angle` of pose (q, qyaw).
bool posesClose(const Vec3& p, double yaw, const Vec3& q, double qyaw, double distance_m, double angle_rad);

/// The set of current viewpoints with their markers and blacklist.
class ViewpointSet {
 public:
  /// Throws ConfigError if invalid. `seed` seeds the "viewpoints" stream.
  ViewpointSet(const ViewpointConfig& config, uint64_t seed);

  /// Frontiers visible from (p, yaw) with a level camera (only those with id ≥ min_frontier_id;
  /// with frontier_view_limit only those not retired and not seen from a marker close to the pose).
  int value(const SphereMap& map, const Vec3& p, double yaw, uint64_t min_frontier_id = 0) const;

  /// One planning step: re-values the existing viewpoints (dropping those whose sphere is gone,
  /// unreachable or below the minimum value), applies VPB for the vehicle pose (the active goal
  /// `goal_id` is exempt) and samples new candidates among `reachable` sphere ids accepted by
  /// `allowed` (e.g. inside the exploration box). `relaxed` uses relaxed_min_value instead of
  /// min_value (nothing else worth flying to). Returns the number of new viewpoints.
  int update(const SphereMap& map, const std::vector<uint64_t>& reachable, const Vec3& vehicle, double vehicle_yaw,
             double t_s, uint64_t goal_id, const std::function<bool(const Vec3&)>& allowed, bool relaxed = false);

  /// Removes a viewpoint (reached goal): leaves a marker at the vehicle pose if VPB is on (with
  /// the map's next frontier id as its watermark).
  void markReached(uint64_t id, const SphereMap& map, const Vec3& vehicle, double vehicle_yaw);
  /// Removes a viewpoint that could not be reached and blacklists its position.
  void markFailed(uint64_t id, double t_s);

  /// Current viewpoints by id.
  const std::map<uint64_t, Viewpoint>& viewpoints() const { return viewpoints_; }
  /// Visited markers in order of creation.
  const std::vector<VisitedMarker>& markers() const { return markers_; }
  /// Viewpoints removed by VPB so far (passed, not targeted).
  int passedCount() const { return passed_; }
  /// Candidates not kept so far, by reason.
  const CandidateRejections& rejections() const { return rejected_; }
  /// Markers from which frontier `id` of `map` is visible (frontier_view_limit; 0 if it is off).
  int views(const SphereMap& map, uint64_t id) const;
  /// Frontiers of `map` seen from frontier_view_limit markers or more (0 if the limit is off).
  int retiredFrontiers(const SphereMap& map) const;

 private:
  enum class Block { kNone, kMarker, kGoalOrFailed };
  // Why a candidate pose is blocked. With vpb_new_frontiers, markers do not block: they raise
  // *min_frontier_id to the newest close marker's watermark instead.
  Block blocked(const Vec3& p, double yaw, double t_s, uint64_t goal_id, uint64_t* min_frontier_id) const;
  // A pose as the value test uses it: position and unit heading (cos yaw, sin yaw, 0).
  struct View {
    Vec3 p, heading;
  };
  static View viewOf(const Vec3& p, double yaw);
  // True if frontier f passes the value test from the pose: in range, in view, facing.
  bool sees(const View& v, const Frontier& f) const;
  // True if `ray` (from the view's position) falls inside the published pinhole frustum.
  bool inPinholeFrustum(const View& v, const Vec3& ray) const;
  // Ids of the frontiers visible from the pose.
  std::vector<uint64_t> visibleFrontiers(const SphereMap& map, const View& v) const;
  // views() of frontier f (id `id`), the view limit on.
  int views(const Frontier& f, uint64_t id) const;
  // Appends a visited marker (and its view).
  void addMarker(const VisitedMarker& m);

  ViewpointConfig config_;
  RngStream rng_;
  std::map<uint64_t, Viewpoint> viewpoints_;
  std::vector<VisitedMarker> markers_;
  std::vector<View> marker_views_;  // the markers' poses as views, in the same order
  double cos_half_fov_ = 1.0;       // cos(fov_half_angle_deg)
  // Frontier id → markers it is visible from, counted over markers_[0, checked) (a frontier
  // keeps its position, so each marker is tested once per frontier).
  struct ViewCount {
    int views = 0;
    size_t checked = 0;
  };
  mutable std::unordered_map<uint64_t, ViewCount> views_;  // only looked up and erased from: order never matters
  std::vector<std::pair<Vec3, double>> blacklist_;         // position, until
  uint64_t next_id_ = 1;
  int passed_ = 0;
  CandidateRejections rejected_;
};

}  // namespace msb
