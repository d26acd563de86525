// What the loop records of a run, as typed values: the trajectory rows (and their determinism
// hash) and the run's status. The words written to metrics.json ("completed", "collided",
// "vio_lost", "diverged", and "error" for a run that threw) are made and read here only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/common/types.h"

namespace msb {

/// One row of trajectory.csv: ground truth, the VIO estimate and the reference.
struct TrajectoryRow {
  double t_s;
  Vec3 position_m;      ///< ground truth
  Quat orientation;     ///< ground truth
  Vec3 velocity_mps;    ///< ground truth
  Vec3 est_position_m;  ///< VIO estimate
  double est_yaw_rad;   ///< VIO estimate
  Vec3 ref_position_m;  ///< trajectory reference (estimate frame)
  double ref_yaw_rad;
  /// VIO estimate: the full orientation (est_yaw_rad is its yaw). Not in hashTrajectory, which
  /// predates it: it is a function of the same estimate the hash covers.
  Quat est_orientation = Quat::Identity();
};

/// Hash of trajectory rows (time, estimate, true pose and velocity).
uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows);

/// How a run ended.
enum class RunStatus {
  kCompleted,            ///< ran its duration
  kCollided,             ///< a real contact ended it
  kVioLost,              ///< the VIO lost track
  kDiverged,             ///< the vehicle left the world or its state became invalid
  kError,                ///< an exception ended it (the message is in metrics.json)
  kMethodTimeout,        ///< a method in its own process did not answer a call within its budget
  kMethodExited,         ///< a method's own process ended (exit, signal, a limit) during the run
  kMethodProtocolError,  ///< a method's own process sent a message msbench does not answer
};

/// True for the statuses of a run that ended in an error (its record is not a result).
bool isErrorStatus(RunStatus s);

/// The word of a status in metrics.json and on the console.
const char* runStatusName(RunStatus s);

/// The status of a word, nullopt for an unknown one.
std::optional<RunStatus> parseRunStatus(const std::string& word);

}  // namespace msb
