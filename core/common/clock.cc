#include "core/common/clock.h"

#include <cmath>
#include <stdexcept>

#include "core/common/types.h"

namespace msb {

double wrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

TickClock::TickClock(int physics_hz) : physics_hz_(physics_hz) {
  if (physics_hz <= 0) throw std::invalid_argument("physics rate must be > 0 Hz");
}

int64_t TickClock::ticksFor(double seconds) const { return static_cast<int64_t>(std::llround(seconds * physics_hz_)); }

int64_t TickClock::divisorFor(double rate_hz, const std::string& stage) const {
  if (!(rate_hz > 0.0) || rate_hz > physics_hz_)
    throw std::invalid_argument(stage + ": rate " + std::to_string(rate_hz) + " Hz must be in (0, " +
                                std::to_string(physics_hz_) + "] Hz");
  const double d = physics_hz_ / rate_hz;
  const auto n = static_cast<int64_t>(std::llround(d));
  if (std::abs(d - static_cast<double>(n)) > 1e-9)
    throw std::invalid_argument(stage + ": rate " + std::to_string(rate_hz) + " Hz does not divide the physics rate " +
                                std::to_string(physics_hz_) + " Hz");
  return n;
}

RateSchedule::RateSchedule(int physics_hz, double rate_hz, const std::string& stage)
    : physics_mhz_(int64_t{physics_hz} * 1000), rate_mhz_(std::llround(rate_hz * 1000.0)) {
  if (rate_mhz_ <= 0 || rate_mhz_ > physics_mhz_)
    throw std::invalid_argument(stage + ": rate " + std::to_string(rate_hz) + " Hz must be in (0, " +
                                std::to_string(physics_hz) + "] Hz");
}

bool RateSchedule::due(int64_t tick) const {
  // Fires when floor(tick · rate / physics) steps up: the first tick at or after k·period.
  if (tick == 0) return true;
  return (tick * rate_mhz_) / physics_mhz_ != ((tick - 1) * rate_mhz_) / physics_mhz_;
}

}  // namespace msb
