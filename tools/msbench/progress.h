// Progress of a long command on standard error (never part of the results).
#pragma once

#include <string>

#include "core/common/wall_time.h"
#include "tools/engine/closed_loop.h"

namespace msb {

/// A progress line for long flights on stderr every 10 simulated seconds with the real-time
/// factor and an ETA (never part of the results).
class ProgressLine {
 public:
  /// `command` prefixes the line; `duration_s` is the run's limit.
  ProgressLine(std::string command, double duration_s);
  /// Call after every tick; prints when a tick completes a tenth simulated second.
  void update(const TickRecord& tick, int physics_hz);

 private:
  std::string command_;
  double duration_s_;
  WallClock::time_point start_;
};

}  // namespace msb
