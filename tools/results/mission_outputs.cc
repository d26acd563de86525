#include "tools/results/mission_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/common/png.h"
#include "tools/results/flight_records.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"
#include "tools/results/run_record.h"

namespace msb {

namespace {
nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json stagesJson(const StageTimes& s, double per) {
  return {
      {"render", s.render_ms / per},  {"tracker", s.tracker_ms / per},   {"triangulation", s.triangulation_ms / per},
      {"map_update", s.map_ms / per}, {"planning", s.planning_ms / per}, {"metric", s.metric_ms / per}};
}
}  // namespace

namespace {

// metrics.json → coverage: the areas, the box's explorable columns, the longest stretch without gain.
nlohmann::json coverageJson(const MissionResult& r) {
  const double cell2 = r.columns.cellM() * r.columns.cellM();
  const size_t in_box = r.columns.countInside(r.exploration_box.min.head<2>(), r.exploration_box.max.head<2>());
  return {
      {"area_m2", r.columns.areaM2()},
      {"area_box_m2", double(in_box) * cell2},
      {"box_explorable_columns", r.box_explorable_columns},
      {"box_explored_explorable_columns", r.box_explored_explorable_columns},
      {"box_share", r.box_explorable_columns
                        ? nlohmann::json(double(r.box_explored_explorable_columns) / r.box_explorable_columns)
                        : nlohmann::json(nullptr)},
      {"box_share_true_frame",
       r.box_explorable_columns
           ? nlohmann::json(double(r.box_true_frame_explored_explorable_columns) / r.box_explorable_columns)
           : nlohmann::json(nullptr)},
      {"longest_no_gain_s", r.longest_no_gain.lengthS()},
      {"longest_no_gain_from_s", r.longest_no_gain.start_s},
      {"area_true_frame_m2", r.columns_gt.areaM2()},
      // The authors' evaluation rule for OctoMap maps (grid baseline; BUG-11, docs/metrics.md).
      {"area_published_rule_m2",
       r.columns_published_rule ? nlohmann::json(r.columns_published_rule->areaM2()) : nlohmann::json(nullptr)},
      // Verified coverage (docs/metrics.md): covered, truly free and seen; null without ground truth.
      {"verified_area_m2", r.columns_verified ? nlohmann::json(r.columns_verified->areaM2()) : nlohmann::json(nullptr)},
      {"verified_box_share", r.columns_verified && r.box_explorable_columns
                                 ? nlohmann::json(double(r.box_verified_explorable_columns) / r.box_explorable_columns)
                                 : nlohmann::json(nullptr)},
      {"seen_area_m2", r.columns_verified ? nlohmann::json(double(r.seen_columns) * cell2) : nlohmann::json(nullptr)},
      {"column_size_m", r.columns.cellM()},
      {"exploration_box", nlohmann::json{{"min", vec(r.exploration_box.min)}, {"max", vec(r.exploration_box.max)}}}};
}

// metrics.json → collision: where, what it hit and how it looks to the front end, the audit.
nlohmann::json collisionJson(const FlightResult& f, const MissionResult& r, const WorldTruth* truth) {
  if (!f.collision) return nullptr;
  const auto& c = *f.collision;
  nlohmann::json j = {{"t_s", c.t_s},
                      {"vehicle_position_m", vec(c.vehicle_position_m)},
                      {"contact_position_m", vec(c.contact_position_m)},
                      {"vehicle_geom", c.vehicle_geom},
                      {"world_geom", c.world_geom}};
  // The object hit and what it looks like to the front end (report: collisions by kind).
  const Shape* hit = truth ? truth->shapeNamed(c.world_geom) : nullptr;
  j["object"] = hit ? nlohmann::json(hit->object.empty() ? hit->name : hit->object) : nlohmann::json(nullptr);
  j["kind"] = hit ? nlohmann::json(obstacleKindName(hit->kind)) : nlohmann::json(nullptr);
  if (r.collision_audit) {
    const CollisionAudit& a = *r.collision_audit;
    j["audit"] = {
        {"cause", a.cause},
        {"slam_points_on_object", a.slam_points_on_object},
        {"slam_points_on_part", a.slam_points_on_part},
        {"map_points_on_object", a.map_points_on_object},
        {"nearest_map_point_m",
         a.nearest_map_point_m < 0 ? nlohmann::json(nullptr) : nlohmann::json(a.nearest_map_point_m)},
        {"inside_free_space", a.inside_free_space},
        {"free_space_since_s", a.free_space_since_s ? nlohmann::json(*a.free_space_since_s) : nlohmann::json(nullptr)},
        {"carved_clearance_m", a.carved_clearance_m ? nlohmann::json(*a.carved_clearance_m) : nlohmann::json(nullptr)},
        {"drift_since_carved_m",
         a.drift_since_carved_m ? nlohmann::json(*a.drift_since_carved_m) : nlohmann::json(nullptr)},
        {"vio_drift_m", a.vio_drift_m},
        {"commanded_speed_mps", a.commanded_speed_mps},
        {"since_last_path_s", a.since_last_path_s < 0 ? nlohmann::json(nullptr) : nlohmann::json(a.since_last_path_s)}};
  }
  return j;
}

// metrics.json → map_accuracy (null: no accuracy measured).
nlohmann::json mapAccuracyJson(const MapAccuracy& a) {
  auto share = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"obstacles", a.obstacles},
          {"obstacles_near_surface_share", share(a.nearSurfaceShare())},
          {"free_elements", a.free_elements},
          {"free_really_free_share", share(a.reallyFreeShare())},
          {"free_volume_m3", a.free_volume_m3},
          {"falsely_free_volume_share", share(a.falselyFreeVolumeShare())},
          {"falsely_free_element_share", share(a.falselyFreeElementShare())}};
}

// metrics.json → wall_ms_per_sim_second: wall time per simulated second, by stage; "other" as
// StageTimes::otherMs (on two threads the loop thread's, with its "waiting" for the second
// thread), as bench-loop splits it.
nlohmann::json wallPerSimSecondJson(const FlightResult& f, const StageTimes& s) {
  const double sim = std::max(f.sim_time_s, 1e-9);
  nlohmann::json st = stagesJson(s, sim);
  if (f.threads > 1) st["waiting"] = f.perception_wait_ms / sim;
  st["other"] = s.otherMs(f.wall_time_s * 1000.0, f.threads, f.perception_wait_ms) / sim;
  st["total"] = f.wall_time_s * 1000.0 / sim;
  return st;
}

}  // namespace

nlohmann::json missionMetrics(const ScenarioSpec& spec, const MissionResult& r, const WorldTruth* truth) {
  const FlightResult& f = r.flight;
  nlohmann::json j;
  j["name"] = spec.name;
  j["status"] = runStatusName(f.status);
  j["seed"] = spec.flight.seed;
  j["world"] = spec.flight.world_name.empty() ? spec.flight.world_path : spec.flight.world_name;
  j["method"] = spec.method.type;
  j["switches"] = spec.method.switches;
  if (!spec.method.reference_code.empty()) j["reference_code"] = spec.method.reference_code;
  // What flew, as config.yaml records it: a Python method's entry, a goal chooser, replayability.
  if (spec.method.type == kPythonMethodType)
    j["method_entry"] = std::any_cast<const PythonMethodConfig&>(spec.method.config).entry;
  if (!spec.method.goal_chooser.empty()) j["goal_chooser"] = spec.method.goal_chooser;
  j["replayable"] = spec.method.not_replayable.empty();
  j["method_confinement"] = spec.method.confinement.empty() ? "compiled into msbench" : spec.method.confinement;
  j["duration_s"] = spec.flight.duration_s;
  j["sim_time_s"] = f.sim_time_s;
  j["coverage"] = coverageJson(r);
  j["collision"] = collisionJson(f, r, truth);
  // The front-end error profile and the final map's accuracy (truth side; core/eval).
  if (r.frontend) j["frontend_profile"] = frontEndProfileJson(*r.frontend);
  if (r.map_accuracy) j["map_accuracy"] = mapAccuracyJson(*r.map_accuracy);
  j["vio_lost_at_s"] = f.vio_lost_at_s >= 0 ? nlohmann::json(f.vio_lost_at_s) : nlohmann::json(nullptr);
  j["distance_flown_m"] = f.distance_flown_m;
  j["perception"] = {{"frames", f.perception_frames},
                     {"tracked_mean", f.perception_frames > 1 ? f.tracked_sum / (f.perception_frames - 1) : 0.0},
                     {"tracked_min", f.tracked_min},
                     {"frames_few_tracks", f.frames_few_tracks}};
  j["final_drift_m"] = f.final_drift_m;
  j["frames_rendered"] = f.frames_rendered;
  j["mujoco_warnings"] = f.mujoco_warnings;
  j["wall_time_s"] = f.wall_time_s;
  j["real_time_factor"] = f.realTimeFactor();
  j["wall_ms_per_sim_second"] = wallPerSimSecondJson(f, r.stages);
  j["map_update_ms"] = {{"updates", r.map_update_ms.size()},
                        {"median", percentile(r.map_update_ms, 0.5)},
                        {"p99", percentile(r.map_update_ms, 0.99)},
                        {"max", percentile(r.map_update_ms, 1.0)}};
  j["peak_rss_mb"] = peakRssMb();
  j["counters"] = r.counters;
  j["versions"] = versionInfo();
  j["machine"] = machineFingerprint(f.gl_description);
  j["trajectory_hash"] = hexHash(f.trajectory_hash);
  j["map_hash"] = hexHash(r.map_hash);
  j["determinism_hash"] = hexHash(r.run_hash);
  return j;
}

std::string coverageCsv(const std::vector<CoverageSample>& samples) {
  std::ostringstream o;
  o << "t_s,area_m2,area_box_m2,area_true_frame_m2,distance_m,box_share,area_verified_m2\n";
  char line[200];
  for (const auto& c : samples) {
    std::snprintf(line, sizeof(line), "%.3f,%.2f,%.2f,%.2f,%.3f,%.4f,%.2f\n", c.t_s, c.area_m2, c.area_box_m2,
                  c.area_gt_m2, c.distance_m, c.box_share, c.area_verified_m2);
    o << line;
  }
  return o.str();
}

std::string timingCsv(const MissionResult& r) {
  std::ostringstream o;
  o << "t_s,render_ms,tracker_ms,triangulation_ms,map_update_ms,planning_ms,metric_ms\n";
  char line[200];
  for (const auto& [t, s] : r.stage_timeline) {
    std::snprintf(line, sizeof(line), "%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n", t, s.render_ms, s.tracker_ms,
                  s.triangulation_ms, s.map_ms, s.planning_ms, s.metric_ms);
    o << line;
  }
  return o.str();
}

std::string mapPly(const ExplorerSnapshot& snap) {
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\ncomment msbench map (VIO frame); kind 0 free-space sphere (radius), "
         "1 obstacle point, 2 frontier\nelement vertex "
      << snap.free_space.size() + snap.obstacles.size() + snap.frontiers.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radius\n"
         "property uchar kind\nend_header\n";
  char line[160];
  for (const auto& s : snap.free_space) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f %.4f 0\n", s.centre.x(), s.centre.y(), s.centre.z(), s.radius);
    ply << line;
  }
  for (const auto& p : snap.obstacles) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f 0 1\n", p.x(), p.y(), p.z());
    ply << line;
  }
  for (const auto& p : snap.frontiers) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f 0 2\n", p.x(), p.y(), p.z());
    ply << line;
  }
  return ply.str();
}

namespace {

// Ground-truth obstacles (not the ground) as faint footprints, coloured by kind: textured grey,
// textureless orange, thin magenta (drawn at least 2 px wide so rods stay visible).
// The convex xy footprint of a shape in pixels: a box's corners, a cylinder's rims, a sphere's
// equator.
template <class ToPixel>
std::vector<cv::Point> footprintHull(const Shape& sh, ToPixel px) {
  std::vector<cv::Point> outline;
  if (sh.type == ShapeType::kBox) {
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner((k & 1 ? 1 : -1) * sh.size.x(), (k & 2 ? 1 : -1) * sh.size.y(), (k & 4 ? 1 : -1) * sh.size.z());
      outline.push_back(px(sh.pose * corner));
    }
  } else {
    const double radius = sh.size.x(), half = sh.type == ShapeType::kCylinder ? sh.size.z() : 0.0;
    for (int k = 0; k < 24; ++k) {
      const double a = 2.0 * M_PI * k / 24;
      for (double end : {-half, half}) {
        const Vec3 local = sh.type == ShapeType::kSphere ? Vec3(radius * std::cos(a), radius * std::sin(a), 0)
                                                         : Vec3(radius * std::cos(a), radius * std::sin(a), end);
        outline.push_back(sh.type == ShapeType::kSphere ? px(sh.pose.translation() + local) : px(sh.pose * local));
      }
    }
  }
  std::vector<cv::Point> hull;
  cv::convexHull(outline, hull);
  return hull;
}

template <class ToPixel>
void drawTruthFootprints(cv::Mat& img, const WorldTruth& truth, ToPixel px) {
  cv::Mat layer = img.clone();
  for (const Shape& sh : truth.shapes()) {
    if (sh.kind == ObstacleKind::kGround || sh.type == ShapeType::kHalfSpace) continue;
    const cv::Scalar colour = sh.kind == ObstacleKind::kTextureless ? cv::Scalar(60, 150, 245)
                              : sh.kind == ObstacleKind::kThin      ? cv::Scalar(200, 0, 200)
                                                                    : cv::Scalar(120, 120, 120);
    const std::vector<cv::Point> hull = footprintHull(sh, px);
    cv::fillConvexPoly(layer, hull, colour, cv::LINE_AA);
    if (sh.kind == ObstacleKind::kThin) cv::polylines(layer, hull, true, colour, 2, cv::LINE_AA);
  }
  cv::addWeighted(layer, 0.3, img, 0.7, 0, img);
}

// A round step for grid lines and the scale bar: about a sixth of the extent.
double niceStepM(double extent_m) {
  for (double s : {1.0, 2.0, 5.0, 10.0, 20.0, 25.0, 50.0, 100.0, 200.0, 500.0})
    if (extent_m / s <= 8) return s;
  return 1000.0;
}

}  // namespace

namespace {

// The top-down picture's frame: the metres it spans, its scale, the image and the mapping.
struct TopdownCanvas {
  Vec2 lo, hi;
  double mpp = 0.05;  // metres per pixel
  int header = 88;    // legend band above the map
  int w = 0, h = 0;
  double step = 10.0;  // grid spacing (m)
  cv::Mat img;
  cv::Point px(const Vec3& p) const {
    return cv::Point(int((p.x() - lo.x()) / mpp), header + int((hi.y() - p.y()) / mpp));
  }
  cv::Point px2(const Vec2& p) const { return px(Vec3(p.x(), p.y(), 0)); }
};

// Extent: the box, the trajectory and the map; a white image with room for the legend.
TopdownCanvas topdownCanvas(const MissionResult& r) {
  TopdownCanvas c;
  Vec2& lo = c.lo;
  Vec2& hi = c.hi;
  lo = r.exploration_box.min.head<2>(), hi = r.exploration_box.max.head<2>();
  if (!(hi.array() > lo.array()).all() || (hi - lo).norm() > 1e5) lo = hi = Vec2::Zero();
  auto grow = [&](const Vec2& p, double m) {
    lo = lo.cwiseMin(Vec2(p.array() - m));
    hi = hi.cwiseMax(Vec2(p.array() + m));
  };
  for (const auto& t : r.flight.trajectory) grow(t.position_m.head<2>(), 5), grow(t.est_position_m.head<2>(), 5);
  for (const auto& d : r.final_map.free_space) grow(d.centre.head<2>(), d.radius);
  c.mpp = std::max({0.05, (hi.x() - lo.x()) / 1600.0, (hi.y() - lo.y()) / 1600.0});
  c.w = std::max(640, int((hi.x() - lo.x()) / c.mpp) + 1);
  c.h = int((hi.y() - lo.y()) / c.mpp) + 1 + c.header;
  c.img = cv::Mat(c.h, c.w, CV_8UC3, cv::Scalar(255, 255, 255));
  c.step = niceStepM(std::max(hi.x() - lo.x(), hi.y() - lo.y()));
  return c;
}

void drawGrid(TopdownCanvas& canvas) {
  cv::Mat& img = canvas.img;
  const Vec2 lo = canvas.lo, hi = canvas.hi;
  const double step = canvas.step;
  auto px2 = [&](const Vec2& p) { return canvas.px2(p); };
  // Metre grid (faint) with labels along the left and top edges of the map.
  for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step) {
    cv::line(img, px2(Vec2(x, lo.y())), px2(Vec2(x, hi.y())), cv::Scalar(225, 225, 225), 1);
    cv::putText(img, std::to_string(int(std::lround(x))), px2(Vec2(x, hi.y())) + cv::Point(2, 12),
                cv::FONT_HERSHEY_SIMPLEX, 0.35, cv::Scalar(110, 110, 110), 1, cv::LINE_AA);
  }
  for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step) {
    cv::line(img, px2(Vec2(lo.x(), y)), px2(Vec2(hi.x(), y)), cv::Scalar(225, 225, 225), 1);
    cv::putText(img, std::to_string(int(std::lround(y))), px2(Vec2(lo.x(), y)) + cv::Point(2, -3),
                cv::FONT_HERSHEY_SIMPLEX, 0.35, cv::Scalar(110, 110, 110), 1, cv::LINE_AA);
  }
}

void drawFreeSpace(TopdownCanvas& canvas, const MissionResult& r) {
  cv::Mat& img = canvas.img;
  const double mpp = canvas.mpp;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  auto px2 = [&](const Vec2& p) { return canvas.px2(p); };
  // Explored columns (light green squares around their nodes), spheres (blue, translucent).
  const double half = 0.5 * r.columns.cellM();
  for (const auto& c : r.columns.columns()) {
    const Vec2 n = r.columns.node(c);
    cv::rectangle(img, px2(n + Vec2(-half, half)), px2(n + Vec2(half, -half)), cv::Scalar(200, 240, 200), -1);
  }
  // Free space as the metric reads it: disks (spheres) and squares (free cells).
  cv::Mat discs = img.clone();
  for (const auto& d : r.final_map.free_space) {
    if (d.footprint == FreeSpaceElement::Footprint::kDisk) {
      cv::circle(discs, px(d.centre), int(d.radius / mpp), cv::Scalar(230, 160, 90), -1);
    } else {
      const Vec2 c = d.centre.head<2>();
      cv::rectangle(discs, px2(c + Vec2(-d.radius, d.radius)), px2(c + Vec2(d.radius, -d.radius)),
                    cv::Scalar(230, 160, 90), -1);
    }
  }
  cv::addWeighted(discs, 0.35, img, 0.65, 0, img);
  cv::rectangle(img, px(r.exploration_box.min), px(r.exploration_box.max), cv::Scalar(0, 0, 0), 1);
}

void drawMapMarks(TopdownCanvas& canvas, const MissionResult& r) {
  cv::Mat& img = canvas.img;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  // Obstacle points: near the ground (z < 0.5 m) light grey, above it black.
  for (const auto& p : r.final_map.obstacles)
    if (p.z() < 0.5) cv::circle(img, px(p), 1, cv::Scalar(185, 185, 185), -1);
  for (const auto& p : r.final_map.obstacles)
    if (p.z() >= 0.5) cv::circle(img, px(p), 1, cv::Scalar(20, 20, 20), -1);
  for (const auto& p : r.final_map.frontiers) cv::circle(img, px(p), 3, cv::Scalar(200, 40, 200), -1);
  auto arrow = [&](const ExplorerSnapshot::Pose2& v, const cv::Scalar& col) {
    const Vec3 tip = v.position + 2.0 * Vec3(std::cos(v.yaw_rad), std::sin(v.yaw_rad), 0);
    cv::arrowedLine(img, px(v.position), px(tip), col, 2, cv::LINE_AA, 0, 0.4);
  };
  for (const auto& v : r.final_map.visited) arrow(v, cv::Scalar(140, 140, 140));
  for (const auto& v : r.final_map.viewpoints) arrow(v, cv::Scalar(0, 160, 255));
}

void drawTrajectories(TopdownCanvas& canvas, const MissionResult& r) {
  cv::Mat& img = canvas.img;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  // Trajectories: estimate (orange) under truth (red).
  const auto& tr = r.flight.trajectory;
  for (size_t i = 1; i < tr.size(); ++i)
    cv::line(img, px(tr[i - 1].est_position_m), px(tr[i].est_position_m), cv::Scalar(0, 150, 255), 2, cv::LINE_AA);
  for (size_t i = 1; i < tr.size(); ++i)
    cv::line(img, px(tr[i - 1].position_m), px(tr[i].position_m), cv::Scalar(0, 0, 220), 1, cv::LINE_AA);
  // The last path sent (blue) and the active goal (red circle).
  const auto& path = r.final_map.path;
  for (size_t i = 1; i < path.size(); ++i)
    cv::line(img, px(path[i - 1]), px(path[i]), cv::Scalar(200, 60, 0), 2, cv::LINE_AA);
  if (r.final_map.goal) cv::circle(img, px(r.final_map.goal->position), 6, cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
  if (r.flight.collision) {
    const cv::Point c = px(r.flight.collision->vehicle_position_m);
    cv::drawMarker(img, c, cv::Scalar(0, 0, 255), cv::MARKER_TILTED_CROSS, 24, 3);
  }
}

// What ended the run, on top of everything: the geom hit (its footprint outlined in red), the
// contact point (a red dot) and a label with its name, kind and height.
void drawCollisionObject(TopdownCanvas& canvas, const MissionResult& r, const WorldTruth& truth) {
  if (!r.flight.collision) return;
  const auto& c = *r.flight.collision;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  const Shape* hit = truth.shapeNamed(c.world_geom);
  std::string label = c.world_geom;
  if (hit && hit->type != ShapeType::kHalfSpace) {
    const std::vector<cv::Point> hull = footprintHull(*hit, px);
    cv::polylines(canvas.img, hull, true, cv::Scalar(255, 255, 255), 5, cv::LINE_AA);
    cv::polylines(canvas.img, hull, true, cv::Scalar(0, 0, 255), 2, cv::LINE_AA);
    char extra[96];
    std::snprintf(extra, sizeof(extra), " (%s, %.1f-%.1f m high)", obstacleKindName(hit->kind), hit->bounds().first.z(),
                  hit->bounds().second.z());
    label += extra;
  }
  const cv::Point at = px(c.contact_position_m);
  cv::circle(canvas.img, at, 5, cv::Scalar(0, 0, 255), -1, cv::LINE_AA);
  char contact[64];
  std::snprintf(contact, sizeof(contact), ", contact at z = %.1f m", c.contact_position_m.z());
  label = "hit " + label + contact;
  const cv::Point text(std::min(at.x + 10, canvas.w - 8 * int(label.size()) - 4),
                       std::max(at.y - 10, canvas.header + 14));
  cv::putText(canvas.img, label, text, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 4, cv::LINE_AA);
  cv::putText(canvas.img, label, text, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 200), 1, cv::LINE_AA);
}

void drawLegend(TopdownCanvas& canvas, const MissionResult& r, bool truth) {
  cv::Mat& img = canvas.img;
  const int w = canvas.w, header = canvas.header;
  char text[200];
  std::snprintf(text, sizeof(text), "A = %.0f m2 (%zu columns), t = %.0f s, %s", r.columns.areaM2(), r.columns.count(),
                r.flight.sim_time_s, runStatusName(r.flight.status));
  cv::rectangle(img, cv::Point(0, 0), cv::Point(w, header - 1), cv::Scalar(255, 255, 255), -1);
  cv::putText(img, text, cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  // The legend names what the map holds: spheres (disk footprints) or free cells (squares).
  const bool spheres = std::any_of(r.final_map.free_space.begin(), r.final_map.free_space.end(),
                                   [](const auto& e) { return e.footprint == FreeSpaceElement::Footprint::kDisk; });
  cv::putText(img,
              spheres ? "green: explored columns, blue: spheres, black/grey: obstacle points (above/below 0.5 m), "
                        "magenta: frontiers,"
                      : "green: explored columns, blue: free cells, black/grey: occupied cells (above/below 0.5 m), "
                        "red circle: goal,",
              cv::Point(8, 42), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  cv::putText(img,
              spheres ? "orange arrows: viewpoints, grey: visited, red: true path, orange: estimate, blue: last path"
                      : "red: true path, orange: estimate, blue: last path",
              cv::Point(8, 60), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  if (truth)
    cv::putText(img,
                "faint: true obstacles (grey textured, orange textureless, magenta thin); grid and labels in metres",
                cv::Point(8, 78), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
}

void drawScaleBar(TopdownCanvas& canvas) {
  cv::Mat& img = canvas.img;
  const int w = canvas.w, h = canvas.h;
  const double step = canvas.step, mpp = canvas.mpp;
  // Scale bar (bottom right) and the grid's unit.
  const int bar = int(step / mpp), bx = w - bar - 20, by = h - 16;
  cv::rectangle(img, cv::Point(bx - 6, by - 22), cv::Point(w - 8, h - 4), cv::Scalar(255, 255, 255), -1);
  cv::line(img, cv::Point(bx, by), cv::Point(bx + bar, by), cv::Scalar(0, 0, 0), 3);
  cv::putText(img, std::to_string(int(step)) + " m", cv::Point(bx, by - 7), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat topdownImage(const MissionResult& r, const WorldTruth* truth) {
  TopdownCanvas c = topdownCanvas(r);
  if (truth) drawTruthFootprints(c.img, *truth, [&](const Vec3& p) { return c.px(p); });
  drawGrid(c);
  drawFreeSpace(c, r);
  drawMapMarks(c, r);
  drawTrajectories(c, r);
  if (truth) drawCollisionObject(c, r, *truth);
  drawLegend(c, r, truth != nullptr);
  drawScaleBar(c);
  return c.img;
}

void writeTopdown(const std::filesystem::path& file, const MissionResult& r, const WorldTruth* truth) {
  const cv::Mat img = topdownImage(r, truth);
  writeFileAtomic(file, encodePng(viewOf(img)));
}

std::string configYamlText(const std::string& scenario_file, bool with_overrides, const std::string& effective_yaml,
                           const std::string& not_replayable) {
  if (!not_replayable.empty())
    return "# NOT REPLAYABLE: " + not_replayable + ".\n# The configuration of " + scenario_file +
           (with_overrides ? " with overrides" : "") +
           " as the run used it; `msbench run` cannot reproduce the run from it.\n" + effective_yaml;
  return "# effective configuration (every key, defaults included) of " + scenario_file +
         (with_overrides ? " with overrides" : "") + "; `msbench run` reproduces the run from it\n" + effective_yaml;
}

nlohmann::json writeMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, const MissionResult& r,
                                   const WorldTruth* truth) {
  nlohmann::json metrics = missionMetrics(spec, r, truth);
  const std::string coverage_csv = coverageCsv(r.coverage);
  metrics["record_digest"] = recordDigest(metrics, coverage_csv);  // the seal report and regress check
  writeFileAtomic(dir / "coverage.csv", coverage_csv);
  writeFileAtomic(dir / "trajectory.csv", trajectoryCsv(r.flight.trajectory));
  writeFileAtomic(dir / "timing.csv", timingCsv(r));
  if (spec.mission.write_map_ply) writeFileAtomic(dir / "map.ply", mapPly(r.final_map));
  writeTopdown(dir / "topdown.png", r, truth);
  writeFileAtomic(dir / "metrics.json", metrics.dump(2) + "\n");
  return metrics;
}

nlohmann::json writeErroredMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, Mission& mission,
                                          const std::string& what, int64_t error_tick, const WorldTruth* truth,
                                          RunStatus status) {
  nlohmann::json m;
  try {
    MissionResult r = mission.finish();
    r.flight.status = status;
    m = writeMissionOutputs(dir, spec, r, truth);
    m.erase("record_digest");  // an error record is no result: nothing to seal
    m["error"] = what;
    if (error_tick < 0) error_tick = r.flight.ticks;
  } catch (const std::exception& again) {
    // The method fails again when asked for its map: the record alone, as before.
    m = errorMetrics(spec, what, status);
    m["finish_error"] = again.what();
  }
  m["error_tick"] = error_tick;
  writeFileAtomic(dir / "metrics.json", m.dump(2) + "\n");
  return m;
}

std::vector<NamedPath> missionInputs(const std::string& scenario_file, const ScenarioSpec& spec,
                                     const std::vector<NamedPath>& extra) {
  std::vector<NamedPath> in = {{"SCENARIO", scenario_file}};
  for (size_t i = 1; i < spec.input_files.size(); ++i) in.push_back({"its base: file", spec.input_files[i]});
  if (!spec.flight.world_path.empty() && spec.flight.world_name.empty())
    in.push_back({"its world file", spec.flight.world_path});
  in.insert(in.end(), extra.begin(), extra.end());
  return in;
}

nlohmann::json errorMetrics(const ScenarioSpec& spec, const std::string& what, RunStatus status) {
  return {{"name", spec.name},
          {"status", runStatusName(status)},
          {"error", what},
          {"seed", spec.flight.seed},
          {"versions", versionInfo()}};
}

nlohmann::json frontEndProfileJson(const FrontEndProfile& p) {
  nlohmann::json bands = nlohmann::json::array();
  for (const DepthBandErrors& b : p.bands)
    bands.push_back({{"depth_from_m", b.lo_m},
                     {"depth_to_m", b.hi_m > 1e8 ? nlohmann::json() : nlohmann::json(b.hi_m)},
                     {"points", b.points},
                     {"median_error_m", b.median_m},
                     {"p90_error_m", b.p90_m},
                     {"share_over_0_5_m", b.share_over_half_m},
                     {"share_over_2_m", b.share_over_2_m}});
  return {{"points", p.points},
          {"depth_bands", bands},
          {"tracks", p.tracks},
          {"moved_over_0_3_m_share", p.moved_share},
          {"median_track_motion_m", p.median_motion_m}};
}

}  // namespace msb
