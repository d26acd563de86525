// Texture realism on rendered images: trackable corners on textured surfaces at 5 m, none inside
// textureless ones, thin rods at most 2 px wide at 10 m.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/physics/quadrotor_sim.h"
#include "sim/render/fisheye_renderer.h"
#include "sim/world/world_cache.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// A one-object world in front of a camera at (0, 0, 1.5) looking along +x.
struct OneObject {
  BuiltWorld world;
  FisheyeCamera camera;
  CameraFrame frame;
  Pose T_W_C;

  explicit OneObject(const ObjectGroupSpec& object, const std::string& tag, const FisheyeRendererConfig& render = {}) {
    WorldSpec s;
    s.name = "probe_" + tag;
    s.ground_size_m = Vec2(100, 100);
    s.exploration_box = {Vec3(-10, -10, 0), Vec3(10, 10, 5)};
    s.start_clearance_m = 0;
    s.objects = {object};
    const fs::path cache = fs::path(::testing::TempDir()) / "msb_world_render";
    world = buildWorld(s, cache.string());
    const Pose T_W_B = poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0);
    QuadrotorSim sim(PhysicsConfig{}, world.world_xml, T_W_B);
    sim.beginTick();
    FisheyeRenderer renderer(render, camera, sim.model());
    T_W_C = T_W_B * camera.T_B_C();
    renderer.render(sim.data(), T_W_C, &frame);
  }

  cv::Mat image() const {
    return cv::Mat(frame.height, frame.width, CV_8UC1, const_cast<uint8_t*>(frame.pixels.data())).clone();
  }

  // Pixels whose ray first hits a shape of `object` (or the shape of that name), eroded by
  // `margin` px (silhouettes excluded).
  cv::Mat mask(const std::string& object, int margin) const {
    const WorldTruth truth(world.generated.shapes);
    cv::Mat m(frame.height, frame.width, CV_8UC1, cv::Scalar(0));
    for (int v = 0; v < frame.height; ++v)
      for (int u = 0; u < frame.width; ++u) {
        if (!camera.pixelInFov(Vec2(u, v))) continue;
        const Vec3 d = T_W_C.linear() * camera.unproject(Vec2(u, v));
        const auto hit = truth.raycast(T_W_C.translation(), d, 200.0);
        if (hit &&
            (world.generated.shapes[hit->shape].object == object || world.generated.shapes[hit->shape].name == object))
          m.at<uint8_t>(v, u) = 255;
      }
    cv::erode(m, m, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * margin + 1, 2 * margin + 1)));
    return m;
  }

  // FAST corners (threshold 15, as the tracker) inside the mask.
  int fastCornersIn(const cv::Mat& m) const {
    std::vector<cv::KeyPoint> kps;
    cv::FAST(image(), kps, 15, true);
    int n = 0;
    for (const auto& k : kps) n += m.at<uint8_t>(int(k.pt.y), int(k.pt.x)) > 0;
    return n;
  }
};

ObjectGroupSpec wallAhead(const std::string& kind, const std::string& variant = "", const std::string& texture = "") {
  ObjectGroupSpec o;
  o.kind = kind;
  o.at = Vec2(5.0 + 2.0, 0.0);  // near face at x = 5 m
  o.yaw_deg = 90;               // length (20 m) across the view, depth 4 m
  o.size_min = o.size_max = Vec3(20.0, 4.0, 10.0);
  o.variant = variant;
  o.burned_fraction = 0.95;
  o.texture = texture;
  return o;
}

TEST(WorldTextures, TexturedWallsAt5mGiveManyFastCorners) {
  for (const std::string tex : {"facade", "bricks", "concrete", "rock"}) {
    OneObject w(wallAhead("building", "", tex), "wall_" + tex);
    const cv::Mat m = w.mask("building_0", 6);
    ASSERT_GT(cv::countNonZero(m), 20000) << tex;
    EXPECT_GE(w.fastCornersIn(m), 50) << tex;
  }
}

TEST(WorldTextures, TexturelessSurfacesGiveNoCornersInside) {
  // A burned (textureless) building face: corners only at its silhouette, none inside.
  OneObject w(wallAhead("building", "burned"), "burned");
  const cv::Mat m = w.mask("building_0_burned", 6);
  ASSERT_GT(cv::countNonZero(m), 20000);
  EXPECT_LE(w.fastCornersIn(m), 2);
  // A car at 5 m.
  ObjectGroupSpec car;
  car.kind = "car";
  car.at = Vec2(7.0, 0.0);
  car.yaw_deg = 90;
  car.size_min = car.size_max = Vec3(4.5, 1.9, 1.5);
  OneObject c(car, "car");
  // Its painted body panel is textureless inside; the car as a whole (windows, tyres, rims,
  // lights, bumpers) has structure a corner detector finds, as the reference's vehicle models.
  const cv::Mat panel = c.mask("car_0_body", 6);
  ASSERT_GT(cv::countNonZero(panel), 1000);
  EXPECT_LE(c.fastCornersIn(panel), 2);
  EXPECT_GE(c.fastCornersIn(c.mask("car_0", 0)), 10);
}

TEST(WorldTextures, EveryVehicleKindHasStructure) {
  // Each vehicle kind 7 m ahead, side on: parts (≥ 12 geoms) and corners on it.
  const std::vector<std::pair<std::string, Vec3>> kinds = {{"car", Vec3(4.5, 1.9, 1.5)},
                                                           {"suv", Vec3(4.8, 2.0, 1.8)},
                                                           {"bus", Vec3(11, 2.5, 3.2)},
                                                           {"fire_truck", Vec3(9, 2.5, 3.2)},
                                                           {"ambulance", Vec3(6, 2.2, 2.7)}};
  for (const auto& [kind, size] : kinds) {
    ObjectGroupSpec v;
    v.kind = kind;
    v.at = Vec2(9.0, 0.0);
    v.yaw_deg = 90;
    v.size_min = v.size_max = size;
    OneObject o(v, "vehicle_" + kind);
    int parts = 0;
    for (const auto& sh : o.world.generated.shapes) parts += sh.object == kind + "_0";
    EXPECT_GE(parts, 12) << kind;
    EXPECT_GE(o.fastCornersIn(o.mask(kind + "_0", 0)), 10) << kind;
  }
}

TEST(WorldTextures, ThinRodsAreAtMost2PixelsWideAt10m) {
  ObjectGroupSpec rod;
  rod.kind = "rod";
  rod.at = Vec2(10.0, 0.0);
  rod.size_min = rod.size_max = Vec3(0.03, 0.0, 6.0);
  FisheyeRendererConfig black_sky;
  black_sky.sky = false;
  OneObject w(rod, "rod", black_sky);
  // Above the horizon the rod stands against a black sky: measure its width on rows there.
  const Vec2 top = w.camera.project(w.T_W_C.inverse() * Vec3(10.0, 0, 4.5));
  const cv::Mat img = w.image();
  int widest = 0, seen_rows = 0;
  for (int v = int(top.y()); v < int(top.y()) + 20; ++v) {
    int width = 0;
    for (int u = int(top.x()) - 8; u <= int(top.x()) + 8; ++u) width += img.at<uint8_t>(v, u) > 40;
    widest = std::max(widest, width);
    seen_rows += width > 0;
  }
  EXPECT_GT(seen_rows, 15);  // the rod is visible
  EXPECT_LE(widest, 2);
}

// The sky (self-lit grey planes around outdoor worlds) and sun (world-fixed directional light),
// both on by default.
TEST(WorldRender, DefaultOutdoorFrameHasABrightSkyAndSunlitFaces) {
  // A bus: its painted lower body is a flat-grey box.
  ObjectGroupSpec bus;
  bus.kind = "bus";
  bus.at = Vec2(9.0, 0.0);
  bus.yaw_deg = 45;  // two faces of its body equally in view, lit 0.77 and 0.11 by the sun
  bus.size_min = bus.size_max = Vec3(4.0, 4.0, 3.0);
  FisheyeRendererConfig plain, sky, def;
  plain.sky = plain.sun = false;
  sky.sun = false;
  OneObject a(bus, "bus_plain", plain), b(bus, "bus_sky", sky), c(bus, "bus_default", def);
  // A pixel 35° above the horizon, straight ahead, sees only sky: black without the switch,
  // bright (≈ 0.5 emission + 0.9 · 0.5 ambient) with it, and bright by default.
  const FisheyeCamera& cam = a.camera;
  const Vec2 up = cam.project(a.T_W_C.inverse().linear() * Vec3(std::cos(0.61), 0, std::sin(0.61)));
  ASSERT_TRUE(up.y() >= 0 && up.y() < a.frame.height && up.x() >= 0 && up.x() < a.frame.width);
  EXPECT_EQ(a.image().at<uint8_t>(int(up.y()), int(up.x())), 0);
  EXPECT_GT(b.image().at<uint8_t>(int(up.y()), int(up.x())), 180);
  EXPECT_GT(c.image().at<uint8_t>(int(up.y()), int(up.x())), 150);
  // The textureless box is uniform under the ambient headlight; by default (sun) its two visible
  // faces differ in brightness (edges a tracker can use, as under Gazebo's sun).
  const cv::Mat m = a.mask("bus_0_body", 3);
  ASSERT_GT(cv::countNonZero(m), 300);
  cv::Scalar mean, sd_plain, sd_sun;
  cv::meanStdDev(a.image(), mean, sd_plain, m);
  cv::meanStdDev(c.image(), mean, sd_sun, m);
  EXPECT_LT(sd_plain[0], 1.0);
  EXPECT_GT(sd_sun[0], 2.0);
}

}  // namespace
}  // namespace msb
