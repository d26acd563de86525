// The top-down picture of a run (topdown.png, the map panel of video.mp4): explored columns,
// free space, obstacle points, frontiers, viewpoints, the true and estimated trajectories, the
// last path and goal, the box, a collision; the ground-truth obstacles faint beneath.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "core/common/aabb.h"
#include "core/eval/column_coverage.h"
#include "core/explorer/snapshot.h"
#include "core/geometry/world_truth.h"
#include "tools/engine/closed_loop.h"

namespace msb {

/// What a top-down picture draws: a run at its end (topdown.png) or as it stands (a video frame).
struct TopdownView {
  const Aabb& box;                                 ///< exploration box
  const std::vector<TrajectoryRow>& trajectory;    ///< flown so far (true and estimated positions)
  const ExplorerSnapshot& map;                     ///< the method's map and plan
  const ColumnCoverage& columns;                   ///< explored columns (VIO frame)
  const std::optional<CollisionEvent>& collision;  ///< what ended the run, if a contact did
  double t_s = 0;                                  ///< simulated time
  RunStatus status = RunStatus::kCompleted;        ///< how the run stands or ended
};

// The top-down picture's frame: the metres it spans, its scale, the image and the mapping.
struct TopdownCanvas {
  Vec2 lo, hi;
  double mpp = 0.05;  // metres per pixel
  int header = 88;    // legend band above the map
  int w = 0, h = 0;
  double step = 10.0;  // grid spacing (m)
  cv::Mat img;
  cv::Point px(const Vec3& p) const {
    return cv::Point(int((p.x() - lo.x()) / mpp), header + int((hi.y() - p.y()) / mpp));
  }
  cv::Point px2(const Vec2& p) const { return px(Vec3(p.x(), p.y(), 0)); }
};

/// The canvas of topdown.png: the box, the trajectory and the map with 5 m to spare, at most
/// 1600 px a side (0.05 m per pixel at best), with a legend band above.
TopdownCanvas fittedCanvas(const TopdownView& v);
/// A fixed canvas over [lo, hi] (m) of width_px x height_px, no legend band (video frames).
TopdownCanvas fixedCanvas(const Vec2& lo, const Vec2& hi, int width_px, int height_px);
/// What does not change during a run: the ground-truth obstacles (faint, by kind; `truth` may be
/// null) and the metre grid.
void drawTopdownBackground(TopdownCanvas& c, const WorldTruth* truth);
/// The run: explored columns, free space, the box, obstacle points, frontiers, viewpoints,
/// visited poses, trajectories, the last path and goal, the collision (and, with `truth`, the
/// object hit outlined and labelled).
void drawTopdownMap(TopdownCanvas& c, const TopdownView& v, const WorldTruth* truth);
/// The scale bar (bottom right).
void drawTopdownScaleBar(TopdownCanvas& c);
/// topdown.png's picture: background, map, legend (its first line: A, t, status) and scale bar.
cv::Mat topdownImage(const TopdownView& v, const WorldTruth* truth);

}  // namespace msb
