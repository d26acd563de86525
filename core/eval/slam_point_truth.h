// Ground truth for SLAM points: where the anchor pixel really looks, what surface that is, and
// how far the estimate is from it (in the estimate frame of the anchor, so drift is excluded).
#pragma once

#include "core/camera/fisheye_camera.h"
#include "core/common/messages.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Ground-truth evaluation of one SLAM point.
struct PointTruth {
  bool has_surface = false;                     ///< the anchor ray hits something within 400 m
  double true_depth_m = 0.0;                    ///< distance from the anchor camera to the true surface
  double error_m = 0.0;                         ///< |estimate − truth| in the anchor's estimate frame
  ObstacleKind kind = ObstacleKind::kTextured;  ///< kind of the surface hit
  bool interior = false;                        ///< the anchor pixel's 3-px neighbours see the same shape
  bool textureless_interior = false;            ///< interior and textureless
  int shape = -1;                               ///< index of the shape hit (WorldTruth::shapes())
};

/// The surface class of a shape for perception tables, from its object's name: ground, walls
/// (buildings, houses, towers, ruins, cave walls and ceilings, rocks), vehicles (cars, buses,
/// trucks), trees, thin (rods, poles), other.
const char* surfaceClass(const Shape& shape);

/// Evaluates `p` given the true camera pose of its anchor observation.
PointTruth evaluatePoint(const SlamPoint& p, const Pose& T_W_C_true_anchor, const WorldTruth& truth,
                         const FisheyeCamera& camera);

}  // namespace msb
