// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Seeded normal draws that give the same bytes on every platform: std::mt19937_64 is fully
// specified by the standard, std::normal_distribution is not (its algorithm is the library's),
// so the uniform comes from raw 53-bit draws (as runner/sim/src/simulation.cc InitialPositions) and
// the normal from our own transform (Marsaglia's polar form of Box-Muller).
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

  // Marsaglia's polar method: a point uniform in the unit disc gives two independent normals
  // with one log and one square root (no sine or cosine: half the cost of Box-Muller).
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double x, y, r2;
    do {
      x = 2.0 * Uniform() - 1.0;
      y = 2.0 * Uniform() - 1.0;
      r2 = x * x + y * y;
    } while (r2 >= 1.0 || r2 == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(r2) / r2);
    spare_ = y * scale;
    has_spare_ = true;
    return x * scale;
  }

  // The engine and the spare normal, both ways (the runner's StateArchive, FixedStateArchive).
  template <typename Archive>
  void VisitState(Archive& a) {
    a(rng_, spare_, has_spare_);
  }

 private:
  // Uniform in [0, 1) from the raw 53 high bits of a draw.
  double Uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }

  std::mt19937_64 rng_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_GAUSSIAN_HPP_
