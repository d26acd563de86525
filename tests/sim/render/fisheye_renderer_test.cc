// Rendering checks on worlds with known content: geometry (bright markers land where the camera
// model predicts), seams (uniform wall stays uniform across cube faces), determinism.
#include "sim/render/fisheye_renderer.h"
#include "sim/render/render_conditions.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "sim/physics/quadrotor_sim.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// Writes an MJCF world with the given worldbody content into a fresh temp file.
std::string writeWorld(const std::string& name, const std::string& assets, const std::string& body) {
  const fs::path dir = fs::path(::testing::TempDir()) / "msb_render_test";
  fs::create_directories(dir);
  const fs::path file = dir / (name + ".xml");
  std::ofstream(file) << "<mujoco model=\"" << name << "\"><asset>" << assets << "</asset><worldbody>" << body
                      << "</worldbody></mujoco>";
  return file.string();
}

struct Scene {
  std::unique_ptr<QuadrotorSim> sim;
  FisheyeCamera camera;
  std::unique_ptr<FisheyeRenderer> renderer;
  Pose T_W_B;

  Scene(const std::string& world, const Pose& T, double scale = 1.0, FisheyeRendererConfig rcfg = {})
      : camera([&] {
          FisheyeCameraConfig c;
          c.scale = scale;
          return c;
        }()),
        T_W_B(T) {
    sim = std::make_unique<QuadrotorSim>(PhysicsConfig{}, world, T);
    sim->beginTick();
    renderer = std::make_unique<FisheyeRenderer>(rcfg, camera, sim->model());
  }
  CameraFrame render() {
    CameraFrame f;
    renderer->render(sim->data(), T_W_B * camera.T_B_C(), &f);
    return f;
  }
};

uint8_t at(const CameraFrame& f, int u, int v) { return f.pixels[size_t(v) * f.width + u]; }

// How two equally sized frames differ: the number of differing pixels and the mean |difference|.
struct PixelDifference {
  long differing = 0;
  double mean_abs = 0;
};
PixelDifference difference(const CameraFrame& a, const CameraFrame& b) {
  PixelDifference out;
  double abs_sum = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const int d = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    out.differing += d > 0;
    abs_sum += d;
  }
  out.mean_abs = a.pixels.empty() ? 0.0 : abs_sum / double(a.pixels.size());
  return out;
}

TEST(FisheyeRenderer, BrightMarkersAppearWhereTheCameraModelPredicts) {
  // Directions in the camera frame: centre, off-axis, on face seams, near the FoV edge.
  const std::vector<Vec3> dirs = {{0, 0, 1},      {0.5, 0, 1},   {1, 0.3, 1},    {-1, -0.2, 1},
                                  {0.2, 1, 1},    {-0.3, -1, 1}, {1, 0.8, 0.9},  {3, 0.2, 0.5},
                                  {-3, 0.3, 0.4}, {1, 1, 0.5},   {-0.6, 0.4, 1}, {2, -0.5, 1}};
  const Pose T_W_B = poseFromXyzYaw(Vec3(1, 2, 10), 0.3);
  const FisheyeCamera cam;
  const Pose T_W_C = T_W_B * cam.T_B_C();
  std::ostringstream body;
  const double range = 8.0, radius = 0.06;
  for (size_t i = 0; i < dirs.size(); ++i) {
    const Vec3 p = T_W_C * (range * dirs[i].normalized());
    body << "<geom name=\"marker" << i << "\" type=\"sphere\" size=\"" << radius << "\" pos=\"" << p.x() << ' ' << p.y()
         << ' ' << p.z() << "\" material=\"bright\"/>";
  }
  const std::string world =
      writeWorld("markers", "<material name=\"bright\" emission=\"1\" rgba=\"1 1 1 1\"/>", body.str());
  Scene scene(world, T_W_B);
  const CameraFrame f = scene.render();
  for (size_t i = 0; i < dirs.size(); ++i) {
    const Vec2 predicted = cam.project(dirs[i]);
    ASSERT_TRUE(cam.inImage(predicted)) << i;
    // Intensity-weighted centroid of bright pixels near the prediction.
    double sw = 0, su = 0, sv = 0;
    const int r = 10;
    for (int v = int(predicted.y()) - r; v <= int(predicted.y()) + r; ++v)
      for (int u = int(predicted.x()) - r; u <= int(predicted.x()) + r; ++u) {
        if (u < 0 || v < 0 || u >= f.width || v >= f.height) continue;
        const double w = at(f, u, v);
        if (w < 40) continue;
        sw += w, su += w * u, sv += w * v;
      }
    ASSERT_GT(sw, 0.0) << "marker " << i << " not visible near " << predicted.transpose();
    const Vec2 seen(su / sw, sv / sw);
    EXPECT_LT((seen - predicted).norm(), 1.0)
        << "marker " << i << " predicted " << predicted.transpose() << " seen " << seen.transpose();
  }
}

// A grey wall 10 m ahead; with `sky`, a white self-lit sky plane 100 m ahead (the sky group).
std::string clipWorld(bool sky) {
  return writeWorld(
      sky ? "clip_sky" : "clip_cave",
      "<material name=\"grey\" rgba=\"0.4 0.4 0.4 1\"/>"
      "<material name=\"sky\" rgba=\"0.85 0.85 0.85 1\" emission=\"1\"/>",
      "<geom name=\"wall\" type=\"box\" pos=\"10 0 0\" size=\"0.2 3 3\" material=\"grey\"/>" +
          std::string(sky ? "<geom name=\"sky_east\" type=\"plane\" pos=\"100 0 0\" size=\"200 200 1\" "
                            "euler=\"0 -90 0\" material=\"sky\" contype=\"0\" conaffinity=\"0\" group=\"5\"/>"
                          : ""));
}

TEST(FisheyeRenderer, NothingBeyondTheCameraClipIsDrawnTheSkyColourShowsInstead) {
  const Pose T = poseFromXyzYaw(Vec3(0, 0, -0.13), 0.0);  // camera centre at the origin, looking along +x
  auto centreAndEdge = [&](bool sky, double clip_m) {
    Scene scene(sky ? clipWorld(true) : clipWorld(false), T);
    FisheyeCameraConfig c;
    c.clip_far_m = clip_m;
    scene.camera = FisheyeCamera(c);
    scene.renderer = std::make_unique<FisheyeRenderer>(FisheyeRendererConfig{}, scene.camera, scene.sim->model());
    const CameraFrame f = scene.render();
    // The wall at the image centre; open sky 40° to the side of it.
    const Vec2 side = scene.camera.project(Vec3(std::sin(0.7), 0, std::cos(0.7)));
    return std::make_pair(int(at(f, 376, 240)), int(at(f, int(side.x()), int(side.y()))));
  };
  const auto [wall, sky] = centreAndEdge(true, 40.0);  // the reference's 40 m clip
  EXPECT_GT(wall, 20);
  EXPECT_LT(wall, 200);
  EXPECT_EQ(sky, 255);  // the sky plane at 100 m is beyond the clip: the sky colour shows
  const auto [clipped_wall, sky2] = centreAndEdge(true, 5.0);
  EXPECT_EQ(clipped_wall, 255);  // the wall at 10 m is beyond a 5 m clip
  EXPECT_EQ(sky2, 255);
  const auto [cave_wall, cave_open] = centreAndEdge(false, 5.0);  // no sky: black beyond the clip
  EXPECT_EQ(cave_wall, 0);
  EXPECT_EQ(cave_open, 0);
}

TEST(FisheyeRenderer, UniformWallHasNoSeamsBetweenCubeFaces) {
  // A flat uniform wall 3 m ahead filling the view up to ~87° off-axis.
  const std::string world =
      writeWorld("uniform_wall", "<material name=\"flat\" rgba=\"0.6 0.6 0.6 1\"/>",
                 "<geom name=\"wall\" type=\"box\" pos=\"3.3 0 0\" size=\"0.2 80 80\" material=\"flat\"/>");
  Scene scene(world, poseFromXyzYaw(Vec3(0, 0, -0.13), 0.0));
  const CameraFrame f = scene.render();
  const auto& cam = scene.camera;
  double lo = 255, hi = 0, sum = 0;
  int n = 0, steps_checked = 0;
  double worst_step = 0;
  for (int v = 0; v < f.height; ++v)
    for (int u = 0; u < f.width; ++u) {
      const Vec3 d = cam.unproject(Vec2(u, v));
      if (std::acos(d.z()) > 80.0 * M_PI / 180.0) continue;
      const double val = at(f, u, v);
      lo = std::min(lo, val), hi = std::max(hi, val), sum += val, ++n;
      // Step to the right neighbour, in particular across face boundaries.
      if (u + 1 < f.width) {
        const Vec3 d2 = cam.unproject(Vec2(u + 1, v));
        if (std::acos(d2.z()) <= 80.0 * M_PI / 180.0) {
          worst_step = std::max(worst_step, std::abs(val - at(f, u + 1, v)));
          ++steps_checked;
        }
      }
    }
  const double mean = sum / n;
  EXPECT_GT(mean, 50.0);
  EXPECT_LT((hi - lo) / mean, 0.02) << "min " << lo << " max " << hi;
  EXPECT_LT(worst_step / mean, 0.02);
  EXPECT_GT(steps_checked, 100000);
}

TEST(FisheyeRenderer, TexturedWorldGivesAStructuredImageAndBlackOutsideTheFov) {
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  Scene scene(world, poseFromXyzYaw(Vec3(0, 0, 1.5), 0.5));
  const CameraFrame f = scene.render();
  ASSERT_EQ(f.width, 752);
  ASSERT_EQ(f.height, 480);
  int bright = 0, dark = 0;
  for (uint8_t p : f.pixels) (p > 128 ? bright : dark)++;
  EXPECT_GT(bright, 20000);
  EXPECT_GT(dark, 20000);
  EXPECT_EQ(at(f, 0, 0), 0);  // image corner: outside the 180° cone
  EXPECT_EQ(at(f, f.width - 1, f.height - 1), 0);
}

TEST(FisheyeRenderer, HalfResolutionRendersTheSameScene) {
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  Scene full(world, poseFromXyzYaw(Vec3(0, 0, 1.5), 0.5));
  Scene half(world, poseFromXyzYaw(Vec3(0, 0, 1.5), 0.5), 0.5);
  const CameraFrame a = full.render(), b = half.render();
  ASSERT_EQ(b.width, 376);
  ASSERT_EQ(b.height, 240);
  // Each half-resolution pixel matches the mean of the corresponding full-resolution 2x2 block.
  double err = 0;
  int n = 0;
  for (int v = 10; v < b.height - 10; ++v)
    for (int u = 10; u < b.width - 10; ++u) {
      const double m =
          (at(a, 2 * u, 2 * v) + at(a, 2 * u + 1, 2 * v) + at(a, 2 * u, 2 * v + 1) + at(a, 2 * u + 1, 2 * v + 1)) / 4.0;
      err += std::abs(m - at(b, u, v)), ++n;
    }
  EXPECT_LT(err / n, 12.0);
}

TEST(FisheyeRenderer, RendersAreBitIdenticalAcrossRepeatsAndInstances) {
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  const Pose T = poseFromXyzYaw(Vec3(2, -1, 1.8), -0.4);
  std::vector<uint8_t> first;
  {
    Scene s(world, T);
    first = s.render().pixels;
    EXPECT_EQ(s.render().pixels, first);
  }
  Scene again(world, T);
  EXPECT_EQ(again.render().pixels, first);
}

TEST(FisheyeRenderer, PerFaceCullingDropsPlanesOutOfViewAndKeepsThePixels) {
  // A closed room of finite planes (floor, ceiling, four walls), alone and with a few boxes.
  const std::string room =
      "<geom type='plane' size='10 10 1' rgba='0.3 0.3 0.3 1'/>"
      "<geom type='plane' size='10 10 1' pos='0 0 8' euler='180 0 0' rgba='0.8 0.8 0.8 1'/>"
      "<geom type='plane' size='10 4 1' pos='10 0 4' euler='0 -90 0' rgba='0.5 0.5 0.5 1'/>"
      "<geom type='plane' size='4 10 1' pos='-10 0 4' euler='0 90 0' rgba='0.6 0.6 0.6 1'/>"
      "<geom type='plane' size='10 4 1' pos='0 10 4' euler='90 0 0' rgba='0.4 0.4 0.4 1'/>"
      "<geom type='plane' size='10 4 1' pos='0 -10 4' euler='-90 0 0' rgba='0.7 0.7 0.7 1'/>";
  std::string boxes;
  for (int i = 0; i < 6; ++i)
    boxes += "<geom type='box' size='0.5 0.5 1' pos='" + std::to_string(-7 + 3 * i) + " " +
             std::to_string(i % 2 ? 6 : -6) + " 1' rgba='0.9 0.9 0.9 1'/>";
  FisheyeRendererConfig off;
  off.cull_per_face = false;
  for (const auto& [name, body, geoms] : {std::tuple{"room", room, 6L}, std::tuple{"room_boxes", room + boxes, 12L}}) {
    const std::string world = writeWorld(name, "", body);
    for (const double yaw : {0.0, 1.1, 2.5, -2.0}) {
      const Pose T = poseFromXyzYaw(Vec3(1, -2, 2), yaw);
      Scene culled(world, T), all(world, T, 1.0, off);
      const CameraFrame a = culled.render(), b = all.render();
      EXPECT_EQ(a.pixels, b.pixels) << name << " yaw " << yaw;
      // Without culling every geom is drawn in every face. With it, in the planes-only room,
      // the up face does not draw the floor, the down face not the ceiling and the front face
      // not the wall behind the camera.
      const long faces = long(all.renderer->faces().size());
      EXPECT_EQ(all.renderer->drawnGeomsLastFrame(), geoms * faces);
      EXPECT_LE(culled.renderer->drawnGeomsLastFrame(), geoms * faces - 3) << name << " yaw " << yaw;
    }
  }
}

TEST(FisheyeRendererTextures, NearestMipFilteringChangesTexturedPixelsSlightlyAndKeepsSharpness) {
  // The textured test world, both texture filters, same pose.
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  const Pose T = poseFromXyzYaw(Vec3(1, 0.5, 1.6), 0.7);
  FisheyeRendererConfig trilinear;
  trilinear.trilinear_textures = true;
  FisheyeRendererConfig nearest_mip;
  nearest_mip.trilinear_textures = false;
  Scene a(world, T, 1.0, trilinear), b(world, T, 1.0, nearest_mip);
  const CameraFrame fa = a.render(), fb = b.render();
  ASSERT_EQ(fa.pixels.size(), fb.pixels.size());
  // Gradient sum over the image's interior rows and columns (black outside the FoV is 0 in both).
  const auto gradient = [](const CameraFrame& f) {
    double g = 0;
    for (int v = 1; v + 1 < f.height; ++v)
      for (int u = 1; u + 1 < f.width; ++u)
        g += std::abs(at(f, u + 1, v) - at(f, u - 1, v)) + std::abs(at(f, u, v + 1) - at(f, u, v - 1));
    return g;
  };
  const PixelDifference d = difference(fa, fb);
  // The switch takes effect (textured surfaces change) ...
  EXPECT_GT(d.differing, 1000);
  // ... by little on average, and the image is not blurrier.
  EXPECT_LT(d.mean_abs, 3.0);
  EXPECT_GT(gradient(fb), 0.97 * gradient(fa));
}

TEST(FisheyeRendererTextures, GreyTexturesKeptAsOneBytePerTexelGiveTheSamePixels) {
  // The textured test world (grey image textures) plus a coloured checker, which stays RGB.
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  FisheyeRendererConfig rgb;
  rgb.single_channel_textures = false;
  for (const double yaw : {0.7, 2.6}) {
    const Pose T = poseFromXyzYaw(Vec3(1, 0.5, 1.6), yaw);
    Scene one_byte(world, T), kept_rgb(world, T, 1.0, rgb);
    EXPECT_GT(one_byte.renderer->luminanceTextures(), 0);
    EXPECT_EQ(one_byte.renderer->luminanceTextures(), one_byte.sim->model()->ntex);
    EXPECT_EQ(kept_rgb.renderer->luminanceTextures(), 0);
    EXPECT_EQ(one_byte.render().pixels, kept_rgb.render().pixels) << "yaw " << yaw;
  }
  const std::string coloured = writeWorld(
      "coloured_checker",
      "<texture name='c' type='2d' builtin='checker' rgb1='1 0 0' rgb2='0 0 1' width='64' height='64'/>"
      "<material name='m' texture='c' texrepeat='4 4'/>",
      "<geom type='plane' size='10 10 1' material='m'/><geom type='box' size='1 1 1' pos='3 0 1' material='m'/>");
  const Pose T = poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0);
  Scene a(coloured, T), b(coloured, T, 1.0, rgb);
  EXPECT_EQ(a.renderer->luminanceTextures(), 0);
  EXPECT_EQ(a.render().pixels, b.render().pixels);
}

TEST(FisheyeRendererFramebuffer, AOneChannelFramebufferGivesTheSamePixelsInAGreyWorld) {
  // The grey test world, plain and in grey fog: one-channel face buffers against RGBA ones
  // converted to grey.
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  for (const bool fog : {false, true}) {
    FisheyeRendererConfig one, rgba;
    rgba.single_channel_framebuffer = false;
    if (fog) {
      one.conditions.fog_start_m = rgba.conditions.fog_start_m = 2.0;
      one.conditions.fog_end_m = rgba.conditions.fog_end_m = 25.0;
    }
    for (const double yaw : {0.4, 2.9}) {
      const Pose T = poseFromXyzYaw(Vec3(1, 0.5, 1.6), yaw);
      Scene a(world, T, 1.0, one), b(world, T, 1.0, rgba);
      EXPECT_TRUE(modelRendersGrey(a.sim->model()));
      EXPECT_TRUE(a.renderer->singleChannelFramebuffer());
      EXPECT_FALSE(b.renderer->singleChannelFramebuffer());
      const CameraFrame fa = a.render(), fb = b.render();
      EXPECT_EQ(fa.pixels, fb.pixels) << "fog " << fog << " yaw " << yaw;
      long lit = 0;
      for (const uint8_t p : fa.pixels) lit += p > 20;
      EXPECT_GT(lit, long(fa.pixels.size() / 4));  // a real image, not an empty one
    }
  }
}

TEST(FisheyeRendererFramebuffer, AColouredWorldOrColouredFogKeepsRgbaFaceBuffers) {
  // A coloured texture, a coloured fog or a coloured geom: the grey image needs all three
  // channels, so the face buffers stay RGBA (and give the same pixels as asked for explicitly).
  FisheyeRendererConfig rgba;
  rgba.single_channel_framebuffer = false;
  const std::string coloured = writeWorld(
      "coloured_checker_fb",
      "<texture name='c' type='2d' builtin='checker' rgb1='1 0 0' rgb2='0 0 1' width='64' height='64'/>"
      "<material name='m' texture='c' texrepeat='4 4'/>",
      "<geom type='plane' size='10 10 1' material='m'/><geom type='box' size='1 1 1' pos='3 0 1' material='m'/>");
  const std::string red_box = writeWorld("red_box", "",
                                         "<geom type='plane' size='10 10 1'/>"
                                         "<geom type='box' size='1 1 1' pos='3 0 1' rgba='1 0 0 1'/>");
  const Pose T = poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0);
  for (const std::string& world : {coloured, red_box}) {
    Scene a(world, T), b(world, T, 1.0, rgba);
    EXPECT_FALSE(modelRendersGrey(a.sim->model())) << world;
    EXPECT_FALSE(a.renderer->singleChannelFramebuffer()) << world;
    EXPECT_EQ(a.render().pixels, b.render().pixels) << world;
  }
  FisheyeRendererConfig tinted_fog;
  tinted_fog.conditions.fog_end_m = 25.0;
  tinted_fog.conditions.fog_colour = {0.8, 0.7, 0.6};
  Scene fogged(std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml", T, 1.0, tinted_fog);
  EXPECT_FALSE(fogged.renderer->singleChannelFramebuffer());
}

TEST(FisheyeRenderer, AFramebufferPerFaceChangesPixelsOnlyByRounding) {
  // Each face rendered into its own framebuffer (viewport at the origin) instead of a viewport
  // of the shared atlas: the window coordinates of the vertices are rounded differently, so a
  // few edge pixels may change; nothing else does.
  const std::string world = std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml";
  FisheyeRendererConfig shared, own;
  shared.framebuffer_per_face = false;
  own.framebuffer_per_face = true;
  for (const double yaw : {0.0, 1.3, -2.2}) {
    const Pose T = poseFromXyzYaw(Vec3(1.5, -0.5, 1.7), yaw);
    Scene per_face(world, T, 1.0, own), one(world, T, 1.0, shared);
    const CameraFrame a = per_face.render(), b = one.render();
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    const PixelDifference d = difference(a, b);
    EXPECT_LT(double(d.differing) / double(a.pixels.size()), 0.01) << "yaw " << yaw;
    EXPECT_LT(d.mean_abs, 0.05) << "yaw " << yaw;
    EXPECT_EQ(per_face.render().pixels, a.pixels);  // and it is deterministic
  }
}

// The names of this process's threads (/proc/self/task/*/comm).
std::vector<std::string> threadNames() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator("/proc/self/task")) {
    std::ifstream in(e.path() / "comm");
    std::string name;
    std::getline(in, name);
    names.push_back(name);
  }
  return names;
}

TEST(FisheyeRenderer, LlvmpipeRasterisesInTheRenderingThreadWhateverLpNumThreadsSays) {
  // Mesa 22.3's llvmpipe worker threads race with the GL thread over a fence (a write into freed
  // memory; docs/robustness.md): the renderer's context must start none, even when asked to.
  // ctest runs each test in its own process, so this context is the process's first.
  ASSERT_EQ(::setenv("LP_NUM_THREADS", "2", 1), 0);
  Scene scene(std::string(MSB_SOURCE_DIR) + "/worlds/test/world.xml", poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0));
  ASSERT_GT(scene.render().pixels.size(), 0u);
  EXPECT_EQ(std::string(std::getenv("LP_NUM_THREADS")), "0");
  for (const std::string& name : threadNames()) EXPECT_EQ(name.rfind("llvmpipe", 0), std::string::npos) << name;
}

TEST(FisheyeRenderer, ThePhysicsModelIsReadNeverWritten) {
  // Every render-only setting (off-screen size, headlight, tessellation, plane grid, lights, sky
  // colour, fog) goes into the renderer's copy: the physics model stays byte for byte as loaded.
  const std::string world =
      writeWorld("physics_untouched", "<material name='sky' rgba='0.8 0.8 0.8 1' emission='0.5'/>",
                 "<light directional='true' dir='0.3 0.2 -1' diffuse='0.6 0.6 0.6'/>"
                 "<geom name='ground' type='plane' size='30 30 0.5' rgba='0.5 0.5 0.5 1'/>"
                 "<geom name='box' type='box' pos='6 0 1' size='1 1 1' rgba='0.3 0.3 0.3 1'/>"
                 "<geom name='sky_top' type='plane' size='80 80 80' pos='0 0 80' euler='180 0 0' material='sky' "
                 "contype='0' conaffinity='0' group='" +
                     std::to_string(kSkyGeomGroup) + "'/>");
  QuadrotorSim sim(PhysicsConfig{}, world, poseFromXyzYaw(Vec3(0, 0, 0.05), 0.0));
  const mjModel* m = sim.model();
  const std::string buffer_before(static_cast<const char*>(m->buffer), size_t(m->nbuffer));
  const mjVisual vis_before = m->vis;
  FisheyeRendererConfig cfg;
  cfg.sun = true;
  cfg.conditions = *conditionsPreset("dusk_haze");  // sun direction and colour, sky level, fog
  FisheyeRenderer renderer(cfg, FisheyeCamera(FisheyeCameraConfig{}), m);
  CameraFrame frame;
  renderer.render(sim.data(), poseFromXyzYaw(Vec3(0, 0, 1.5), 0.0), &frame, nullptr);
  ASSERT_GT(frame.pixels.size(), 0u);
  EXPECT_TRUE(std::string(static_cast<const char*>(m->buffer), size_t(m->nbuffer)) == buffer_before)
      << "the renderer changed the physics model's arrays";
  EXPECT_EQ(std::memcmp(&m->vis, &vis_before, sizeof(mjVisual)), 0)
      << "the renderer changed the physics model's visual settings";
}

}  // namespace
}  // namespace msb
