#include "core/perception/oracle_features.h"

#include <algorithm>
#include <cmath>

namespace msb {

void OracleFeatureConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

OracleFeatureSource::OracleFeatureSource(const OracleFeatureConfig& config, const FisheyeCamera& camera,
                                         const WorldTruth& truth, uint64_t seed)
    : config_(checkValid(config)), camera_(camera), truth_(truth), noise_(seed, "oracle_pixel_noise") {
  RngStream rng(seed, "oracle_landmarks");
  sampleLandmarks(rng);
  // Shuffle once (Fisher–Yates) so that taking new tracks in index order spreads them.
  for (size_t i = landmarks_.size(); i > 1; --i) std::swap(landmarks_[i - 1], landmarks_[rng.uniformInt(i)]);
  track_of_.assign(landmarks_.size(), 0);
  age_.assign(landmarks_.size(), 0);
}

void OracleFeatureSource::sampleLandmarks(RngStream& rng) {
  // Extent of the bounded shapes: ground planes carry landmarks over it plus a margin.
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const Shape& s : truth_.shapes()) {
    if (s.type == ShapeType::kHalfSpace) continue;
    const auto [a, b] = s.bounds();
    lo = lo.cwiseMin(a);
    hi = hi.cwiseMax(b);
  }
  lo.array() -= config_.ground_margin_m;
  hi.array() += config_.ground_margin_m;
  // Every shape's surfaces, in shape order (the stream's draws follow it).
  for (const Shape& s : truth_.shapes()) {
    if (s.kind == ObstacleKind::kTextureless && !config_.textureless_landmarks) continue;
    if (s.kind == ObstacleKind::kThin && !config_.thin_landmarks) continue;
    switch (s.type) {
      case ShapeType::kBox:
        sampleBox(s, rng);
        break;
      case ShapeType::kCylinder:
        sampleCylinder(s, rng);
        break;
      case ShapeType::kSphere:
        sampleSphere(s, rng);
        break;
      case ShapeType::kHalfSpace:
        samplePlane(s, lo, hi, rng);
        break;
      case ShapeType::kConvex:
        sampleConvex(s, rng);
        break;
    }
  }
}

int OracleFeatureSource::landmarkCount(double area, RngStream& rng) const {
  // Points on a surface of `area` m²: the expected count, rounded at random.
  const double density = 1.0 / (config_.landmark_spacing_m * config_.landmark_spacing_m);
  const double n = area * density;
  return int(std::floor(n)) + (rng.uniform() < n - std::floor(n) ? 1 : 0);
}

void OracleFeatureSource::addLandmark(const Shape& s, const Vec3& p_S, const Vec3& n_S) {
  landmarks_.push_back({s.pose * p_S, s.pose.linear() * n_S});
}

void OracleFeatureSource::sampleBox(const Shape& s, RngStream& rng) {
  // Six faces: axis k at ±size_k, uniform over the other two axes.
  const Vec3& a = s.size;
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    for (double sign : {-1.0, 1.0}) {
      const int n = landmarkCount(4.0 * a[u] * a[v], rng);
      for (int i = 0; i < n; ++i) {
        Vec3 p;
        p[k] = sign * a[k];
        p[u] = rng.uniform(-a[u], a[u]);
        p[v] = rng.uniform(-a[v], a[v]);
        addLandmark(s, p, sign * Vec3::Unit(k));
      }
    }
  }
}

void OracleFeatureSource::sampleCylinder(const Shape& s, RngStream& rng) {
  // The side, then the two caps.
  const double r = s.size.x(), h = s.size.z();
  const int n_side = landmarkCount(2.0 * M_PI * r * 2.0 * h, rng);
  for (int i = 0; i < n_side; ++i) {
    const double phi = rng.uniform(0, 2 * M_PI);
    const Vec3 n(std::cos(phi), std::sin(phi), 0);
    addLandmark(s, Vec3(r * n.x(), r * n.y(), rng.uniform(-h, h)), n);
  }
  for (double sign : {-1.0, 1.0}) {
    const int n_cap = landmarkCount(M_PI * r * r, rng);
    for (int i = 0; i < n_cap; ++i) {
      const double rho = r * std::sqrt(rng.uniform()), phi = rng.uniform(0, 2 * M_PI);
      addLandmark(s, Vec3(rho * std::cos(phi), rho * std::sin(phi), sign * h), Vec3(0, 0, sign));
    }
  }
}

void OracleFeatureSource::sampleSphere(const Shape& s, RngStream& rng) {
  const double r = s.size.x();
  const int n = landmarkCount(4.0 * M_PI * r * r, rng);
  for (int i = 0; i < n; ++i) {
    Vec3 d = rng.normal3();
    if (d.norm() < 1e-9) d = Vec3::UnitZ();
    d.normalize();
    addLandmark(s, r * d, d);
  }
}

void OracleFeatureSource::sampleConvex(const Shape& s, RngStream& rng) {
  // Each surface triangle, uniformly (world frame: the pose is the identity).
  const ConvexPolytope& P = *s.polytope;
  for (const auto& t : P.triangles) {
    const Vec3 &a = P.vertices[t[0]], &b = P.vertices[t[1]], &c = P.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const int n = landmarkCount(0.5 * cross.norm(), rng);
    for (int i = 0; i < n; ++i) {
      double u = rng.uniform(), v = rng.uniform();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      landmarks_.push_back({a + u * (b - a) + v * (c - a), cross.normalized()});
    }
  }
}

void OracleFeatureSource::samplePlane(const Shape& s, const Vec3& lo, const Vec3& hi, RngStream& rng) {
  // A ground (or ceiling) plane: landmarks over the objects' xy extent, on the plane.
  const Vec3 n_W = s.pose.linear().col(2), p0 = s.pose.translation();
  if (std::abs(n_W.z()) < 0.5 || (hi.x() < lo.x())) return;
  const int n = landmarkCount((hi.x() - lo.x()) * (hi.y() - lo.y()), rng);
  for (int i = 0; i < n; ++i) {
    const double x = rng.uniform(lo.x(), hi.x()), y = rng.uniform(lo.y(), hi.y());
    const double z = p0.z() - (n_W.x() * (x - p0.x()) + n_W.y() * (y - p0.y())) / n_W.z();
    landmarks_.push_back({Vec3(x, y, z), n_W});
  }
}

bool OracleFeatureSource::visible(const Landmark& l, const Pose& T_W_C, Vec2* pixel) const {
  // Cheap tests first: range, facing the camera, field of view (with the border), image.
  const Vec3 cam = T_W_C.translation();
  const Vec3 d = l.p_W - cam;
  const double dist2 = d.squaredNorm();
  if (dist2 > config_.max_range_m * config_.max_range_m || dist2 < 1e-4) return false;
  if (l.normal_W.dot(d) >= 0) return false;
  const Vec3 p_C = T_W_C.linear().transpose() * d;
  const double theta = std::atan2(p_C.head<2>().norm(), p_C.z());
  if (theta > camera_.halfFovRad() - config_.border_px / camera_.fx()) return false;
  const Vec2 px = camera_.project(p_C);
  const double b = config_.border_px;
  if (px.x() < b || px.y() < b || px.x() > camera_.width() - 1 - b || px.y() > camera_.height() - 1 - b) return false;
  // Occlusion: nothing of the world between the camera and the landmark.
  const double dist = std::sqrt(dist2);
  if (truth_.raycast(cam, d / dist, dist - 0.05)) return false;
  *pixel = px;
  return true;
}

TrackFrame OracleFeatureSource::process(const CameraFrame& frame) {
  TrackFrame out;
  out.tick = frame.tick;
  out.t_s = frame.t_s;
  const Pose& T_W_C = frame.T_W_C;
  const int max_tracks = config_.max_tracks;
  // Accepted pixels on a grid of min_distance_px cells, for the spacing of new features.
  const double cell = std::max(1.0, config_.min_distance_px);
  const int gw = int(std::ceil(camera_.width() / cell)) + 1, gh = int(std::ceil(camera_.height() / cell)) + 1;
  std::vector<std::vector<Vec2>> grid(size_t(gw) * size_t(gh));
  auto cellOf = [&](const Vec2& px) { return std::pair<int, int>(int(px.x() / cell), int(px.y() / cell)); };
  auto isolated = [&](const Vec2& px) {
    const auto [cx, cy] = cellOf(px);
    for (int y = std::max(0, cy - 1); y <= std::min(gh - 1, cy + 1); ++y)
      for (int x = std::max(0, cx - 1); x <= std::min(gw - 1, cx + 1); ++x)
        for (const Vec2& q : grid[size_t(y) * gw + x])
          if ((q - px).norm() < config_.min_distance_px) return false;
    return true;
  };
  auto accept = [&](size_t li, const Vec2& px) {
    const auto [cx, cy] = cellOf(px);
    grid[size_t(cy) * gw + cx].push_back(px);
    const Vec2 noisy = px + config_.pixel_noise_px * Vec2(noise_.normal(), noise_.normal());
    out.tracks.push_back({track_of_[li], noisy, age_[li]});
  };

  // 1. Continue the tracks of the previous frame while their landmark stays visible.
  std::vector<size_t> now;
  now.reserve(size_t(max_tracks));
  for (size_t li : tracked_) {
    Vec2 px;
    if (int(now.size()) < max_tracks && visible(landmarks_[li], T_W_C, &px)) {
      ++age_[li];
      now.push_back(li);
      accept(li, px);
    } else {
      track_of_[li] = 0;
      ++out.lost_tracks;
    }
  }
  // 2. New tracks from the visible landmarks, spaced like detections (bounded ray casts).
  int casts = 0;
  const int max_casts = 4 * max_tracks;
  for (size_t li = 0; li < landmarks_.size() && int(now.size()) < max_tracks && casts < max_casts; ++li) {
    if (track_of_[li]) continue;
    const Landmark& l = landmarks_[li];
    const Vec3 d = l.p_W - T_W_C.translation();
    if (d.squaredNorm() > config_.max_range_m * config_.max_range_m || l.normal_W.dot(d) >= 0) continue;
    const Vec3 p_C = T_W_C.linear().transpose() * d;
    if (p_C.z() <= -1e-9 && camera_.halfFovRad() <= M_PI / 2) continue;
    if (!camera_.inFieldOfView(p_C) || !isolated(camera_.project(p_C))) continue;
    ++casts;
    Vec2 px;
    if (!visible(l, T_W_C, &px)) continue;
    track_of_[li] = next_id_++;
    age_[li] = 0;
    now.push_back(li);
    accept(li, px);
    ++out.new_tracks;
  }
  tracked_ = std::move(now);
  return out;
}

}  // namespace msb
