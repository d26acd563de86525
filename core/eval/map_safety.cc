#include "core/eval/map_safety.h"

#include <cmath>

namespace msb {

MapSafetyCheck::MapSafetyCheck(const WorldTruth& truth, uint64_t seed, double max_intrusion_m, int samples_per_sphere)
    : truth_(truth),
      samples_(seed, "map_safety_samples"),
      max_intrusion_m_(max_intrusion_m),
      samples_per_sphere_(samples_per_sphere) {}

std::string MapSafetyCheck::rule() const {
  char text[128];
  std::snprintf(text, sizeof(text), "sphere reaches > %g m into a real obstacle (centre mapped to the true frame)",
                max_intrusion_m_);
  return text;
}

void MapSafetyCheck::checkSphere(const Vec3& centre_est, double radius, const Pose& T_true_est) {
  const Vec3 centre = T_true_est * centre_est;
  const NearestObstacle n = truth_.nearest(centre, radius + 1.0);
  const double volume = 4.0 / 3.0 * M_PI * std::pow(radius, 3);
  ++stats_.events;
  stats_.volume += volume;
  // Volume inside obstacles: uniform samples in the ball (rejection from the cube).
  int occupied = 0;
  for (int k = 0; k < samples_per_sphere_; ++k) {
    Vec3 u;
    do u = Vec3(samples_.uniform(-1, 1), samples_.uniform(-1, 1), samples_.uniform(-1, 1));
    while (u.squaredNorm() > 1.0);
    occupied += truth_.inside(T_true_est * (centre_est + radius * u));
  }
  const double occupied_volume = volume * occupied / samples_per_sphere_;
  const std::string near_kind = n.shape >= 0 ? obstacleKindName(truth_.shapes()[n.shape].kind) : "none";
  stats_.volume_by_kind[near_kind] += volume;
  stats_.occupied_volume_by_kind[near_kind] += occupied_volume;
  stats_.occupied_volume += occupied_volume;
  // Unsafe: the sphere reaches too deep into the nearest obstacle.
  if (n.shape >= 0 && radius - n.distance_m > max_intrusion_m_) {
    const Shape& shape = truth_.shapes()[n.shape];
    const std::string kind = obstacleKindName(shape.kind);
    ++stats_.unsafe;
    stats_.unsafe_volume += volume;
    ++stats_.unsafe_by_kind[kind];
    ++stats_.unsafe_by_object[shape.object];
    stats_.intrusion_m.push_back(radius - n.distance_m);
    stats_.unsafe_volume_by_kind[kind] += volume;
  }
}

}  // namespace msb
