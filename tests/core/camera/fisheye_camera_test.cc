#include "core/camera/fisheye_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "core/common/rng.h"

namespace msb {
namespace {

TEST(FisheyeCamera, DefaultIntrinsicsFollowDesign) {
  const FisheyeCamera cam;
  EXPECT_EQ(cam.width(), 752);
  EXPECT_EQ(cam.height(), 480);
  EXPECT_DOUBLE_EQ(cam.fx(), 227.4);
  EXPECT_DOUBLE_EQ(cam.halfFovRad(), M_PI / 2);
  FisheyeCameraConfig half;
  half.scale = 0.5;
  const FisheyeCamera h(half);
  EXPECT_EQ(h.width(), 376);
  EXPECT_EQ(h.height(), 240);
  EXPECT_DOUBLE_EQ(h.fx(), 113.7);
  EXPECT_DOUBLE_EQ(h.cx(), 188.0);
}

TEST(FisheyeCamera, RoundTripPixelRayPixelOverTheWholeImage) {
  for (double scale : {1.0, 0.5}) {
    FisheyeCameraConfig cfg;
    cfg.scale = scale;
    const FisheyeCamera cam(cfg);
    double worst = 0.0;
    for (int v = 0; v < cam.height(); ++v) {
      for (int u = 0; u < cam.width(); ++u) {
        const Vec2 px(u + 0.25, v + 0.75);
        const Vec3 ray = cam.unproject(px);
        ASSERT_NEAR(ray.norm(), 1.0, 1e-12);
        worst = std::max(worst, (cam.project(3.7 * ray) - px).norm());
      }
    }
    EXPECT_LT(worst, 1e-6) << "scale " << scale;
  }
}

TEST(FisheyeCamera, AgreesWithOpenCvFisheyeProjectPoints) {
  const FisheyeCamera cam;
  RngStream rng(5, "camera_test");
  std::vector<cv::Point3d> pts;
  for (int i = 0; i < 5000; ++i) {
    // Random directions in front of the camera (OpenCV's model needs z > 0), random depth.
    const double theta = rng.uniform(0.0, 1.5), phi = rng.uniform(-M_PI, M_PI);
    const double depth = rng.uniform(0.3, 40.0);
    pts.emplace_back(depth * std::sin(theta) * std::cos(phi), depth * std::sin(theta) * std::sin(phi),
                     depth * std::cos(theta));
  }
  const cv::Matx33d K(cam.fx(), 0, cam.cx(), 0, cam.fy(), cam.cy(), 0, 0, 1);
  const cv::Vec4d D(cam.k()[0], cam.k()[1], cam.k()[2], cam.k()[3]);
  std::vector<cv::Point2d> cv_px;
  cv::fisheye::projectPoints(pts, cv_px, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  double worst = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec2 ours = cam.project(Vec3(pts[i].x, pts[i].y, pts[i].z));
    worst = std::max(worst, (ours - Vec2(cv_px[i].x, cv_px[i].y)).norm());
  }
  EXPECT_LT(worst, 1e-3);
}

TEST(FisheyeCamera, JacobianMatchesFiniteDifferences) {
  const FisheyeCamera cam;
  RngStream rng(9, "jacobian");
  for (int i = 0; i < 500; ++i) {
    Vec3 p(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-1, 8));
    if (p.norm() < 0.5) continue;
    Eigen::Matrix<double, 2, 3> J;
    cam.project(p, &J);
    for (int k = 0; k < 3; ++k) {
      Vec3 d = Vec3::Zero();
      d[k] = 1e-6;
      const Vec2 num = (cam.project(p + d) - cam.project(p - d)) / 2e-6;
      EXPECT_NEAR((J.col(k) - num).norm(), 0.0, 1e-4 * (1.0 + num.norm())) << p.transpose();
    }
  }
  // On the optical axis.
  Eigen::Matrix<double, 2, 3> J;
  cam.project(Vec3(0, 0, 2), &J);
  EXPECT_NEAR(J(0, 0), cam.fx() / 2, 1e-9);
  EXPECT_NEAR(J(1, 1), cam.fy() / 2, 1e-9);
}

TEST(FisheyeCamera, FieldOfViewEdge) {
  const FisheyeCamera cam;
  // On the horizontal axis the 180° cone ends at θ = 90°, still inside the 752 px width.
  const double just_in = M_PI / 2 - 1e-3, just_out = M_PI / 2 + 1e-3;
  EXPECT_TRUE(cam.inFieldOfView(Vec3(std::sin(just_in), 0, std::cos(just_in))));
  EXPECT_FALSE(cam.inFieldOfView(Vec3(std::sin(just_out), 0, std::cos(just_out))));
  EXPECT_FALSE(cam.inFieldOfView(Vec3(0, 0, -1)));  // behind
  EXPECT_LT(cam.project(Vec3(1, 0, 0)).x(), cam.width() - 0.5);
  // Vertically the image (480 px) ends before the cone: θ ≈ 60° is the last row.
  const double rows_theta = cam.undistort((cam.height() - 0.5 - cam.cy()) / cam.fy());
  EXPECT_NEAR(rows_theta, 1.03, 0.02);
  EXPECT_TRUE(cam.inFieldOfView(Vec3(0, std::sin(rows_theta - 0.01), std::cos(rows_theta - 0.01))));
  EXPECT_FALSE(cam.inFieldOfView(Vec3(0, std::sin(rows_theta + 0.01), std::cos(rows_theta + 0.01))));
  // Image corners lie outside the cone: they stay black in rendered images.
  EXPECT_FALSE(cam.pixelInFov(Vec2(0, 0)));
  EXPECT_TRUE(cam.pixelInFov(Vec2(cam.cx(), cam.cy())));
  // Projection is continuous through θ = 90° (no atan(r/z) singularity).
  const Vec2 a = cam.project(Vec3(1, 0, 1e-9)), b = cam.project(Vec3(1, 0, -1e-9));
  EXPECT_LT((a - b).norm(), 1e-6);
}

TEST(FisheyeCamera, MountIsForwardLookingAboveAndAheadOfTheBody) {
  const FisheyeCamera cam;
  const Pose& T = cam.T_B_C();
  EXPECT_TRUE(T.linear().col(2).isApprox(Vec3::UnitX()));   // optical axis = body forward
  EXPECT_TRUE(T.linear().col(0).isApprox(-Vec3::UnitY()));  // image right = body right
  EXPECT_TRUE(T.linear().col(1).isApprox(-Vec3::UnitZ()));  // image down = body down
  EXPECT_TRUE(T.translation().isApprox(Vec3(0.085, 0, 0.13)));
}

TEST(FisheyeCamera, InvalidConfigNamesTheKey) {
  FisheyeCameraConfig cfg;
  cfg.fx_px = -1;
  cfg.scale = 0.3;
  try {
    FisheyeCamera cam(cfg);
    FAIL();
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.issues().size(), 2u);
    EXPECT_EQ(e.issues()[0].key, "fx_px");
    EXPECT_EQ(e.issues()[1].key, "scale");
  }
}

}  // namespace
}  // namespace msb
