#include "sim/world/mjcf_world_builder.h"

#include <array>
#include <cmath>

#include "sim/world/procedural_textures.h"

namespace msb {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}
std::string vec(const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }
std::string quat(const Mat3& R) {
  Quat q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z());
}

// A box's surface: 6 quads, each with its own 4 vertices (flat shading), counter-clockwise
// from outside; without the top face if `skip_top`. With `uv` (tile size `tile` m), texture
// coordinates in tiles: world-scale metres along each face.
void boxSurface(const Pose& T, const Vec3& half, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& f,
                bool skip_top = false, std::vector<Vec2>* uv = nullptr, double tile = 1.0) {
  const std::array<std::array<int, 2>, 4> corners = {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int sign : {1, -1}) {
      if (axis == 2 && sign > 0 && skip_top) continue;
      const int base = int(v.size());
      std::array<int, 4> order = {0, 1, 2, 3};
      if (sign < 0) order = {3, 2, 1, 0};
      for (int k : order) {
        Vec3 local = Vec3::Zero();
        local[axis] = sign * half[axis];
        local[a] = corners[k][0] * half[a];
        local[b] = corners[k][1] * half[b];
        v.push_back(T * local);
        if (uv) uv->emplace_back((corners[k][0] + 1) * half[a] / tile, (corners[k][1] + 1) * half[b] / tile);
      }
      f.push_back({base, base + 1, base + 2});
      f.push_back({base, base + 2, base + 3});
    }
  }
}

// A cylinder's surface along T's z: an n-sided prism and two cap fans with their own vertices.
// Without texture coordinates the side vertices are shared around (the side is shaded smoothly);
// with them (`uv`, tiles of `tile` m) the seam column is repeated so the texture wraps around the
// circumference, and the caps are mapped in plan.
void cylinderSurface(const Pose& T, double radius, double half_height, int n, std::vector<Vec3>& v,
                     std::vector<std::array<int, 3>>& f, std::vector<Vec2>* uv = nullptr, double tile = 1.0) {
  const int side = int(v.size()), columns = uv ? n + 1 : n;
  const double arc = 2 * M_PI * radius / n;
  for (int k = 0; k < columns; ++k) {
    const double ang = 2 * M_PI * k / n;
    for (double z : {-half_height, half_height}) {
      v.push_back(T * Vec3(radius * std::cos(ang), radius * std::sin(ang), z));
      if (uv) uv->emplace_back(k * arc / tile, (z + half_height) / tile);
    }
  }
  for (int k = 0; k < n; ++k) {
    const int a = side + 2 * k, b = side + 2 * ((k + 1) % columns);  // bottom vertices; +1 = top
    f.push_back({a, b, b + 1});
    f.push_back({a, b + 1, a + 1});
  }
  for (double z : {-half_height, half_height}) {
    const int centre = int(v.size());
    v.push_back(T * Vec3(0, 0, z));
    if (uv) uv->emplace_back(0, 0);
    const int ring = int(v.size());
    for (int k = 0; k < n; ++k) {
      const double ang = 2 * M_PI * k / n;
      v.push_back(T * Vec3(radius * std::cos(ang), radius * std::sin(ang), z));
      if (uv) uv->emplace_back(radius * std::cos(ang) / tile, radius * std::sin(ang) / tile);
    }
    for (int k = 0; k < n; ++k) {
      const int a = ring + k, b = ring + (k + 1) % n;
      if (z > 0)
        f.push_back({centre, a, b});
      else
        f.push_back({centre, b, a});
    }
  }
}

}  // namespace

void MjcfWorldBuilder::mergeSurface(const Look& look, const std::vector<Vec3>& v,
                                    const std::vector<std::array<int, 3>>& faces) {
  MergedMesh& m = merged_[{look.merge_group, material(look)}];
  const int base = int(m.vertices.size());
  m.vertices.insert(m.vertices.end(), v.begin(), v.end());
  for (const auto& t : faces) m.faces.push_back({base + t[0], base + t[1], base + t[2]});
}

std::string MjcfWorldBuilder::material(const Look& look) {
  switch (look.type) {
    case Look::kTextured:
      textures_.insert(look.texture);
      return "mat_" + look.texture;
    case Look::kCube:
      textures_.insert(look.texture);
      cube_textures_.insert(look.texture);
      return "matcube_" + look.texture;
    case Look::kHidden:
      return "";
    case Look::kFlat: {
      const int g = std::clamp(int(std::lround(look.grey * 255)), 0, 255);
      auto it = flat_materials_.find(g);
      if (it == flat_materials_.end()) it = flat_materials_.emplace(g, "flat_" + std::to_string(g)).first;
      return it->second;
    }
  }
  return "";
}

std::string MjcfWorldBuilder::collisionGeom(const Shape& s, const Look& look, const std::string& mat) {
  std::ostringstream g;
  const char* type = s.type == ShapeType::kBox ? "box" : s.type == ShapeType::kCylinder ? "cylinder" : "sphere";
  g << "    <geom name=\"" << s.name << "\" type=\"" << type << "\" pos=\"" << vec(s.pose.translation()) << "\"";
  if (s.type != ShapeType::kSphere) g << " quat=\"" << quat(s.pose.linear()) << "\"";
  g << " size=\"";
  if (s.type == ShapeType::kBox)
    g << vec(s.size);
  else if (s.type == ShapeType::kCylinder)
    g << num(s.size.x()) << " " << num(s.size.z());
  else
    g << num(s.size.x());
  g << "\"";
  if (look.type == Look::kTextured || look.type == Look::kHidden || merged(look))
    g << " group=\"" << geom_groups::kCollisionOnly << "\" rgba=\"0.5 0.5 0.5 1\"";
  else
    g << " group=\"" << geom_groups::kRendered << "\" material=\"" << mat << "\"";
  g << "/>\n";
  return g.str();
}

void MjcfWorldBuilder::addMesh(const std::string& name, const std::vector<Vec3>& v, const std::vector<Vec2>& uv,
                               const std::vector<std::array<int, 3>>& faces, const std::string& mat) {
  assets_ << "    <mesh name=\"" << name << "\" vertex=\"";
  for (size_t i = 0; i < v.size(); ++i) assets_ << (i ? " " : "") << vec(v[i]);
  if (!uv.empty()) {  // texture coordinates (none for a flat mesh)
    assets_ << "\" texcoord=\"";
    for (size_t i = 0; i < uv.size(); ++i) assets_ << (i ? " " : "") << num(uv[i].x()) << " " << num(uv[i].y());
  }
  assets_ << "\" face=\"";
  for (size_t i = 0; i < faces.size(); ++i)
    assets_ << (i ? " " : "") << faces[i][0] << " " << faces[i][1] << " " << faces[i][2];
  assets_ << "\"/>\n";
  bodies_ << "    <geom name=\"" << name << "\" type=\"mesh\" mesh=\"" << name << "\" material=\"" << mat
          << "\" contype=\"0\" conaffinity=\"0\" group=\"" << geom_groups::kVisualMesh << "\"/>\n";
  ++visual_geoms_;
}

void MjcfWorldBuilder::addBox(const std::string& name, const std::string& object, const Pose& T, const Vec3& half,
                              ObstacleKind kind, const Look& look) {
  Shape s{ShapeType::kBox, T, half, kind, name, object};
  const std::string mat = material(look);
  bodies_ << collisionGeom(s, look, mat);
  shapes_.push_back(s);
  if (merged(look)) {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> f;
    boxSurface(T, half, v, f);
    mergeSurface(look, v, f);
  }
  if (look.type == Look::kTextured) {
    if (!look.top_texture.empty()) textures_.insert(look.top_texture);
    addBoxMesh(name + "_vis", T, half, look.texture, look.top_texture);
  }
}

void MjcfWorldBuilder::addVisualSlab(const std::string& name, const Pose& T, const Vec3& half,
                                     const std::string& texture) {
  textures_.insert(texture);
  addBoxMesh(name, T, half, texture);
}

void MjcfWorldBuilder::addBoxMesh(const std::string& name, const Pose& T, const Vec3& half, const std::string& texture,
                                  const std::string& top_texture) {
  // Visual mesh: 6 quads with texture coordinates in tiles (the top one separately for roofs).
  std::vector<Vec3> v;
  std::vector<Vec2> uv;
  std::vector<std::array<int, 3>> f;
  boxSurface(T, half, v, f, !top_texture.empty(), &uv, textureTileMeters(texture));
  addMesh(name, v, uv, f, "mat_" + texture);
  if (!top_texture.empty()) {
    // The top face alone, as a thin slab of the roof pattern flush with the box's top.
    Pose top = T;
    top.translation() = T * Vec3(0, 0, half.z() - 0.005);
    addBoxMesh(name + "_top", top, Vec3(half.x(), half.y(), 0.005), top_texture);
  }
}

void MjcfWorldBuilder::addCylinder(const std::string& name, const std::string& object, const Pose& T, double radius,
                                   double half_height, ObstacleKind kind, const Look& look) {
  Shape s{ShapeType::kCylinder, T, Vec3(radius, radius, half_height), kind, name, object};
  const std::string mat = material(look);
  bodies_ << collisionGeom(s, look, mat);
  shapes_.push_back(s);
  if (merged(look)) {
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> f;
    cylinderSurface(T, radius, half_height, radius > 0.5 ? 24 : 12, v, f);
    mergeSurface(look, v, f);
  }
  if (look.type != Look::kTextured) return;

  // Visual prism with N sides (texture wraps around the circumference) and two cap fans.
  std::vector<Vec3> v;
  std::vector<Vec2> uv;
  std::vector<std::array<int, 3>> f;
  cylinderSurface(T, radius, half_height, radius > 0.5 ? 24 : 12, v, f, &uv, textureTileMeters(look.texture));
  addMesh(name + "_vis", v, uv, f, mat);
}

void MjcfWorldBuilder::addSphere(const std::string& name, const std::string& object, const Vec3& centre, double radius,
                                 ObstacleKind kind, const Look& look) {
  Pose T = Pose::Identity();
  T.translation() = centre;
  Shape s{ShapeType::kSphere, T, Vec3::Constant(radius), kind, name, object};
  // Spheres are drawn as primitives: a textured look becomes a cube-mapped texture.
  const Look l = look.type == Look::kTextured ? Look::cube(look.texture) : look;
  bodies_ << collisionGeom(s, l, material(l));
  shapes_.push_back(s);
}

void MjcfWorldBuilder::addConvex(const std::string& name, const std::string& object, ConvexPolytope piece,
                                 ObstacleKind kind, bool ground) {
  assets_ << "    <mesh name=\"" << name << "\" vertex=\"";
  for (size_t i = 0; i < piece.vertices.size(); ++i) assets_ << (i ? " " : "") << vec(piece.vertices[i]);
  assets_ << "\"/>\n";
  bodies_ << "    <geom name=\"" << name << "\" type=\"mesh\" mesh=\"" << name << "\" group=\""
          << geom_groups::kCollisionOnly << "\" rgba=\"0.5 0.5 0.5 1\"";
  if (ground) bodies_ << " conaffinity=\"" << (1 | kGroundConaffinityBit) << "\"";
  bodies_ << "/>\n";
  Shape s;
  s.type = ShapeType::kConvex;
  const auto [lo, hi] = piece.bounds();
  s.size = 0.5 * (hi - lo);
  s.kind = kind, s.name = name, s.object = object;
  s.polytope = std::make_shared<const ConvexPolytope>(std::move(piece));
  shapes_.push_back(std::move(s));
}

void MjcfWorldBuilder::addTexturedMesh(const std::string& name, const std::vector<Vec3>& v, const std::vector<Vec2>& uv,
                                       const std::vector<std::array<int, 3>>& faces, const std::string& texture) {
  if (!image_textures_.count(texture)) textures_.insert(texture);
  addMesh(name, v, uv, faces, "mat_" + texture);
}

void MjcfWorldBuilder::addFlatMesh(const std::string& name, const std::vector<Vec3>& v,
                                   const std::vector<std::array<int, 3>>& faces, double grey) {
  addMesh(name, v, {}, faces, material(Look::flat(grey)));
}

void MjcfWorldBuilder::setGround(const Vec2& size_m, const std::string& texture) {
  textures_.insert(texture);
  Pose T = Pose::Identity();
  shapes_.push_back({ShapeType::kHalfSpace, T, Vec3::Zero(), ObstacleKind::kGround, "ground", "ground"});
  const double rep = 1.0 / textureTileMeters(texture);
  assets_ << "    <material name=\"mat_ground\" texture=\"tex_" << texture << "\" texrepeat=\"" << num(rep) << " "
          << num(rep) << "\" texuniform=\"true\"/>\n";
  bodies_ << "    <geom name=\"ground\" type=\"plane\" size=\"" << num(size_m.x() / 2) << " " << num(size_m.y() / 2)
          << " 20\" material=\"mat_ground\" group=\"" << geom_groups::kRendered << "\"/>\n";
}

void MjcfWorldBuilder::setOutdoorSky(const Vec2& ground_size_m) {
  outdoor_ = true;
  // Planes at D from the origin, each facing inwards (a plane faces its local +z); D stays well
  // inside the renderer's far clipping distance. Self-lit (emission 1) and bright enough to
  // saturate whatever the lighting, so the sky is a uniform white without seams between planes
  // (an overcast bright sky, as the reference's Gazebo sky is to a grey-scale camera).
  const double D = 0.5 * ground_size_m.maxCoeff() + 100.0;
  assets_ << "    <material name=\"mat_sky\" rgba=\"0.85 0.85 0.85 1\" emission=\"1\"/>\n";
  struct Plane {
    const char* name;
    Vec3 pos;
    const char* euler;
  };
  const Plane planes[] = {{"sky_top", Vec3(0, 0, D), "180 0 0"},
                          {"sky_east", Vec3(D, 0, 0), "0 -90 0"},
                          {"sky_west", Vec3(-D, 0, 0), "0 90 0"},
                          {"sky_north", Vec3(0, D, 0), "90 0 0"},
                          {"sky_south", Vec3(0, -D, 0), "-90 0 0"}};
  for (const Plane& p : planes)
    bodies_ << "    <geom name=\"" << p.name << "\" type=\"plane\" size=\"" << num(D) << " " << num(D) << " " << num(D)
            << "\" pos=\"" << num(p.pos.x()) << " " << num(p.pos.y()) << " " << num(p.pos.z()) << "\" euler=\""
            << p.euler << "\" material=\"mat_sky\" contype=\"0\" conaffinity=\"0\" group=\"" << geom_groups::kSky
            << "\"/>\n";
  visual_geoms_ += 5;
}

std::string MjcfWorldBuilder::mjcf() const {
  std::ostringstream os;
  os << "<!-- Generated by msbench world build: do not edit; edit the spec instead. -->\n"
     << "<mujoco model=\"" << model_name_ << "\">\n  <asset>\n";
  for (const auto& t : textures_) {
    os << "    <texture name=\"tex_" << t << "\" type=\"2d\" file=\"textures/" << t << ".png\"/>\n"
       << "    <material name=\"mat_" << t << "\" texture=\"tex_" << t << "\"/>\n";
  }
  for (const auto& t : image_textures_) {
    os << "    <texture name=\"tex_" << t << "\" type=\"2d\" file=\"textures/" << t << ".png\"/>\n"
       << "    <material name=\"mat_" << t << "\" texture=\"tex_" << t << "\"/>\n";
  }
  for (const auto& t : cube_textures_) {
    os << "    <texture name=\"texcube_" << t << "\" type=\"cube\" file=\"textures/" << t
       << ".png\"/>\n    <material name=\"matcube_" << t << "\" texture=\"texcube_" << t << "\"/>\n";
  }
  for (const auto& [g, name] : flat_materials_) {
    const std::string c = num(g / 255.0);
    os << "    <material name=\"" << name << "\" rgba=\"" << c << " " << c << " " << c << " 1\"/>\n";
  }
  // Outdoors, a sun: a world-fixed directional light (used with the renderer's `sun` switch),
  // so faces of different orientation differ in brightness, as under Gazebo's sun.
  // Merged meshes of flat parts (no texture coordinates: one uniform material each).
  std::ostringstream merged_assets, merged_geoms;
  for (const auto& [key, m] : merged_) {
    const std::string name = key.first + "_" + key.second;
    merged_assets << "    <mesh name=\"" << name << "\" vertex=\"";
    for (size_t i = 0; i < m.vertices.size(); ++i) merged_assets << (i ? " " : "") << vec(m.vertices[i]);
    merged_assets << "\" face=\"";
    for (size_t i = 0; i < m.faces.size(); ++i)
      merged_assets << (i ? " " : "") << m.faces[i][0] << " " << m.faces[i][1] << " " << m.faces[i][2];
    merged_assets << "\"/>\n";
    merged_geoms << "    <geom name=\"" << name << "\" type=\"mesh\" mesh=\"" << name << "\" material=\"" << key.second
                 << "\" contype=\"0\" conaffinity=\"0\" group=\"" << geom_groups::kVisualMesh << "\"/>\n";
  }
  os << assets_.str() << merged_assets.str() << "  </asset>\n  <worldbody>\n";
  if (outdoor_)
    os << "    <light name=\"sun\" directional=\"true\" castshadow=\"false\" pos=\"0 0 60\" dir=\""
       << (sun_direction_ == Vec3(0.62, 0.47, -0.63) ? std::string("0.62 0.47 -0.63") : vec(sun_direction_))
       << "\" diffuse=\"0.45 0.45 0.45\" specular=\"0 0 0\" ambient=\"0 0 0\"/>\n";
  os << bodies_.str() << merged_geoms.str() << "  </worldbody>\n</mujoco>\n";
  return os.str();
}

}  // namespace msb
