// The collision audit (docs/planner.md, "Collision audit"): what the method's map knew at the
// moment of contact, and from it a cause class —
//   unseen          the part hit (its geom: e.g. a building's burned part) never gave a SLAM
//                   point (textureless, thin, never in view);
//   planner         the map held an obstacle point closer than the clearance to the contact
//                   (the path ran through known points);
//   seen-but-freed  the object gave SLAM points, but the map held none of them at contact
//                   (deleted or never inserted), or its free space covered the contact;
//   drift           the free space at the contact was truly free where it was carved (mapped
//                   with the VIO correction of that moment) and the drift since has moved it onto
//                   the object by more than the clearance; or the map held the object's points,
//                   but the VIO estimate had drifted by more than the clearance (the map's copy
//                   was displaced from where the vehicle was);
//   other           none of these.
// Evaluation only (ground truth): no method sees it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/messages.h"
#include "core/explorer/snapshot.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Thresholds of the audit's classes.
struct CollisionAuditThresholds {
  double clearance_m = 0.6;  ///< vehicle radius (0.36 m: arm + rotor) plus a margin
  double on_object_m = 0.5;  ///< a map point within this of the object's surface (after the drift) is on it
};

/// What the audit needs at the moment of contact.
struct CollisionAuditInput {
  std::string object;                       ///< the object hit (Shape::object of the world geom)
  Vec3 contact_W = Vec3::Zero();            ///< contact point, true frame
  Pose T_true_from_est = Pose::Identity();  ///< the VIO frame → true frame at contact (latest frame)
  double vio_drift_m = 0.0;                 ///< |estimated − true| vehicle position at contact
  int slam_points_on_object = 0;            ///< SLAM points ever tracked on the object
  int slam_points_on_part = 0;              ///< ... on the part hit (the world geom)
  const ExplorerSnapshot* map = nullptr;    ///< the method's map at contact (VIO frame)
  const std::map<uint64_t, double>* free_space_first_seen_s = nullptr;  ///< element id → first seen
  /// (t_s, VIO frame → true frame) over the run, ascending in time (the metric's samples).
  const std::vector<std::pair<double, Pose>>* true_from_est_history = nullptr;
  double commanded_speed_mps = 0.0;  ///< the tracker's reference speed at contact
  double since_last_path_s = -1.0;   ///< time since the method's last path command (-1: none)
};

/// The audit of one collision.
struct CollisionAudit {
  int slam_points_on_object = 0;
  int slam_points_on_part = 0;
  int map_points_on_object = 0;              ///< map obstacle points on the object at contact
  double nearest_map_point_m = -1.0;         ///< from the contact (VIO frame); -1: the map has none
  bool inside_free_space = false;            ///< the contact lay inside a free-space element
  std::optional<double> free_space_since_s;  ///< since when (the earliest containing element)
  /// Where the contact lay when that free space was carved (the VIO correction of then): its
  /// distance from the true obstacles, and how far the drift since has moved it.
  std::optional<double> carved_clearance_m;
  std::optional<double> drift_since_carved_m;
  double vio_drift_m = 0.0;
  double commanded_speed_mps = 0.0;
  double since_last_path_s = -1.0;
  std::string cause;  ///< unseen, planner, seen-but-freed, drift, other
};

/// What the audit needs from the whole run, recorded as it goes (truth side): the object and
/// the part each new SLAM point lies on, when each free-space element was first seen, and the
/// VIO correction at every metric sample.
class CollisionAuditRecorder {
 public:
  CollisionAuditRecorder(const WorldTruth& truth, const FisheyeCamera& camera) : truth_(truth), camera_(camera) {}

  /// A perception frame: the points anchored in it (anchor tick = `points.tick`, the points new
  /// in that frame) are attributed to the surface their anchor ray meets from the frame's true
  /// camera pose `T_W_C_true`, which belongs to tick `pose_tick`. The pipelined loop hands the
  /// points over frames after their own tick: a pose of another tick than `points.tick` is a
  /// caller's error (std::logic_error).
  void addFrame(const SlamPointsFrame& points, const Pose& T_W_C_true, int64_t pose_tick);
  /// A metric sample: the free space's first-seen times and the VIO → true correction then.
  void addSample(double t_s, const std::vector<FreeSpaceElement>& free_space, const Pose& true_from_est);
  /// The run-long part of the audit's input for a contact with `world_geom` (object, SLAM-point
  /// counts, first-seen times, correction history); the caller adds the moment's facts.
  CollisionAuditInput input(const std::string& world_geom) const;

 private:
  const WorldTruth& truth_;
  FisheyeCamera camera_;
  std::set<uint64_t> audited_tracks_;                   // SLAM points already attributed
  std::map<std::string, int> slam_points_by_object_;    // SLAM points ever tracked, per object
  std::map<std::string, int> slam_points_by_geom_;      // ... per part (world geom)
  std::map<uint64_t, double> free_space_first_seen_s_;  // free-space element id → first sampled
  std::vector<std::pair<double, Pose>> true_from_est_history_;
};

/// Audits a collision against the world's ground truth.
CollisionAudit auditCollision(const CollisionAuditInput& in, const WorldTruth& truth,
                              const CollisionAuditThresholds& thresholds = {});

}  // namespace msb
