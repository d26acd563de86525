#include "tools/msbench/progress.h"

#include <algorithm>
#include <cstdio>

namespace msb {

ProgressLine::ProgressLine(std::string command, double duration_s)
    : command_(std::move(command)), duration_s_(duration_s), start_(WallClock::now()) {}

void ProgressLine::update(const TickRecord& tick, int physics_hz) {
  if (!tick.completed || tick.tick == 0 || tick.tick % (10 * int64_t(physics_hz)) != 0) return;
  const double sim_s = double(tick.tick) / physics_hz;
  const double rtf = sim_s / std::max(secondsSince(start_), 1e-9);
  std::fprintf(stderr, "%s: t = %.0f / %.0f s simulated, real-time factor %.1f, ETA %.0f s\n", command_.c_str(), sim_s,
               duration_s_, rtf, (duration_s_ - sim_s) / rtf);
}

}  // namespace msb
