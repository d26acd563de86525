// Wall-clock stage timing. Wall time is recorded for reports only; it never influences a
// decision (docs/architecture.md §2), which is why it lives apart from the tick clock.
#pragma once

#include <chrono>

namespace msb {

/// Monotonic wall clock for stage timings.
using WallClock = std::chrono::steady_clock;

/// Milliseconds elapsed since t0.
inline double msSince(WallClock::time_point t0) {
  return std::chrono::duration<double, std::milli>(WallClock::now() - t0).count();
}

/// Seconds elapsed since t0.
inline double secondsSince(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

}  // namespace msb
