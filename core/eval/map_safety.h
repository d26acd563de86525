// Map safety against ground truth: is the free space a mapper creates really free? Every
// sphere created or grown is mapped from the estimate to the true frame of that moment and
// checked against the world's geometry: it is *unsafe* when it reaches more than
// `max_intrusion_m` into a real obstacle; its volume actually inside obstacles is estimated by
// Monte Carlo sampling. Statistics are kept by the kind of the nearest obstacle (textured,
// textureless, thin, ground) and by object.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/common/rng.h"
#include "core/geometry/world_truth.h"

namespace msb {

/// Accumulated map-safety statistics.
struct MapSafetyStats {
  long events = 0, unsafe = 0;           ///< spheres checked, unsafe ones
  double volume = 0, unsafe_volume = 0;  ///< m³
  std::map<std::string, long> unsafe_by_kind;
  std::map<std::string, double> unsafe_volume_by_kind;
  std::map<std::string, long> unsafe_by_object;
  std::vector<double> intrusion_m;               ///< how deep unsafe spheres reach
  std::map<std::string, double> volume_by_kind;  ///< by the kind nearest the centre
  std::map<std::string, double> occupied_volume_by_kind;
  double occupied_volume = 0;  ///< Monte Carlo estimate, m³
};

/// Checks spheres against a world's ground truth.
class MapSafetyCheck {
 public:
  /// `seed` seeds the Monte Carlo stream `map_safety_samples` (results depend on the map only).
  explicit MapSafetyCheck(const WorldTruth& truth, uint64_t seed = 0, double max_intrusion_m = 0.3,
                          int samples_per_sphere = 128);
  /// Checks one sphere (estimate frame) given the estimate → truth correction of the moment.
  void checkSphere(const Vec3& centre_est, double radius_m, const Pose& T_true_est);
  /// The statistics so far.
  const MapSafetyStats& stats() const { return stats_; }
  /// The rule in words (for reports).
  std::string rule() const;

 private:
  const WorldTruth& truth_;
  RngStream samples_;
  double max_intrusion_m_;
  int samples_per_sphere_;
  MapSafetyStats stats_;
};

}  // namespace msb
