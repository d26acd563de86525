#include "sim/physics/contact_gate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msb {

namespace {

// Slack beyond the contact margin: the narrow phase's own tolerances are far below it.
constexpr double kSlackM = 0.01;

// MuJoCo's rule for whether two geoms may collide at all (contype of one & conaffinity of the other).
bool compatible(const mjModel* m, int a, int b) {
  return (m->geom_contype[a] & m->geom_conaffinity[b]) || (m->geom_contype[b] & m->geom_conaffinity[a]);
}

// Half extents of a mesh's vertices in its geom frame, or nothing when they do not lie within
// the geom's bounding sphere (then the frames would differ and the box could not be trusted).
bool meshHalfExtents(const mjModel* m, int g, Vec3* centre, Vec3* half) {
  const int mesh = m->geom_dataid[g];
  if (mesh < 0 || m->mesh_vertnum[mesh] <= 0) return false;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const float* v = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
  for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) {
    const Vec3 p(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    if (p.norm() > m->geom_rbound[g] * (1 + 1e-6) + 1e-9) return false;
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  *centre = 0.5 * (lo + hi);
  *half = 0.5 * (hi - lo);
  return true;
}

}  // namespace

ContactGate::ContactGate(const mjModel* m, const mjData* d, int vehicle_body) {
  if (m->npair > 0) why_inactive_ = "the model has explicit contact pairs";
  // The vehicle's ball and the largest margin any pair can have.
  double margin = mjENABLED(mjENBL_OVERRIDE) ? m->opt.o_margin : 0.0;
  std::vector<int> vehicle;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != vehicle_body) continue;
    vehicle.push_back(g);
    const Vec3 pos(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
    vehicle_radius_ = std::max(vehicle_radius_, pos.norm() + m->geom_rbound[g]);
    margin = std::max(margin, m->geom_margin[g]);
  }
  // Every other geom the vehicle can touch: static, with a box or a half-space.
  for (int g = 0; g < m->ngeom && active(); ++g) {
    const int body = m->geom_bodyid[g];
    if (body == vehicle_body) continue;
    if (std::none_of(vehicle.begin(), vehicle.end(), [&](int v) { return compatible(m, g, v); })) continue;
    if (m->body_weldid[body] != 0 || m->body_mocapid[body] >= 0) {
      why_inactive_ = "a moving body other than the vehicle has collision geoms";
      break;
    }
    margin = std::max(margin, m->geom_margin[g]);
    addGeom(m, d, g);
  }
  reach_ = vehicle_radius_ + margin + kSlackM;
}

void ContactGate::addGeom(const mjModel* m, const mjData* d, int g) {
  const mjtNum* x = d->geom_xmat + 9 * g;  // row-major: column k is local axis k in the world
  Mat3 R;
  R << x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8];
  const Vec3 pos(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  const mjtNum* s = m->geom_size + 3 * g;
  const double rb = m->geom_rbound[g];
  Vec3 centre = Vec3::Zero(), half;
  switch (m->geom_type[g]) {
    case mjGEOM_PLANE:  // MuJoCo collides with a plane as the half-space below its +z
      planes_.push_back({R.col(2), R.col(2).dot(pos)});
      return;
    case mjGEOM_BOX:
      half = Vec3(s[0], s[1], s[2]);
      break;
    case mjGEOM_SPHERE:
      half = Vec3::Constant(s[0]);
      break;
    case mjGEOM_CYLINDER:
      half = Vec3(s[0], s[0], s[1]);
      break;
    case mjGEOM_CAPSULE:
      half = Vec3(s[0], s[0], s[1] + s[0]);
      break;
    case mjGEOM_ELLIPSOID:
      half = Vec3(s[0], s[1], s[2]);
      break;
    default:
      if (m->geom_type[g] == mjGEOM_MESH && meshHalfExtents(m, g, &centre, &half)) break;
      if (rb <= 0) {
        why_inactive_ = "a collision geom has no bounding sphere";
        return;
      }
      half = Vec3::Constant(rb);  // the cube around the bounding sphere
  }
  boxes_.push_back({pos + R * centre, R, half});
}

double ContactGate::clearance(const Vec3& p) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Box& b : boxes_) {
    const Vec3 q = b.R.transpose() * (p - b.centre);
    nearest = std::min(nearest, (q.cwiseAbs() - b.half).cwiseMax(0.0).norm());
  }
  for (const HalfSpace& h : planes_) nearest = std::min(nearest, h.normal.dot(p) - h.offset);
  return nearest - reach_;
}

bool ContactGate::mayTouch(const Vec3& p) {
  if (!active()) return true;
  // Within the ball measured last, nothing can be nearer than it was by more than the distance moved.
  if (free_radius_ > 0 && (p - anchor_).norm() < free_radius_) return false;
  anchor_ = p;
  free_radius_ = clearance(p);
  return free_radius_ <= 0;
}

}  // namespace msb
