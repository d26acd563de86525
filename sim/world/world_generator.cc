#include "sim/world/world_generator.h"
#include "sim/world/vehicle_models.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <tuple>

#include "core/common/rng.h"
#include "core/common/types.h"
#include "sim/world/mjcf_world_builder.h"

namespace msb {

namespace {

// Pose from a ground position, base height, yaw and optional roll/pitch tilt.
Pose placed(const Vec2& xy, double z, double yaw, double roll = 0, double pitch = 0) {
  Pose T = Pose::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                Eigen::AngleAxisd(roll, Vec3::UnitX()))
                   .toRotationMatrix();
  T.translation() = Vec3(xy.x(), xy.y(), z);
  return T;
}

// A point of an object's local frame (x along its length) in the world.
Pose local(const Pose& base, const Vec3& offset, const Mat3& R = Mat3::Identity()) {
  Pose T = base;
  T.translation() = base * offset;
  T.linear() = base.linear() * R;
  return T;
}

std::string pick(const std::string& override_texture, const char* def) {
  return override_texture.empty() ? def : override_texture;
}

// A collapsed building, with or without a burned end.
bool isCollapsed(const ObjectGroupSpec& g) {
  return g.kind == "building" && (g.variant == "collapsed" || g.variant == "collapsed_burned");
}

// Horizontal radius that an object of this kind and size occupies (for placement).
double footprintRadius(const ObjectGroupSpec& g, const Vec3& s) {
  const std::string& k = g.kind;
  if (k == "tree") return std::max(0.5 * s.x(), 0.3);
  if (k == "rod" || k == "pole" || k == "pillar") return s.x() + s.z() * std::sin(g.tilt_max_deg * kDeg);
  if (isCollapsed(g)) return 0.5 * std::hypot(s.x(), s.y()) + 0.4 * s.z();
  if (k == "gazebo" || k == "house") return 0.5 * std::hypot(s.x(), s.y()) + 0.5;
  return 0.5 * std::hypot(s.x(), s.y());
}

// Emits the solids of one object. `detail` draws spec-only randomness (rubble, tilt).
// One object to build: its group, id, base pose, size, heading, detail stream and the builder.
struct ObjectBuild {
  const ObjectGroupSpec& g;
  const std::string& id;
  const Pose& base;
  const Vec3& s;
  double yaw;
  RngStream& detail;
  MjcfWorldBuilder& b;
};

// The burned part of a building: flat black and textureless, or the group's `burned_texture`.
std::pair<ObstacleKind, Look> burnedLook(const ObjectGroupSpec& g) {
  if (g.burned_texture.empty()) return {ObstacleKind::kTextureless, Look::flat(0.12)};
  return {ObstacleKind::kTextured, Look::textured(g.burned_texture)};
}

// A building or tower: whole, with a burned part, or collapsed (block, slab, rubble).
void buildBuilding(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  const Look look = Look::textured(pick(g.texture, k == "tower" ? "concrete" : "facade"), "gravel");
  const auto [burned_kind, burned_look] = burnedLook(g);
  if (g.variant == "burned") {
    // A textured part and a burned part along the building's length.
    const double lb = g.burned_fraction * s.x(), lt = s.x() - lb;
    b.addBox(id + "_intact", id, local(base, Vec3(-0.5 * s.x() + 0.5 * lt, 0, 0.5 * s.z())),
             Vec3(0.5 * lt, 0.5 * s.y(), 0.5 * s.z()), T, look);
    b.addBox(id + "_burned", id, local(base, Vec3(0.5 * s.x() - 0.5 * lb, 0, 0.45 * s.z())),
             Vec3(0.5 * lb, 0.5 * s.y(), 0.45 * s.z()), burned_kind, burned_look);
  } else if (isCollapsed(g)) {
    // A lower remaining block, a slab leaning against it, and rubble. `collapsed_burned`: the
    // far end of the block (burned_fraction of its length, away from the slab) is burned.
    const double block_l = 0.7 * s.x();
    const double lb = g.variant == "collapsed_burned" ? g.burned_fraction * block_l : 0.0;
    b.addBox(id + "_block", id, local(base, Vec3(-0.15 * s.x() + 0.5 * lb, 0, 0.3 * s.z())),
             Vec3(0.5 * (block_l - lb), 0.5 * s.y(), 0.3 * s.z()), T, look);
    if (lb > 0.0)
      b.addBox(id + "_burned", id, local(base, Vec3(-0.5 * s.x() + 0.5 * lb, 0, 0.3 * s.z())),
               Vec3(0.5 * lb, 0.5 * s.y(), 0.3 * s.z()), burned_kind, burned_look);
    const double pitch = detail.uniform(25, 40) * kDeg;
    const Mat3 R = Eigen::AngleAxisd(-pitch, Vec3::UnitY()).toRotationMatrix();
    b.addBox(
        id + "_slab", id,
        local(base, Vec3(0.2 * s.x() + 0.25 * s.z() * std::cos(pitch), 0, 0.25 * s.z() * std::sin(pitch) + 0.2), R),
        Vec3(0.25 * s.z(), 0.45 * s.y(), 0.2), T, Look::textured("concrete"));
    for (int r = 0; r < 4; ++r) {
      const Vec3 half(detail.uniform(0.4, 1.2), detail.uniform(0.4, 1.0), detail.uniform(0.3, 0.7));
      const Vec3 off(detail.uniform(0.25, 0.5) * s.x(), detail.uniform(-0.4, 0.4) * s.y(), 0.5 * half.z());
      const Mat3 Rr = Eigen::AngleAxisd(detail.uniform(0, M_PI), Vec3::UnitZ()).toRotationMatrix();
      b.addBox(id + "_rubble" + std::to_string(r), id, local(base, off, Rr), half, T, Look::textured("concrete"));
    }
  } else {
    b.addBox(id, id, local(base, Vec3(0, 0, 0.5 * s.z())), 0.5 * s, T, look);
  }
}

// A house: brick walls and a gable roof of two slabs (30° pitch) meeting at the ridge.
void buildHouse(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  // Brick walls and a gable roof of two slabs (30° pitch) meeting at the ridge.
  b.addBox(id + "_walls", id, local(base, Vec3(0, 0, 0.5 * s.z())), 0.5 * s, T,
           Look::textured(pick(g.texture, "bricks")));
  const double pitch = 30 * kDeg, half_w = 0.5 * s.y() + 0.4;
  const double slab = half_w / std::cos(pitch);
  for (int side : {1, -1}) {
    const Mat3 R = Eigen::AngleAxisd(side * pitch, Vec3::UnitX()).toRotationMatrix();
    const Vec3 c(0, -side * 0.5 * half_w, s.z() + 0.5 * half_w * std::tan(pitch));
    b.addBox(id + (side > 0 ? "_roof_a" : "_roof_b"), id, local(base, c, R), Vec3(0.5 * s.x() + 0.3, 0.5 * slab, 0.12),
             T, Look::textured("wood"));
  }
}

// A tree: a bark trunk up into a foliage canopy.
void buildTree(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  // Bark trunk up into a foliage canopy (sphere of diameter size.x, top at size.z).
  const double r = 0.5 * s.x(), trunk_r = std::max(0.12, 0.05 * s.x());
  const double trunk_h = s.z() - r;
  b.addCylinder(id + "_trunk", id, local(base, Vec3(0, 0, 0.5 * trunk_h)), trunk_r, 0.5 * trunk_h, T,
                Look::textured("bark"));
  b.addSphere(id + "_canopy", id, base * Vec3(0, 0, s.z() - r), r, T, Look::textured(pick(g.texture, "foliage")));
}

// A rod, pole or pillar, tilted.
void buildRod(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  // Rods at ruins lean outwards (`yaw` is the ruin's outward normal there), others anywhere.
  const double tilt = detail.uniform(0, g.tilt_max_deg) * kDeg;
  const double dir = g.near == "ruins" ? yaw + detail.uniform(-0.25 * M_PI, 0.25 * M_PI) : detail.uniform(-M_PI, M_PI);
  const Mat3 R = (Eigen::AngleAxisd(dir, Vec3::UnitZ()) * Eigen::AngleAxisd(tilt, Vec3::UnitY())).toRotationMatrix();
  Pose T_axis = base;
  T_axis.linear() = R;
  T_axis.translation() = base.translation() + R * Vec3(0, 0, 0.5 * s.z());
  const bool thin = k == "rod";
  b.addCylinder(id, id, T_axis, s.x(), 0.5 * s.z(), thin ? ObstacleKind::kThin : T,
                thin ? Look::flat(0.55) : Look::textured(pick(g.texture, k == "pillar" ? "rock" : "concrete")));
}

// A rock: a tilted box.
void buildRock(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  const Mat3 R = (Eigen::AngleAxisd(detail.uniform(-1, 1) * g.tilt_max_deg * kDeg, Vec3::UnitX()) *
                  Eigen::AngleAxisd(detail.uniform(-1, 1) * g.tilt_max_deg * kDeg, Vec3::UnitY()))
                     .toRotationMatrix();
  b.addBox(id, id, local(base, Vec3(0, 0, 0.3 * s.z()), R), 0.5 * s, T, Look::textured(pick(g.texture, "rock")));
}

// A gazebo: four posts and a roof slab.
void buildGazebo(const ObjectBuild& o) {
  [[maybe_unused]] auto& [g, id, base, s, yaw, detail, b] = o;
  [[maybe_unused]] const std::string& k = g.kind;
  [[maybe_unused]] const auto T = ObstacleKind::kTextured;
  // Four posts and a roof slab.
  const std::string tex = pick(g.texture, "wood");
  int p = 0;
  for (double sx : {-0.5, 0.5})
    for (double sy : {-0.5, 0.5})
      b.addCylinder(id + "_post" + std::to_string(p++), id, local(base, Vec3(sx * s.x(), sy * s.y(), 0.5 * s.z())), 0.1,
                    0.5 * s.z(), T, Look::textured(tex));
  b.addBox(id + "_roof", id, local(base, Vec3(0, 0, s.z() + 0.15)), Vec3(0.5 * s.x() + 0.4, 0.5 * s.y() + 0.4, 0.15), T,
           Look::textured(tex));
}

void buildObject(const ObjectGroupSpec& g, const std::string& id, const Vec2& xy, double yaw, const Vec3& s,
                 RngStream& detail, MjcfWorldBuilder& b) {
  const std::string& k = g.kind;
  const Pose base = placed(xy, g.base_z_m, yaw);
  const ObjectBuild o{g, id, base, s, yaw, detail, b};
  if (k == "building" || k == "tower")
    buildBuilding(o);
  else if (k == "house")
    buildHouse(o);
  else if (isVehicleKind(k))
    buildVehicle(k, id, base, s, detail, b);
  else if (k == "tree")
    buildTree(o);
  else if (k == "rod" || k == "pole" || k == "pillar")
    buildRod(o);
  else if (k == "wall")
    b.addBox(id, id, local(base, Vec3(0, 0, 0.5 * s.z())), 0.5 * s, ObstacleKind::kTextured,
             Look::textured(pick(g.texture, "bricks")));
  else if (k == "rock")
    buildRock(o);
  else if (k == "gazebo")
    buildGazebo(o);
  else if (k == "dumpster")  // a closed bin: one box of its size, grimy painted metal
    b.addBox(id, id, local(base, Vec3(0, 0, 0.5 * s.z())), 0.5 * s, ObstacleKind::kTextured,
             Look::textured(pick(g.texture, "concrete")));
}

// Carves the cave: solid rock everywhere in the footprint except chambers and tunnels, and a
// ceiling over each carved cell at its height. Rectangles of equal cells are merged into boxes.
constexpr double kCaveSkin = 0.02;  // thickness of the cave's visual skins

// The cave's plan: cells of cell_m, each solid (0) or carved to a ceiling height.
struct CaveGrid {
  int nx = 0, ny = 0;
  std::vector<double> height;  // 0 = solid, else ceiling height
  double at(int i, int j) const { return (i < 0 || j < 0 || i >= nx || j >= ny) ? 0.0 : height[size_t(j) * nx + i]; }
};

// Carves the chambers and tunnels: a cell takes the highest ceiling of those covering its centre.
CaveGrid carveCave(const CaveSpec& cave) {
  CaveGrid g;
  g.nx = int(std::ceil((cave.max.x() - cave.min.x()) / cave.cell_m));
  g.ny = int(std::ceil((cave.max.y() - cave.min.y()) / cave.cell_m));
  g.height.assign(size_t(g.nx) * g.ny, 0.0);
  const int nx = g.nx, ny = g.ny;
  std::vector<double>& height = g.height;
  auto centre = [&](int i, int j) {
    return Vec2(cave.min.x() + (i + 0.5) * cave.cell_m, cave.min.y() + (j + 0.5) * cave.cell_m);
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 c = centre(i, j);
      double& h = height[size_t(j) * nx + i];
      for (const auto& ch : cave.chambers)
        if ((c.array() >= ch.min.array()).all() && (c.array() <= ch.max.array()).all()) h = std::max(h, ch.ceiling_m);
      for (const auto& t : cave.tunnels) {
        const Vec2 ab = t.to - t.from;
        const double u = std::clamp((c - t.from).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((t.from + u * ab - c).norm() <= 0.5 * t.width_m) h = std::max(h, t.ceiling_m);
      }
    }
  return g;
}

// Rock boxes over the solid cells and above the carved ones, merged into rectangles of equal
// height; a visible skin under every ceiling.
void buildRockAndCeilings(const CaveSpec& cave, const CaveGrid& g, MjcfWorldBuilder& b) {
  constexpr double kSkin = kCaveSkin;
  const int nx = g.nx, ny = g.ny;
  const std::vector<double>& height = g.height;
  // Greedy rectangle merging of cells with equal height (rows first, then extend downwards).
  std::vector<bool> used(height.size(), false);
  int rock = 0, ceiling = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t idx = size_t(j) * nx + i;
      if (used[idx]) continue;
      const double h = height[idx];
      int w = 1;
      while (i + w < nx && !used[size_t(j) * nx + i + w] && height[size_t(j) * nx + i + w] == h) ++w;
      int d = 1;
      for (bool ok = true; ok && j + d < ny;) {
        for (int k = 0; k < w; ++k) {
          const size_t q = size_t(j + d) * nx + i + k;
          if (used[q] || height[q] != h) {
            ok = false;
            break;
          }
        }
        if (ok) ++d;
      }
      for (int dj = 0; dj < d; ++dj)
        for (int k = 0; k < w; ++k) used[size_t(j + dj) * nx + i + k] = true;
      const Vec2 lo(cave.min.x() + i * cave.cell_m, cave.min.y() + j * cave.cell_m);
      const Vec2 hi = lo + Vec2(w * cave.cell_m, d * cave.cell_m);
      const double z0 = h;  // rock from the floor (solid) or from the ceiling height up
      Pose T = Pose::Identity();
      T.translation() = Vec3(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), 0.5 * (z0 + cave.rock_top_m));
      const Vec3 half(0.5 * (hi.x() - lo.x()), 0.5 * (hi.y() - lo.y()), 0.5 * (cave.rock_top_m - z0));
      const std::string name =
          h == 0.0 ? "cave_rock_" + std::to_string(rock++) : "cave_ceiling_" + std::to_string(ceiling++);
      b.addBox(name, h == 0.0 ? "cave_rock" : "cave_ceiling", T, half,
               h == 0.0 ? ObstacleKind::kTextured : ObstacleKind::kGround, Look::hidden());
      if (h > 0.0) {  // visible skin: the ceiling's underside
        Pose S = Pose::Identity();
        S.translation() = Vec3(T.translation().x(), T.translation().y(), h + 0.5 * kSkin);
        b.addVisualSlab("cave_ceiling_skin_" + std::to_string(ceiling - 1), S, Vec3(half.x(), half.y(), 0.5 * kSkin),
                        cave.texture);
      }
    }
}

void buildWallSkins(const CaveSpec& cave, const CaveGrid& g, MjcfWorldBuilder& b) {
  constexpr double kSkin = kCaveSkin;
  const int nx = g.nx, ny = g.ny;
  // Wall skins: wherever a carved cell borders rock (or a lower ceiling), a thin textured slab
  // just inside the rock. Drawing only these faces, not the rock boxes, avoids rendering hidden
  // faces and overdraw. Faces along one boundary line with equal heights are merged.
  std::map<std::tuple<int, int, int, double, double>, std::vector<int>> runs;
  auto heightAt = [&](int i, int j) { return g.at(i, j); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double h = heightAt(i, j);
      if (h == 0.0) continue;
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int k = 0; k < 4; ++k) {
        const double hn = heightAt(i + di[k], j + dj[k]);
        if (hn >= h) continue;
        const int axis = k < 2 ? 0 : 1, sign = k % 2 == 0 ? 1 : -1;  // towards the rock
        const int line = axis == 0 ? i + (sign > 0 ? 1 : 0) : j + (sign > 0 ? 1 : 0);
        runs[{axis, sign, line, hn, h}].push_back(axis == 0 ? j : i);
      }
    }
  int skin = 0;
  for (auto& [key, cells] : runs) {
    const auto [axis, sign, line, zlo, zhi] = key;
    std::sort(cells.begin(), cells.end());
    for (size_t a = 0; a < cells.size();) {
      size_t e = a;
      while (e + 1 < cells.size() && cells[e + 1] == cells[e] + 1) ++e;
      const double along0 = (axis == 0 ? cave.min.y() : cave.min.x()) + cells[a] * cave.cell_m;
      const double along1 = (axis == 0 ? cave.min.y() : cave.min.x()) + (cells[e] + 1) * cave.cell_m;
      const double across = (axis == 0 ? cave.min.x() : cave.min.y()) + line * cave.cell_m + sign * 0.5 * kSkin;
      Pose S = Pose::Identity();
      Vec3 half;
      if (axis == 0) {
        S.translation() = Vec3(across, 0.5 * (along0 + along1), 0.5 * (zlo + zhi));
        half = Vec3(0.5 * kSkin, 0.5 * (along1 - along0), 0.5 * (zhi - zlo));
      } else {
        S.translation() = Vec3(0.5 * (along0 + along1), across, 0.5 * (zlo + zhi));
        half = Vec3(0.5 * (along1 - along0), 0.5 * kSkin, 0.5 * (zhi - zlo));
      }
      b.addVisualSlab("cave_wall_skin_" + std::to_string(skin++), S, half, cave.texture);
      a = e + 1;
    }
  }
}

void buildCave(const CaveSpec& cave, MjcfWorldBuilder& b) {
  const CaveGrid g = carveCave(cave);
  buildRockAndCeilings(cave, g, b);
  buildWallSkins(cave, g, b);
}

// Places the objects of a world spec one by one (in spec order, drawing from one placement
// stream), keeping the start area and the take-off corridor free, and records the ruins that
// reinforcement bars are later placed at.
class ObjectPlacer {
 public:
  ObjectPlacer(const WorldSpec& spec, MjcfWorldBuilder& b)
      : spec_(spec),
        b_(b),
        start_xy_(spec.start_position_m.head<2>()),
        half_ground_(0.5 * spec.ground_size_m),
        heading_(std::cos(spec.start_yaw_deg * kDeg), std::sin(spec.start_yaw_deg * kDeg)),
        placement_(spec.seed, "world_gen_" + spec.name) {}

  // Builds every object of group `gi`, counting them by kind in `counts` and listing them in `placed`.
  void placeGroup(size_t gi, std::map<std::string, int>& counts, std::vector<PlacedObject>& placed) {
    const ObjectGroupSpec& g = spec_.objects[gi];
    // Sizes and details depend on the spec only (not on the seed).
    RngStream sizes(0, "world_sizes_" + spec_.name + "_" + std::to_string(gi));
    for (int n = 0; n < g.count; ++n) {
      Vec3 size;
      for (int k = 0; k < 3; ++k) size[k] = sizes.uniform(g.size_min[k], g.size_max[k] + 1e-12);
      RngStream detail(n, "world_detail_" + spec_.name + "_" + std::to_string(gi));
      const double r = footprintRadius(g, size);
      const std::string id = g.kind + "_" + std::to_string(counts[g.kind]++);
      Vec2 xy;
      double yaw;
      if (g.at) {
        xy = *g.at;
        yaw = g.yaw_deg.value_or(0.0) * kDeg;
      } else if (g.near == "ruins") {
        placeAtRuin(gi, id, r, &xy, &yaw);
      } else {
        placeInRegion(g, gi, id, r, &xy, &yaw);
      }
      const size_t shapes_before = b_.shapes().size();
      // The solid's centre: `offset` in the object's frame from its position (zero for most specs).
      const Vec2 centre = xy + Eigen::Rotation2Dd(yaw) * g.offset;
      buildObject(g, id, centre, yaw, size, detail, b_);
      placed.push_back({id, g.kind, g.name, xy, yaw / kDeg});
      recordRuin(g, id, centre, yaw, size);
      if (g.at) checkFixedObjectClearsStart(gi, id, xy, shapes_before);
    }
  }

 private:
  // A footprint ruin (burned part, collapsed building) for reinforcement bars.
  struct Ruin {
    std::string object;
    Vec2 centre, half;
    double yaw;
  };

  // Clearance of a candidate footprint disc from everything built so far (exact distance to
  // the existing shapes, probed at several heights; ground, floor and cave ceilings skipped).
  double clearance(const Vec2& xy) const {
    double d = 1e9;
    for (const auto& s : b_.shapes()) {
      if (s.kind == ObstacleKind::kGround) continue;
      for (double z : {0.5, 2.0, 4.0, 7.0, 12.0}) d = std::min(d, s.signedDistance(Vec3(xy.x(), xy.y(), z)));
    }
    return d;
  }

  // Distance from the take-off corridor's centre line (from the start along its heading).
  double corridorDistance(const Vec2& xy) const {
    const double t = std::clamp((xy - start_xy_).dot(heading_), 0.0, spec_.start_corridor_m);
    return (xy - (start_xy_ + t * heading_)).norm();
  }

  // Clear of the start and the take-off corridor by a footprint of radius r.
  bool clearOfStart(const Vec2& xy, double r) const {
    return (xy - start_xy_).norm() >= spec_.start_clearance_m + r &&
           corridorDistance(xy) >= spec_.start_corridor_half_width_m + r;
  }

  // Reinforcement bars standing out of a ruin: the base on the ruin's footprint edge (up to
  // 0.2 m inside its walls, 0.8 m out into the rubble), leaning outwards; clear of the start,
  // the take-off corridor and every other object.
  void placeAtRuin(size_t gi, const std::string& id, double r, Vec2* xy, double* yaw) {
    if (ruins_.empty())
      throw std::runtime_error("world '" + spec_.name + "': objects[" + std::to_string(gi) +
                               "] are placed at ruins, but no burned or collapsed building comes before them");
    bool ok = false;
    for (int attempt = 0; attempt < 3000 && !ok; ++attempt) {
      const Ruin& ruin = ruins_[std::min(ruins_.size() - 1, size_t(placement_.uniform(0, double(ruins_.size()))))];
      const double perimeter = 4 * (ruin.half.x() + ruin.half.y());
      double t = placement_.uniform(0, perimeter);
      const double out_m = placement_.uniform(-0.2, 0.8);
      Vec2 local_xy, normal;
      if (t < 2 * ruin.half.x())
        local_xy = Vec2(-ruin.half.x() + t, ruin.half.y() + out_m), normal = Vec2(0, 1);
      else if ((t -= 2 * ruin.half.x()) < 2 * ruin.half.y())
        local_xy = Vec2(ruin.half.x() + out_m, ruin.half.y() - t), normal = Vec2(1, 0);
      else if ((t -= 2 * ruin.half.y()) < 2 * ruin.half.x())
        local_xy = Vec2(ruin.half.x() - t, -ruin.half.y() - out_m), normal = Vec2(0, -1);
      else
        t -= 2 * ruin.half.x(), local_xy = Vec2(-ruin.half.x() - out_m, -ruin.half.y() + t), normal = Vec2(-1, 0);
      const Eigen::Rotation2Dd R(ruin.yaw);
      *xy = ruin.centre + R * local_xy;
      const Vec2 outward = R * normal;
      *yaw = std::atan2(outward.y(), outward.x());
      double d = 1e9;  // from everything but the ruin itself
      for (const auto& sh : b_.shapes()) {
        if (sh.kind == ObstacleKind::kGround || sh.object == ruin.object) continue;
        for (double z : {0.5, 2.0, 4.0}) d = std::min(d, sh.signedDistance(Vec3(xy->x(), xy->y(), z)));
      }
      ok = clearOfStart(*xy, r) && d >= r + 1.0;
    }
    if (!ok)
      throw std::runtime_error("world '" + spec_.name + "': could not place " + id + " (objects[" + std::to_string(gi) +
                               "]) at the ruins");
  }

  // Rejection sampling: inside the region and the ground, clear of the start, the take-off
  // corridor and other objects (1 m gap), and for caves clear of the rock.
  void placeInRegion(const ObjectGroupSpec& g, size_t gi, const std::string& id, double r, Vec2* xy, double* yaw) {
    bool ok = false;
    for (int attempt = 0; attempt < 3000 && !ok; ++attempt) {
      *xy = Vec2(placement_.uniform(g.region_min->x(), g.region_max->x()),
                 placement_.uniform(g.region_min->y(), g.region_max->y()));
      *yaw = g.yaw_deg ? *g.yaw_deg * kDeg : placement_.uniform(-M_PI, M_PI);
      ok = clearOfStart(*xy, r) && (xy->cwiseAbs().array() <= (half_ground_.array() - r)).all() &&
           clearance(*xy) >= r + 1.0;
    }
    if (!ok)
      throw std::runtime_error("world '" + spec_.name + "': could not place " + id + " (objects[" + std::to_string(gi) +
                               "]) in its region");
  }

  // A burned building's burned part, or a collapsed building, is a ruin.
  void recordRuin(const ObjectGroupSpec& g, const std::string& id, const Vec2& xy, double yaw, const Vec3& size) {
    if (g.kind == "building" && g.variant == "burned") {
      const double lb = g.burned_fraction * size.x();
      ruins_.push_back(
          {id, xy + Eigen::Rotation2Dd(yaw) * Vec2(0.5 * size.x() - 0.5 * lb, 0), Vec2(0.5 * lb, 0.5 * size.y()), yaw});
    } else if (isCollapsed(g)) {
      ruins_.push_back({id, xy, Vec2(0.5 * size.x(), 0.5 * size.y()), yaw});
    }
  }

  // The start area is kept free of every object, fixed ones too: the nearest surface of what
  // was just built (probed at several heights above the start) lies outside the clearance, and
  // nothing lies in the take-off corridor.
  void checkFixedObjectClearsStart(size_t gi, const std::string& id, const Vec2& xy, size_t shapes_before) const {
    double d = 1e9;
    for (size_t k = shapes_before; k < b_.shapes().size(); ++k)
      for (double z : {0.05, 0.5, 2.0, 4.0})
        d = std::min(d, b_.shapes()[k].signedDistance(Vec3(start_xy_.x(), start_xy_.y(), z)));
    for (double t = 1.0; t <= spec_.start_corridor_m; t += 1.0)
      for (size_t k = shapes_before; k < b_.shapes().size(); ++k)
        for (double z : {0.5, 2.0, 4.0}) {
          const Vec2 c = start_xy_ + t * heading_;
          if (b_.shapes()[k].signedDistance(Vec3(c.x(), c.y(), z)) < spec_.start_corridor_half_width_m)
            throw ConfigError("objects[" + std::to_string(gi) + "].at", id + " lies in the take-off corridor (" +
                                                                            std::to_string(spec_.start_corridor_m) +
                                                                            " m along the start heading)");
        }
    if (d < spec_.start_clearance_m) {
      char why[200];
      std::snprintf(why, sizeof(why),
                    "%s at (%g, %g) comes within %.2f m of the start (%g, %g): inside the start "
                    "clearance of %g m",
                    id.c_str(), xy.x(), xy.y(), std::max(d, 0.0), start_xy_.x(), start_xy_.y(),
                    spec_.start_clearance_m);
      throw ConfigError("objects[" + std::to_string(gi) + "].at", why);
    }
  }

  const WorldSpec& spec_;
  MjcfWorldBuilder& b_;
  Vec2 start_xy_, half_ground_, heading_;
  RngStream placement_;
  std::vector<Ruin> ruins_;
};

}  // namespace

GeneratedWorld generateWorld(const WorldSpec& spec) {
  checkValid(spec);
  MjcfWorldBuilder b(spec.name);
  if (spec.ground_enabled) b.setGround(spec.ground_size_m, spec.ground_texture);
  if (!spec.cave) b.setOutdoorSky(spec.ground_size_m);  // caves: no sky, no sun
  b.setSunDirection(spec.sun_direction);
  GeneratedWorld out;
  out.name = spec.name;
  out.paper_world = spec.paper_world;
  out.meshes = buildMeshes(spec, b, out.image_textures);
  if (spec.cave) {
    buildCave(*spec.cave, b);
    out.object_counts["cave_box"] = b.collisionGeoms() - 1;
  }
  // The objects, group by group.
  ObjectPlacer placer(spec, b);
  for (size_t gi = 0; gi < spec.objects.size(); ++gi) placer.placeGroup(gi, out.object_counts, out.objects);
  // The world's files and facts.
  out.mjcf = b.mjcf();
  out.textures.assign(b.texturesUsed().begin(), b.texturesUsed().end());
  out.shapes = b.shapes();
  out.start = poseFromXyzYaw(spec.start_position_m, spec.start_yaw_deg * kDeg);
  out.exploration_box = spec.exploration_box;
  out.collision_geoms = b.collisionGeoms();
  out.visual_geoms = b.visualGeoms();
  return out;
}

}  // namespace msb
