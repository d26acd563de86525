// msbench fly: flies a scripted waypoint list and writes trajectory, IMU, frames and metrics.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/geometry/world_truth.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/crash_handler.h"
#include "tools/msbench/interrupt.h"
#include "tools/msbench/progress.h"
#include "tools/results/flight_records.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

nlohmann::json flightMetrics(const FlightSpec& spec, const FlightResult& r) {
  nlohmann::json j;
  j["status"] = runStatusName(r.status);
  j["seed"] = spec.seed;
  j["world"] = spec.world_path;
  j["sim_time_s"] = r.sim_time_s;
  j["wall_time_s"] = r.wall_time_s;
  j["real_time_factor"] = r.realTimeFactor();
  j["ticks"] = r.ticks;
  j["path_finished"] = r.path_finished;
  j["distance_flown_m"] = r.distance_flown_m;
  j["tracking_rms_m"] = r.tracking_rms_m;
  j["tracking_max_m"] = r.tracking_max_m;
  j["final_drift_m"] = r.final_drift_m;
  j["drift_percent_of_distance"] = r.distance_flown_m > 0 ? 100.0 * r.final_drift_m / r.distance_flown_m : 0.0;
  j["vio_lost_at_s"] = r.vio_lost_at_s >= 0 ? nlohmann::json(r.vio_lost_at_s) : nlohmann::json(nullptr);
  j["frames_rendered"] = r.frames_rendered;
  j["trajectory_hash"] = hexHash(r.trajectory_hash);
  if (r.collision) {
    const auto& c = *r.collision;
    j["collision"] = {
        {"t_s", c.t_s},
        {"tick", c.tick},
        {"vehicle_position_m", {c.vehicle_position_m.x(), c.vehicle_position_m.y(), c.vehicle_position_m.z()}},
        {"contact_position_m", {c.contact_position_m.x(), c.contact_position_m.y(), c.contact_position_m.z()}},
        {"vehicle_geom", c.vehicle_geom},
        {"world_geom", c.world_geom}};
  } else {
    j["collision"] = nullptr;
  }
  if (r.frames_rendered > 0) {
    const double n = r.frames_rendered;
    const auto& t = r.render_time_sum;
    j["render_ms_per_frame"] = {{"scene", t.scene_ms / n},
                                {"render", t.render_ms / n},
                                {"readback", t.readback_ms / n},
                                {"remap", t.remap_ms / n},
                                {"total", t.totalMs() / n}};
  }
  j["gl"] = r.gl_description;
  j["mujoco_warnings"] = r.mujoco_warnings;
  j["versions"] = versionInfo();
  return j;
}

}  // namespace

int runFlyCommand(int argc, char** argv) {
  ArgParser args("msbench fly",
                 "Fly a scripted waypoint list in a world (no perception yet).\n"
                 "Writes trajectory.csv, imu.csv, frames/*.png, config.yaml and "
                 "metrics.json into DIR.");
  args.positional("FILE.yaml", "flight description (world, start, waypoints, sensors)")
      .option("out", "", "output directory (created; must not hold results)", true)
      .flag("overwrite", "replace an existing non-empty output directory");
  if (!args.parse(argc, argv)) return kExitOk;

  // Load and validate everything before anything is written.
  const std::string file = args.get("FILE.yaml");
  FlightSpec spec = loadFlightSpec(file);
  const std::optional<BuiltWorld> built = resolveFlightWorld(file, spec);
  std::optional<WorldTruth> truth;  // for the oracle feature source
  if (built && spec.perception.enabled && spec.perception.source == FeatureSourceKind::kOracle)
    truth.emplace(built->generated.shapes);
  // The loop (world model, renderer) before any output exists: a bad world writes nothing.
  LoopSetup setup;
  setup.truth = truth ? &*truth : nullptr;
  ClosedLoop loop = buildNamingFile(file, [&] { return ClosedLoop(spec, setup); });
  checkNoOverlap(flightInputs(file, spec), {{"--out", args.get("out")}});
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kFly);
  fs::create_directories(out.staging() / "frames");

  // Fly: the closed loop without an explorer follows the waypoints; every N-th frame is saved;
  // SIGINT/SIGTERM stop at the end of a tick and leave nothing.
  ProgressLine progress("fly", spec.duration_s);
  int saved = 0, index = 0;
  const int every = spec.camera_stream.save_every_n;
  while (loop.running()) {
    throwIfInterrupted();
    const TickRecord& t = loop.step();
    setCrashContext(t.tick, t.t_s);
    if (t.frame) {
      if (every > 0 && index % every == 0) {
        char name[64];
        std::snprintf(name, sizeof(name), "frame_%06d_t%07.2f.png", index, t.frame->t_s);
        writeFileAtomic(out.staging() / "frames" / name, encodePng(*t.frame));
        ++saved;
      }
      ++index;
    }
    progress.update(t, loop.physicsHz());
  }
  const FlightResult& r = loop.finish();

  writeFileAtomic(out.staging() / "config.yaml", readFileText(file));
  writeFileAtomic(out.staging() / "trajectory.csv", trajectoryCsv(r.trajectory));
  writeFileAtomic(out.staging() / "imu.csv", imuCsv(r.imu));
  nlohmann::json metrics = flightMetrics(spec, r);
  metrics["frames_saved"] = saved;
  writeFileAtomic(out.staging() / "metrics.json", metrics.dump(2) + "\n");
  out.commit();

  std::printf(
      "fly: %s after %.2f s simulated (%.2f s wall, real-time factor %.2f); "
      "tracking RMS %.3f m; %d frames (%d saved); hash %s -> %s\n",
      runStatusName(r.status), r.sim_time_s, r.wall_time_s, r.realTimeFactor(), r.tracking_rms_m, r.frames_rendered,
      saved, hexHash(r.trajectory_hash).c_str(), out.finalDir().c_str());
  if (r.collision)
    std::printf("fly: collision at t=%.3f s, vehicle at (%.2f, %.2f, %.2f), %s hit %s\n", r.collision->t_s,
                r.collision->vehicle_position_m.x(), r.collision->vehicle_position_m.y(),
                r.collision->vehicle_position_m.z(), r.collision->vehicle_geom.c_str(),
                r.collision->world_geom.c_str());
  return kExitOk;
}

}  // namespace msb
