// The front-end error profile of a run (docs/perception.md, "The front-end error profile"): how
// wrong the SLAM points a method received were, measured against the ground truth and never shown
// to the method. Each evaluated frame's points are taken to the true frame with that frame's VIO
// error (estimated camera pose -> true camera pose), and each point's error is its distance to
// the nearest true surface, by depth band; each track's published estimate is followed over its
// life (how far it moved from where it was first published). Deterministic (ordered containers).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "core/common/messages.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// SLAM-point errors of one depth band.
struct DepthBandErrors {
  double lo_m = 0.0, hi_m = 0.0;  ///< depth from the camera [lo, hi)
  long points = 0;                ///< point publications evaluated
  double median_m = 0.0, p90_m = 0.0;
  double share_over_half_m = 0.0;  ///< error > 0.5 m
  double share_over_2_m = 0.0;     ///< error > 2 m: wrong points
};

/// The profile of a run.
struct FrontEndProfile {
  std::vector<DepthBandErrors> bands;  ///< 0-5, 5-10, 10-20, 20+ m
  long points = 0;                     ///< point publications evaluated (all bands)
  long tracks = 0;                     ///< tracks published in at least two evaluated frames
  double moved_share = 0.0;            ///< of those, the share whose estimate moved > 0.3 m
  double median_motion_m = 0.0;        ///< median over those of the largest move
};

/// Accumulates the profile frame by frame.
class FrontEndProfiler {
 public:
  /// `every`: evaluate one frame in `every` (1: all) — the points of consecutive frames are
  /// nearly the same, and a nearest-surface query per point is the cost.
  explicit FrontEndProfiler(const WorldTruth& truth, int every = 3);

  /// One published frame of SLAM points and the true camera pose of that frame, which belongs
  /// to tick `pose_tick`: a pose of another tick than `frame.tick` (the pipelined loop hands
  /// points over frames after their own tick) is a caller's error (std::logic_error).
  void addFrame(const SlamPointsFrame& frame, const Pose& T_W_C_true, int64_t pose_tick);

  /// The profile so far.
  FrontEndProfile result() const;

 private:
  struct TrackMotion {
    Vec3 first = Vec3::Zero();
    double max_move_m = 0.0;
    int seen = 0;
  };
  const WorldTruth& truth_;
  int every_;
  long frames_ = 0;
  std::vector<std::vector<double>> errors_;  ///< per band
  std::map<uint64_t, TrackMotion> tracks_;
};

}  // namespace msb
