// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Closed loops on the ideal models: the discrete protocol on the exact discrete model (40)
// (Theorem 2's quasi-sliding band), the continuous protocol on the double integrator with a
// fine zero-order hold (Theorem 1, and the flaw of its lower-bound compensation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/metrics.hpp>
#include <mjformation/formation/shape.hpp>
#include <random>
#include <stdexcept>
#include <vector>

#include "test_util.hpp"

namespace mjf::formation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's leader (section 6): circle of 20 m about the origin at 0.157 rad/s.
struct CircleLeader {
  double radius = 20.0, omega = 0.157;
  void State(double t, double* pv) const {
    pv[0] = radius * std::cos(omega * t);
    pv[1] = radius * std::sin(omega * t);
    pv[2] = -radius * omega * std::sin(omega * t);
    pv[3] = radius * omega * std::cos(omega * t);
  }
  double Input(double t, int axis) const {  // u_0, |u_0| <= r w^2 = 0.49 m/s^2
    return -radius * omega * omega * (axis == 0 ? std::cos(omega * t) : std::sin(omega * t));
  }
};

void DiscreteBandHolds(const Graph& g, double T, double u_min, double u_max, unsigned seed) {
  const int n = g.num_followers();
  DiscreteSmcParams p;
  p.period = T;
  p.u_min = u_min;
  p.u_max = u_max;
  DiscreteSmc smc(g, p);
  const auto shape = MakeCircleShape(n, 10.0, 0.314, 0.0, 2 * kPi / n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> start(-20.0, 20.0), leader_input(u_min, u_max);
  std::vector<double> leader = {20.0, 0.0, 0.0, 3.14};
  std::vector<double> followers(4 * n, 0.0), now(6 * n), next(6 * n);
  for (int i = 0; i < n; ++i) {
    followers[4 * i] = start(rng);
    followers[4 * i + 1] = start(rng);
  }
  std::vector<int> reached_at(2 * n, -1);
  const int steps = 3000;
  double max_after = 0.0, sigma_max_late = 0.0;
  for (int k = 0; k < steps; ++k) {
    shape->Evaluate(k * T, now.data());
    shape->Evaluate((k + 1) * T, next.data());
    smc.Update({leader.data(), followers.data(), now.data(), next.data()});
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < 2; ++a) {
        const double s = std::abs(smc.sliding()[2 * i + a]);
        const double band = smc.delta(i) + 1e-9 * (1 + std::abs(leader[0]) + std::abs(leader[2]));
        int& reached = reached_at[2 * i + a];
        if (reached < 0 && s <= band) reached = k;
        if (reached >= 0) {
          ASSERT_LE(s, band) << "follower " << i + 1 << " axis " << a << " left the band "
                             << smc.delta(i) << " at step " << k << " (entered at " << reached
                             << "), T = " << T;
          max_after = std::max(max_after, s / smc.delta(i));
        }
      }
    }
    if (k > steps / 2) {
      sigma_max_late =
          std::max(sigma_max_late, FormationError(n, followers.data(), leader.data(), now.data()));
    }
    // Exact model (40) for everyone; the leader's input is random in [u_min, u_max].
    for (int a = 0; a < 2; ++a) {
      leader[a] += T * leader[2 + a];
      leader[2 + a] += T * leader_input(rng);
      for (int i = 0; i < n; ++i) {
        followers[4 * i + a] += T * followers[4 * i + 2 + a];
        followers[4 * i + 2 + a] += T * smc.acceleration()[2 * i + a];
      }
    }
  }
  for (int m = 0; m < 2 * n; ++m) {
    EXPECT_GE(reached_at[m], 0) << "follower " << m / 2 + 1 << " never reached the band, T = " << T;
    EXPECT_LT(reached_at[m], steps / 2);
  }
  // Our ultimate bound assumes f_ip(k+1) = f_ip(k) + T f_iv(k); the circle misses that by
  // delta_f <= T^2 r w^2 / 2 per step, which adds at most delta_f / (1 - |1 - a|) to |z_ip| and
  // k1 / k2 times that to |z_iv| (a = T k1 / k2).
  const double a = T * p.gains.k1 / p.gains.k2;
  const double shape_p = 0.5 * T * T * 10.0 * 0.314 * 0.314 / (1.0 - std::abs(1.0 - a));
  const double shape_term = std::sqrt(2.0 * n) * shape_p * std::hypot(1.0, p.gains.k1 / p.gains.k2);
  const double rederived = smc.ultimate_error_bound() + shape_term;
  EXPECT_LE(sigma_max_late, rederived) << "T = " << T;
  std::printf(
      "[ info ] n = %d T = %.2f: Delta = %.4g, max |s|/Delta_i after reaching = %.3f, "
      "max sigma_f (2nd half) = %.4g, bound (47) = %.4g, re-derived bound = %.4g\n",
      n, T, smc.delta(), max_after, sigma_max_late, smc.error_bound(), rederived);
}

TEST(DiscreteClosedLoopTest, StaysInQuasiSlidingBandPaperGraph) {
  for (double T : {0.01, 0.05, 0.2}) DiscreteBandHolds(testing::PaperGraph(), T, -1.0, 1.0, 1);
}

TEST(DiscreteClosedLoopTest, StaysInQuasiSlidingBandRandomGraphs) {
  std::mt19937 rng(5);
  for (double T : {0.01, 0.05, 0.2}) {
    DiscreteBandHolds(testing::RandomGraph(12, 20, true, &rng), T, -0.5, 1.5, 2);
    DiscreteBandHolds(testing::RandomGraph(12, 20, false, &rng), T, -1.0, 1.0, 3);
  }
}

// Theorem 2 keeps |s_i| <= Delta, but on model (40) s_i = 0 means e_ip(k+1) = (1 - T k1/k2)
// e_ip(k): with T k1 / k2 >= 2 (allowed by Algorithm 2) the formation diverges inside the band.
TEST(DiscreteClosedLoopTest, SurfaceUnstableWhenTk1OverK2AtLeastTwo) {
  DiscreteSmcParams p;
  p.period = 0.1;
  p.gains = {25.0, 1.0};  // T k1 / k2 = 2.5; Theorem 2's conditions hold (1 - qT = 0.55)
  EXPECT_THROW(DiscreteSmc(testing::PaperGraph(), p), std::invalid_argument);
  p.require_stable_surface = false;
  DiscreteSmc smc(testing::PaperGraph(), p);
  EXPECT_EQ(smc.ultimate_error_bound(), std::numeric_limits<double>::infinity());
  const auto shape = MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);
  std::vector<double> leader = {20.0, 0.0, 0.0, 3.14}, followers(24, 0.0), now(36), next(36);
  for (int i = 0; i < 6; ++i) followers[4 * i] = 2.0 * i - 6.0;
  double sigma = 0.0;
  bool all_in_band_at_step_30 = false;
  for (int k = 0; k < 60; ++k) {
    shape->Evaluate(k * p.period, now.data());
    shape->Evaluate((k + 1) * p.period, next.data());
    smc.Update({leader.data(), followers.data(), now.data(), next.data()});
    if (k == 30) {
      all_in_band_at_step_30 = true;
      for (int i = 0; i < 6; ++i) {
        for (int a = 0; a < 2; ++a) {
          all_in_band_at_step_30 &= std::abs(smc.sliding()[2 * i + a]) <= smc.delta(i) + 1e-6;
        }
      }
    }
    sigma = FormationError(6, followers.data(), leader.data(), now.data());
    for (int a = 0; a < 2; ++a) {
      leader[a] += p.period * leader[2 + a];
      for (int i = 0; i < 6; ++i) {
        followers[4 * i + a] += p.period * followers[4 * i + 2 + a];
        followers[4 * i + 2 + a] += p.period * smc.acceleration()[2 * i + a];
      }
    }
  }
  EXPECT_TRUE(all_in_band_at_step_30);
  EXPECT_GT(sigma, 1e6);
}

struct ContinuousRun {
  std::vector<std::vector<double>> sliding;  // per step, [2n]
  std::vector<double> sigma;                 // eq. (68) per step
  std::vector<double> follower1_slot_error;  // m, per step
};

// Double integrator, control held over h (exact integration), leader on the paper's circle.
ContinuousRun RunContinuous(const Graph& g, const ContinuousSmcParams& p, double duration, double h,
                            double offset, unsigned seed) {
  const int n = g.num_followers();
  ContinuousSmc smc(g, p);
  const auto shape = MakeCircleShape(n, 10.0, 0.314, 0.0, kPi / 3);
  const CircleLeader leader_path;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-offset, offset);
  std::vector<double> leader(4), followers(4 * n), f(6 * n);
  leader_path.State(0.0, leader.data());
  shape->Evaluate(0.0, f.data());
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 4; ++c) followers[4 * i + c] = leader[c] + f[6 * i + c] + jitter(rng);
  }
  ContinuousRun run;
  const int steps = static_cast<int>(std::lround(duration / h));
  for (int k = 0; k <= steps; ++k) {
    const double t = k * h;
    leader_path.State(t, leader.data());
    shape->Evaluate(t, f.data());
    smc.Update({leader.data(), followers.data(), f.data(), nullptr});
    run.sliding.push_back(smc.sliding());
    run.sigma.push_back(FormationError(n, followers.data(), leader.data(), f.data()));
    run.follower1_slot_error.push_back(
        std::hypot(followers[0] - leader[0] - f[0], followers[1] - leader[1] - f[1]));
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < 2; ++a) {
        const double u = smc.acceleration()[2 * i + a];
        followers[4 * i + a] += h * followers[4 * i + 2 + a] + 0.5 * h * h * u;
        followers[4 * i + 2 + a] += h * u;
      }
    }
  }
  return run;
}

// EQUATIONS.md: with u_min alone (30 as printed) s_1' = -rho sgn(s_1) - k2 (u_0 - u_min) <= -0.45
// whatever the sign of s_1 (|u_0| <= 0.49 < -u_min - rho), so s_1 runs off to -infinity and the
// formation with it. Theorem 1's step (38)-(39) multiplies s_i' <= -rho sgn(s_i) by s_i < 0.
TEST(ContinuousClosedLoopTest, LowerBoundCompensationDriftsWithoutBound) {
  ContinuousSmcParams p;  // the paper's printed form and values: k = [3 1], rho 0.05, u_min -1
  const double h = 1e-3;
  const ContinuousRun run = RunContinuous(testing::PaperGraph(), p, 40.0, h, 0.0, 1);
  const double k_min_rate = 1.0 * (1.0 - 20.0 * 0.157 * 0.157) - p.rho;  // k2 (u0 - u_min) - rho
  ASSERT_GT(k_min_rate, 0.45);
  for (int k = 1000; k < static_cast<int>(run.sliding.size()); k += 1000) {
    const double t = k * h;
    for (int a = 0; a < 2; ++a) {
      EXPECT_LE(run.sliding[k][a], -k_min_rate * t + 1e-2) << "s_1 axis " << a << " at t = " << t;
    }
  }
  EXPECT_LT(run.sliding.back()[0], -18.0);
  EXPECT_GT(run.follower1_slot_error.back(), 5.0);
  EXPECT_GT(run.follower1_slot_error.back(), 1.5 * run.follower1_slot_error[20000]);
  EXPECT_GT(run.sigma.back(), 10.0);
  std::printf(
      "[ info ] lower_bound: s_1x(40) = %.3f, follower 1 slot error %.2f m, sigma_f(40) = %.2f\n",
      run.sliding.back()[0], run.follower1_slot_error.back(), run.sigma.back());
}

void CheckReaching(const ContinuousRun& run, const ContinuousSmcParams& p, double h, int n) {
  double worst_margin = -1e9, worst_band = 0.0;
  for (int m = 0; m < 2 * n; ++m) {
    const double s0 = run.sliding[0][m];
    const double bound = p.reaching == Reaching::kConstant
                             ? std::abs(s0) / p.rho
                             : std::log1p(p.q * std::abs(s0) / p.rho) / p.q;
    int crossed = -1;
    for (size_t k = 1; k < run.sliding.size(); ++k) {
      if (run.sliding[k][m] == 0.0 || (run.sliding[k][m] > 0) != (s0 > 0)) {
        crossed = static_cast<int>(k);
        break;
      }
    }
    ASSERT_GE(crossed, 0) << "s never reached 0, follower " << m / 2 + 1;
    EXPECT_LE(crossed * h, bound + 0.02) << "follower " << m / 2 + 1 << " axis " << m % 2;
    worst_margin = std::max(worst_margin, crossed * h - bound);
    for (size_t k = crossed; k < run.sliding.size(); ++k) {
      worst_band = std::max(worst_band, std::abs(run.sliding[k][m]));
    }
  }
  EXPECT_LE(worst_band, 5e-3);
  std::printf("[ info ] reaching time - bound (worst) = %.4f s, band after reaching = %.2e\n",
              worst_margin, worst_band);
}

TEST(ContinuousClosedLoopTest, SwitchingCompensationReachesWithinBound) {
  ContinuousSmcParams p;
  p.compensation = Compensation::kSwitching;
  const double h = 2e-4;  // zero-order hold: the reaching time is exact up to O(h t)
  const Graph g = testing::PaperGraph();
  const ContinuousRun run = RunContinuous(g, p, 30.0, h, 0.1, 2);
  double s0_max = 0.0;
  for (double s : run.sliding[0]) s0_max = std::max(s0_max, std::abs(s));
  ASSERT_LT(s0_max / p.rho, 28.0) << "initial offsets too large for the run length";
  CheckReaching(run, p, h, 6);
  EXPECT_LT(run.sigma.back(), 0.05);
}

TEST(ContinuousClosedLoopTest, ExponentialReachingReachesWithinBound) {
  ContinuousSmcParams p;
  p.compensation = Compensation::kSwitching;
  p.reaching = Reaching::kExponential;
  const double h = 2e-4;
  const ContinuousRun run = RunContinuous(testing::PaperGraph(), p, 10.0, h, 2.0, 3);
  CheckReaching(run, p, h, 6);
  EXPECT_LT(run.sigma.back(), 0.05);
}

}  // namespace
}  // namespace mjf::formation
