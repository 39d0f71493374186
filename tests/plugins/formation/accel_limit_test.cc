// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The input-constrained reaching law of the discrete protocol (accel_limit, (C0)-(C8) of
// docs/DISCUSSION.md): law (48) bit for bit where its demand is feasible, a demand inside the
// disc always, refused bounds, and on the ideal model (40) with the bound as the vehicle's
// limit: Theorem 2's band Delta from the last constrained sample on (Proposition C2), reaching
// within the bound (C10) of the transient.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/shape.hpp>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "test_util.hpp"

namespace mjf::formation {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Swarm {  // one evaluation's input, with its buffers
  std::vector<double> leader, followers, now, next;
  explicit Swarm(int n) : leader(4), followers(4 * n), now(6 * n), next(6 * n) {}
  FormationInput Input() const {
    return {leader.data(), followers.data(), now.data(), next.data()};
  }
};

// A random swarm state about the paper's circle: followers within `spread` m (and m/s) of
// their slots.
Swarm RandomSwarm(int n, double T, double spread, std::mt19937* rng) {
  Swarm w(n);
  std::uniform_real_distribution<double> u(-1.0, 1.0), time(0.0, 40.0);
  const auto shape = MakeCircleShape(n, 10.0, 0.314, 0.0, 2 * kPi / n);
  const double t = time(*rng);
  shape->Evaluate(t, w.now.data());
  shape->Evaluate(t + T, w.next.data());
  for (int c = 0; c < 4; ++c) w.leader[c] = 20.0 * u(*rng);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 4; ++c) {
      w.followers[4 * i + c] = w.leader[c] + w.now[6 * i + c] + spread * u(*rng);
    }
  }
  return w;
}

double Norm(const std::vector<double>& u, int i) { return std::hypot(u[2 * i], u[2 * i + 1]); }

TEST(AccelLimitTest, EqualsThePapersLawBitForBitWhereFeasible) {
  std::mt19937 rng(11);
  int whole = 0, partial = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double T = trial % 2 ? 0.05 : 0.2;
    const Graph g = trial % 3 ? testing::PaperGraph() : testing::RandomGraph(9, 12, true, &rng);
    const int n = g.num_followers();
    DiscreteSmcParams p;
    p.period = T;
    DiscreteSmc paper(g, p);
    const Swarm w = RandomSwarm(n, T, trial % 4 == 0 ? 3.0 : 0.05, &rng);
    paper.Update(w.Input());
    std::vector<double> norms(n);
    for (int i = 0; i < n; ++i) norms[i] = Norm(paper.acceleration(), i);
    // A bound just above the largest demand (all feasible) or between two of them (some).
    std::vector<double> sorted = norms;
    std::sort(sorted.begin(), sorted.end());
    const bool all = trial % 2 == 0;
    p.accel_limit =
        all ? sorted.back() * (1 + 1e-12) + 1e-300 : 0.5 * (sorted[n / 2] + sorted[n - 1]);
    if (!(p.accel_limit > std::sqrt(2.0))) continue;  // (C0) refuses it
    DiscreteSmc constrained(g, p);
    constrained.Update(w.Input());
    for (int i = 0; i < n; ++i) {
      if (norms[i] > p.accel_limit) continue;
      for (int a = 0; a < 2; ++a) {
        ASSERT_EQ(constrained.acceleration()[2 * i + a], paper.acceleration()[2 * i + a])
            << "trial " << trial << " follower " << i;
      }
    }
    for (int k = 0; k < 2 * n; ++k) ASSERT_EQ(constrained.sliding()[k], paper.sliding()[k]);
    (all ? whole : partial) += 1;
  }
  EXPECT_GT(whole, 100);
  EXPECT_GT(partial, 50);  // followers whose demand is feasible keep it while others do not
}

TEST(AccelLimitTest, DemandNeverExceedsTheBound) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> bound(1.5, 12.0);
  long constrained_followers = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double T = trial % 2 ? 0.05 : 0.2;
    const Graph g = trial % 3 ? testing::PaperGraph() : testing::RandomGraph(9, 12, false, &rng);
    DiscreteSmcParams p;
    p.period = T;
    p.accel_limit = bound(rng);
    if (trial % 5 == 0) p.reach_accel = 0.5 * p.accel_limit;
    DiscreteSmc smc(g, p);
    const Swarm w = RandomSwarm(g.num_followers(), T, trial % 4 ? 60.0 : 1.0, &rng);
    smc.Update(w.Input());
    for (int i = 0; i < g.num_followers(); ++i) {
      ASSERT_LE(Norm(smc.acceleration(), i), p.accel_limit * (1 + 1e-12)) << "trial " << trial;
      ASSERT_TRUE(std::isfinite(smc.acceleration()[2 * i]));
    }
    constrained_followers += smc.constraint_stats().constrained;
  }
  EXPECT_GT(constrained_followers, 1000);  // the bound was active, not vacuous
}

TEST(AccelLimitTest, RefusesBadBounds) {
  DiscreteSmcParams p;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double bad : {0.0, -3.0, nan, -std::numeric_limits<double>::infinity(), 1.0, 1.41}) {
    p.accel_limit = bad;  // 1.0, 1.41: not above the leader's sqrt(2) max(|u_min|, |u_max|)
    try {
      p.Validate();
      ADD_FAILURE() << "accepted accel_limit = " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("accel_limit"), std::string::npos) << e.what();
    }
  }
  p.accel_limit = 1.42;
  EXPECT_NO_THROW(p.Validate());
  p.u_max = 2.0;  // the leader may now reach 2 sqrt(2) m/s^2
  EXPECT_THROW(p.Validate(), std::invalid_argument);
  p.accel_limit = std::numeric_limits<double>::infinity();  // "none"
  EXPECT_NO_THROW(p.Validate());
  p.reach_accel = -1.0;
  EXPECT_THROW(p.Validate(), std::invalid_argument);
}

// Model (40) with the demand as the input (a point mass whose limit is the bound), a random
// leader within Assumption 1 (a new input in [u_min, u_max]^2 each sample), followers at rest
// far from their slots. Returns false (with a message) on a violation.
struct BandResult {
  int last_constrained = -1, entered = -1;
  double max_ratio = 0.0, reach_time_bound = 0.0;
};

BandResult RunIdeal(double T, double bound, unsigned seed) {
  const Graph g = testing::PaperGraph();
  const int n = g.num_followers();
  DiscreteSmcParams p;
  p.period = T;
  p.accel_limit = bound;
  DiscreteSmc smc(g, p);
  const auto shape = MakeCircleShape(n, 10.0, 0.314, 0.0, kPi / 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> start(-20.0, 20.0), leader_input(p.u_min, p.u_max);
  Swarm w(n);
  w.leader = {20.0, 0.0, 0.0, 3.14};
  for (int i = 0; i < n; ++i) {
    w.followers[4 * i] = start(rng);
    w.followers[4 * i + 1] = start(rng);
  }
  BandResult r;
  const int steps = static_cast<int>(std::lround(60.0 / T));
  std::vector<std::vector<double>> sliding(steps);
  for (int k = 0; k < steps; ++k) {
    shape->Evaluate(k * T, w.now.data());
    shape->Evaluate((k + 1) * T, w.next.data());
    const long before = smc.constraint_stats().constrained;
    smc.Update(w.Input());
    if (smc.constraint_stats().constrained > before) r.last_constrained = k;
    sliding[k] = smc.sliding();
    for (int i = 0; i < n; ++i) EXPECT_LE(Norm(smc.acceleration(), i), bound * (1 + 1e-12));
    for (int a = 0; a < 2; ++a) {
      w.leader[a] += T * w.leader[2 + a];
      w.leader[2 + a] += T * leader_input(rng);
      for (int i = 0; i < n; ++i) {
        w.followers[4 * i + a] += T * w.followers[4 * i + 2 + a];
        w.followers[4 * i + 2 + a] += T * smc.acceleration()[2 * i + a];
      }
    }
  }
  // Proposition C2: from the last constrained sample on, (C7) is law (48) and Theorem 2 holds:
  // once every |s_i| <= Delta_i, it stays there.
  for (int k = r.last_constrained + 1; k < steps; ++k) {
    bool inside = true;
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < 2; ++a) {
        const double s = std::abs(sliding[k][2 * i + a]);
        inside = inside && s <= smc.delta(i) * (1 + 1e-9);
        if (r.entered >= 0) r.max_ratio = std::max(r.max_ratio, s / smc.delta(i));
      }
    }
    if (r.entered < 0 && inside) r.entered = k;
  }
  return r;
}

TEST(AccelLimitTest, BandHoldsOnTheIdealModelOverRandomLeaders) {
  // The bound must hold (48)'s demand inside the band (Proposition C2's premise): g tan 0.55
  // for T = 0.05; T = 0.2 switches harder (KB = 0.2) and needs g tan 0.78.
  for (const auto& [T, bound] : {std::pair{0.05, 6.0146}, std::pair{0.2, 9.7047}}) {
    int constrained_runs = 0, worst_last = 0, worst_entered = 0;
    for (unsigned seed = 0; seed < 100; ++seed) {
      const BandResult r = RunIdeal(T, bound, 100 + seed);
      ASSERT_GE(r.entered, 0) << "T = " << T << " seed " << seed << ": never in the band";
      ASSERT_LE(r.max_ratio, 1.0 + 1e-9) << "T = " << T << " seed " << seed << " left the band";
      constrained_runs += r.last_constrained >= 0;
      worst_last = std::max(worst_last, r.last_constrained);
      worst_entered = std::max(worst_entered, r.entered);
    }
    EXPECT_EQ(constrained_runs, 100);  // every run starts far beyond the bound
    std::printf(
        "[ info ] T = %.2f: last constrained sample at most %.2f s, every |s_i| in "
        "Delta by %.2f s (100 leaders)\n",
        T, worst_last * T, worst_entered * T);
  }
}

}  // namespace
}  // namespace mjf::formation
