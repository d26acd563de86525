// One sample of a mission's coverage record (a row of coverage.csv), and the longest stretch of
// a record without coverage gain (a stalled explorer shows as a long one).
#pragma once

#include <vector>

namespace msb {

/// Explored area at one moment of a mission.
struct CoverageSample {
  double t_s = 0;
  double area_m2 = 0;           ///< unbounded, VIO frame (as the paper)
  double area_box_m2 = 0;       ///< columns whose node lies in the exploration box
  double area_gt_m2 = 0;        ///< unbounded, free space mapped to the true frame when first seen
  double area_verified_m2 = 0;  ///< verified columns (seen, covered, truly free; docs/metrics.md)
  double score_earned_m3 = 0;   ///< the earned score before any collision forfeit (docs/metrics.md)
  double distance_m = 0;        ///< flown so far (ground truth)
  double box_share = 0;         ///< explored explorable columns of the box / explorable (0 if unknown)
};

/// A stretch of a mission without coverage gain: A (area_m2) did not grow from start_s to end_s.
struct NoGainInterval {
  double start_s = 0, end_s = 0;
  /// Its length in simulated seconds.
  double lengthS() const { return end_s - start_s; }
};

/// The longest stretch of the record over which area_m2 did not grow (ties: the earliest);
/// a stretch still open at the last sample ends there.
inline NoGainInterval longestIntervalWithoutGain(const std::vector<CoverageSample>& samples) {
  NoGainInterval best, current;
  if (samples.empty()) return best;
  current.start_s = current.end_s = samples.front().t_s;
  double last_area = samples.front().area_m2;
  for (const CoverageSample& s : samples) {
    if (s.area_m2 > last_area) {
      current.start_s = s.t_s;  // a gain: a new stretch starts here
      last_area = s.area_m2;
    }
    current.end_s = s.t_s;
    if (current.lengthS() > best.lengthS()) best = current;
  }
  return best;
}

}  // namespace msb
