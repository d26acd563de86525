// msbench render-probe: one grey-scale fisheye frame from a vehicle pose, as PNG.
#include <cstdio>
#include <optional>
#include <sstream>
#include <vector>

#include "core/common/png.h"
#include "core/common/strict_number.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/render/fisheye_renderer.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/flight_records.h"
#include "tools/results/output_files.h"

namespace msb {

namespace {

// Parses "x,y,z,yaw_deg".
Vec4 parsePose(const std::string& s) {
  // Exactly four comma-separated numbers, each through the strict reader.
  std::vector<std::string> parts;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, ',');) parts.push_back(part);
  if (!s.empty() && s.back() == ',') parts.push_back("");
  if (parts.size() != 4)
    throw UsageError("--pose: expected x,y,z,yaw_deg (four numbers), got " + std::to_string(parts.size()) +
                     " values in '" + s + "'");
  Vec4 v;
  for (int i = 0; i < 4; ++i) {
    std::string why;
    if (!parseNumber(parts[size_t(i)], &v[i], &why))
      throw UsageError("--pose: value " + std::to_string(i + 1) + ": " + why);
  }
  return v;
}

double parseScale(const ArgParser& args) {
  const double s = args.getDouble("scale");
  if (s != 1.0 && s != 0.5) throw UsageError("--scale: must be 1 or 0.5");
  return s;
}

}  // namespace

int runRenderProbeCommand(int argc, char** argv) {
  ArgParser args("msbench render-probe",
                 "Render one grey-scale fisheye frame from a vehicle pose and write it as PNG.");
  args.option("world", "test", "world name or MJCF file")
      .option("pose", "0,0,1.5,0", "vehicle body pose x,y,z (m), yaw (deg)")
      .option("out", "", "output PNG file", true)
      .flag("overwrite", "replace an existing output file")
      .option("scale", "1", "image scale: 1 (752x480) or 0.5 (376x240)")
      .option("face-focal-ratio", "1.0", "cube-face focal length / fisheye focal length")
      .flag("no-sky", "leave the sky black (render.sky: false)")
      .flag("no-sun", "no sun, ambient light only (render.sun: false)")
      .option("conditions", "default",
              "light and visibility preset (docs/conditions.md): default, noon,\n"
              "low_sun, dusk, overcast, haze, fog, dusk_haze");
  if (!args.parse(argc, argv)) return kExitOk;
  const Vec4 pose = parsePose(args.get("pose"));
  FisheyeCameraConfig cam_cfg;
  cam_cfg.scale = parseScale(args);
  FisheyeRendererConfig render_cfg;
  render_cfg.face_focal_ratio = args.getDouble("face-focal-ratio");
  render_cfg.sky = !args.has("no-sky");
  render_cfg.sun = !args.has("no-sun");
  const auto conditions = conditionsPreset(args.get("conditions"));
  if (!conditions) throw UsageError("--conditions: unknown preset '" + args.get("conditions") + "'");
  render_cfg.conditions = *conditions;
  const std::string world = resolveWorld(args.get("world")).world_xml;
  checkOutputFile(args.get("out"), args.has("overwrite"), "out", isMsbenchPng);

  const Pose T_W_B = poseFromXyzYaw(pose.head<3>(), pose[3] * M_PI / 180.0);
  // The start pose is what the user gave as --pose: a refusal names that flag, not start.position.
  std::optional<QuadrotorSim> built;
  try {
    built.emplace(PhysicsConfig{}, world, T_W_B);
  } catch (const ConfigError& e) {
    if (e.issues().size() != 1 || e.issues()[0].key != "start.position") throw;
    throw UsageError("--pose " + args.get("pose") + ": " + e.issues()[0].reason);
  }
  QuadrotorSim& sim = *built;
  const FisheyeCamera camera(cam_cfg);
  FisheyeRenderer renderer(render_cfg, camera, sim.model());
  CameraFrame frame;
  RenderTiming t;
  renderer.render(sim.data(), T_W_B * camera.T_B_C(), &frame, &t);
  throwIfInterrupted();  // rendered, nothing written yet
  writeFileAtomic(args.get("out"), encodePng(frame));
  std::printf(
      "render-probe: %dx%d frame in %.1f ms (scene %.1f, render %.1f, read-back %.1f, "
      "remap %.1f) -> %s\n",
      frame.width, frame.height, t.totalMs(), t.scene_ms, t.render_ms, t.readback_ms, t.remap_ms,
      args.get("out").c_str());
  return kExitOk;
}

}  // namespace msb
