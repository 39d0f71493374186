// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The laws from the literature on the point mass (ideal double integrators, Euler at dt), each
// against a property its source proves: variable-structure tracking errors decay to zero when
// beta exceeds the leader's acceleration bound (Cao & Ren 2012); super-twisting reaches s = 0
// within Moreno & Osorio's bound (2012) and keeps it under a leader of bounded jerk (Levant
// 1993); the adaptive gains stay bounded with leakage (Li, Liu, Ren & Xie 2013); the leader-
// velocity estimates converge (Hong, Hu & Gao 2006); on the terminal sliding surface the errors
// reach zero within Feng, Yu & Man's sliding-phase time (2002).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <mjformation/formation/adaptive_tracking.hpp>
#include <mjformation/formation/metrics.hpp>
#include <mjformation/formation/observer_tracking.hpp>
#include <mjformation/formation/shape.hpp>
#include <mjformation/formation/super_twisting.hpp>
#include <mjformation/formation/terminal_smc.hpp>
#include <mjformation/formation/vs_tracking.hpp>
#include <vector>

namespace mjf::formation {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Exp 2's topology: follower 1 hears the leader, a bidirectional ring 1-2-...-6-1.
Graph RingGraph() {
  std::vector<Edge> edges;
  for (int i = 0; i < 6; ++i) {
    edges.push_back({i, (i + 1) % 6});
    edges.push_back({(i + 1) % 6, i});
  }
  return Graph(6, {1, 0, 0, 0, 0, 0}, edges);
}

// A leader on a circle (radius r, rate w; |u_0| = r w^2, |u_0'| = r w^3), or on a straight line
// at constant velocity when w = 0 (u_0 = 0).
struct Leader {
  double radius = 20.0, omega = 0.157, vx = 2.0, vy = 1.0;
  void State(double t, double* pv) const {
    if (omega == 0.0) {
      pv[0] = 20.0 + vx * t, pv[1] = vy * t, pv[2] = vx, pv[3] = vy;
      return;
    }
    pv[0] = radius * std::cos(omega * t), pv[1] = radius * std::sin(omega * t);
    pv[2] = -radius * omega * std::sin(omega * t), pv[3] = radius * omega * std::cos(omega * t);
  }
};

// Six point masses flown by `law` (input, t) -> accelerations [2i + axis], Euler at dt, the
// formation of Exp 2 (10 m circle at 0.314 rad/s); `observe` (t, input) after each evaluation.
// Followers start at their slots displaced by `offset` m (x) and -offset/2 m (y).
using Law = std::function<const std::vector<double>&(const FormationInput&, double)>;
using Observe = std::function<void(double, const FormationInput&)>;
void Fly(const Leader& leader, double offset, double dt, double duration, const Law& law,
         const Observe& observe) {
  const auto shape = MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);
  std::vector<double> leader_pv(4), follower_pv(24), now(36);
  leader.State(0.0, leader_pv.data());
  shape->Evaluate(0.0, now.data());
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 4; ++k) follower_pv[4 * i + k] = leader_pv[k] + now[6 * i + k];
    follower_pv[4 * i] += offset;
    follower_pv[4 * i + 1] -= 0.5 * offset;
  }
  const long steps = std::lround(duration / dt);
  for (long step = 0; step <= steps; ++step) {
    const double t = step * dt;
    leader.State(t, leader_pv.data());
    shape->Evaluate(t, now.data());
    const FormationInput input{leader_pv.data(), follower_pv.data(), now.data(), nullptr};
    const std::vector<double>& u = law(input, t);
    observe(t, input);
    for (int i = 0; i < 6; ++i) {
      for (int axis = 0; axis < 2; ++axis) {
        follower_pv[4 * i + axis] += dt * follower_pv[4 * i + 2 + axis];
        follower_pv[4 * i + 2 + axis] += dt * u[2 * i + axis];
      }
    }
  }
}

double Sigma(const FormationInput& in) {
  return FormationError(6, in.follower_pv, in.leader_pv, in.shape_now);
}

// Cao & Ren: with beta > |u_0| (0.49 m/s^2 here) the tracking error goes to zero in continuous
// time. Euler at dt leaves a chattering floor of order beta dt, so the property checked is that
// the floor shrinks in proportion to dt; with beta below |u_0| it does not (the sign term cannot
// reject the leader's input).
double VsLateSigma(double beta, double dt) {
  VsTrackingParams params;
  params.beta = beta;
  VsTracking law(RingGraph(), params);
  double late = 0.0;
  Fly(
      Leader{}, 20.0, dt, 40.0,
      [&](const FormationInput& in, double) -> const std::vector<double>& {
        law.Update(in);
        return law.acceleration();
      },
      [&](double t, const FormationInput& in) {
        if (t >= 30.0) late = std::max(late, Sigma(in));
      });
  return late;
}

TEST(VsTrackingTest, ErrorsGoToZeroWithTheStepWhenBetaExceedsTheLeaderInput) {
  const double coarse = VsLateSigma(1.5, 1e-3), fine = VsLateSigma(1.5, 2.5e-4);
  RecordProperty("max_sigma_f_30_40s_dt_1ms", std::to_string(coarse));
  RecordProperty("max_sigma_f_30_40s_dt_0_25ms", std::to_string(fine));
  EXPECT_LT(coarse, 0.2);
  EXPECT_LT(fine, 0.35 * coarse);  // O(dt): 0.25 for a floor exactly proportional to dt
  const double weak_coarse = VsLateSigma(0.2, 1e-3), weak_fine = VsLateSigma(0.2, 2.5e-4);
  RecordProperty("max_sigma_f_30_40s_beta_0_2", std::to_string(weak_fine));
  EXPECT_GT(weak_fine, 10.0 * fine);
  EXPECT_GT(weak_fine, 0.7 * weak_coarse);  // not a discretization floor
}

// Moreno & Osorio: with d = 0 (leader at constant velocity) every s_i reaches 0 within
// T = 2 V(0)^(1/2) / g; on the Euler-discretized loop "0" is a band of width O(dt).
TEST(SuperTwistingTest, ReachesWithinMorenoOsorioBound) {
  SuperTwisting law(RingGraph(), SuperTwistingParams{});
  Leader line;
  line.omega = 0.0;
  double reached = -1.0;
  const double band = 1e-3;
  Fly(
      line, 2.0, 1e-4, 40.0,
      [&](const FormationInput& in, double t) -> const std::vector<double>& {
        law.Update(in, t);
        return law.acceleration();
      },
      [&](double t, const FormationInput&) {
        double worst = 0.0;
        for (double s : law.sliding()) worst = std::max(worst, std::abs(s));
        if (worst > band) reached = -1.0;
        if (worst <= band && reached < 0.0) reached = t;
      });
  const double bound = law.reaching_time_bound();
  RecordProperty("reaching_time_s", std::to_string(reached));
  RecordProperty("moreno_osorio_bound_s", std::to_string(bound));
  ASSERT_GE(reached, 0.0) << "never settled in |s| <= " << band;
  EXPECT_LE(reached, bound);
  EXPECT_GT(reached, 0.05 * bound);  // the bound is of the right order, not vacuous
}

// Levant: with the leader's jerk bounded (|u_0'| <= r w^3, C = k2 a_i0 r w^3 for follower 1)
// and alpha > C, lambda^2 >= 4 C (alpha + C) / (alpha - C), s stays at 0 after reaching and the
// integral term w_1 takes over the perturbation: w_1 -> k2 a_10 u_0.
TEST(SuperTwistingTest, RejectsTheLeaderInputUnderLevantsCondition) {
  const SuperTwistingParams params;
  const Leader circle{20.0, 0.4};  // |u_0| = 3.2 m/s^2, |u_0'| = 1.28 m/s^3
  const double c = params.gains.k2 * 1.0 * circle.radius * std::pow(circle.omega, 3);
  SuperTwistingParams strong = params;
  strong.alpha = 2.0 * c;
  strong.lambda = std::sqrt(4.0 * c * (strong.alpha + c) / (strong.alpha - c)) + 0.5;
  ASSERT_TRUE(LevantConditionHolds(strong.lambda, strong.alpha, c));
  SuperTwisting law(RingGraph(), strong);
  double worst_late = 0.0, worst_w_error = 0.0;
  Fly(
      circle, 2.0, 1e-4, 40.0,
      [&](const FormationInput& in, double t) -> const std::vector<double>& {
        law.Update(in, t);
        return law.acceleration();
      },
      [&](double t, const FormationInput&) {
        if (t < 30.0) return;
        for (double s : law.sliding()) worst_late = std::max(worst_late, std::abs(s));
        const double u0x =
            -circle.radius * circle.omega * circle.omega * std::cos(circle.omega * t);
        worst_w_error = std::max(worst_w_error, std::abs(law.integral()[0] - u0x));
      });
  RecordProperty("max_abs_s_30_40s", std::to_string(worst_late));
  RecordProperty("max_w1_minus_k2_u0", std::to_string(worst_w_error));
  EXPECT_LT(worst_late, 1e-3);
  EXPECT_LT(worst_w_error, 0.01 * circle.radius * circle.omega * circle.omega);
}

// Li, Liu, Ren & Xie: with leakage phi > 0 the gains d_i and the tracking error are uniformly
// ultimately bounded, for a leader input (3.2 m/s^2) far above the initial gain d0 = 0.1 and
// unknown to the law: d_i rises past the leader's bound, then stops growing; the ultimate error
// shrinks with phi.
struct AdaptiveRun {
  double d_at_60 = 0.0, d_max_late = 0.0, d_max = 0.0, sigma_late = 0.0;
};
AdaptiveRun FlyAdaptive(double phi) {
  AdaptiveTrackingParams params;
  params.d0 = 0.1;
  params.tau = 0.5;
  params.phi = phi;
  AdaptiveTracking law(RingGraph(), params);
  AdaptiveRun run;
  Fly(
      Leader{20.0, 0.4}, 2.0, 1e-3, 90.0,
      [&](const FormationInput& in, double t) -> const std::vector<double>& {
        law.Update(in, t);
        return law.acceleration();
      },
      [&](double t, const FormationInput& in) {
        const double d = *std::max_element(law.gain().begin(), law.gain().end());
        if (std::abs(t - 60.0) < 5e-4) run.d_at_60 = d;
        if (t >= 60.0) run.d_max_late = std::max(run.d_max_late, d);
        if (t >= 60.0) run.sigma_late = std::max(run.sigma_late, Sigma(in));
      });
  run.d_max = law.max_gain();
  return run;
}

TEST(AdaptiveTrackingTest, GainsStayBoundedForAnUnknownLeaderInputBound) {
  const AdaptiveRun run = FlyAdaptive(0.05);
  RecordProperty("max_d_60s", std::to_string(run.d_at_60));
  RecordProperty("max_d_60_90s", std::to_string(run.d_max_late));
  RecordProperty("max_sigma_f_60_90s", std::to_string(run.sigma_late));
  EXPECT_GT(run.d_max, 3.2);                         // it adapted past the unknown bound r w^2
  EXPECT_LT(run.d_max_late, 1.01 * run.d_at_60);     // and stopped growing
  EXPECT_LT(run.sigma_late, 5.0);                    // ultimately bounded
  const AdaptiveRun less_leak = FlyAdaptive(0.005);  // a smaller ultimate bound
  RecordProperty("max_sigma_f_60_90s_phi_0_005", std::to_string(less_leak.sigma_late));
  EXPECT_LT(less_leak.sigma_late, 0.6 * run.sigma_late);
}

// Hong, Hu & Gao: with a leader at constant velocity (its input known, = 0) every follower's
// estimate vbar_i converges to v_0 (never measured).
TEST(ObserverTrackingTest, LeaderVelocityEstimatesConverge) {
  ObserverTrackingParams params;
  params.k = 2.0;  // the ring's slowest mode (lambda_min(L_H) = 0.109) decays at 0.11/s
  params.gamma = 1.0;
  params.kv = 8.0;
  ObserverTracking law(RingGraph(), params);
  Leader line;
  line.omega = 0.0;
  double early = 0.0, late = 0.0;
  Fly(
      line, 5.0, 1e-3, 120.0,
      [&](const FormationInput& in, double t) -> const std::vector<double>& {
        law.Update(in, t);
        return law.acceleration();
      },
      [&](double t, const FormationInput&) {
        double worst = 0.0;
        for (int i = 0; i < 6; ++i) {
          worst = std::max(worst, std::hypot(law.leader_velocity_estimate()[2 * i] - line.vx,
                                             law.leader_velocity_estimate()[2 * i + 1] - line.vy));
        }
        if (t >= 20.0 && t < 40.0) early = std::max(early, worst);
        if (t >= 100.0) late = std::max(late, worst);
      });
  RecordProperty("max_estimate_error_20_40s", std::to_string(early));
  RecordProperty("max_estimate_error_100_120s", std::to_string(late));
  EXPECT_LT(late, 1e-3 * std::hypot(line.vx, line.vy));
  EXPECT_LT(late, 0.01 * early);
}

// Feng, Yu & Man: once s_i = 0 (at t_r), e_ip reaches 0 within
// t_s = p / (beta^(q/p) (p - q)) |e_ip(t_r)|^(1 - q/p). Checked per follower and axis.
TEST(TerminalSmcTest, ErrorsReachZeroWithinTheSlidingPhaseTime) {
  const TerminalSmcParams params;
  TerminalSmc law(RingGraph(), params);
  Leader line;
  line.omega = 0.0;
  std::vector<double> reach_time(12, -1.0), x1_at_reach(12, 0.0), zero_time(12, -1.0);
  const double s_band = 1e-3, x_band = 1e-3;
  Fly(
      line, 3.0, 1e-4, 30.0,
      [&](const FormationInput& in, double) -> const std::vector<double>& {
        law.Update(in);
        return law.acceleration();
      },
      [&](double t, const FormationInput&) {
        for (int i = 0; i < 6; ++i) {
          for (int axis = 0; axis < 2; ++axis) {
            const int j = 2 * i + axis;
            const double x1 = law.error()[4 * i + axis];
            if (reach_time[j] < 0.0 && std::abs(law.sliding()[j]) <= s_band) {
              reach_time[j] = t, x1_at_reach[j] = x1;
            }
            if (reach_time[j] >= 0.0 && zero_time[j] < 0.0 && std::abs(x1) <= x_band) {
              zero_time[j] = t;
            }
          }
        }
      });
  for (int j = 0; j < 12; ++j) {
    ASSERT_GE(reach_time[j], 0.0) << "channel " << j << " never reached s = 0";
    ASSERT_GE(zero_time[j], 0.0) << "channel " << j << " never reached e_p = 0";
    const double t_s = TerminalSlidingTime(params, x1_at_reach[j]);
    EXPECT_LE(zero_time[j] - reach_time[j], t_s + 1e-3)
        << "channel " << j << ": e_p(t_r) = " << x1_at_reach[j];
  }
  RecordProperty("reach_time_channel0_s", std::to_string(reach_time[0]));
  RecordProperty("zero_time_channel0_s", std::to_string(zero_time[0]));
}

}  // namespace
}  // namespace mjf::formation
