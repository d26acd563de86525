// The simulation clock: an integer tick count (one tick = one physics step). Every periodic
// stage runs at an integer divisor of the physics rate, so schedules are exact and deterministic.
#pragma once

#include <cstdint>
#include <string>

namespace msb {

/// Integer tick clock. Time in seconds is derived, never accumulated from floats.
class TickClock {
 public:
  /// `physics_hz` must be a positive integer rate (default 500 Hz, 2 ms ticks).
  explicit TickClock(int physics_hz = 500);

  /// Physics rate in Hz.
  int physicsHz() const { return physics_hz_; }
  /// Duration of one tick in seconds.
  double tickSeconds() const { return 1.0 / physics_hz_; }
  /// Current tick.
  int64_t tick() const { return tick_; }
  /// Current simulated time in seconds (tick / rate).
  double seconds() const { return static_cast<double>(tick_) / physics_hz_; }
  /// Advances by one tick.
  void advance() { ++tick_; }
  /// Number of ticks covering `seconds` (rounded to the nearest tick).
  int64_t ticksFor(double seconds) const;
  /// Tick divisor for a stage running at `rate_hz`; throws std::invalid_argument naming
  /// `stage` if the rate does not divide the physics rate exactly.
  int64_t divisorFor(double rate_hz, const std::string& stage) const;
  /// True if a stage with the given divisor runs on the current tick.
  bool due(int64_t divisor) const { return tick_ % divisor == 0; }

 private:
  int physics_hz_;
  int64_t tick_ = 0;
};

/// Schedule of a stage whose rate need not divide the physics rate (e.g. a 200 Hz IMU on
/// 500 Hz physics): it fires on the first tick at or after each multiple of its period, using
/// exact integer arithmetic (rates are resolved to 1 mHz). Over any second it fires exactly
/// `rate` times; the spacing alternates between neighbouring tick counts.
class RateSchedule {
 public:
  /// `rate_hz` must be in (0, physics_hz]; throws std::invalid_argument naming `stage` if not.
  RateSchedule(int physics_hz, double rate_hz, const std::string& stage);
  /// True if the stage fires on `tick`.
  bool due(int64_t tick) const;

 private:
  int64_t physics_mhz_;
  int64_t rate_mhz_;
};

}  // namespace msb
