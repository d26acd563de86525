#include "core/geometry/shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msb {

const char* obstacleKindName(ObstacleKind kind) {
  switch (kind) {
    case ObstacleKind::kTextured:
      return "textured";
    case ObstacleKind::kTextureless:
      return "textureless";
    case ObstacleKind::kThin:
      return "thin";
    case ObstacleKind::kGround:
      return "ground";
  }
  return "?";
}

namespace {

// Smallest root t >= 0 of a t² + 2 b t + c = 0 (the first crossing), if any.
std::optional<double> firstRoot(double a, double b, double c) {
  const double disc = b * b - a * c;
  if (disc < 0.0 || a <= 0.0) return std::nullopt;
  const double s = std::sqrt(disc);
  const double t0 = (-b - s) / a, t1 = (-b + s) / a;
  if (t0 >= 0.0) return t0;
  if (t1 >= 0.0) return 0.0;  // origin inside
  return std::nullopt;
}

}  // namespace

double Shape::signedDistance(const Vec3& p) const {
  if (type == ShapeType::kConvex) return polytope->signedDistance(p);
  const Vec3 q = pose.linear().transpose() * (p - pose.translation());
  switch (type) {
    case ShapeType::kBox: {
      const Vec3 d = q.cwiseAbs() - size;
      return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
    }
    case ShapeType::kCylinder: {
      const double dr = std::hypot(q.x(), q.y()) - size.x();
      const double dz = std::abs(q.z()) - size.z();
      return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
    }
    case ShapeType::kSphere:
      return q.norm() - size.x();
    case ShapeType::kHalfSpace:
      return q.z();
    case ShapeType::kConvex:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

std::optional<double> Shape::raycast(const Vec3& o_w, const Vec3& d_w) const {
  if (type == ShapeType::kConvex) return polytope->raycast(o_w, d_w);
  const Mat3 Rt = pose.linear().transpose();
  const Vec3 o = Rt * (o_w - pose.translation()), d = Rt * d_w;
  switch (type) {
    case ShapeType::kBox: {
      // Slab method.
      double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-15) {
          if (std::abs(o[i]) > size[i]) return std::nullopt;
          continue;
        }
        double a = (-size[i] - o[i]) / d[i], b = (size[i] - o[i]) / d[i];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) return std::nullopt;
      }
      return t0;
    }
    case ShapeType::kCylinder: {
      double best = std::numeric_limits<double>::infinity();
      // Side: x² + y² = r² within |z| <= h.
      const double a = d.x() * d.x() + d.y() * d.y();
      if (a > 1e-15) {
        const double b = o.x() * d.x() + o.y() * d.y();
        const double c = o.x() * o.x() + o.y() * o.y() - size.x() * size.x();
        const double disc = b * b - a * c;
        if (disc >= 0.0) {
          const double s = std::sqrt(disc);
          for (double t : {(-b - s) / a, (-b + s) / a})
            if (t >= 0.0 && std::abs(o.z() + t * d.z()) <= size.z()) best = std::min(best, t);
        }
      }
      // Caps: z = ±h within the disc.
      if (std::abs(d.z()) > 1e-15) {
        for (double zc : {-size.z(), size.z()}) {
          const double t = (zc - o.z()) / d.z();
          const Vec3 hit = o + t * d;
          if (t >= 0.0 && hit.x() * hit.x() + hit.y() * hit.y() <= size.x() * size.x()) best = std::min(best, t);
        }
      }
      if (signedDistance(o_w) <= 0.0) return 0.0;
      return std::isfinite(best) ? std::optional<double>(best) : std::nullopt;
    }
    case ShapeType::kSphere:
      return firstRoot(d.squaredNorm(), o.dot(d), o.squaredNorm() - size.x() * size.x());
    case ShapeType::kHalfSpace: {
      if (o.z() <= 0.0) return 0.0;
      if (d.z() >= 0.0) return std::nullopt;
      return -o.z() / d.z();
    }
    case ShapeType::kConvex:
      break;
  }
  return std::nullopt;
}

std::pair<Vec3, Vec3> Shape::bounds() const {
  if (type == ShapeType::kHalfSpace) return {Vec3::Constant(-1e9), Vec3::Constant(1e9)};
  if (type == ShapeType::kConvex) return polytope->bounds();
  Vec3 half;
  const Mat3 A = pose.linear().cwiseAbs();
  switch (type) {
    case ShapeType::kBox:
      half = A * size;
      break;
    case ShapeType::kCylinder:
      // Extent of a disc of radius r with normal n along axis i: r·sqrt(1 − n_i²).
      for (int i = 0; i < 3; ++i) {
        const double n = pose.linear()(i, 2);
        half[i] = size.x() * std::sqrt(std::max(0.0, 1.0 - n * n)) + size.z() * std::abs(n);
      }
      break;
    default:
      half = Vec3::Constant(size.x());
      break;
  }
  return {pose.translation() - half, pose.translation() + half};
}

}  // namespace msb
