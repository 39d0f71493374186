// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Seeded normal draws that give the same bytes on every platform: std::mt19937_64 is fully
// specified by the standard, std::normal_distribution is not (its algorithm is the library's),
// so the uniform comes from raw 53-bit draws (as runner/src/simulation.cc InitialPositions) and
// the normal from our own Box-Muller transform.
#ifndef MJFORMATION_REALISM_GAUSSIAN_HPP_
#define MJFORMATION_REALISM_GAUSSIAN_HPP_

#include <cmath>
#include <cstdint>
#include <random>

namespace mjf::realism {

// A seed for stream `stream` of vehicle `vehicle` from the run's seed: SplitMix64 finaliser of a
// mix, so neighbouring seeds and vehicles give unrelated mt19937_64 states.
inline uint64_t StreamSeed(uint64_t run_seed, uint64_t vehicle, uint64_t stream) {
  uint64_t z = run_seed + 0x9E3779B97F4A7C15ull * (vehicle + 1) + 0xD1B54A32D192ED03ull * stream;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Standard normal N(0, 1) draws.
class Gaussian {
 public:
  explicit Gaussian(uint64_t seed) : rng_(seed) {}

  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    // u1 in (0, 1] so log(u1) is finite; u2 in [0, 1).
    const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 2.0 * M_PI * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }

 private:
  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_GAUSSIAN_HPP_
