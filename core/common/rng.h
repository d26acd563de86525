// Named random streams. Every noise source owns one stream, seeded from the scenario seed and
// the stream's name, so adding a source never shifts another's numbers. Uniform and normal
// transforms are our own: standard-library distributions differ between implementations.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

#include "core/common/types.h"

namespace msb {

/// 64-bit FNV-1a hash of a byte range, continuing from `h`.
uint64_t fnv1a64(const void* data, size_t size, uint64_t h = 0xcbf29ce484222325ULL);

/// One deterministic random stream (std::mt19937_64 with portable transforms).
class RngStream {
 public:
  /// Seeds from (scenario seed, stream name) through a hash mix.
  RngStream(uint64_t scenario_seed, std::string_view name);

  /// 64 raw random bits (the engine's next output).
  uint64_t bits() { return engine_(); }
  /// Uniform double in [0, 1) with 53 random bits.
  double uniform();
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n) (n > 0), unbiased by rejection.
  uint64_t uniformInt(uint64_t n);
  /// Standard normal (Marsaglia polar method; the spare value is cached).
  double normal();
  /// Normal with the given mean and standard deviation.
  double normal(double mean, double stddev) { return mean + stddev * normal(); }
  /// Vector of three independent standard normals.
  Vec3 normal3() { return {normal(), normal(), normal()}; }
  /// The seed actually used for the engine (for logs).
  uint64_t engineSeed() const { return engine_seed_; }

 private:
  uint64_t engine_seed_;
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace msb
