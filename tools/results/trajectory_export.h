// A run's trajectory in the formats estimator tools read: TUM (`timestamp tx ty tz qx qy qz qw`,
// space-separated, seconds and metres; evo's `evo_ape tum truth.tum estimate.tum`), made from the
// run's trajectory.csv with each number copied as written there (docs/interop.md).
#pragma once

#include <optional>
#include <string>

#include "core/common/types.h"

namespace msb {

/// The TUM files of one trajectory.csv.
struct TumTrajectories {
  std::string truth;     ///< the true body pose in the world frame (ROS `map`)
  std::string estimate;  ///< the VIO's body pose in its own drifting frame (ROS `odom`); "" if the file has no est_q*
  int rows = 0;          ///< poses in each
  /// The estimate → truth correction at the last row (T_true_est = T_W_B · T_V_B⁻¹: ROS's
  /// map → odom at the end of the run); none without the VIO's full orientation.
  std::optional<Pose> T_true_est_final;
};

/// The TUM texts of `csv`, a trajectory.csv (`where` names it in errors). A file written before
/// the VIO's full orientation was recorded (no est_qw..est_qz columns) gives the truth only.
/// Throws InputFileError (exit 2) naming the file and line for a header msbench does not write,
/// a row with the wrong number of cells or a cell that is not a finite number.
TumTrajectories tumFromTrajectoryCsv(const std::string& csv, const std::string& where);

}  // namespace msb
