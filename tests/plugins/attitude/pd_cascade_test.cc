// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjcf/quadrotor.xml with the pure PdCascade and guidance classes in MuJoCo closed loops.
#include "mjformation/attitude/pd_cascade.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mjformation/guidance/circle.hpp"
#include "mjformation/guidance/hover.hpp"
#include "vehicle_fixture.hpp"

namespace mjf::test {
namespace {

using attitude::Mixer;
using attitude::PdCascade;
using attitude::Setpoint;
using attitude::VehicleState;

class QuadrotorTest : public VehicleFixture {
 protected:
  void SetUp() override { Load("quadrotor.xml"); }

  PdCascade MakeController(const PdCascade::Gains& gains = {}) const {
    PdCascade::Vehicle vehicle{Mass(), Gravity(), Inertia()};
    return PdCascade(gains, vehicle, Rotors());
  }

  void Apply(const std::array<double, 4>& ctrl) {
    for (int k = 0; k < 4; ++k) d_->ctrl[k] = ctrl[k];
  }

  // Runs seconds of closed loop with a setpoint function of (time, state).
  template <typename SetpointFn, typename Observe>
  void Fly(PdCascade& controller, double seconds, SetpointFn setpoint, Observe observe) {
    const int steps = static_cast<int>(std::lround(seconds / m_->opt.timestep));
    for (int i = 0; i < steps && !HasFatalFailure(); ++i) {
      Step([&](const VehicleState& s) {
        const Setpoint sp = setpoint(d_->time, s);
        Apply(controller.Update(s, sp, m_->opt.timestep).ctrl);
        observe(d_->time, s, sp);
      });
    }
  }
};

TEST_F(QuadrotorTest, ModelFollowsTheContract) {
  EXPECT_EQ(m_->nu, 4);
  EXPECT_NEAR(Mass(), 1.5, 1e-12);
  EXPECT_NEAR(Inertia()[0], 0.029125, 1e-12);
  EXPECT_NEAR(Inertia()[2], 0.055225, 1e-12);
  EXPECT_EQ(m_->opt.timestep, 0.001);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(m_->actuator_trntype[k], mjTRN_SITE);
    EXPECT_EQ(m_->actuator_dyntype[k], mjDYN_FILTER);
    EXPECT_TRUE(m_->actuator_ctrllimited[k]);
    EXPECT_NEAR(m_->actuator_ctrlrange[2 * k + 1], 7.066, 1e-9);
  }
  EXPECT_GE(mj_name2id(m_, mjOBJ_SITE, "imu"), 0);
  // Thrust to weight ratio of the Iris: about 1.9.
  EXPECT_NEAR(4 * 7.066 / (Mass() * Gravity()), 1.92, 0.01);
}

TEST_F(QuadrotorTest, AllocationIsInvertibleWithTheRightSigns) {
  PlaceFree({0, 0, 1.5});
  const Mixer mixer(Rotors());
  const Eigen::Matrix4d& b = mixer.allocation();
  std::printf("allocation matrix B (rows thrust, tx, ty, tz; columns rotor0..3):\n");
  for (int r = 0; r < 4; ++r) {
    std::printf("  % .4f % .4f % .4f % .4f\n", b(r, 0), b(r, 1), b(r, 2), b(r, 3));
  }
  std::printf("condition number %.3f\n", mixer.condition_number());
  EXPECT_LT(mixer.condition_number(), 20);
  EXPECT_NEAR((b * mixer.inverse() - Eigen::Matrix4d::Identity()).norm(), 0, 1e-12);
  // tau = r x (0, 0, f) = (y f, -x f, 0) plus the reaction torque gear[5] f.
  const double x[4] = {0.13, -0.13, 0.13, -0.13}, y[4] = {-0.22, 0.22, 0.22, -0.22};
  const double c[4] = {-0.06, -0.06, 0.06, 0.06};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(b(0, k), 1, 1e-12);
    EXPECT_NEAR(b(1, k), y[k], 1e-9) << k;
    EXPECT_NEAR(b(2, k), -x[k], 1e-9) << k;
    EXPECT_NEAR(b(3, k), c[k], 1e-9) << k;
  }
}

// Open loop: hover thrust plus one pure torque through the mixer; the body must turn about the
// commanded axis in the commanded direction (MuJoCo applies the site wrenches, not our matrix).
TEST_F(QuadrotorTest, PureTorqueCommandsTurnTheBodyTheRightWay) {
  const Mixer mixer(Rotors());
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      PlaceFree({0, 0, 1.5});
      attitude::Wrench w(Mass() * Gravity(), 0, 0, 0);
      w[1 + axis] = sign * 0.05;  // N m
      const auto ctrl = mixer.Mix(w).ctrl;
      for (int k = 0; k < 4; ++k) d_->act[k] = ctrl[k];  // motors already spun up
      for (int i = 0; i < 200; ++i) Step([&](const VehicleState&) { Apply(ctrl); });
      const VehicleState s = State();
      for (int j = 0; j < 3; ++j) {
        if (j == axis) {
          EXPECT_GT(sign * s.gyro[j], 0.1) << "axis " << axis << " sign " << sign;
        } else {
          EXPECT_NEAR(s.gyro[j], 0, 1e-6) << "axis " << axis << " cross-coupling into " << j;
        }
      }
    }
  }
}

TEST_F(QuadrotorTest, MotorLagFollowsTheTimeConstant) {
  PlaceFree({0, 0, 1.5});
  const double tau = m_->actuator_dynprm[0];
  EXPECT_NEAR(tau, 0.025, 1e-12);
  const double command = 5.0;  // N
  double worst = 0;
  for (int i = 0; i < 150; ++i) {
    Step([&](const VehicleState&) { Apply({command, command, command, command}); });
    const double expected = command * (1 - std::exp(-d_->time / tau));
    for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(d_->act[k] - expected));
  }
  std::printf("motor lag: max |act - ctrl (1 - exp(-t / tau))| = %.4f N of %.1f N\n", worst,
              command);
  EXPECT_LT(worst, 0.01 * command);
  // Controls beyond ctrlrange are clamped: the lag settles at Tmax.
  for (int i = 0; i < 500; ++i) Step([&](const VehicleState&) { Apply({100, 100, 100, 100}); });
  EXPECT_NEAR(d_->act[0], 7.066, 1e-3);
}

TEST_F(QuadrotorTest, HoverHoldsPosition) {
  const std::array<double, 3> start{3, -2, 1.5};
  PlaceFree(start);
  PdCascade controller = MakeController();
  guidance::HoverGuidance::Config config;
  config.position = start;
  const guidance::HoverGuidance hover(config);
  double worst_xy = 0, worst_z = 0;
  Fly(
      controller, 23,
      [&](double, const VehicleState& s) {
        const auto out = hover.Update(s.pos, s.vel);
        Setpoint sp;
        sp.acc = out.acc;
        sp.pos = out.pos;
        sp.vel = out.vel;
        sp.yaw = out.yaw;
        return sp;
      },
      [&](double t, const VehicleState& s, const Setpoint&) {
        if (t < 3) return;
        worst_xy = std::max(worst_xy, std::hypot(s.pos[0] - start[0], s.pos[1] - start[1]));
        worst_z = std::max(worst_z, std::abs(s.pos[2] - start[2]));
      });
  std::printf("hover 3..23 s: max horizontal error %.2e m, max altitude error %.2e m\n", worst_xy,
              worst_z);
  EXPECT_LT(worst_xy, 0.1);
  EXPECT_LT(worst_z, 0.05);
}

TEST_F(QuadrotorTest, HoverRecoversFromATiltedMovingStart) {
  const std::array<double, 3> start{0, 0, 10};
  PlaceFree(start);
  // Rolled 0.3 rad, pitched -0.2 rad, moving at (1, -1, 0.5) m/s and spinning.
  const double roll = 0.3, pitch = -0.2;
  d_->qpos[3] = std::cos(roll / 2) * std::cos(pitch / 2);
  d_->qpos[4] = std::sin(roll / 2) * std::cos(pitch / 2);
  d_->qpos[5] = std::cos(roll / 2) * std::sin(pitch / 2);
  d_->qpos[6] = -std::sin(roll / 2) * std::sin(pitch / 2);
  d_->qvel[0] = 1;
  d_->qvel[1] = -1;
  d_->qvel[2] = 0.5;
  d_->qvel[3] = 1;
  d_->qvel[5] = -2;
  mj_forward(m_, d_);
  PdCascade controller = MakeController();
  guidance::HoverGuidance::Config config;
  config.position = start;
  const guidance::HoverGuidance hover(config);
  double worst = 0, peak = 0, peak_late_tilt = 0;
  Fly(
      controller, 20,
      [&](double, const VehicleState& s) {
        const auto out = hover.Update(s.pos, s.vel);
        Setpoint sp;
        sp.acc = out.acc;
        sp.pos = out.pos;
        sp.vel = out.vel;
        return sp;
      },
      [&](double t, const VehicleState& s, const Setpoint&) {
        const double error =
            std::hypot(s.pos[0] - start[0], s.pos[1] - start[1], s.pos[2] - start[2]);
        peak = std::max(peak, error);
        const auto e = attitude::EulerZYX(s.quat);
        if (t >= 3) peak_late_tilt = std::max(peak_late_tilt, std::hypot(e[0], e[1]));
        if (t >= 8) worst = std::max(worst, error);
      });
  std::printf(
      "disturbed hover: peak excursion %.3f m, max tilt after 3 s %.3f rad, max error 8..20 s "
      "%.2e m\n",
      peak, peak_late_tilt, worst);
  EXPECT_LT(peak_late_tilt, 0.05);
  EXPECT_LT(peak, 1.0);
  EXPECT_LT(worst, 0.02);
}

TEST_F(QuadrotorTest, YawSetpointIsReachedWithTheRightSign) {
  PlaceFree({0, 0, 1.5});
  PdCascade controller = MakeController();
  Setpoint sp;
  sp.pos = {0, 0, 1.5};
  sp.yaw = 0.8;
  double max_yaw = 0;
  Fly(
      controller, 5, [&](double, const VehicleState&) { return sp; },
      [&](double, const VehicleState& s, const Setpoint&) {
        max_yaw = std::max(max_yaw, attitude::EulerZYX(s.quat)[2]);
      });
  const double yaw = attitude::EulerZYX(State().quat)[2];
  std::printf("yaw step 0.8 rad: final %.4f rad, peak %.4f rad\n", yaw, max_yaw);
  EXPECT_NEAR(yaw, 0.8, 0.01);
  EXPECT_LT(max_yaw, 0.8 * 1.1);
}

// A horizontal acceleration step: tilt settles at the eq. (9) reference, the vehicle accelerates
// in the commanded world direction whatever its yaw, and a large command is held at tilt_max.
TEST_F(QuadrotorTest, AccelerationStepTiltsAndAcceleratesTheRightWay) {
  for (double yaw : {0.0, M_PI / 2}) {
    for (int axis = 0; axis < 2; ++axis) {
      for (double command : {2.0, 8.0}) {
        PlaceFree({0, 0, 20}, yaw);
        PdCascade controller = MakeController();
        const double tilt_ref = std::min(command / Gravity(), controller.gains().tilt_max);
        double peak_tilt = 0, rise_time = -1;
        Setpoint sp;
        sp.pos = {0, 0, 20};
        sp.yaw = yaw;
        sp.acc[axis] = command;
        VehicleState before;
        Fly(
            controller, 1.5, [&](double, const VehicleState&) { return sp; },
            [&](double t, const VehicleState& s, const Setpoint&) {
              const auto e = attitude::EulerZYX(s.quat);
              peak_tilt = std::max(peak_tilt, std::hypot(e[0], e[1]));
              if (rise_time < 0 && std::hypot(e[0], e[1]) >= 0.9 * tilt_ref) rise_time = t;
              if (std::abs(t - 1.0) < 1e-9) before = s;
            });
        const VehicleState after = State();
        const auto e = attitude::EulerZYX(after.quat);
        const double tilt = std::hypot(e[0], e[1]);
        const double overshoot = (peak_tilt - tilt_ref) / tilt_ref;
        // World acceleration over the last 0.5 s.
        const double acc = (after.vel[axis] - before.vel[axis]) / 0.5;
        const double cross = (after.vel[1 - axis] - before.vel[1 - axis]) / 0.5;
        std::printf(
            "yaw %.2f axis %d command %.1f: tilt %.4f (ref %.4f), 90 %% rise %.3f s, overshoot "
            "%.2f %%, acc %.3f, cross %.3f\n",
            yaw, axis, command, tilt, tilt_ref, rise_time, 100 * overshoot, acc, cross);
        EXPECT_NEAR(tilt, tilt_ref, 0.01 * tilt_ref + 1e-3);
        EXPECT_LE(peak_tilt, controller.gains().tilt_max * 1.05);
        EXPECT_LT(overshoot, 0.1);
        EXPECT_LT(rise_time, 0.3);
        const double expected_acc = Gravity() * std::tan(tilt_ref);  // thrust tilt-compensated
        EXPECT_GT(acc, 0) << "wrong direction";
        EXPECT_NEAR(acc, expected_acc, 0.1 * expected_acc);
        EXPECT_NEAR(cross, 0, 0.05 * expected_acc);
        EXPECT_NEAR(after.pos[2], 20, 0.1) << "altitude lost";
      }
    }
  }
}

TEST_F(QuadrotorTest, TracksTheLeaderCircle) {
  PlaceFree({20, 0, 5});
  PdCascade controller = MakeController();
  guidance::CircleGuidance::Config config;  // paper: 20 m, 0.157 rad/s, about the origin
  const guidance::CircleGuidance circle(config);
  double worst = 0, sum = 0, worst_z = 0, peak_tilt = 0;
  int n = 0;
  Fly(
      controller, 40,
      [&](double t, const VehicleState& s) {
        const auto out = circle.Update(t, s.pos, s.vel);
        Setpoint sp;
        sp.acc = out.acc;
        sp.pos = out.pos;
        sp.vel = out.vel;
        sp.yaw = out.yaw;
        return sp;
      },
      [&](double t, const VehicleState& s, const Setpoint& sp) {
        const auto e = attitude::EulerZYX(s.quat);
        peak_tilt = std::max(peak_tilt, std::hypot(e[0], e[1]));
        if (t < 10) return;
        const double error = std::hypot(s.pos[0] - sp.pos[0], s.pos[1] - sp.pos[1]);
        worst = std::max(worst, error);
        worst_z = std::max(worst_z, std::abs(s.pos[2] - 5));
        sum += error;
        ++n;
      });
  std::printf(
      "circle 10..40 s: max error %.3e m, mean %.3e m, max altitude error %.2e m, peak "
      "tilt %.3f rad\n",
      worst, sum / n, worst_z, peak_tilt);
  EXPECT_LT(worst, 0.5);
  EXPECT_LT(worst_z, 0.05);
}

TEST_F(QuadrotorTest, AltitudeIntegratorRemovesAMassError) {
  // The controller believes the vehicle 10 % lighter than it is; the integrator makes up for it.
  PlaceFree({0, 0, 2});
  PdCascade::Vehicle wrong{0.9 * Mass(), Gravity(), Inertia()};
  PdCascade controller(PdCascade::Gains{}, wrong, Rotors());
  Setpoint sp;
  sp.pos = {0, 0, 2};
  Fly(
      controller, 10, [&](double, const VehicleState&) { return sp; },
      [](double, const VehicleState&, const Setpoint&) {});
  EXPECT_NEAR(State().pos[2], 2, 0.01);
  EXPECT_LE(std::abs(controller.altitude_integral()), PdCascade::Gains{}.imax_z + 1e-12);
}

TEST(PdCascadeTest, RefusesBadConfiguration) {
  std::array<attitude::RotorGeometry, 4> rotors;
  for (int k = 0; k < 4; ++k) {
    rotors[k].pos = {k < 2 ? 0.1 : -0.1, k % 2 ? 0.1 : -0.1, 0};
    rotors[k].gear = {0, 0, 1, 0, 0, k % 3 == 0 ? 0.06 : -0.06};
    rotors[k].ctrl_max = 5;
  }
  const PdCascade::Vehicle ok{1.5, 9.81, {0.03, 0.03, 0.05}};
  EXPECT_NO_THROW(PdCascade(PdCascade::Gains{}, ok, rotors));
  PdCascade::Gains bad;
  bad.tilt_max = 2;
  EXPECT_THROW(PdCascade(bad, ok, rotors), std::invalid_argument);
  EXPECT_THROW(PdCascade(PdCascade::Gains{}, PdCascade::Vehicle{0, 9.81, {1, 1, 1}}, rotors),
               std::invalid_argument);
  // Above 0.65 rad only with both large-tilt fixes (Exp 2 flips otherwise).
  PdCascade::Gains wide;
  wide.tilt_max = 0.78;
  EXPECT_THROW(PdCascade(wide, ok, rotors), std::invalid_argument);
  wide.euler_rate_damping = true;
  EXPECT_THROW(PdCascade(wide, ok, rotors), std::invalid_argument);
  wide.allocation = Mixer::Priority::kRollPitchFirst;
  EXPECT_NO_THROW(PdCascade(wide, ok, rotors));
  auto coplanar = rotors;  // all rotors on the x axis: no roll authority
  for (auto& r : coplanar) r.pos[1] = 0;
  EXPECT_THROW(PdCascade(PdCascade::Gains{}, ok, coplanar), std::invalid_argument);
}

TEST(MixerTest, SaturationKeepsThrustThenRollPitchThenYaw) {
  std::array<attitude::RotorGeometry, 4> rotors;
  const double x[4] = {0.13, -0.13, 0.13, -0.13}, y[4] = {-0.22, 0.22, 0.22, -0.22};
  const double c[4] = {-0.06, -0.06, 0.06, 0.06};
  for (int k = 0; k < 4; ++k) {
    rotors[k].pos = {x[k], y[k], 0};
    rotors[k].gear = {0, 0, 1, 0, 0, c[k]};
    rotors[k].ctrl_max = 7;
  }
  const Mixer mixer(rotors);
  // Feasible: delivered exactly.
  const attitude::Wrench easy(15, 0.1, -0.1, 0.02);
  auto r = mixer.Mix(easy);
  Eigen::Vector4d u(r.ctrl[0], r.ctrl[1], r.ctrl[2], r.ctrl[3]);
  EXPECT_NEAR((mixer.allocation() * u - easy).norm(), 0, 1e-12);
  // Too much yaw: thrust and roll/pitch are kept, yaw is cut.
  const attitude::Wrench yaw_heavy(15, 0.2, 0, 2);
  r = mixer.Mix(yaw_heavy);
  u << r.ctrl[0], r.ctrl[1], r.ctrl[2], r.ctrl[3];
  const Eigen::Vector4d got = mixer.allocation() * u;
  EXPECT_NEAR(got[0], 15, 1e-9);
  EXPECT_NEAR(got[1], 0.2, 1e-9);
  EXPECT_LT(r.yaw_scale, 1);
  EXPECT_GT(got[3], 0);
  // More thrust than the rotors have: thrust is cut to 4 Tmax, all controls in range.
  r = mixer.Mix(attitude::Wrench(40, 0, 0, 0));
  EXPECT_TRUE(r.thrust_saturated);
  for (double v : r.ctrl) EXPECT_NEAR(v, 7, 1e-12);
}

}  // namespace
}  // namespace mjf::test
