// Changing conditions (docs/conditions.md): fog lowers the contrast of far objects and leaves
// near ones, the sun's azimuth decides which face of a box is the brighter, frames under
// conditions are bit-identical across renderers, and the default conditions change nothing.
#include "sim/render/render_conditions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "sim/physics/quadrotor_sim.h"
#include "sim/render/fisheye_renderer.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

std::string writeWorld(const std::string& name, const std::string& assets, const std::string& body) {
  const fs::path dir = fs::path(::testing::TempDir()) / "msb_conditions_test";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".xml");
  std::ofstream(file) << "<mujoco model=\"" << name << "\"><asset>" << assets << "</asset><worldbody>" << body
                      << "</worldbody></mujoco>";
  return file.string();
}

// Renders one frame of `world` from the body pose with the given conditions.
CameraFrame renderWith(const std::string& world, const Pose& T_W_B, const RenderConditions& conditions) {
  const FisheyeCamera camera;
  QuadrotorSim sim(PhysicsConfig{}, world, T_W_B);
  sim.beginTick();
  FisheyeRendererConfig cfg;
  cfg.conditions = conditions;
  FisheyeRenderer renderer(cfg, camera, sim.model());
  CameraFrame f;
  renderer.render(sim.data(), T_W_B * camera.T_B_C(), &f);
  return f;
}

// Mean and standard deviation of the pixels within `r` of the projection of camera-frame point p.
std::pair<double, double> patchStats(const CameraFrame& f, const Vec3& p_C, int r) {
  const FisheyeCamera camera;
  const Vec2 c = camera.project(p_C);
  double s = 0, s2 = 0;
  int n = 0;
  for (int v = int(c.y()) - r; v <= int(c.y()) + r; ++v)
    for (int u = int(c.x()) - r; u <= int(c.x()) + r; ++u) {
      const double x = f.pixels[size_t(v) * f.width + u];
      s += x, s2 += x * x, ++n;
    }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean))};
}

TEST(RenderConditions, FogLowersTheContrastOfFarObjectsOnly) {
  // Two checker boxes straight ahead, one near (6 m) and one far (35 m), a little apart.
  const Pose T_W_B = poseFromXyzYaw(Vec3(0, 0, 5), 0.0);
  const FisheyeCamera camera;
  const Pose T_W_C = T_W_B * camera.T_B_C();
  const Vec3 near_C(-1.6, 0, 6), far_C(8, 0, 35);
  const Vec3 near_W = T_W_C * near_C, far_W = T_W_C * far_C;
  std::ostringstream body;
  body << "<geom type=\"box\" size=\"1 1 1\" pos=\"" << near_W.transpose() << "\" material=\"chk\"/>"
       << "<geom type=\"box\" size=\"4 4 4\" pos=\"" << far_W.transpose() << "\" material=\"chk\"/>";
  const std::string world = writeWorld(
      "fog",
      "<texture name=\"chk\" type=\"cube\" builtin=\"checker\" rgb1=\"1 1 1\" rgb2=\"0.1 0.1 0.1\" width=\"64\" "
      "height=\"64\"/><material name=\"chk\" texture=\"chk\" texrepeat=\"1 1\"/>",
      body.str());
  RenderConditions fog;
  fog.fog_start_m = 4, fog.fog_end_m = 45, fog.fog_colour = {0.7, 0.7, 0.7};
  const CameraFrame clear = renderWith(world, T_W_B, {}), foggy = renderWith(world, T_W_B, fog);
  const auto far_clear = patchStats(clear, far_C - Vec3(0, 0, 4), 10),
             far_fog = patchStats(foggy, far_C - Vec3(0, 0, 4), 10);
  const auto near_clear = patchStats(clear, near_C - Vec3(0, 0, 1), 14),
             near_fog = patchStats(foggy, near_C - Vec3(0, 0, 1), 14);
  std::printf("checker contrast (std): far %.1f -> %.1f, near %.1f -> %.1f\n", far_clear.second, far_fog.second,
              near_clear.second, near_fog.second);
  ASSERT_GT(far_clear.second, 20.0) << "the far checker is not visible";
  ASSERT_GT(near_clear.second, 20.0) << "the near checker is not visible";
  EXPECT_LT(far_fog.second, 0.35 * far_clear.second) << far_clear.second << " -> " << far_fog.second;
  EXPECT_GT(near_fog.second, 0.8 * near_clear.second) << near_clear.second << " -> " << near_fog.second;
}

TEST(RenderConditions, TheSunsAzimuthDecidesWhichFaceIsBrighter) {
  // A flat grey box turned 45° so that two faces face the camera; a directional sun.
  const Pose T_W_B = poseFromXyzYaw(Vec3(0, 0, 3), 0.0);
  const FisheyeCamera camera;
  const Pose T_W_C = T_W_B * camera.T_B_C();
  const Vec3 centre = T_W_C * Vec3(0, 0, 10);
  const double a = 2.0;
  std::ostringstream body;
  body << "<light directional=\"true\" dir=\"0 0 -1\" diffuse=\"0.5 0.5 0.5\" specular=\"0 0 0\"/>"
       << "<geom type=\"box\" size=\"" << a << ' ' << a << ' ' << a << "\" pos=\"" << centre.transpose()
       << "\" euler=\"0 0 45\" material=\"grey\"/>";
  const std::string world = writeWorld("sun", "<material name=\"grey\" rgba=\"0.5 0.5 0.5 1\"/>", body.str());
  // The two faces that face the camera, and a point in the middle of each.
  std::vector<Vec3> normals, points_C;
  for (double yaw_deg : {45.0, 135.0, 225.0, 315.0}) {
    const Vec3 n(std::cos(yaw_deg * M_PI / 180), std::sin(yaw_deg * M_PI / 180), 0);
    if (n.dot(T_W_C.translation() - centre) <= 0) continue;
    normals.push_back(n);
    points_C.push_back(T_W_C.inverse() * (centre + 1.01 * a * n / std::sqrt(1.0)));
  }
  ASSERT_EQ(normals.size(), 2u);
  auto contrast = [&](const Vec3& towards_sun) {
    RenderConditions c;
    c.sun_elevation_deg = 15;
    c.sun_azimuth_deg = std::atan2(towards_sun.y(), towards_sun.x()) * 180 / M_PI;
    c.sun_intensity = 0.6;
    const CameraFrame f = renderWith(world, T_W_B, c);
    return patchStats(f, points_C[0], 3).first - patchStats(f, points_C[1], 3).first;
  };
  std::printf("face 0 - face 1 brightness: sun facing face 0 %.1f, facing face 1 %.1f\n", contrast(normals[0]),
              contrast(normals[1]));
  // Sun behind the camera's left or right face: the face it faces is the brighter one.
  EXPECT_GT(contrast(normals[0]), 20.0);
  EXPECT_LT(contrast(normals[1]), -20.0);
}

TEST(RenderConditions, FramesUnderConditionsAreBitIdenticalAndDefaultsChangeNothing) {
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  const Pose T_W_B = poseFromXyzYaw(Vec3(0.5, -1, 1.5), 0.4);
  const RenderConditions dusk_haze = *conditionsPreset("dusk_haze");
  const CameraFrame a = renderWith(world, T_W_B, dusk_haze), b = renderWith(world, T_W_B, dusk_haze);
  EXPECT_EQ(a.pixels, b.pixels);
  const CameraFrame plain = renderWith(world, T_W_B, {});
  EXPECT_NE(a.pixels, plain.pixels);
  EXPECT_FALSE(RenderConditions{}.changesAnything());
  EXPECT_FALSE(conditionsPreset("default")->changesAnything());
  EXPECT_EQ(renderWith(world, T_W_B, *conditionsPreset("default")).pixels, plain.pixels);
  // Every preset is valid; an unknown name is none.
  for (const auto& name : conditionsPresetNames()) {
    ASSERT_TRUE(conditionsPreset(name).has_value()) << name;
    EXPECT_NO_THROW(checkValid(*conditionsPreset(name))) << name;
  }
  EXPECT_FALSE(conditionsPreset("mars").has_value());
  RenderConditions bad;
  bad.fog_start_m = 30, bad.fog_end_m = 10;
  EXPECT_THROW(checkValid(bad), ConfigError);
}

}  // namespace
}  // namespace msb
