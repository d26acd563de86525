// msbench export RUN --out DIR: a finished run in the formats the field's tools read
// (docs/interop.md) — truth.tum and estimate.tum (evo), map.bt (octovis, liboctomap) when the
// run's method left its OctoMap, the map as binary PLYs in both frames, with --euroc the run's frames and IMU as an
// EuRoC dataset plus the calibration (Kalibr, ROS CameraInfo) — and export.json saying what each file is and in which
// frame. The run directory is only read; the output is a staged directory of its own.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/common/config_check.h"
#include "core/common/input_file.h"
#include "tools/config/method_table.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/engine/mission.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/compute_log.h"
#include "tools/results/dataset_export.h"
#include "tools/results/flight_records.h"
#include "tools/results/map_export.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"
#include "tools/results/run_record.h"
#include "tools/results/trajectory_export.h"

namespace fs = std::filesystem;

namespace msb {

namespace {

// The run's scenario, ready to replay: its config.yaml as msbench run wrote it. Refused (exit
// 2, nothing written) for a Python method (the binary embeds no Python), a held-out world (its
// frames would publish the world: docs/worlds.md, "Held-out worlds") and a record msbench
// cannot read (no hash to check the replay against).
ScenarioSpec replayScenario(const fs::path& run, std::string& recorded_hash) {
  const fs::path config = run / "config.yaml";
  const MissionRecordRead read = readMissionRecord(run / "metrics.json");
  if (!read.record) throw UsageError("--euroc: " + read.problem);
  recorded_hash = read.record->determinism_hash;
  if (readInputFile(config).rfind("# NOT REPLAYABLE", 0) == 0)
    throw UsageError("--euroc: " + config.string() + ": the run is not replayable (its first line says why)");
  ScenarioSpec spec = loadScenario(config.string(), {});
  loadComputeReplay(spec, config.string());
  if (spec.method.type == kPythonMethodType || spec.goals)
    throw UsageError("--euroc: " + config.string() + ": a method written in Python; its run cannot be replayed here");
  if (spec.flight.held_out)
    throw UsageError("--euroc: " + config.string() +
                     ": a held-out world; its frames are not exported (they would publish the world)");
  if (!spec.flight.camera_stream.enabled)
    throw UsageError("--euroc: " + config.string() + ": the run rendered no frames (camera_stream.enabled: false)");
  return spec;
}

// The replayed run's EuRoC dataset under `mav0`: every rendered frame as cam0/data/<ns>.png
// while it flies, then the frame index, the IMU, the ground truth and each sensor.yaml; and the
// calibration beside mav0. Throws if the replay is not the recorded run (another build or
// machine): the staging directory, and so every file, goes.
int writeEuroc(Mission& mission, const ScenarioSpec& spec, const std::string& recorded_hash, const fs::path& dir) {
  const fs::path cam = dir / "mav0" / "cam0", imu = dir / "mav0" / "imu0";
  const fs::path gt = dir / "mav0" / "state_groundtruth_estimate0";
  for (const fs::path& d : {cam / "data", imu, gt}) fs::create_directories(d);
  std::vector<int64_t> stamps;
  while (mission.running()) {
    throwIfInterrupted();
    const TickRecord& t = mission.step();
    if (!t.frame) continue;
    stamps.push_back(nanoseconds(t.frame->t_s));
    writeFileAtomic(cam / "data" / (std::to_string(stamps.back()) + ".png"), encodePng(*t.frame));
  }
  const MissionResult r = mission.finish();
  if (hexHash(r.run_hash) != recorded_hash)
    throw std::runtime_error("the replay is not the recorded run (hash " + hexHash(r.run_hash) + ", recorded " +
                             recorded_hash + "; another build or machine?); nothing exported");
  const FisheyeCamera& camera = mission.loop().camera();
  writeFileAtomic(cam / "data.csv", eurocCameraCsv(stamps));
  writeFileAtomic(cam / "sensor.yaml", eurocCameraSensorYaml(camera, spec.flight.camera_stream.rate_hz));
  writeFileAtomic(imu / "data.csv", eurocImuCsv(r.flight.imu));
  writeFileAtomic(imu / "sensor.yaml", eurocImuSensorYaml(spec.flight.imu));
  writeFileAtomic(gt / "data.csv", eurocGroundTruthCsv(r.flight.trajectory));
  writeFileAtomic(gt / "sensor.yaml", eurocGroundTruthSensorYaml(spec.mission.trajectory_rate_hz));
  writeFileAtomic(dir / "camchain.yaml", kalibrCamchainYaml(camera));
  writeFileAtomic(dir / "imu.yaml", kalibrImuYaml(spec.flight.imu));
  writeFileAtomic(dir / "camera_info.yaml", rosCameraInfoYaml(camera));
  return static_cast<int>(stamps.size());
}

// export.json's entries for the EuRoC dataset.
void describeEuroc(nlohmann::ordered_json& files) {
  files["mav0/cam0/data.csv"] = "EuRoC frame index: timestamp [ns], file; mav0/cam0/data/<ns>.png, mono8, every frame";
  files["mav0/imu0/data.csv"] = "EuRoC IMU: timestamp [ns], gyro (rad/s) then accel (m/s²), body frame (base_link)";
  files["mav0/state_groundtruth_estimate0/data.csv"] =
      "EuRoC ground truth: timestamp [ns], true body position, quaternion (w first), velocity; world frame (map); "
      "no bias columns";
  files["camchain.yaml"] = "Kalibr camera chain: pinhole-equi (Kannala-Brandt k1..k4), T_cam_imu";
  files["imu.yaml"] = "Kalibr IMU: noise densities and random walks of the simulated IMU";
  files["camera_info.yaml"] = "ROS CameraInfo (camera_calibration_parsers), distortion_model equidistant";
}

}  // namespace

int runExportCommand(int argc, char** argv) {
  ArgParser args("msbench export",
                 "A finished run in the formats of the field's tools (docs/interop.md): truth.tum and\n"
                 "estimate.tum (TUM: timestamp tx ty tz qx qy qz qw; evo_ape tum truth.tum estimate.tum),\n"
                 "map.bt (the method's OctoMap, when it has one: octovis), map_odom.ply and map_world.ply\n"
                 "(the map in the VIO frame and moved into the world frame: Open3D, CloudCompare) and\n"
                 "export.json (what each is).\n"
                 "--euroc replays the run (same build and machine: checked by its hash) and adds its\n"
                 "frames, IMU and ground truth as an EuRoC dataset (mav0/) with the camera's calibration\n"
                 "(camchain.yaml, imu.yaml: Kalibr; camera_info.yaml: ROS).");
  args.positional("RUN", "a run's result directory (msbench run --out)")
      .option("out", "", "output directory", true)
      .flag("euroc", "also the frames, IMU and ground truth as an EuRoC dataset (replays the run)")
      .flag("quiet", "no progress line during the --euroc replay")
      .flag("overwrite", "replace an existing export directory");
  if (!args.parse(argc, argv)) return kExitOk;
  const fs::path run = args.get("RUN");
  if (!isMsbenchOutput(run, OutputKind::kRun))
    throw UsageError("RUN: '" + run.string() + "' is not a run directory msbench wrote (msbench run --out)");
  checkNoOverlap({{"RUN", run}}, {{"--out", args.get("out")}});
  // Everything read and converted before the output exists: a bad run writes nothing.
  const fs::path csv = run / "trajectory.csv";
  const TumTrajectories tum = tumFromTrajectoryCsv(readInputFile(csv), csv.string());
  const bool has_bt = fs::is_regular_file(run / "map.bt");
  std::optional<MapPlys> map;
  if (const fs::path ply = run / "map.ply"; fs::is_regular_file(ply))
    map = mapPlysFromMapPly(readInputFile(ply), ply.string(), tum.T_true_est_final);
  nlohmann::ordered_json j;
  j["run"] = fs::absolute(run).lexically_normal().string();
  j["poses"] = tum.rows;
  j["files"]["truth.tum"] = "the true body pose, world frame (ROS map), REP-103 axes (x forward, z up); s, m";
  if (!tum.estimate.empty())
    j["files"]["estimate.tum"] = "the VIO's body pose, its drifting frame (ROS odom), as the controller flew on it";
  else
    j["not_exported"]["estimate.tum"] = "trajectory.csv predates the VIO's full orientation (est_qw..est_qz)";
  if (has_bt)
    j["files"]["map.bt"] = "the method's OctoMap at the end (liboctomap binary), VIO frame (ROS odom)";
  else
    j["not_exported"]["map.bt"] = "the run's method keeps no OctoMap (map.ply holds its map)";
  if (map) {
    j["map"] = {{"free_space", map->free_space}, {"obstacles", map->obstacles}, {"frontiers", map->frontiers}};
    j["files"]["map_odom.ply"] = "the method's map as it mapped it, VIO frame (ROS odom); binary PLY, colour by kind";
    if (!map->world.empty())
      j["files"]["map_world.ply"] =
          "the same map moved into the world frame (ROS map) by the estimate-to-truth correction at the run's end";
    else
      j["not_exported"]["map_world.ply"] = "trajectory.csv predates the VIO's full orientation (no correction)";
  } else {
    j["not_exported"]["map_odom.ply"] = "the run has no map.ply (mission.write_map_ply: false)";
  }
  // --euroc: the replay is built (its world compiled) before the output exists.
  std::string recorded_hash;
  std::optional<ScenarioSpec> spec;
  std::optional<MissionWorld> world;
  std::unique_ptr<Mission> mission;
  if (args.has("euroc")) {
    spec = replayScenario(run, recorded_hash);
    const std::string config = (run / "config.yaml").string();
    world = prepareMissionWorld(config, *spec);
    const WorldTruth* truth = world->truth ? &*world->truth : nullptr;
    mission = buildNamingFile(config, [&] { return std::make_unique<Mission>(*spec, world->box, truth); });
    describeEuroc(j["files"]);
  } else {
    j["not_exported"]["mav0"] = "the EuRoC dataset is made by msbench export --euroc (a replay of the run)";
  }
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kExport);
  int frames = 0;
  if (mission) {
    if (!args.has("quiet")) std::fprintf(stderr, "export: replaying %s for its frames and IMU\n", run.c_str());
    frames = writeEuroc(*mission, *spec, recorded_hash, out.staging());
    j["frames"] = frames;
  }
  writeFileAtomic(out.staging() / "truth.tum", tum.truth);
  if (!tum.estimate.empty()) writeFileAtomic(out.staging() / "estimate.tum", tum.estimate);
  if (has_bt) copyInputFile(run / "map.bt", out.staging() / "map.bt", [] {});
  if (map) writeFileAtomic(out.staging() / "map_odom.ply", map->odom);
  if (map && !map->world.empty()) writeFileAtomic(out.staging() / "map_world.ply", map->world);
  writeFileAtomic(out.staging() / "export.json", j.dump(2) + "\n");
  out.commit();
  std::printf("export: %d poses%s%s -> %s\n", tum.rows, has_bt ? ", map.bt" : "",
              mission ? (", EuRoC: " + std::to_string(frames) + " frames").c_str() : "", args.get("out").c_str());
  return kExitOk;
}

}  // namespace msb
