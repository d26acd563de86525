#include "tools/engine/records.h"

#include "core/common/rng.h"

namespace msb {

uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows) {
  uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& r : rows) {
    const double v[15] = {r.t_s,
                          r.est_position_m.x(),
                          r.est_position_m.y(),
                          r.est_position_m.z(),
                          r.est_yaw_rad,
                          r.position_m.x(),
                          r.position_m.y(),
                          r.position_m.z(),
                          r.orientation.w(),
                          r.orientation.x(),
                          r.orientation.y(),
                          r.orientation.z(),
                          r.velocity_mps.x(),
                          r.velocity_mps.y(),
                          r.velocity_mps.z()};
    h = fnv1a64(v, sizeof(v), h);
  }
  return h;
}

const char* runStatusName(RunStatus s) {
  switch (s) {
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kCollided:
      return "collided";
    case RunStatus::kVioLost:
      return "vio_lost";
    case RunStatus::kDiverged:
      return "diverged";
    case RunStatus::kError:
      return "error";
    case RunStatus::kMethodTimeout:
      return "method_timeout";
    case RunStatus::kMethodExited:
      return "method_exited";
    case RunStatus::kMethodProtocolError:
      return "method_protocol_error";
  }
  return "?";
}

bool isErrorStatus(RunStatus s) {
  return s == RunStatus::kError || s == RunStatus::kMethodTimeout || s == RunStatus::kMethodExited ||
         s == RunStatus::kMethodProtocolError;
}

std::optional<RunStatus> parseRunStatus(const std::string& word) {
  for (RunStatus s :
       {RunStatus::kCompleted, RunStatus::kCollided, RunStatus::kVioLost, RunStatus::kDiverged, RunStatus::kError,
        RunStatus::kMethodTimeout, RunStatus::kMethodExited, RunStatus::kMethodProtocolError})
    if (word == runStatusName(s)) return s;
  return std::nullopt;
}

}  // namespace msb
