// The top-down picture shows what ended a run: the geom hit is outlined on top of the map.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tools/results/mission_outputs.h"

namespace msb {
namespace {

// Pure red (BGR 0, 0, 255) pixels of the image.
int redPixels(const cv::Mat& img) {
  int n = 0;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) n += img.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 255);
  return n;
}

TEST(Topdown, TheCollisionObjectIsOutlinedOnTopOfTheMap) {
  Shape wall;
  wall.type = ShapeType::kBox;
  wall.pose = poseFromXyzYaw(Vec3(5, 0, 1), 0.0);
  wall.size = Vec3(1, 4, 1);
  wall.kind = ObstacleKind::kTextureless;
  wall.name = "wall_1";
  const WorldTruth truth({wall});
  MissionResult r;
  r.exploration_box = {Vec3(-10, -10, 0), Vec3(10, 10, 5)};
  // A sphere of the map over the wall: the outline must still show on top of it.
  r.final_map.free_space.push_back({1, Vec3(5, 0, 1), 3.0, FreeSpaceElement::Footprint::kDisk});
  const int before = redPixels(topdownImage(r, &truth));
  CollisionEvent c;
  c.t_s = 10.0;
  c.vehicle_position_m = Vec3(3.6, 0, 1);
  c.contact_position_m = Vec3(4.0, 0, 1);
  c.world_geom = "wall_1";
  r.flight.collision = c;
  r.flight.status = RunStatus::kCollided;
  const cv::Mat img = topdownImage(r, &truth);
  // The outline's perimeter (2 × (2 + 8) m at 0.05 m a pixel, 2 px wide) is drawn in red.
  EXPECT_GT(redPixels(img) - before, 600);
}

}  // namespace
}  // namespace msb
