// msbench bench-sim: physics steps per second and the fisheye frame's cost by stage, and
// --compare-* runs of two renderer settings side by side (time, differing frames, sharpness).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "core/common/clock.h"
#include "core/common/strict_number.h"
#include "core/common/wall_time.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/physics/se3_controller.h"
#include "sim/render/fisheye_renderer.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/flight_records.h"
#include "tools/results/output_files.h"

namespace msb {

namespace {

// Pixels whose four neighbours are inside the field of view (where sharpness is measured).
std::vector<uint8_t> innerFovMask(const FisheyeCamera& camera) {
  const int W = camera.width(), H = camera.height();
  std::vector<uint8_t> in(size_t(W) * H, 0), inner(size_t(W) * H, 0);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) in[size_t(v) * W + u] = camera.pixelInFov(Vec2(u, v)) ? 1 : 0;
  for (int v = 1; v + 1 < H; ++v)
    for (int u = 1; u + 1 < W; ++u) {
      const size_t i = size_t(v) * W + u;
      inner[i] = in[i - 1] && in[i + 1] && in[i - W] && in[i + W];
    }
  return inner;
}

// Sharpness of a frame: mean of |I(u+1,v) − I(u−1,v)| + |I(u,v+1) − I(u,v−1)| over half, over the
// mask's pixels (inside the field of view: the black outside would dominate).
double meanGradient(const CameraFrame& f, const std::vector<uint8_t>& mask) {
  double sum = 0.0;
  long n = 0;
  const size_t W = size_t(f.width);
  for (size_t i = 0; i < f.pixels.size() && i < mask.size(); ++i) {
    if (!mask[i]) continue;
    sum += 0.5 * (std::abs(int(f.pixels[i + 1]) - int(f.pixels[i - 1])) +
                  std::abs(int(f.pixels[i + W]) - int(f.pixels[i - W])));
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

// Mean absolute grey-level difference of two frames of the same size.
double meanAbsDifference(const CameraFrame& a, const CameraFrame& b) {
  if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

// A renderer switch bench-sim can compare: its --compare-* flag, the config field, and the
// labels of its two settings (each with a leading space).
struct RendererSwitch {
  const char* flag;
  bool FisheyeRendererConfig::*field;
  const char* label_on;
  const char* label_off;
  /// The label of a setting of the switch.
  const char* label(bool on) const { return on ? label_on : label_off; }
};
const RendererSwitch kRendererSwitches[] = {
    {"compare-cull", &FisheyeRendererConfig::cull_per_face, " culled", " not culled"},
    {"compare-textures", &FisheyeRendererConfig::trilinear_textures, " trilinear", " nearest mip"},
    {"compare-framebuffers", &FisheyeRendererConfig::framebuffer_per_face, " framebuffer per face",
     " shared framebuffer"},
    {"compare-texture-format", &FisheyeRendererConfig::single_channel_textures, " one-byte textures", " RGB textures"},
    {"compare-framebuffer-format", &FisheyeRendererConfig::single_channel_framebuffer, " one-channel framebuffer",
     " RGBA framebuffer"},
};

// Physics: a controlled hover at 2 m, controller every step, with the contact gate on and off;
// prints steps/s and how many steps ran collision detection.
void benchPhysics(const std::string& world, long steps) {
  const Vec3 p0(0, 0, 2.0);
  for (const bool gate : {true, false}) {
    PhysicsConfig pcfg;
    pcfg.contact_gate = gate;
    QuadrotorSim sim(pcfg, world, poseFromXyzYaw(p0, 0.0));
    const Se3Controller controller(Se3ControllerConfig{}, QuadrotorConfig{});
    TrajectoryReference ref;
    ref.position_m = p0;
    auto t0 = WallClock::now();
    for (long i = 0; i < steps; ++i) {
      if (i % 1000 == 0) throwIfInterrupted();  // a timing loop still stops on Ctrl-C
      sim.beginTick();
      sim.endTick(controller.compute(sim.groundTruth(), ref));
    }
    const double phys_s = secondsSince(t0);
    if (gate) std::printf("world: %s (%d geoms)\n", world.c_str(), sim.geomCount());
    std::printf(
        "physics, contact gate %s: %.0f steps/s with controller (%.2f us/step, %.0fx real time at 500 Hz); "
        "collision detection in %lld of %ld steps\n",
        gate ? "on " : "off", steps / phys_s, 1e6 * phys_s / steps, steps / phys_s / 500.0,
        static_cast<long long>(sim.stepsDetected()), steps);
  }
}

// The renderer settings the flags ask for.
FisheyeRendererConfig rendererConfigOf(const ArgParser& args) {
  FisheyeRendererConfig rcfg;
  rcfg.face_focal_ratio = args.getDouble("face-focal-ratio");
  rcfg.read_red_channel_only = args.has("red-only");
  rcfg.sky = !args.has("no-sky");
  rcfg.sun = !args.has("no-sun");
  rcfg.cull_per_face = !args.has("no-cull");
  rcfg.trilinear_textures = args.has("trilinear");
  rcfg.framebuffer_per_face = !args.has("shared-framebuffer");
  rcfg.single_channel_textures = !args.has("rgb-textures");
  rcfg.single_channel_framebuffer = !args.has("rgba-framebuffer");
  return rcfg;
}

// What rendering `frames` frames measured, per renderer (one, or two for a --compare-* flag).
struct RenderBench {
  std::vector<RenderTiming> sums;
  std::vector<std::vector<double>> totals;  // per frame, ms
  std::vector<double> sharpness;
  double abs_difference = 0.0;
  long different = 0;
};

// Renders `frames` frames (after two warm-up frames) turning 6° per frame, with every renderer
// in turn.
RenderBench timeRenderers(std::vector<std::unique_ptr<FisheyeRenderer>>& renderers, QuadrotorSim& rsim,
                          const FisheyeCamera& camera, const Vec3& p0, long frames) {
  const bool compare = renderers.size() > 1;
  RenderBench b;
  b.sums.resize(renderers.size());
  b.totals.resize(renderers.size());
  b.sharpness.assign(renderers.size(), 0.0);
  const std::vector<uint8_t> inner_fov = innerFovMask(camera);
  std::vector<CameraFrame> frames_out(renderers.size());
  RenderTiming t;
  for (long i = 0; i < frames + 2; ++i) {
    throwIfInterrupted();
    const Pose T_W_B = poseFromXyzYaw(p0, i * 6.0 * M_PI / 180.0);
    for (size_t k = 0; k < renderers.size(); ++k) {
      renderers[k]->render(rsim.data(), T_W_B * camera.T_B_C(), &frames_out[k], &t);
      if (i < 2) continue;  // warm-up
      RenderTiming& sum = b.sums[k];
      sum.scene_ms += t.scene_ms, sum.render_ms += t.render_ms;
      sum.readback_ms += t.readback_ms, sum.remap_ms += t.remap_ms;
      b.totals[k].push_back(t.totalMs());
      b.sharpness[k] += meanGradient(frames_out[k], inner_fov);
    }
    if (i < 2) continue;
    if (compare && frames_out[0].pixels != frames_out[1].pixels) ++b.different;
    if (compare) b.abs_difference += meanAbsDifference(frames_out[0], frames_out[1]);
  }
  return b;
}

// Rendering at one resolution: one renderer, or two that differ in the compared switch
// rendering every frame alternately; prints each one's split and the comparison.
void benchRendering(const std::string& world, double scale, const FisheyeRendererConfig& rcfg,
                    const RendererSwitch* compared, long frames) {
  const Vec3 p0(0, 0, 2.0);
  FisheyeCameraConfig cam_cfg;
  cam_cfg.scale = scale;
  const FisheyeCamera camera(cam_cfg);
  QuadrotorSim rsim(PhysicsConfig{}, world, poseFromXyzYaw(p0, 0.0));
  rsim.beginTick();
  std::vector<std::unique_ptr<FisheyeRenderer>> renderers;
  renderers.push_back(std::make_unique<FisheyeRenderer>(rcfg, camera, rsim.model()));
  if (compared) {
    FisheyeRendererConfig other = rcfg;
    other.*compared->field = !(rcfg.*compared->field);
    renderers.push_back(std::make_unique<FisheyeRenderer>(other, camera, rsim.model()));
  }
  RenderBench b = timeRenderers(renderers, rsim, camera, p0, frames);
  const double n = static_cast<double>(frames);
  for (size_t k = 0; k < renderers.size(); ++k) {
    const FisheyeRenderer& renderer = *renderers[k];
    const RenderTiming& sum = b.sums[k];
    std::sort(b.totals[k].begin(), b.totals[k].end());
    const char* label = !compared ? "" : compared->label((k == 0) == (rcfg.*compared->field));
    std::printf(
        "fisheye %dx%d%s: %.1f ms/frame (%.1f frames/s, median %.1f ms) = scene %.2f + "
        "render %.2f + read-back %.2f + remap %.2f ms; %ld face pixels in %d faces, "
        "atlas %dx%d, face focal ratio %.2f, sharpness (mean |gradient| in the FoV) %.3f\n",
        camera.width(), camera.height(), label, sum.totalMs() / n, 1000.0 * n / sum.totalMs(),
        b.totals[k][b.totals[k].size() / 2], sum.scene_ms / n, sum.render_ms / n, sum.readback_ms / n, sum.remap_ms / n,
        renderer.renderedPixels(), static_cast<int>(renderer.faces().size()), renderer.atlasSize().width,
        renderer.atlasSize().height, rcfg.face_focal_ratio, b.sharpness[k] / n);
  }
  if (compared) {
    // Time of the default setting over the other, whichever renderer had which.
    const bool default_value = FisheyeRendererConfig{}.*compared->field;
    const size_t by_default = rcfg.*compared->field == default_value ? 0 : 1, on = rcfg.*compared->field ? 0 : 1;
    std::printf(
        "fisheye %dx%d: %s / %s time %.2f; frames with different pixels: %ld of %ld; "
        "mean |pixel difference| %.4f grey levels",
        camera.width(), camera.height(), compared->label(default_value) + 1, compared->label(!default_value) + 1,
        b.sums[by_default].totalMs() / b.sums[1 - by_default].totalMs(), b.different, frames, b.abs_difference / n);
    if (compared->field == &FisheyeRendererConfig::single_channel_textures)
      std::printf(" (%d of %d textures grey)", renderers[on]->luminanceTextures(), rsim.model()->ntex);
    if (compared->field == &FisheyeRendererConfig::single_channel_framebuffer)
      std::printf(" (model renders grey: %s)", renderers[on]->singleChannelFramebuffer() ? "yes" : "no");
    std::printf("\n");
  }
  if (scale == 1.0) std::printf("gl: %s\n", renderers[0]->description().c_str());
}

}  // namespace

int runBenchSimCommand(int argc, char** argv) {
  ArgParser args("msbench bench-sim",
                 "Measure physics steps/s (controlled hover) and fisheye frames/s with the\n"
                 "split of a frame's cost. Wall-clock figures; run on an idle machine.");
  args.option("world", "test", "world name or MJCF file")
      .option("steps", "20000", "physics steps to time")
      .option("frames", "60", "frames to time per resolution")
      .option("face-focal-ratio", "1.0", "cube-face focal length / fisheye focal length")
      .flag("red-only", "read back the red channel only (grey-scale worlds)")
      .flag("no-sky", "leave the sky black (render.sky: false)")
      .flag("no-sun", "no sun, ambient light only (render.sun: false)")
      .flag("no-cull", "draw every geom in every cube face (render.cull_per_face: false)")
      .flag("trilinear", "blend two mip levels per texture sample (render.trilinear_textures: true)")
      .flag("compare-cull",
            "time per-face culling on and off side by side, frame by frame, and check\n"
            "that both give the same pixels")
      .flag("compare-textures",
            "time trilinear and nearest-mip texture filtering side by side, frame\n"
            "by frame, with the mean pixel difference and each one's sharpness")
      .flag("rgb-textures", "keep grey textures as RGB (render.single_channel_textures: false)")
      .flag("compare-texture-format",
            "time one-byte and RGB grey textures side by side, frame by frame,\n"
            "and check that both give the same pixels")
      .flag("shared-framebuffer", "render all faces into one framebuffer (render.framebuffer_per_face: false)")
      .flag("compare-framebuffers",
            "time one framebuffer per face and one shared by all faces side by side,\n"
            "frame by frame, and check that both give the same pixels")
      .flag("rgba-framebuffer", "keep RGBA face buffers in grey worlds (render.single_channel_framebuffer: false)")
      .flag("compare-framebuffer-format",
            "time one-channel and RGBA face buffers side by side, frame by frame,\n"
            "and check that both give the same pixels");
  if (!args.parse(argc, argv)) return kExitOk;
  const std::string world = resolveWorld(args.get("world")).world_xml;
  const long steps = args.getInt("steps"), frames = args.getInt("frames");
  if (steps < 1 || frames < 1) throw UsageError("--steps and --frames must be >= 1");
  const RendererSwitch* compared = nullptr;  // the switch of a --compare-* flag, if any
  for (const RendererSwitch& sw : kRendererSwitches) {
    if (!args.has(sw.flag)) continue;
    if (compared) throw UsageError("the --compare-* flags exclude each other");
    compared = &sw;
  }
  benchPhysics(world, steps);
  // Rendering at full and half resolution, turning 6 degrees per frame.
  for (const double scale : {1.0, 0.5}) benchRendering(world, scale, rendererConfigOf(args), compared, frames);
  return kExitOk;
}

}  // namespace msb
