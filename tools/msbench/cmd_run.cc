// msbench run: one closed-loop exploration mission from a scenario file, headless, to its end
// (duration, collision or vio_lost), with a progress line and the mission's result files.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/common/wall_time.h"
#include "core/geometry/world_truth.h"
#include "tools/config/method_table.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/engine/mission.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/crash_handler.h"
#include "tools/msbench/interrupt.h"
#include "tools/results/compute_log.h"
#include "tools/results/flight_records.h"
#include "tools/results/input_files.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/output_files.h"
#include "tools/results/perception_log.h"
#include "tools/results/provenance.h"
#include "tools/results/record_seal.h"
#include "tools/results/run_record.h"
#include "tools/results/run_video.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// Progress on stderr every 10 simulated seconds: time, real-time factor, coverage, the counters
// the method's table entry names, ETA.
void printProgress(const std::string& name, const std::string& method, double duration_s, double sim_s, double wall_s,
                   double area, const std::map<std::string, double>& c) {
  const double rtf = sim_s / std::max(wall_s, 1e-9);
  std::string counters;
  if (const MethodRegistration* entry = findRegistration(method))
    for (const std::string& k : entry->info.progress_counters)
      if (const auto it = c.find(k); it != c.end())
        counters += ", " + k + " " + std::to_string(static_cast<long>(it->second));
  std::fprintf(stderr, "run %s: t = %.0f / %.0f s, RTF %.2f, A = %.0f m²%s, ETA %.0f s\n", name.c_str(), sim_s,
               duration_s, rtf, area, counters.c_str(), (duration_s - sim_s) / std::max(rtf, 1e-9));
}

// Steps the mission to its end; records perception, video frames and progress between ticks;
// stops at the end of a tick on SIGINT/SIGTERM (nothing is kept). Returns the wall seconds the
// video took (recorded, never used).
double stepToEnd(Mission& mission, const ScenarioSpec& spec, PerceptionLogWriter* recorder, RunVideo* video,
                 bool quiet) {
  const auto wall_start = WallClock::now();
  const int64_t progress_ticks = 10 * int64_t(mission.physicsHz());
  const int64_t video_ticks = video ? video->periodTicks(mission.physicsHz()) : 0;
  if (video) video->setWaitHook([] { throwIfInterrupted(); });  // a stuck encoder never blocks a signal
  double video_s = 0;
  while (mission.running()) {
    throwIfInterrupted();
    const TickRecord& t = mission.step();
    setCrashContext(t.tick, t.t_s);
    if (recorder && t.points) recorder->write(*t.points, t.perceived->T_W_C);
    if (video && t.completed && t.tick % video_ticks == 0) {
      const auto start = WallClock::now();
      video->addFrame(mission);
      video_s += secondsSince(start);
    }
    if (!quiet && t.completed && t.tick > 0 && t.tick % progress_ticks == 0)
      printProgress(spec.name, spec.method.type, spec.flight.duration_s, t.t_s, secondsSince(wall_start),
                    mission.areaM2(), mission.explorer().counters());
  }
  return video_s;
}

// The run's result line, and the collision's if it ended in one.
void printRunSummary(const ScenarioSpec& spec, const MissionResult& r, const nlohmann::json& metrics,
                     const fs::path& dir) {
  const auto& cov = metrics["coverage"];
  char share[64] = "";  // ", NN % of explorable" when the box has explorable columns
  if (!cov["box_share"].is_null())
    std::snprintf(share, sizeof(share), ", %d %% of explorable", int(100 * cov["box_share"].get<double>()));
  std::printf(
      "run %s (%s): %s after %.0f s simulated (%.0f s wall, RTF %.2f); A = %.0f m² (box %.0f m²%s), "
      "%.0f m flown; hash %s -> %s\n",
      spec.name.c_str(), methodLabel(spec.method).c_str(), runStatusName(r.flight.status), r.flight.sim_time_s,
      r.flight.wall_time_s, r.flight.realTimeFactor(), cov["area_m2"].get<double>(), cov["area_box_m2"].get<double>(),
      share, r.flight.distance_flown_m, hexHash(r.run_hash).c_str(), dir.c_str());
  if (r.flight.collision)
    std::printf("run %s: collision at t = %.1f s, vehicle at (%.1f, %.1f, %.1f), %s hit %s\n", spec.name.c_str(),
                r.flight.collision->t_s, r.flight.collision->vehicle_position_m.x(),
                r.flight.collision->vehicle_position_m.y(), r.flight.collision->vehicle_position_m.z(),
                r.flight.collision->vehicle_geom.c_str(), r.flight.collision->world_geom.c_str());
}

// A scenario whose method is written in Python runs in the Python module, which binds this same
// loop (the binary embeds no Python): `MSB_PYTHON -m msbench run ARGS...` replaces this process.
[[noreturn]] void execPythonRun(const std::vector<std::string>& args) {
  std::string path = MSB_PYTHON_DIR;
  if (const char* old = std::getenv("PYTHONPATH"); old && *old) path.append(":").append(old);
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> all = {MSB_PYTHON, "-m", "msbench", "run"};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  execv(MSB_PYTHON, argv.data());
  throw std::runtime_error(std::string("cannot start ") + MSB_PYTHON + " for a Python method: " + std::strerror(errno));
}

}  // namespace

int runRunCommand(int argc, char** argv) {
  const std::vector<std::string> original_args(argv, argv + argc);
  const std::vector<std::string> sets = takeRepeatedOption(argc, argv, "set");
  ArgParser args("msbench run",
                 "Run one exploration mission headless. Writes config.yaml (effective scenario),\n"
                 "metrics.json, coverage.csv, trajectory.csv, timing.csv, map.ply and topdown.png\n"
                 "into DIR. --set KEY=VALUE (repeatable) overrides a scenario key, e.g.\n"
                 "--set method.switches.fff=false --set method.planner.local_radius_m=20.");
  args.positional("SCENARIO.yaml", "scenario file (see scenarios/)")
      .option("out", "", "output directory (created; must not hold results)", true)
      .option("seed", "", "override the scenario seed")
      .option("duration", "", "override the mission duration (simulated seconds)")
      .option("record", "", "also record the perception stream to this log (for map-replay)")
      .flag("video", "also write video.mp4: the camera beside the growing map (needs ffmpeg; docs/video.md)")
      .flag("quiet", "no progress line")
      .flag("overwrite", "replace an existing non-empty output directory");
  if (!args.parse(argc, argv)) return kExitOk;

  // Load, override and validate everything before anything is written.
  const std::string file = args.get("SCENARIO.yaml");
  std::vector<std::string> all_sets = sets;
  if (args.given("seed")) all_sets.push_back("seed=" + args.get("seed"));
  if (args.given("duration")) all_sets.push_back("duration_s=" + args.get("duration"));
  if (args.has("video")) all_sets.push_back("video.enabled=true");
  ScenarioSpec spec = loadScenario(file, all_sets);
  loadComputeReplay(spec, file);
  // No encoder: the encoder is named, and the flag or key that asked for it.
  if (spec.video.enabled && findFfmpeg().empty())
    throw UsageError(std::string(args.has("video") ? "--video" : file + ": video.enabled") +
                     ": the video encoder (the ffmpeg program) is not installed or not on PATH (apt-get install "
                     "ffmpeg); the scenario itself is fine");
  if (spec.method.type == kPythonMethodType || spec.goals) execPythonRun(original_args);
  // A key file named but unusable: the run goes on, self-sealed, and says so first.
  if (const SealingKey& key = processSealingKey(); !key.problem.empty())
    std::fprintf(stderr, "msbench run: the record will be self-sealed (not ranked as evaluated): %s\n",
                 key.problem.c_str());
  const std::string effective_yaml =
      effectiveScenarioYaml(runOwnComputeLog(spec));  // before the world fills in the start
  MissionWorld world = prepareMissionWorld(file, spec);
  const Aabb& box = world.box;
  std::optional<WorldTruth>& truth = world.truth;
  // Outputs never overlap the inputs or each other; a replaced log must be a perception log.
  checkNoOverlap(missionInputs(file, spec), {{"--out", args.get("out")}, {"--record", args.get("record")}});
  if (!args.get("record").empty())
    checkOutputFile(args.get("record"), args.has("overwrite"), "record", kPerceptionLogMagic);
  // Build the mission (world model, renderer, method) before any output exists: a world that
  // does not compile is bad input (exit 2) and leaves nothing behind.
  Mission mission = buildNamingFile(file, [&] { return Mission(spec, box, truth ? &*truth : nullptr); });
  StagedOutputDir out(args.get("out"), args.has("overwrite"));
  // One writer per recording too (the log is written as the run flies).
  std::optional<OutputLock> record_lock;
  if (!args.get("record").empty()) record_lock.emplace(outputPathOf(args.get("record")), "--record");
  writeFileAtomic(out.staging() / "config.yaml", configYamlText(file, !all_sets.empty(), effective_yaml));

  const bool quiet = args.has("quiet") || !spec.mission.progress;
  std::unique_ptr<PerceptionLogWriter> recorder;
  if (!args.get("record").empty())
    recorder = std::make_unique<PerceptionLogWriter>(
        args.get("record"),
        nlohmann::json{{"world", spec.flight.world_name.empty() ? spec.flight.world_path : spec.flight.world_name},
                       {"seed", spec.flight.seed},
                       {"camera_scale", spec.flight.camera.scale},
                       {"scenario", file}});
  std::unique_ptr<RunVideo> video;
  if (spec.video.enabled) {
    // The caption names the run and its method, and shows the method's progress counters.
    video = std::make_unique<RunVideo>(out.staging() / "video.mp4", spec.video,
                                       spec.name + " (" + methodLabel(spec.method) + ")", spec.flight.duration_s, box,
                                       truth ? &*truth : nullptr, mission.loop().camera().width(),
                                       mission.loop().camera().height());
    if (const MethodRegistration* e = findRegistration(spec.method.type))
      video->setCaptionCounters(e->info.progress_counters);
  }
  MissionResult r;
  double video_s = 0;
  try {
    video_s = stepToEnd(mission, spec, recorder.get(), video.get(), quiet);
    r = mission.finish();
  } catch (const Interrupted&) {
    throw;  // unwinds: the recorder and the staging directory remove themselves
  } catch (const std::exception& e) {
    // A crashed run leaves a record saying so, and what it flew up to the error (a sweep goes on
    // with the next run).
    writeErroredMissionOutputs(out.staging(), spec, mission, e.what(), -1, truth ? &*truth : nullptr);
    out.commit();
    std::fprintf(stderr, "msbench run: error: %s (recorded in %s)\n", e.what(), out.finalDir().c_str());
    return kExitRuntime;
  }

  if (recorder) recorder->close();
  // The video ends after the run's other files are written (on a full disk they go first).
  const auto extra = [&] {
    nlohmann::json j = nlohmann::json::object();
    if (video)
      j["video"] = finishRunVideo(*video, r, mission.loop().sharedFrame().get(), video_s, out.finalDir() / "video.mp4");
    return j;
  };
  nlohmann::json metrics;
  try {
    metrics = writeMissionOutputs(out.staging(), spec, r, truth ? &*truth : nullptr, extra);
  } catch (const std::exception& e) {
    // A video that took the room the run's files needed (a full disk) is given up for them:
    // the run is written again without it, its error saying why.
    if (!video) throw;
    const std::string why = std::string("given up for the run's other files: ") + e.what();
    video->abandon(why);
    const auto without = [&] { return nlohmann::json{{"video", {{"file", nullptr}, {"error", why}}}}; };
    metrics = writeMissionOutputs(out.staging(), spec, r, truth ? &*truth : nullptr, without);
    std::fprintf(stderr, "msbench run: video not written: %s\n", why.c_str());
  }
  out.commit();

  printRunSummary(spec, r, metrics, out.finalDir());
  if (const SealingKey& key = processSealingKey(); key.key)
    std::printf("run %s: record sealed under evaluator key %s\n", spec.name.c_str(), key.key->id.c_str());
  return kExitOk;
}

namespace {

// The scenario of a finished run, replayable: its config.yaml with `video.enabled` and the
// video keys given by --set; a Python method's run cannot be replayed here.
ScenarioSpec replayableScenario(const fs::path& config, std::vector<std::string> sets) {
  for (const std::string& kv : sets)
    if (kv.rfind("video.", 0) != 0) throw UsageError("--set " + kv + ": msbench video takes video.KEY=VALUE only");
  if (readInputFile(config).rfind("# NOT REPLAYABLE", 0) == 0)  // a FIFO or device refused, not read
    throw UsageError(config.string() + ": the run is not replayable (its first line says why)");
  sets.push_back("video.enabled=true");
  ScenarioSpec spec = loadScenario(config.string(), sets);
  loadComputeReplay(spec, config.string());
  if (spec.method.type == kPythonMethodType || spec.goals)
    throw UsageError(config.string() + ": a method written in Python; its video is not available (docs/video.md)");
  return spec;
}

}  // namespace

int runVideoCommand(int argc, char** argv) {
  const std::vector<std::string> sets = takeRepeatedOption(argc, argv, "set");
  ArgParser args("msbench video",
                 "Video of a finished run: replays RUN/config.yaml (same build and machine: the run\n"
                 "reproduces bit for bit), checks the replay's hash against RUN/metrics.json and adds\n"
                 "RUN/video.mp4; nothing else in RUN changes. --set video.KEY=VALUE (speedup, fps,\n"
                 "height) as in a scenario's video section (docs/video.md).");
  args.positional("RUN", "a run's directory (config.yaml, metrics.json)")
      .flag("quiet", "no progress line")
      .flag("overwrite", "replace RUN/video.mp4");
  if (!args.parse(argc, argv)) return kExitOk;
  const fs::path run = args.get("RUN");
  const MissionRecordRead read = readMissionRecord(run / "metrics.json");
  if (!read.record) throw UsageError(read.problem);
  ScenarioSpec spec = replayableScenario(run / "config.yaml", sets);
  if (findFfmpeg().empty())
    throw UsageError("msbench video: the ffmpeg program is not installed (apt-get install ffmpeg)");
  const fs::path file = run / "video.mp4";
  if (fs::exists(fs::symlink_status(file)) && !args.has("overwrite"))
    throw UsageError(file.string() + ": exists; --overwrite replaces it");
  const OutputLock lock(file, "RUN/video.mp4");
  clearStaleVideoStaging(run);  // a killed replay's encoder directory (the lock is ours: none is in use)
  MissionWorld world = prepareMissionWorld((run / "config.yaml").string(), spec);
  const WorldTruth* truth = world.truth ? &*world.truth : nullptr;
  Mission mission = buildNamingFile((run / "config.yaml").string(), [&] { return Mission(spec, world.box, truth); });

  // The replay with its video; the video is kept only if the replay is the recorded run.
  RunVideo video(file, spec.video, spec.name, spec.flight.duration_s, world.box, truth, mission.loop().camera().width(),
                 mission.loop().camera().height());
  stepToEnd(mission, spec, nullptr, &video, args.has("quiet") || !spec.mission.progress);
  const MissionResult r = mission.finish();
  video.addFinalFrames(r, mission.loop().sharedFrame().get());
  if (const std::string error = video.finish(); !error.empty())
    throw std::runtime_error("video " + file.string() + " not written: " + error);
  if (hexHash(r.run_hash) != read.record->determinism_hash)
    throw std::runtime_error("the replay of " + run.string() + " is not the recorded run (hash " + hexHash(r.run_hash) +
                             ", recorded " + read.record->determinism_hash +
                             "; another build or machine?); no video written");
  if (const std::string error = video.commit(); !error.empty())
    throw std::runtime_error("video " + file.string() + " not written: " + error);
  std::printf("video %s: %d frames of %dx%d at %d fps (%.0fx), replay hash %s matches\n", file.c_str(), video.frames(),
              video.width(), video.height(), spec.video.fps, spec.video.speedup, hexHash(r.run_hash).c_str());
  return kExitOk;
}

}  // namespace msb
