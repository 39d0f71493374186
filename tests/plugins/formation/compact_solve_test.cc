// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The compact forms (33) and (53), computed with one L_H solve, satisfy the per-agent protocols
// (30) and (48) as printed, and produce the closed loops (35) and (55).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/linear_consensus.hpp>
#include <random>
#include <vector>

#include "test_util.hpp"

namespace mjf::formation {
namespace {

struct Sample {
  std::vector<double> leader, followers, shape_now, shape_next;
  FormationInput Input() const {
    return FormationInput{leader.data(), followers.data(), shape_now.data(), shape_next.data()};
  }
};

Sample RandomSample(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-20.0, 20.0), w(-3.0, 3.0);
  Sample s;
  s.leader = {u(*rng), u(*rng), w(*rng), w(*rng)};
  for (int i = 0; i < n; ++i) {
    s.followers.insert(s.followers.end(), {u(*rng), u(*rng), w(*rng), w(*rng)});
    for (auto* f : {&s.shape_now, &s.shape_next}) {
      f->insert(f->end(), {u(*rng), u(*rng), w(*rng), w(*rng), w(*rng), w(*rng)});
    }
  }
  return s;
}

// Naive eq. (16)-(17) for follower i, axis a.
double NaiveSliding(const Graph& g, const SlidingGains& k, const Sample& x,
                    const std::vector<double>& f, int i, int a) {
  auto rel = [&](int j, int c) { return x.followers[4 * j + c] - f[6 * j + c]; };
  double ep = g.leader_weight(i) * (rel(i, a) - x.leader[a]);
  double ev = g.leader_weight(i) * (rel(i, 2 + a) - x.leader[2 + a]);
  for (int m = g.in_begin(i); m < g.in_end(i); ++m) {
    const int j = g.in_neighbor(m);
    ep += g.in_weight(m) * (rel(i, a) - rel(j, a));
    ev += g.in_weight(m) * (rel(i, 2 + a) - rel(j, 2 + a));
  }
  return k.k1 * ep + k.k2 * ev;
}

double Sgn(double s) { return s > 0 ? 1.0 : (s < 0 ? -1.0 : 0.0); }

struct Case {
  int n;
  bool weighted;
};
const Case kCases[] = {{1, false}, {2, true},    {6, false}, {6, true},
                       {20, true}, {100, false}, {500, true}};

TEST(CompactSolveTest, ContinuousMatchesPerAgentEq30) {
  std::mt19937 rng(42);
  for (const Case& c : kCases) {
    const Graph g = testing::RandomGraph(c.n, 2 * c.n, c.weighted, &rng);
    for (Compensation comp : {Compensation::kLowerBound, Compensation::kSwitching}) {
      for (Reaching reach : {Reaching::kConstant, Reaching::kExponential}) {
        ContinuousSmcParams p;
        p.gains = {2.5, 1.3};
        p.rho = 0.3;
        p.q = 2.0;
        p.u_min = -0.7;
        p.u_max = 1.2;
        p.compensation = comp;
        p.reaching = reach;
        ContinuousSmc smc(g, p);
        const Sample x = RandomSample(c.n, &rng);
        smc.Update(x.Input());
        const auto& u = smc.acceleration();
        const double mu1 = 0.5 * (p.u_max + p.u_min), mu2 = 0.5 * (p.u_max - p.u_min);
        const double k1 = p.gains.k1, k2 = p.gains.k2;
        double worst = 0.0;
        for (int i = 0; i < c.n; ++i) {
          for (int a = 0; a < 2; ++a) {
            const double s = NaiveSliding(g, p.gains, x, x.shape_now, i, a);
            ASSERT_NEAR(smc.sliding()[2 * i + a], s, 1e-12 * (1 + std::abs(s)));
            const double a0 = g.leader_weight(i), D = g.in_degree(i) + a0;
            const double u_tilde = comp == Compensation::kLowerBound ? p.u_min : mu1 - mu2 * Sgn(s);
            auto kf_dot = [&](int j) {
              return k1 * x.shape_now[6 * j + 2 + a] + k2 * x.shape_now[6 * j + 4 + a];
            };
            double sum_u = 0, sum_v = 0, sum_kf = 0, scale = 0;
            for (int m = g.in_begin(i); m < g.in_end(i); ++m) {
              const int j = g.in_neighbor(m);
              sum_u += g.in_weight(m) * u[2 * j + a];
              sum_v += g.in_weight(m) * x.followers[4 * j + 2 + a];
              sum_kf += g.in_weight(m) * kf_dot(j);
              scale +=
                  g.in_weight(m) * (std::abs(u[2 * j + a]) + std::abs(x.followers[4 * j + 2 + a]) +
                                    std::abs(kf_dot(j)));
            }
            // eq. (30) times k2 (d_i + a_i0):
            const double bracket = k1 * (D * x.followers[4 * i + 2 + a] - sum_v) -
                                   a0 * k1 * x.leader[2 + a] - a0 * k2 * u_tilde + p.rho * Sgn(s) +
                                   (reach == Reaching::kExponential ? p.q * s : 0.0) -
                                   (D * kf_dot(i) - sum_kf);
            const double residual = k2 * D * u[2 * i + a] - (k2 * sum_u - bracket);
            scale += D * (std::abs(u[2 * i + a]) + std::abs(x.followers[4 * i + 2 + a]) +
                          std::abs(kf_dot(i))) +
                     std::abs(bracket) + 1.0;
            worst = std::max(worst, std::abs(residual) / scale);
          }
        }
        EXPECT_LT(worst, 1e-12) << "n = " << c.n;
      }
    }
  }
}

TEST(CompactSolveTest, DiscreteMatchesPerAgentEq48) {
  std::mt19937 rng(43);
  for (const Case& c : kCases) {
    const Graph g = testing::RandomGraph(c.n, 2 * c.n, c.weighted, &rng);
    for (double T : {0.01, 0.05, 0.2}) {
      DiscreteSmcParams p;
      p.gains = {3.0, 1.0};
      p.eps = 0.05;
      p.q = 4.5;
      p.period = T;
      p.u_min = -1.0;
      p.u_max = 1.5;
      DiscreteSmc smc(g, p);
      const Sample x = RandomSample(c.n, &rng);
      smc.Update(x.Input());
      const auto& u = smc.acceleration();
      const double mu1 = 0.5 * (p.u_max + p.u_min), mu2 = 0.5 * (p.u_max - p.u_min);
      const double k1 = p.gains.k1, k2 = p.gains.k2, KB = k2 * T;
      auto ka = [&](const double* pv, int a) {
        return k1 * (pv[a] + T * pv[2 + a]) + k2 * pv[2 + a];
      };
      auto kf = [&](int j, int a) {
        return k1 * x.shape_next[6 * j + a] + k2 * x.shape_next[6 * j + 2 + a];
      };
      double worst = 0.0;
      for (int i = 0; i < c.n; ++i) {
        for (int a = 0; a < 2; ++a) {
          const double s = NaiveSliding(g, p.gains, x, x.shape_now, i, a);
          const double a0 = g.leader_weight(i), D = g.in_degree(i) + a0;
          const double u_tilde = mu1 - mu2 * Sgn(s);
          double sum_u = 0, sum_ka = 0, sum_kf = 0, scale = 1.0;
          for (int m = g.in_begin(i); m < g.in_end(i); ++m) {
            const int j = g.in_neighbor(m);
            sum_u += g.in_weight(m) * u[2 * j + a];
            sum_ka += g.in_weight(m) * ka(&x.followers[4 * j], a);
            sum_kf += g.in_weight(m) * kf(j, a);
            scale += g.in_weight(m) * (KB * std::abs(u[2 * j + a]) +
                                       std::abs(ka(&x.followers[4 * j], a)) + std::abs(kf(j, a)));
          }
          // eq. (48) times KB (d_i + a_i0):
          const double bracket = (D * ka(&x.followers[4 * i], a) - sum_ka) -
                                 a0 * ka(x.leader.data(), a) - a0 * KB * u_tilde +
                                 (p.q * T - 1) * s + p.eps * T * Sgn(s) - (D * kf(i, a) - sum_kf);
          const double residual = KB * D * u[2 * i + a] - (KB * sum_u - bracket);
          scale += D * (KB * std::abs(u[2 * i + a]) + std::abs(ka(&x.followers[4 * i], a)) +
                        std::abs(kf(i, a))) +
                   std::abs(s);
          worst = std::max(worst, std::abs(residual) / scale);
        }
      }
      EXPECT_LT(worst, 1e-12) << "n = " << c.n << ", T = " << T;
    }
  }
}

// One step of model (40) under (53) gives exactly the sliding dynamics (55).
TEST(CompactSolveTest, DiscreteOneStepGivesEq55) {
  std::mt19937 rng(44);
  std::uniform_real_distribution<double> leader_input(-1.0, 1.5);
  for (const Case& c : kCases) {
    const Graph g = testing::RandomGraph(c.n, c.n, c.weighted, &rng);
    DiscreteSmcParams p;
    p.period = 0.05;
    p.u_min = -1.0;
    p.u_max = 1.5;
    DiscreteSmc smc(g, p);
    const double T = p.period, KB = p.gains.k2 * T;
    Sample x = RandomSample(c.n, &rng);
    smc.Update(x.Input());
    const std::vector<double> s_now = smc.sliding();
    const double u0[2] = {leader_input(rng), leader_input(rng)};
    Sample next = x;
    for (int a = 0; a < 2; ++a) {
      next.leader[a] += T * x.leader[2 + a];  // model (40)
      next.leader[2 + a] += T * u0[a];
      for (int i = 0; i < c.n; ++i) {
        next.followers[4 * i + a] += T * x.followers[4 * i + 2 + a];
        next.followers[4 * i + 2 + a] += T * smc.acceleration()[2 * i + a];
      }
    }
    std::vector<double> e(4 * c.n), s_next(2 * c.n);
    ComputeErrorAndSliding(g, p.gains, next.leader.data(), next.followers.data(),
                           x.shape_next.data(), e.data(), s_next.data());
    const double mu1 = 0.5 * (p.u_max + p.u_min), mu2 = 0.5 * (p.u_max - p.u_min);
    for (int i = 0; i < c.n; ++i) {
      for (int a = 0; a < 2; ++a) {
        const double s = s_now[2 * i + a];
        const double predicted = (1 - p.q * T) * s - p.eps * T * Sgn(s) -
                                 g.leader_weight(i) * KB * (u0[a] - (mu1 - mu2 * Sgn(s)));  // (55)
        EXPECT_NEAR(s_next[2 * i + a], predicted, 1e-10 * (1 + std::abs(s))) << "n = " << c.n;
      }
    }
  }
}

// The exact derivative of s under (33) is (35) (lower_bound) or its switching version.
TEST(CompactSolveTest, ContinuousSlidingDerivativeIsEq35) {
  std::mt19937 rng(45);
  std::uniform_real_distribution<double> leader_input(-1.0, 1.0);
  for (const Case& c : kCases) {
    const Graph g = testing::RandomGraph(c.n, c.n, c.weighted, &rng);
    for (Compensation comp : {Compensation::kLowerBound, Compensation::kSwitching}) {
      ContinuousSmcParams p;
      p.compensation = comp;
      ContinuousSmc smc(g, p);
      const Sample x = RandomSample(c.n, &rng);
      smc.Update(x.Input());
      // x' = [v, u], f' = [f_v, f_a]: build the "derivative sample" and reuse eq. (16)-(17).
      Sample dx = x;
      const double u0[2] = {leader_input(rng), leader_input(rng)};
      std::vector<double> df(6 * c.n);
      for (int a = 0; a < 2; ++a) {
        dx.leader[a] = x.leader[2 + a];
        dx.leader[2 + a] = u0[a];
        for (int i = 0; i < c.n; ++i) {
          dx.followers[4 * i + a] = x.followers[4 * i + 2 + a];
          dx.followers[4 * i + 2 + a] = smc.acceleration()[2 * i + a];
          df[6 * i + a] = x.shape_now[6 * i + 2 + a];
          df[6 * i + 2 + a] = x.shape_now[6 * i + 4 + a];
        }
      }
      std::vector<double> e(4 * c.n), s_dot(2 * c.n);
      ComputeErrorAndSliding(g, p.gains, dx.leader.data(), dx.followers.data(), df.data(), e.data(),
                             s_dot.data());
      const double mu1 = 0.5 * (p.u_max + p.u_min), mu2 = 0.5 * (p.u_max - p.u_min);
      for (int i = 0; i < c.n; ++i) {
        for (int a = 0; a < 2; ++a) {
          const double s = smc.sliding()[2 * i + a];
          const double u_tilde = comp == Compensation::kLowerBound ? p.u_min : mu1 - mu2 * Sgn(s);
          const double predicted =
              -p.rho * Sgn(s) - g.leader_weight(i) * p.gains.k2 * (u0[a] - u_tilde);
          EXPECT_NEAR(s_dot[2 * i + a], predicted, 1e-10 * (1 + std::abs(s))) << "n = " << c.n;
        }
      }
    }
  }
}

TEST(CompactSolveTest, LinearConsensusIsTheDocumentedLaw) {
  std::mt19937 rng(46);
  const Graph g = testing::RandomGraph(8, 10, true, &rng);
  LinearConsensusParams p{1.5, 2.5};
  LinearConsensus lc(g, p);
  const Sample x = RandomSample(8, &rng);
  lc.Update(x.Input());
  for (int i = 0; i < 8; ++i) {
    for (int a = 0; a < 2; ++a) {
      auto rel = [&](int j, int c) { return x.followers[4 * j + c] - x.shape_now[6 * j + c]; };
      double u = x.shape_now[6 * i + 4 + a];
      for (int m = g.in_begin(i); m < g.in_end(i); ++m) {
        const int j = g.in_neighbor(m);
        u += g.in_weight(m) *
             (-p.kp * (rel(i, a) - rel(j, a)) - p.kv * (rel(i, 2 + a) - rel(j, 2 + a)));
      }
      u += g.leader_weight(i) *
           (-p.kp * (rel(i, a) - x.leader[a]) - p.kv * (rel(i, 2 + a) - x.leader[2 + a]));
      EXPECT_NEAR(lc.acceleration()[2 * i + a], u, 1e-12 * (1 + std::abs(u)));
    }
  }
}

}  // namespace
}  // namespace mjf::formation
