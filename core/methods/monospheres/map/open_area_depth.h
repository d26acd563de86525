// Open-area virtual depth estimation, OVDE (MonoSpheres §III-B, docs/architecture.md §7 step 3).
//
// Sparse SLAM sees nothing in open areas (sky, far fields), so P_f would end where the tracked
// points end. OVDE places virtual points at 15 m along a 6×6 grid of rays over the central 60 %
// of the image and lets them extend P_f when the assumption "nothing within 15 m there" is
// supported: the point stayed inside the central view (and in front of the camera) of every
// buffered past pose, as the paper's p_{k-n} ... p_{k-1} (`visibility`), and some pair of those poses sees it
// with ≥ 0.07 rad parallax, i.e. the camera translated enough that a real obstacle there would
// have been triangulated. A pose buffer keeps up to 10 past poses, adding one when the camera
// moved > 0.3 m or turned > 45° since the last one. Virtual points only extend free space:
// they never become obstacle points and never delete any.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/types.h"

namespace msb {

/// OVDE parameters (docs/architecture.md §7 defaults).
struct OpenAreaDepthConfig {
  int grid = 6;                    ///< grid × grid virtual points
  double central_fraction = 0.6;   ///< of the image width and height, centred
  double range_m = 15.0;           ///< virtual depth
  int max_poses = 10;              ///< pose buffer size
  double min_translation_m = 0.3;  ///< add a pose after this translation ...
  double min_rotation_deg = 45.0;  ///< ... or this rotation
  double min_parallax_rad = 0.07;  ///< activation threshold
  /// Which buffered poses must have seen a virtual point in their central view:
  /// "whole_buffer" — every buffered pose, as the paper states it (§III-B: "at the current pose
  /// p_k and also at previous poses p_{k-n}, ..., p_{k-1}");
  /// "recent_run" — only the unbroken run back from now, of any length (msbench before 2026-11-25).
  std::string visibility = "whole_buffer";

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("grid", s.grid, Limits::range(1, 50));
    v.key("central_fraction", s.central_fraction, Limits::range(0.05, 1.0));
    v.key("range_m", s.range_m, Limits::positive());
    v.key("max_poses", s.max_poses, Limits::range(1, 1000));
    v.key("min_translation_m", s.min_translation_m, Limits::nonNegative());
    v.key("min_rotation_deg", s.min_rotation_deg, Limits::range(0.0, 180.0));
    v.key("min_parallax_rad", s.min_parallax_rad, Limits::positive());
    v.key("visibility", s.visibility, Choices{"recent_run", "whole_buffer"});
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// OVDE's pose buffer, oldest first: the state OVDE keeps between frames (the owner's, e.g. the
/// sphere map's state; OpenAreaDepth holds only the parameters).
using OvdePoseBuffer = std::deque<Pose>;

/// Virtual-point activation over a pose buffer.
class OpenAreaDepth {
 public:
  /// Throws ConfigError.
  OpenAreaDepth(const OpenAreaDepthConfig& config, const FisheyeCamera& camera);

  /// Records the current camera pose in `poses` (added if it moved or turned enough since the
  /// newest) and returns the active virtual points (world frame) for it.
  std::vector<Vec3> update(const Pose& T_W_C, OvdePoseBuffer& poses) const;
  /// All virtual points of a pose (active or not), world frame.
  std::vector<Vec3> candidates(const Pose& T_W_C) const;
  /// The published activation (method.reference_code.ovde_parallax_frames; SBM
  /// `ofs_freespace_update` ~1039-1140, `init_ofs_freespace_pts` ~1149-1180): the grid's points
  /// are the pinhole K's rays through the central image (edges included) at range_m; a pose is
  /// buffered after min_translation_m or a turn of the optical axis by min_rotation_deg, and only
  /// then is `active` (one flag per point, kept between calls) recomputed: a point is active when
  /// some buffered pose, within the run of poses that see it (pinhole, inside the central image)
  /// counted from the *oldest*, gives a parallax angle ≥ min_parallax_rad, that angle taken
  /// between the current egocentric point and that point moved by the relative translation
  /// expressed in the old pose's frame (the published code mixes the two frames). Returns the
  /// active points, world frame.
  std::vector<Vec3> updatePublished(const Pose& T_W_C, OvdePoseBuffer& poses, std::vector<bool>& active) const;

 private:
  bool inCentralView(const Pose& T_W_C, const Vec3& p_W) const;

  OpenAreaDepthConfig config_;
  FisheyeCamera camera_;
};

}  // namespace msb
