// msbench map-replay: run the MonoSpheres mapper over a recorded perception log and export the
// map (map.ply, map_stats.csv, topdown.png, summary.json).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/common/png.h"
#include "core/common/strict_number.h"
#include "core/common/wall_time.h"
#include "core/eval/column_coverage.h"
#include "core/eval/map_safety.h"
#include "core/methods/monospheres/map/sphere_map.h"
#include "core/methods/monospheres/planner/monospheres_explorer.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/map_replay.h"
#include "tools/results/flight_records.h"
#include "tools/results/mission_outputs.h"
#include "tools/results/output_files.h"
#include "tools/results/perception_log.h"

namespace msb {

namespace {

// map_stats.csv: one line per map update.
std::string mapStatsCsv(const Replay& r) {
  std::ostringstream csv;
  csv << "t,skipped,input_points,virtual_points,spheres,obstacles,new_spheres,updated_spheres,deleted_spheres,"
         "sparsified_spheres,deleted_obstacles,protected_obstacles,inserted_obstacles,frontiers,new_frontiers,"
         "dropped_frontiers,polyhedron_ms,dbof_ms,spheres_ms,sampling_ms,graph_ms,obstacles_ms,frontiers_ms,total_ms\n";
  for (size_t i = 0; i < r.stats.size(); ++i) {
    const auto& s = r.stats[i];
    csv << r.t[i] << ',' << s.skipped << ',' << s.input_points << ',' << s.virtual_points << ',' << r.spheres[i] << ','
        << r.obstacles[i] << ',' << s.new_spheres << ',' << s.updated_spheres << ',' << s.deleted_spheres << ','
        << s.sparsified_spheres << ',' << s.deleted_obstacles << ',' << s.protected_obstacles << ','
        << s.inserted_obstacles << ',' << r.frontiers[i] << ',' << s.new_frontiers << ',' << s.dropped_frontiers << ','
        << s.polyhedron_ms << ',' << s.dbof_ms << ',' << s.spheres_ms << ',' << s.sampling_ms << ',' << s.graph_ms
        << ',' << s.obstacles_ms << ',' << s.frontiers_ms << ',' << r.total_ms[i] << '\n';
  }
  return csv.str();
}

// topdown.png: spheres (blue discs), obstacle points (black), frontiers (magenta), the estimated
// camera path (orange), over 2.5 m column grid lines.
cv::Mat replayTopDown(const PerceptionLog& log, const SphereMap& map) {
  Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const auto& f : log.frames) {
    lo = lo.cwiseMin(f.points.T_W_C.translation().head<2>());
    hi = hi.cwiseMax(f.points.T_W_C.translation().head<2>());
  }
  for (const auto& [id, s] : map.spheres()) {
    lo = lo.cwiseMin(Vec2(s.centre.head<2>() - Vec2::Constant(s.radius)));
    hi = hi.cwiseMax(Vec2(s.centre.head<2>() + Vec2::Constant(s.radius)));
  }
  lo.array() -= 5, hi.array() += 5;
  const double mpp = std::max(0.05, std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 1000.0);
  cv::Mat img(int((hi.y() - lo.y()) / mpp), int((hi.x() - lo.x()) / mpp), CV_8UC3, cv::Scalar(245, 245, 245));
  auto px = [&](const Vec3& p) { return cv::Point(int((p.x() - lo.x()) / mpp), int((hi.y() - p.y()) / mpp)); };
  // Column grid lines (2.5 m, or coarser on huge extents: at most ~400 lines a direction).
  const double step = std::max(2.5, std::ceil(std::max(hi.x() - lo.x(), hi.y() - lo.y()) / 400.0 / 2.5) * 2.5);
  for (int k = 0; k <= int((hi.x() - lo.x()) / step) + 1; ++k) {
    const double x = std::floor(lo.x() / step) * step + k * step;
    cv::line(img, px({x, lo.y(), 0}), px({x, hi.y(), 0}), cv::Scalar(225, 225, 225));
  }
  for (int k = 0; k <= int((hi.y() - lo.y()) / step) + 1; ++k) {
    const double y = std::floor(lo.y() / step) * step + k * step;
    cv::line(img, px({lo.x(), y, 0}), px({hi.x(), y, 0}), cv::Scalar(225, 225, 225));
  }
  cv::Mat discs = img.clone();
  for (const auto& [id, s] : map.spheres())
    cv::circle(discs, px(s.centre), int(s.radius / mpp), cv::Scalar(230, 160, 90), -1);
  cv::addWeighted(discs, 0.45, img, 0.55, 0, img);
  for (const auto& [id, o] : map.obstacles()) cv::circle(img, px(o.position), 1, cv::Scalar(20, 20, 20), -1);
  for (const auto& [id, f] : map.frontiers()) cv::circle(img, px(f.position), 3, cv::Scalar(200, 40, 200), -1);
  for (size_t i = 1; i < log.frames.size(); ++i)
    cv::line(img, px(log.frames[i - 1].points.T_W_C.translation()), px(log.frames[i].points.T_W_C.translation()),
             cv::Scalar(0, 140, 255), 2);
  return img;
}

// Ground truth for the safety check when the log's world is a generated world; else none and
// the reason, said in summary.json and on stdout (never silently).
struct LogTruth {
  std::optional<WorldTruth> truth;
  std::string missing;  ///< why there is none ("" with truth)
};
LogTruth logTruth(const PerceptionLog& log) {
  LogTruth t;
  if (!log.header.contains("world")) {
    t.missing = "the log's header names no world";
    return t;
  }
  const std::string world = log.header["world"].get<std::string>();
  try {
    const ResolvedWorld w = resolveWorld(world);
    if (w.built)
      t.truth.emplace(w.built->generated.shapes);
    else
      t.missing = "world '" + world + "' is an MJCF file, not a generated world with ground truth";
  } catch (const std::exception& e) {
    t.missing = "world '" + world + "' cannot be resolved here: " + e.what();
  }
  return t;
}

// Corridor coverage: share of the flown camera positions (every 10th frame) inside the map's
// free space at the end; also without the take-off and landing metres (camera below 1 m).
struct PathCoverage {
  long samples = 0, covered = 0, high_samples = 0, high_covered = 0;
};
PathCoverage pathCoverage(const PerceptionLog& log, const SphereMap& map) {
  PathCoverage c;
  for (size_t i = 0; i < log.frames.size(); i += 10) {
    const Vec3 p = log.frames[i].points.T_W_C.translation();
    const bool inside = !map.spheresNear(p, 0.0).empty();
    ++c.samples;
    c.covered += inside;
    if (log.frames[i].T_W_C_truth.translation().z() >= 1.0) ++c.high_samples, c.high_covered += inside;
  }
  return c;
}

// summary.json → map_safety (worlds with ground truth).
nlohmann::json mapSafetyJson(const Replay& r) {
  const auto& sf = r.safety;
  nlohmann::json by_kind;
  for (const auto& [k, n] : sf.unsafe_by_kind)
    by_kind[k] = {{"unsafe_share", double(n) / std::max(1L, sf.events)},
                  {"unsafe_volume_share", sf.unsafe_volume_by_kind.at(k) / std::max(1e-9, sf.volume)}};
  return {{"sphere_events", sf.events},
          {"unsafe_share", double(sf.unsafe) / std::max(1L, sf.events)},
          {"unsafe_volume_share", sf.unsafe_volume / std::max(1e-9, sf.volume)},
          {"safe_volume_share", 1.0 - sf.unsafe_volume / std::max(1e-9, sf.volume)},
          {"unsafe_by_kind", by_kind},
          {"unsafe_by_object", sf.unsafe_by_object},
          {"free_volume_share", 1.0 - sf.occupied_volume / std::max(1e-9, sf.volume)},
          {"free_volume_share_by_nearest_kind",
           [&] {
             nlohmann::json k;
             for (const auto& [kind, v] : sf.volume_by_kind)
               k[kind] = 1.0 - sf.occupied_volume_by_kind.at(kind) / std::max(1e-9, v);
             return k;
           }()},
          {"median_intrusion_m", percentile(sf.intrusion_m, 0.5)},
          {"rule", r.safety_rule}};
}

// summary.json → obstacle_truth: the obstacle points by placement against the truth.
nlohmann::json obstacleTruthJson(const Replay& r) {
  const auto counts = [](const PointPlacement& p) {
    return nlohmann::json{{"inside", p.inside},
                          {"near_surface", p.near_surface},
                          {"floating", p.floating},
                          {"floating_over_2m", p.floating_far},
                          {"floating_share", double(p.floating) / double(std::max<size_t>(1, p.total()))}};
  };
  return {{"inserted", counts(r.inserted)},
          {"dbof_deleted", counts(r.dbof_deleted)},
          {"final", counts(r.final_obstacles)},
          {"rule",
           "each point classified in the true frame of the update that inserted it: inside an obstacle "
           "(signed distance < -0.5 m), near a surface (|d| <= 0.5 m), floating in free space (d > 0.5 m; "
           "floating_over_2m: d > 2 m)"}};
}

// The obstacle points by placement on stdout.
void printObstacleTruth(const Replay& r) {
  const auto line = [](const char* what, const PointPlacement& p) {
    const double pct = 100.0 / double(std::max<size_t>(1, p.total()));
    std::printf(
        "obstacle points %s: %zu (%.1f %% floating in free space, %.1f %% over 2 m from a surface; "
        "%.1f %% near a surface, %.1f %% inside)\n",
        what, p.total(), pct * p.floating, pct * p.floating_far, pct * p.near_surface, pct * p.inside);
  };
  line("inserted", r.inserted);
  line("deleted by DBOF", r.dbof_deleted);
  line("in the final map", r.final_obstacles);
}

// The safety statistics on stdout.
void printMapSafety(const Replay& r) {
  const auto& sf = r.safety;
  std::printf("map safety: %ld sphere creations/growths, %.2f %% unsafe (%.2f %% of volume)", sf.events,
              100.0 * sf.unsafe / std::max(1L, sf.events), 100.0 * sf.unsafe_volume / std::max(1e-9, sf.volume));
  for (const auto& [k, n] : sf.unsafe_by_kind) std::printf("; %s %ld", k.c_str(), n);
  std::printf("\nmap safety: %.2f %% of the sphere volume is really free",
              100.0 * (1.0 - sf.occupied_volume / std::max(1e-9, sf.volume)));
  for (const auto& [kind, v] : sf.volume_by_kind)
    std::printf("; near %s %.2f %%", kind.c_str(),
                100.0 * (1.0 - sf.occupied_volume_by_kind.at(kind) / std::max(1e-9, v)));
  std::printf("\n");
}

}  // namespace

int runMapReplayCommand(int argc, char** argv) {
  const std::vector<std::string> sets = takeRepeatedOption(argc, argv, "set");
  ArgParser args("msbench map-replay",
                 "Run the MonoSpheres mapper over a recorded perception log (vio-eval --record) and\n"
                 "write map.ply, map_stats.csv, topdown.png and summary.json. --set map.KEY=VALUE\n"
                 "(repeatable) changes mapper settings, spelt as in a scenario without `method.`:\n"
                 "--set switches.dbof=false, --set map.r_max_m=8.");
  args.positional("LOG", "perception log")
      .option("out", "", "output directory", true)
      .option("map-rate-hz", "5", "map update rate")
      .option("seed", "1", "seed of the map_sampling stream")
      .flag("overwrite", "replace an existing output directory");
  if (!args.parse(argc, argv)) return kExitOk;
  const SphereMapConfig cfg = loadMapOverrides(sets);
  const double rate_hz = args.getDoubleIn("map-rate-hz", 0.01, 1000.0);
  uint64_t seed;
  std::string why;
  if (!parseUnsigned(args.get("seed"), &seed, &why)) throw UsageError("--seed: " + why);
  checkNoOverlap({{"LOG", args.get("LOG")}}, {{"--out", args.get("out")}});
  const PerceptionLog log = readReplayableLog(args.get("LOG"));
  StagedOutputDir out(args.get("out"), args.has("overwrite"), OutputKind::kMapReplay);
  SphereMap map(cfg, cameraFromHeader(args.get("LOG"), log.header), seed);
  // Ground truth for the safety check when the log's world is a generated world.
  const LogTruth lt = logTruth(log);
  const std::optional<WorldTruth>& truth = lt.truth;
  const Replay r = replay(log, map, rate_hz, truth ? &*truth : nullptr);

  writeFileAtomic(out.staging() / "map_stats.csv", mapStatsCsv(r));

  // map.ply: spheres (kind 0, with radius), obstacle points (1), frontiers (2).
  writeFileAtomic(out.staging() / "map.ply", mapPly(sphereMapSnapshot(map)));

  writePng(out.staging() / "topdown.png", viewOf(replayTopDown(log, map)));

  // Explored area as in the paper (the metric of core/eval, final map only).
  ColumnCoverage columns;
  for (const auto& [id, sp] : map.spheres()) columns.markDisk(sp.centre.head<2>(), sp.radius);
  double volume = 0;
  for (const auto& [id, sp] : map.spheres()) volume += 4.0 / 3.0 * M_PI * std::pow(sp.radius, 3);
  const PathCoverage pc = pathCoverage(log, map);
  const nlohmann::json j = {
      {"updates", r.stats.size()},
      {"covered_columns", columns.count()},
      {"covered_area_m2", columns.areaM2()},
      {"flown_path_in_free_space_share", double(pc.covered) / std::max(1L, pc.samples)},
      {"flown_path_above_1m_in_free_space_share", double(pc.high_covered) / std::max(1L, pc.high_samples)},
      {"flown_path_above_1m_in_free_space_at_the_time_share", double(r.live_covered) / std::max(1L, r.live_samples)},
      {"sphere_volume_sum_m3", volume},
      {"spheres", map.spheres().size()},
      {"obstacle_points", map.obstacles().size()},
      {"frontiers", map.frontiers().size()},
      {"graph_connected", map.connected()},
      {"update_ms",
       {{"median", percentile(r.total_ms, 0.5)},
        {"p95", percentile(r.total_ms, 0.95)},
        {"p99", percentile(r.total_ms, 0.99)},
        {"max", percentile(r.total_ms, 1.0)}}},
      {"log", args.get("LOG")}};
  nlohmann::json summary = j;
  if (truth) {
    summary["map_safety"] = mapSafetyJson(r);
    summary["obstacle_truth"] = obstacleTruthJson(r);
    printMapSafety(r);
    printObstacleTruth(r);
  } else {
    summary["map_safety"] = nullptr;
    summary["map_safety_missing"] = lt.missing;
    std::printf("map-replay: no map safety statistics: %s\n", lt.missing.c_str());
  }
  writeFileAtomic(out.staging() / "summary.json", summary.dump(2) + "\n");
  out.commit();
  std::printf(
      "map-replay: %zu updates, %zu spheres, %zu obstacle points, %zu columns covered (%.0f m2), "
      "%.0f %% of the flown path in free space (%.0f %% above 1 m; %.0f %% at the time); update ms median %.2f, p99 "
      "%.2f -> %s\n",
      r.stats.size(), map.spheres().size(), map.obstacles().size(), columns.count(), columns.areaM2(),
      100.0 * pc.covered / std::max(1L, pc.samples), 100.0 * pc.high_covered / std::max(1L, pc.high_samples),
      100.0 * r.live_covered / std::max(1L, r.live_samples), percentile(r.total_ms, 0.5), percentile(r.total_ms, 0.99),
      out.finalDir().c_str());
  return kExitOk;
}

}  // namespace msb
