#include "sim/world/vehicle_models.h"

#include <algorithm>
#include <cmath>

namespace msb {

namespace {

constexpr auto kPaint = ObstacleKind::kTextureless;

// Proportions of one kind (fractions of the overall size unless stated).
struct VehicleShape {
  double wheel_radius;          ///< of the height
  double body_top;              ///< top of the lower body (of the height)
  double cabin_length;          ///< of the length (the upper box)
  double cabin_offset;          ///< centre of the upper box along x (of the length; + = front)
  double cabin_width;           ///< of the width
  int axles;                    ///< 2 or 3
  double paint_min, paint_max;  ///< grey range of the paint
};

VehicleShape shapeOf(const std::string& kind) {
  if (kind == "car") return {0.21, 0.55, 0.50, -0.05, 0.88, 2, 0.15, 0.85};
  if (kind == "suv") return {0.22, 0.55, 0.62, -0.08, 0.92, 2, 0.15, 0.85};
  if (kind == "bus") return {0.16, 0.35, 0.98, 0.0, 1.0, 2, 0.35, 0.80};
  if (kind == "fire_truck") return {0.17, 0.45, 0.22, 0.36, 1.0, 3, 0.30, 0.40};
  return {0.17, 0.40, 0.72, -0.13, 1.0, 2, 0.80, 0.92};  // ambulance: cab + box body
}

Pose at(const Pose& base, const Vec3& offset, const Mat3& R = Mat3::Identity()) {
  Pose T = base;
  T.translation() = base * offset;
  T.linear() = base.linear() * R;
  return T;
}

}  // namespace

bool isVehicleKind(const std::string& kind) {
  return kind == "car" || kind == "suv" || kind == "bus" || kind == "fire_truck" || kind == "ambulance";
}

// One vehicle being built: its kind, id, pose, dimensions, paint and the looks of its parts.
struct VehicleBuild {
  const std::string& kind;
  const std::string& id;
  const Pose& base;
  VehicleShape v;
  double L, W, H, paint, rw, clearance, body_top;
  double cl, cw, cx;  // the upper box: length, width, offset along x
  Look body, dark, rim, light, rear_light, bumper;
  Look flat(double grey) const { return Look::flat(grey).mergedInto(id); }
};

// Lower body (from the ground clearance to the belt line) and the upper box (cabin, bus body,
// ambulance box, fire-truck cab).
void buildBodies(const VehicleBuild& c, MjcfWorldBuilder& b) {
  const auto& [kind, id, base, v, L, W, H, paint, rw, clearance, body_top, cl, cw, cx, body, dark, rim, light,
               rear_light, bumper] = c;
  b.addBox(id + "_body", id, at(base, Vec3(0, 0, 0.5 * (clearance + body_top))),
           Vec3(0.5 * L, 0.5 * W, 0.5 * (body_top - clearance)), kPaint, body);
  b.addBox(id + "_upper", id, at(base, Vec3(cx, 0, 0.5 * (body_top + H))),
           Vec3(0.5 * cl, 0.5 * cw, 0.5 * (H - body_top)), kPaint,
           kind == "ambulance" ? c.flat(std::min(1.0, paint + 0.05)) : body);
}

// Windows, and the ambulance's band and light bar, the fire truck's ladder and lockers.
void buildWindowsAndFittings(const VehicleBuild& c, MjcfWorldBuilder& b) {
  const auto& [kind, id, base, v, L, W, H, paint, rw, clearance, body_top, cl, cw, cx, body, dark, rim, light,
               rear_light, bumper] = c;
  auto flat = [&c](double grey) { return c.flat(grey); };
  // Windows: dark panes standing 2 cm proud of the upper box's sides and front.
  const double win_h = kind == "bus" ? 0.45 * (H - body_top) : 0.6 * (H - body_top);
  const double win_z = kind == "bus" ? body_top + 0.5 * (H - body_top) : body_top + 0.45 * (H - body_top);
  const bool side_windows = kind != "ambulance" && kind != "fire_truck";
  if (side_windows) {
    // Side windows in panes with pillars between them.
    const int panes = kind == "bus" ? 6 : 2;
    const double pane_l = 0.85 * cl / panes;
    for (int side : {-1, 1})
      for (int p = 0; p < panes; ++p) {
        const double x = cx - 0.5 * 0.85 * cl + (p + 0.5) * pane_l;
        b.addBox(id + "_win" + (side > 0 ? "l" : "r") + std::to_string(p), id,
                 at(base, Vec3(x, side * (0.5 * cw + 0.01), win_z)), Vec3(0.42 * pane_l, 0.02, 0.5 * win_h), kPaint,
                 dark);
      }
  }
  // Windscreen (front of the upper box) and, for cars, the rear window.
  const double front_x = cx + 0.5 * cl;
  b.addBox(id + "_windscreen", id, at(base, Vec3(front_x + 0.01, 0, win_z)), Vec3(0.02, 0.4 * cw, 0.5 * win_h), kPaint,
           dark);
  if (kind == "car" || kind == "suv")
    b.addBox(id + "_rearwin", id, at(base, Vec3(cx - 0.5 * cl - 0.01, 0, win_z)), Vec3(0.02, 0.38 * cw, 0.45 * win_h),
             kPaint, dark);
  if (kind == "ambulance") {
    // A dark band along the box and a light bar on the cab.
    for (int side : {-1, 1})
      b.addBox(id + "_band" + (side > 0 ? "l" : "r"), id,
               at(base, Vec3(cx, side * (0.5 * cw + 0.01), body_top + 0.15 * H)), Vec3(0.45 * cl, 0.02, 0.06 * H),
               kPaint, flat(0.25));
    b.addBox(id + "_lightbar", id, at(base, Vec3(front_x + 0.1 * L, 0, 0.5 * (body_top + H) + 0.02)),
             Vec3(0.06 * L, 0.35 * W, 0.05), kPaint, flat(0.6));
  }
  if (kind == "fire_truck") {
    // A ladder on the rear deck: two rails and rungs, and equipment lockers on the sides.
    const double deck = body_top + 0.05;
    for (int side : {-1, 1})
      b.addBox(id + "_rail" + (side > 0 ? "l" : "r"), id, at(base, Vec3(-0.12 * L, side * 0.25 * W, deck + 0.25)),
               Vec3(0.36 * L, 0.04, 0.05), kPaint, rim);
    for (int r = 0; r < 8; ++r)
      b.addBox(id + "_rung" + std::to_string(r), id, at(base, Vec3(-0.45 * L + r * 0.09 * L, 0, deck + 0.25)),
               Vec3(0.03, 0.25 * W, 0.025), kPaint, rim);
    for (int side : {-1, 1})
      for (int k = 0; k < 3; ++k)
        b.addBox(id + "_locker" + (side > 0 ? "l" : "r") + std::to_string(k), id,
                 at(base, Vec3(-0.35 * L + k * 0.22 * L, side * (0.5 * W + 0.01), 0.5 * (clearance + body_top))),
                 Vec3(0.09 * L, 0.02, 0.32 * (body_top - clearance)), kPaint, flat(std::min(1.0, paint + 0.35)));
  }
}

// Tyres with rims, bumpers and lights.
void buildRunningGear(const VehicleBuild& c, MjcfWorldBuilder& b) {
  const auto& [kind, id, base, v, L, W, H, paint, rw, clearance, body_top, cl, cw, cx, body, dark, rim, light,
               rear_light, bumper] = c;
  // Tyres (axis along y) with rims standing out of the body's sides.
  const Mat3 axis_y = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  std::vector<double> axles = {0.34 * L, -0.32 * L};
  if (v.axles == 3) axles.push_back(-0.18 * L);
  const double tyre_w = std::clamp(0.12 * W, 0.18, 0.3);
  for (size_t a = 0; a < axles.size(); ++a)
    for (int side : {-1, 1}) {
      const std::string w = id + "_wheel" + std::to_string(a) + (side > 0 ? "l" : "r");
      const double y = side * (0.5 * W - 0.5 * tyre_w + 0.04);
      b.addCylinder(w + "_tyre", id, at(base, Vec3(axles[a], y, rw), axis_y), rw, 0.5 * tyre_w, kPaint, dark);
      b.addCylinder(w + "_rim", id, at(base, Vec3(axles[a], y + side * 0.5 * tyre_w, rw), axis_y), 0.55 * rw, 0.02,
                    kPaint, rim);
    }

  // Bumpers and lights, front (+x) and rear.
  for (int end : {1, -1}) {
    const double x = end * (0.5 * L + 0.04);
    b.addBox(id + (end > 0 ? "_bumper_f" : "_bumper_r"), id, at(base, Vec3(x, 0, clearance + 0.1 * H)),
             Vec3(0.05, 0.5 * W, 0.05 * H), kPaint, bumper);
    for (int side : {-1, 1})
      b.addBox(id + (end > 0 ? "_light_f" : "_light_r") + (side > 0 ? "l" : "r"), id,
               at(base, Vec3(x - end * 0.02, side * 0.36 * W, body_top - 0.12 * H)), Vec3(0.03, 0.08 * W, 0.04 * H),
               kPaint, end > 0 ? light : rear_light);
  }
}

void buildVehicle(const std::string& kind, const std::string& id, const Pose& base, const Vec3& size, RngStream& detail,
                  MjcfWorldBuilder& b) {
  // Every part is drawn as part of one mesh per grey level of this vehicle (a few draws instead
  // of one per part); the parts stay separate collision geoms.
  const VehicleShape v = shapeOf(kind);
  const double L = size.x(), W = size.y(), H = size.z();
  const double paint = detail.uniform(v.paint_min, v.paint_max);
  const double rw = v.wheel_radius * H;
  auto flat = [&id](double grey) { return Look::flat(grey).mergedInto(id); };
  const VehicleBuild c{kind,
                       id,
                       base,
                       v,
                       L,
                       W,
                       H,
                       paint,
                       rw,
                       0.45 * rw,
                       v.body_top * H,
                       v.cabin_length * L,
                       v.cabin_width * W,
                       v.cabin_offset * L,
                       flat(paint),
                       flat(0.07),
                       flat(0.75),
                       flat(0.97),
                       flat(0.28),
                       flat(0.18)};
  buildBodies(c, b);
  buildWindowsAndFittings(c, b);
  buildRunningGear(c, b);
}

}  // namespace msb
