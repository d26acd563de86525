#include "tools/results/topdown.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace msb {

namespace {

// Ground-truth obstacles (not the ground) as faint footprints, coloured by kind: textured grey,
// textureless orange, thin magenta (drawn at least 2 px wide so rods stay visible).
// The convex xy footprint of a shape in pixels: a box's corners, a cylinder's rims, a sphere's
// equator, a convex piece's vertices.
template <class ToPixel>
std::vector<cv::Point> footprintHull(const Shape& sh, ToPixel px) {
  std::vector<cv::Point> outline;
  if (sh.type == ShapeType::kConvex) {
    for (const Vec3& v : sh.polytope->vertices) outline.push_back(px(v));
  } else if (sh.type == ShapeType::kBox) {
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

TopdownCanvas fittedCanvas(const TopdownView& r) {
  TopdownCanvas c;
  Vec2& lo = c.lo;
  Vec2& hi = c.hi;
  lo = r.box.min.head<2>(), hi = r.box.max.head<2>();
  if (!(hi.array() > lo.array()).all() || (hi - lo).norm() > 1e5) lo = hi = Vec2::Zero();
  auto grow = [&](const Vec2& p, double m) {
    lo = lo.cwiseMin(Vec2(p.array() - m));
    hi = hi.cwiseMax(Vec2(p.array() + m));
  };
  for (const auto& t : r.trajectory) grow(t.position_m.head<2>(), 5), grow(t.est_position_m.head<2>(), 5);
  for (const auto& d : r.map.free_space) grow(d.centre.head<2>(), d.radius);
  c.mpp = std::max({0.05, (hi.x() - lo.x()) / 1600.0, (hi.y() - lo.y()) / 1600.0});
  c.w = std::max(640, int((hi.x() - lo.x()) / c.mpp) + 1);
  c.h = int((hi.y() - lo.y()) / c.mpp) + 1 + c.header;
  c.img = cv::Mat(c.h, c.w, CV_8UC3, cv::Scalar(255, 255, 255));
  c.step = niceStepM(std::max(hi.x() - lo.x(), hi.y() - lo.y()));
  return c;
}

namespace {

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

void drawFreeSpace(TopdownCanvas& canvas, const TopdownView& r) {
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
  for (const auto& d : r.map.free_space) {
    if (d.footprint == FreeSpaceElement::Footprint::kDisk) {
      cv::circle(discs, px(d.centre), int(d.radius / mpp), cv::Scalar(230, 160, 90), -1);
    } else {
      const Vec2 c = d.centre.head<2>();
      cv::rectangle(discs, px2(c + Vec2(-d.radius, d.radius)), px2(c + Vec2(d.radius, -d.radius)),
                    cv::Scalar(230, 160, 90), -1);
    }
  }
  cv::addWeighted(discs, 0.35, img, 0.65, 0, img);
  cv::rectangle(img, px(r.box.min), px(r.box.max), cv::Scalar(0, 0, 0), 1);
}

void drawMapMarks(TopdownCanvas& canvas, const TopdownView& r) {
  cv::Mat& img = canvas.img;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  // Obstacle points: near the ground (z < 0.5 m) light grey, above it black.
  for (const auto& p : r.map.obstacles)
    if (p.z() < 0.5) cv::circle(img, px(p), 1, cv::Scalar(185, 185, 185), -1);
  for (const auto& p : r.map.obstacles)
    if (p.z() >= 0.5) cv::circle(img, px(p), 1, cv::Scalar(20, 20, 20), -1);
  // Frontiers (magenta): at most 0.3 m across on the ground and translucent, so the explored
  // columns beneath stay visible on a coarse canvas (the video's) with thousands of them.
  if (!r.map.frontiers.empty()) {
    const int radius = std::clamp(int(std::lround(0.3 / canvas.mpp)), 1, 3);
    cv::Mat marks = img.clone();
    for (const auto& p : r.map.frontiers) cv::circle(marks, px(p), radius, cv::Scalar(200, 40, 200), -1);
    cv::addWeighted(marks, 0.6, img, 0.4, 0, img);
  }
  auto arrow = [&](const ExplorerSnapshot::Pose2& v, const cv::Scalar& col) {
    const Vec3 tip = v.position + 2.0 * Vec3(std::cos(v.yaw_rad), std::sin(v.yaw_rad), 0);
    cv::arrowedLine(img, px(v.position), px(tip), col, 2, cv::LINE_AA, 0, 0.4);
  };
  for (const auto& v : r.map.visited) arrow(v, cv::Scalar(140, 140, 140));
  for (const auto& v : r.map.viewpoints) arrow(v, cv::Scalar(0, 160, 255));
}

void drawTrajectories(TopdownCanvas& canvas, const TopdownView& r) {
  cv::Mat& img = canvas.img;
  auto px = [&](const Vec3& p) { return canvas.px(p); };
  // Trajectories: estimate (orange) under truth (red).
  const auto& tr = r.trajectory;
  for (size_t i = 1; i < tr.size(); ++i)
    cv::line(img, px(tr[i - 1].est_position_m), px(tr[i].est_position_m), cv::Scalar(0, 150, 255), 2, cv::LINE_AA);
  for (size_t i = 1; i < tr.size(); ++i)
    cv::line(img, px(tr[i - 1].position_m), px(tr[i].position_m), cv::Scalar(0, 0, 220), 1, cv::LINE_AA);
  // The last path sent (blue) and the active goal (red circle).
  const auto& path = r.map.path;
  for (size_t i = 1; i < path.size(); ++i)
    cv::line(img, px(path[i - 1]), px(path[i]), cv::Scalar(200, 60, 0), 2, cv::LINE_AA);
  if (r.map.goal) cv::circle(img, px(r.map.goal->position), 6, cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
  if (r.collision) {
    const cv::Point c = px(r.collision->vehicle_position_m);
    cv::drawMarker(img, c, cv::Scalar(0, 0, 255), cv::MARKER_TILTED_CROSS, 24, 3);
  }
}

// What ended the run, on top of everything: the geom hit (its footprint outlined in red), the
// contact point (a red dot) and a label with its name, kind and height.
void drawCollisionObject(TopdownCanvas& canvas, const TopdownView& r, const WorldTruth& truth) {
  if (!r.collision) return;
  const auto& c = *r.collision;
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

void drawLegend(TopdownCanvas& canvas, const TopdownView& r, bool truth) {
  cv::Mat& img = canvas.img;
  const int w = canvas.w, header = canvas.header;
  char text[200];
  std::snprintf(text, sizeof(text), "A = %.0f m2 (%zu columns), t = %.0f s, %s", r.columns.areaM2(), r.columns.count(),
                r.t_s, runStatusName(r.status));
  cv::rectangle(img, cv::Point(0, 0), cv::Point(w, header - 1), cv::Scalar(255, 255, 255), -1);
  cv::putText(img, text, cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  // The legend names what the map holds: spheres (disk footprints) or free cells (squares).
  const bool spheres = std::any_of(r.map.free_space.begin(), r.map.free_space.end(),
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

void drawTopdownBackground(TopdownCanvas& c, const WorldTruth* truth) {
  if (truth) drawTruthFootprints(c.img, *truth, [&](const Vec3& p) { return c.px(p); });
  drawGrid(c);
}

void drawTopdownMap(TopdownCanvas& c, const TopdownView& r, const WorldTruth* truth) {
  drawFreeSpace(c, r);
  drawMapMarks(c, r);
  drawTrajectories(c, r);
  if (truth) drawCollisionObject(c, r, *truth);
}

void drawTopdownScaleBar(TopdownCanvas& c) { drawScaleBar(c); }

cv::Mat topdownImage(const TopdownView& r, const WorldTruth* truth) {
  TopdownCanvas c = fittedCanvas(r);
  drawTopdownBackground(c, truth);
  drawTopdownMap(c, r, truth);
  drawLegend(c, r, truth != nullptr);
  drawScaleBar(c);
  return c.img;
}

TopdownCanvas fixedCanvas(const Vec2& lo, const Vec2& hi, int width_px, int height_px) {
  TopdownCanvas c;
  c.header = 0;
  c.mpp = std::max((hi.x() - lo.x()) / width_px, (hi.y() - lo.y()) / height_px);
  // [lo, hi] centred in the canvas; the spare metres go to both sides.
  const Vec2 centre = 0.5 * (lo + hi), half = 0.5 * c.mpp * Vec2(width_px, height_px);
  c.lo = centre - half, c.hi = centre + half;
  c.w = width_px, c.h = height_px;
  c.img = cv::Mat(c.h, c.w, CV_8UC3, cv::Scalar(255, 255, 255));
  c.step = niceStepM(std::max(hi.x() - lo.x(), hi.y() - lo.y()));
  return c;
}

}  // namespace msb
