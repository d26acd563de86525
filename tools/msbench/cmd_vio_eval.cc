// msbench vio-eval: a scripted flight with the full perception running, evaluated against the
// world's ground truth by tools/results/vio_evaluation (tracks and SLAM points per frame, point
// error by distance, points on textureless or thin surfaces, drift, the cost of tracking and
// triangulation); this command flies, draws the annotated frames and prints the summary.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/common/png.h"
#include "core/eval/frontend_profile.h"
#include "core/eval/slam_point_truth.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/crash_handler.h"
#include "tools/msbench/interrupt.h"
#include "tools/msbench/progress.h"
#include "tools/results/flight_records.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/output_files.h"
#include "tools/results/perception_log.h"
#include "tools/results/provenance.h"
#include "tools/results/vio_evaluation.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// Annotated frame: tracks in grey, SLAM points coloured by depth (red near, blue far at 40 m).
cv::Mat annotate(const PerceptionSample& s) {
  const cv::Mat grey(s.frame.height, s.frame.width, CV_8UC1, const_cast<uint8_t*>(s.frame.pixels.data()));
  cv::Mat img;
  cv::cvtColor(grey, img, cv::COLOR_GRAY2BGR);
  std::map<uint64_t, double> depth;
  for (const auto& p : s.points.points) depth[p.track_id] = (p.p_W - s.points.T_W_C.translation()).norm();
  for (const auto& t : s.tracks.tracks) {
    const cv::Point c(int(t.pixel.x()), int(t.pixel.y()));
    const auto it = depth.find(t.id);
    if (it == depth.end()) {
      cv::circle(img, c, 2, cv::Scalar(160, 160, 160), 1);
      continue;
    }
    cv::Mat v(1, 1, CV_8UC1, cv::Scalar(255 - int(std::clamp(it->second / 40.0, 0.0, 1.0) * 255)));
    cv::Mat col;
    cv::applyColorMap(v, col, cv::COLORMAP_JET);
    const cv::Vec3b b = col.at<cv::Vec3b>(0, 0);
    cv::circle(img, c, 3, cv::Scalar(b[0], b[1], b[2]), -1);
  }
  char text[128];
  std::snprintf(text, sizeof(text), "t=%.2fs tracks=%zu slam=%zu (colour: depth 0-40 m)", s.frame.t_s,
                s.tracks.tracks.size(), s.points.points.size());
  cv::putText(img, text, cv::Point(8, 18), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 255, 255), 1);
  return img;
}

// The summary on stdout.
void printSummary(const nlohmann::json& j, const VioStats& st, const FlightResult& r, bool truth, const fs::path& dir) {
  const double n = std::max(1, st.frames);
  const double ps = std::max<long>(1, st.point_samples);
  const nlohmann::json& bins = j["point_error_by_distance"];
  const nlohmann::json& by_surface = j["slam_points_per_frame_by_surface"];
  std::printf("vio-eval %s: %s after %.1f s, %d frames%s\n", j["world"].get<std::string>().c_str(),
              runStatusName(r.status), r.sim_time_s, st.frames,
              r.collision ? (" (hit " + r.collision->world_geom + ")").c_str() : "");
  std::printf("  tracks/frame %.0f (min %d), SLAM points/frame %.0f, drift %.2f %% of %.0f m\n", st.tracks_sum / n,
              st.frames ? st.min_tracks : 0, st.points_sum / n, j["drift_percent_of_distance"].get<double>(),
              r.distance_flown_m);
  std::printf("  SLAM points per frame by distance from the camera:");
  for (int b = 0; b < kBins; ++b)
    std::printf(" %s %.1f", bins[b]["bin"].get<std::string>().c_str(), st.points_by_distance[b] / n);
  std::printf("\n");
  if (truth) {
    std::printf("  SLAM points per frame by surface:");
    for (const auto& [surface, v] : by_surface.items()) std::printf(" %s %.1f", surface.c_str(), v.get<double>());
    std::printf("\n");
    std::printf(
        "  points on textureless surfaces %.2f %% (%.2f %% incl. their silhouettes), thin %.2f %%, "
        "no surface %.2f %%\n",
        100 * st.textureless_interior / ps, 100 * st.textureless / ps, 100 * st.thin / ps, 100 * st.no_surface / ps);
    std::printf("  RANSAC rejected %.2f %% of tracked pairs; points < 1 m from the camera %.3f %%, spurious %.3f %%\n",
                100.0 * st.ransac_rejected / std::max<long>(1, st.ransac_tested), 100 * st.near_points / ps,
                100 * st.spurious_near / ps);
    std::printf("  errors of interior points (%.1f %% of points lie on silhouettes, not compared):\n",
                100 * st.silhouette / ps);
    std::printf("  %-9s %8s %10s %10s %14s\n", "depth", "samples", "median m", "p90 m", "pred. std m");
    for (const auto& b : bins)
      std::printf("  %-9s %8zu %10.3f %10.3f %14.3f\n", b["bin"].get<std::string>().c_str(), b["samples"].get<size_t>(),
                  b["median_error_m"].get<double>(), b["p90_error_m"].get<double>(),
                  b["median_predicted_depth_std_m"].get<double>());
  }
  std::printf("  ms/frame: tracker %.2f, triangulation %.2f, render %.2f -> %s\n", st.tracker_ms / n, st.tri_ms / n,
              st.render_ms / n, dir.c_str());
}

}  // namespace

int runVioEvalCommand(int argc, char** argv) {
  ArgParser args("msbench vio-eval",
                 "Fly a scripted path with the feature tracker and SLAM points running and evaluate\n"
                 "them against the world's ground truth (generated worlds). Writes frames.csv,\n"
                 "summary.json, trajectory.csv and annotated/*.png into DIR.");
  args.positional("FILE.yaml", "flight description (as for fly)")
      .option("out", "", "output directory", true)
      .option("annotate-every", "30", "write every N-th processed frame annotated (0 = none)")
      .option("record", "", "also record the perception stream to this log (for map-replay)")
      .flag("overwrite", "replace an existing output directory");
  if (!args.parse(argc, argv)) return kExitOk;
  const std::string file = args.get("FILE.yaml");
  FlightSpec spec = loadFlightSpec(file);
  spec.perception.enabled = true;
  const std::optional<BuiltWorld> built = resolveFlightWorld(file, spec);
  const long annotate_every = args.getIntIn("annotate-every", 0, 1000000);
  checkNoOverlap(flightInputs(file, spec), {{"--out", args.get("out")}, {"--record", args.get("record")}});
  if (!args.get("record").empty())
    checkOutputFile(args.get("record"), args.has("overwrite"), "record", kPerceptionLogMagic);
  std::optional<WorldTruth> truth;
  if (built) truth.emplace(built->generated.shapes);
  // The loop (world model, renderer) before any output exists: a bad world writes nothing.
  LoopSetup setup;
  setup.truth = truth ? &*truth : nullptr;
  ClosedLoop loop = buildNamingFile(file, [&] { return ClosedLoop(spec, setup); });
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kVioEval);
  fs::create_directories(out.staging() / "annotated");
  const FisheyeCamera camera(spec.camera);
  std::map<int64_t, Pose> gt_camera;  // ground-truth camera pose per rendered tick
  VioStats st;
  std::unique_ptr<PerceptionLogWriter> recorder;
  if (!args.get("record").empty())
    recorder = std::make_unique<PerceptionLogWriter>(
        args.get("record"), nlohmann::json{{"world", spec.world_name.empty() ? spec.world_path : spec.world_name},
                                           {"seed", spec.seed},
                                           {"camera_scale", spec.camera.scale},
                                           {"flight", file}});

  // Each processed frame: recorded, evaluated (and profiled against the truth), every N-th drawn.
  std::optional<FrontEndProfiler> profiler;
  if (truth) profiler.emplace(*truth);
  auto evaluate = [&](const PerceptionSample& s) {
    if (recorder) recorder->write(s.points, s.frame.T_W_C);
    addSample(st, s, truth, camera, gt_camera);
    if (profiler) profiler->addFrame(s.points, s.frame.T_W_C, s.frame.tick);
    if (annotate_every > 0 && (st.frames - 1) % annotate_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "frame_%06d_t%07.2f.png", st.frames - 1, s.frame.t_s);
      writePng(out.staging() / "annotated" / name, viewOf(annotate(s)));
    }
  };
  // Fly the path with perception on; evaluate every processed frame; stop on SIGINT/SIGTERM.
  ProgressLine progress("vio-eval", spec.duration_s);
  while (loop.running()) {
    throwIfInterrupted();
    const TickRecord& t = loop.step();
    setCrashContext(t.tick, t.t_s);
    if (t.points)
      evaluate(
          {*t.perceived, *t.tracks, *t.points, t.timing.tracker_ms, t.timing.triangulation_ms, t.timing.render_ms});
    progress.update(t, loop.physicsHz());
  }
  const FlightResult& r = loop.finish();
  if (recorder) recorder->close();

  nlohmann::json j = summaryJson(st, r, spec, bool(truth));
  if (profiler) j["frontend_profile"] = frontEndProfileJson(profiler->result());  // as a mission's metrics.json
  writeFileAtomic(out.staging() / "frames.csv", st.csv);
  writeFileAtomic(out.staging() / "summary.json", j.dump(2) + "\n");
  writeFileAtomic(out.staging() / "trajectory.csv", trajectoryCsv(r.trajectory));
  out.commit();

  printSummary(j, st, r, bool(truth), out.finalDir());
  return kExitOk;
}

}  // namespace msb
