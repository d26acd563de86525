// The MRS trajectory generator's cost per planning step (issue 91): paths shaped as published
// MonoSpheres sends them (the vehicle, then 3–12 sphere centres 1.5–4 m apart with turns of up to
// 90°, 15 m at most), from rest and in motion, under `fast` and `medium`. Prints wall time per
// generation (median, 90th percentile, max), the trajectory's duration, splits and fallbacks.
// Build and run from the repository root:
//   g++ -O2 -std=c++20 -I. -I/usr/include/eigen3 results/mrs_generator/measure.cc \
//     sim/physics/mrs_trajectory_generator.cc sim/physics/polynomial_trajectory.cc \
//     core/common/config_check.cc core/common/config_fields.cc core/common/clock.cc -lnlopt \
//     -o /tmp/mrs_measure && /tmp/mrs_measure
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "sim/physics/mrs_trajectory_generator.h"

using namespace msb;

namespace {

// A random sphere-centre path from the origin: n points, each 1.5–4 m on, turning ≤ 90°.
std::vector<Waypoint> randomPath(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> step(1.5, 4.0), turn(-1.57, 1.57), climb(-0.3, 0.3);
  std::vector<Waypoint> w;
  Vec3 p(0, 0, 2);
  double dir = 0, len = 0;
  for (int i = 0; i < n && len < 15.0; ++i) {
    dir += turn(rng) * (i > 0);
    const double s = step(rng);
    p += Vec3(s * std::cos(dir), s * std::sin(dir), climb(rng));
    len += s;
    w.push_back({p, std::nullopt});
  }
  return w;
}

void measure(const char* set, bool moving) {
  MrsGeneratorConfig c;
  c.constraints = *MrsConstraints::preset(set);
  const MrsTrajectoryGenerator g(c);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> count(3, 12);
  std::vector<double> ms;
  double dur = 0, splits = 0;
  int fallbacks = 0;
  constexpr int kPaths = 300;
  for (int i = 0; i < kPaths; ++i) {
    MrsInitialState s;
    s.reference.position_m = Vec3(0, 0, 2);
    if (moving) s.reference.velocity_mps = Vec3(1.5, 0.5, 0), s.moving = true;
    const auto path = randomPath(rng, count(rng));
    const auto t0 = std::chrono::steady_clock::now();
    const MrsTrajectory t = g.generate(s, path);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    dur += double(t.samples.size() - 1) * t.dt_s;
    splits += t.deviation_splits;
    fallbacks += t.fallback;
  }
  std::sort(ms.begin(), ms.end());
  std::printf(
      "%-6s %-7s median %6.2f ms  p90 %6.2f ms  max %7.2f ms  trajectory %5.2f s  splits %.2f  fallbacks %d/%d\n", set,
      moving ? "moving" : "rest", ms[ms.size() / 2], ms[ms.size() * 9 / 10], ms.back(), dur / kPaths, splits / kPaths,
      fallbacks, kPaths);
}

}  // namespace

int main() {
  for (const char* set : {"fast", "medium"})
    for (bool moving : {false, true}) measure(set, moving);
}
