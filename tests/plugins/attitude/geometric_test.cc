// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The geometric attitude controller (and, for comparison, pd_cascade) in MuJoCo closed loops:
// step responses, recovery from a 100 deg attitude error, the nonlinear acceleration map, the
// same default gains on a heavier and wider vehicle, q / -q, mixer priority, bad gains.
#include "mjformation/attitude/geometric.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mjformation/attitude/pd_cascade.hpp"
#include "mjformation/guidance/hover.hpp"
#include "vehicle_fixture.hpp"

namespace mjf::test {
namespace {

using attitude::Geometric;
using attitude::Mixer;
using attitude::PdCascade;
using attitude::Setpoint;
using attitude::VehicleState;

const std::string kHeavy = std::string(MJF_TEST_DATA_DIR) + "/heavy_quadrotor.xml";

// Angle between body z and world z, rad (no Euler angles: valid upside down too).
double Tilt(const std::array<double, 4>& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r33 = 1 - 2 * (x * x + y * y);
  (void)w;
  (void)z;
  return std::acos(std::clamp(r33, -1.0, 1.0));
}

class GeometricTest : public VehicleFixture {
 protected:
  Geometric MakeGeometric(const Geometric::Gains& gains = {}) const {
    Geometric::Vehicle v;
    v.mass = Mass();
    v.gravity = Gravity();
    v.inertia = Inertia();
    v.motor_lag = MotorLag();
    v.timestep = m_->opt.timestep;
    return Geometric(gains, v, Rotors());
  }
  PdCascade MakeCascade(const PdCascade::Gains& gains = {}) const {
    return PdCascade(gains, PdCascade::Vehicle{Mass(), Gravity(), Inertia()}, Rotors());
  }

  // Sets the attitude to a rotation of angle (rad) about the unit body axis, then yaw about z.
  void SetAttitude(double angle, const std::array<double, 3>& axis, double yaw = 0) {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) *
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d(axis[0], axis[1], axis[2])));
    d_->qpos[3] = q.w();
    d_->qpos[4] = q.x();
    d_->qpos[5] = q.y();
    d_->qpos[6] = q.z();
    mj_forward(m_, d_);
  }

  template <typename Controller, typename SetpointFn, typename Observe>
  void Fly(Controller& controller, double seconds, SetpointFn setpoint, Observe observe) {
    const int steps = static_cast<int>(std::lround(seconds / m_->opt.timestep));
    for (int i = 0; i < steps && !HasFatalFailure(); ++i) {
      Step([&](const VehicleState& s) {
        const Setpoint sp = setpoint(d_->time, s);
        const auto out = controller.Update(s, sp, m_->opt.timestep);
        for (int k = 0; k < 4; ++k) d_->ctrl[k] = out.ctrl[k];
        observe(d_->time, s, sp);
      });
    }
  }

  // Hover at start from a disturbed state; returns the largest position error after settle_s.
  template <typename Controller>
  double DisturbedHover(Controller& controller, const std::array<double, 3>& start, double settle_s,
                        double seconds) {
    PlaceFree(start);
    SetAttitude(0.3, {0.6, 0.8, 0}, 0.2);
    d_->qvel[0] = 1;
    d_->qvel[1] = -1;
    d_->qvel[2] = 0.5;
    d_->qvel[3] = 1;
    d_->qvel[5] = -2;
    mj_forward(m_, d_);
    guidance::HoverGuidance::Config config;
    config.position = start;
    const guidance::HoverGuidance hover(config);
    double worst = 0;
    Fly(
        controller, seconds,
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
          if (t < settle_s) return;
          worst = std::max(
              worst, std::hypot(s.pos[0] - start[0], s.pos[1] - start[1], s.pos[2] - start[2]));
        });
    return worst;
  }

  struct StepResult {
    double final_tilt = 0, rise = -1, settle = 0, overshoot = 0;
  };
  // Horizontal acceleration step of `command` m/s^2 along x at hover: tilt response.
  template <typename Controller>
  StepResult TiltStep(Controller& controller, double command) {
    PlaceFree({0, 0, 20});
    Setpoint sp;
    sp.pos = {0, 0, 20};
    sp.acc = {command, 0, 0};
    std::vector<std::pair<double, double>> trace;
    Fly(
        controller, 2.0, [&](double, const VehicleState&) { return sp; },
        [&](double t, const VehicleState& s, const Setpoint&) {
          trace.emplace_back(t, Tilt(s.quat));
        });
    StepResult r;
    int n = 0;
    double peak = 0;
    for (const auto& [t, tilt] : trace) {
      peak = std::max(peak, tilt);
      if (t >= 1.5) {
        r.final_tilt += tilt;
        ++n;
      }
    }
    r.final_tilt /= n;
    r.overshoot = (peak - r.final_tilt) / r.final_tilt;
    double t10 = -1, t90 = -1;
    for (const auto& [t, tilt] : trace) {
      if (t10 < 0 && tilt >= 0.1 * r.final_tilt) t10 = t;
      if (t90 < 0 && tilt >= 0.9 * r.final_tilt) t90 = t;
      if (std::abs(tilt - r.final_tilt) > 0.02 * r.final_tilt) r.settle = t;  // last exit
    }
    r.rise = t90 - t10;
    return r;
  }
};

// Both plugins' tilt step (2 m/s^2, about 11.5 deg): the closed-loop attitude bandwidth, measured.
// A first-order loop of bandwidth w has a 10-90 % rise of 2.2 / w.
TEST_F(GeometricTest, StepResponsesOfBothPlugins) {
  Load("quadrotor.xml");
  Geometric geometric = MakeGeometric();
  PdCascade cascade = MakeCascade();
  const StepResult g = TiltStep(geometric, 2.0);
  const StepResult c = TiltStep(cascade, 2.0);
  for (const auto& [name, r] : {std::pair{"geometric", g}, std::pair{"pd_cascade", c}}) {
    std::printf(
        "%-10s tilt step: final %.4f rad, 10-90 %% rise %.3f s (bandwidth ~ %.1f rad/s), 2 %% "
        "settling %.3f s, overshoot %.2f %%\n",
        name, r.final_tilt, r.rise, 2.2 / r.rise, r.settle, 100 * r.overshoot);
    EXPECT_LT(r.overshoot, 0.10) << name;
    EXPECT_LT(r.settle, 0.8) << name;
    EXPECT_GT(r.rise, 0) << name;
  }
  // The geometric loop tilts to atan(a / g) exactly (F = m (a + g e3)); eq. (9) to a / g.
  EXPECT_NEAR(g.final_tilt, std::atan(2.0 / Gravity()), 2e-3);
  EXPECT_NEAR(c.final_tilt, 2.0 / Gravity(), 2e-3);
  const auto& k = geometric.derived();
  std::printf(
      "geometric derived (Iris): k_rate %.2f 1/s, k_att %.2f 1/s, k_yaw %.2f 1/s, kp_z "
      "%.2f, kd_z %.2f, ki_z %.2f\n",
      k.k_rate, k.k_att, k.k_yaw, k.kp_z, k.kd_z, k.ki_z);
}

// The nonlinear map: a 8 m/s^2 command gives 8 m/s^2 (tilt atan(8 / g) = 39 deg) at constant
// altitude; 20 m/s^2 is held at tilt_max with the altitude kept (altitude priority).
TEST_F(GeometricTest, AccelerationIsExactAndAltitudeHasPriority) {
  Load("quadrotor.xml");
  for (double command : {8.0, 20.0}) {
    PlaceFree({0, 0, 20});
    Geometric controller = MakeGeometric();
    Setpoint sp;
    sp.pos = {0, 0, 20};
    sp.acc = {0, command, 0};
    VehicleState before;
    double peak_tilt = 0;
    Fly(
        controller, 2.0, [&](double, const VehicleState&) { return sp; },
        [&](double t, const VehicleState& s, const Setpoint&) {
          peak_tilt = std::max(peak_tilt, Tilt(s.quat));
          if (std::abs(t - 1.5) < 1e-9) before = s;
        });
    const VehicleState after = State();
    const double acc = (after.vel[1] - before.vel[1]) / 0.5;
    const double tilt_max = controller.gains().tilt_max;
    const double expected = std::min(command, Gravity() * std::tan(tilt_max));
    std::printf("command %.0f m/s^2: acc %.3f (expected %.3f), tilt %.4f, peak %.4f rad, z %.3f\n",
                command, acc, expected, Tilt(after.quat), peak_tilt, after.pos[2]);
    EXPECT_NEAR(acc, expected, 0.03 * expected);
    EXPECT_LE(peak_tilt, std::min(std::atan(command / Gravity()), tilt_max) + 0.03);
    EXPECT_NEAR(after.pos[2], 20, 0.15);
    EXPECT_NEAR(after.vel[0], 0, 0.05);
  }
}

// 100 deg of tilt about several axes (one past pitch 90 deg, where ZYX Euler angles are singular)
// and a yaw far from the setpoint: the vehicle turns back the short way, never beyond where it
// started, is level within 3 s and does not fall far.
TEST_F(GeometricTest, RecoversFromA100DegreeErrorWithoutFlipping) {
  Load("quadrotor.xml");
  const double start_tilt = 100 * M_PI / 180;
  const std::array<double, 3> axes[] = {{1, 0, 0}, {0, 1, 0}, {0.6, -0.8, 0}};
  for (const auto& axis : axes) {
    for (double yaw : {0.0, 2.5}) {
      PlaceFree({0, 0, 30});
      SetAttitude(start_tilt, axis, yaw);
      Geometric controller = MakeGeometric();
      Setpoint sp;
      sp.pos = {0, 0, 30};
      double peak = 0, level_at = -1, lowest = 30;
      Fly(
          controller, 6.0, [&](double, const VehicleState&) { return sp; },
          [&](double t, const VehicleState& s, const Setpoint&) {
            const double tilt = Tilt(s.quat);
            peak = std::max(peak, tilt);
            if (tilt > 0.05) level_at = -1;
            if (tilt <= 0.05 && level_at < 0) level_at = t;
            lowest = std::min(lowest, s.pos[2]);
          });
      std::printf(
          "axis (%.1f, %.1f) yaw %.1f: peak tilt %.1f deg, level (< 3 deg) from %.2f s, "
          "lowest %.2f m, final yaw %.3f rad\n",
          axis[0], axis[1], yaw, peak * 180 / M_PI, level_at, lowest,
          attitude::EulerZYX(State().quat)[2]);
      EXPECT_LE(peak, start_tilt + 0.02) << "turned the long way (flip)";
      EXPECT_GE(level_at, 0);
      EXPECT_LT(level_at, 3.0);
      EXPECT_GT(lowest, 30 - 3.0);
      EXPECT_NEAR(attitude::EulerZYX(State().quat)[2], 0, 0.02);
    }
  }
}

// The same default attributes hover the Iris and a 4 kg, wider, slower vehicle (test-only model)
// within 0.1 m from 8 s after a disturbed start (hover guidance: 1 rad/s); gains come from each
// vehicle's info.
TEST_F(GeometricTest, SameDefaultsHoverAHeavierWiderVehicle) {
  for (const std::string& file : {std::string("quadrotor.xml"), kHeavy}) {
    Load(file);
    Geometric controller = MakeGeometric();
    const double worst = DisturbedHover(controller, {1, 2, 5}, 8.0, 20.0);
    const auto& k = controller.derived();
    std::printf(
        "%s: mass %.2f kg, lag %.3f s -> k_rate %.1f, k_att %.1f; max error 8..20 s "
        "%.2e m\n",
        file.substr(file.rfind('/') + 1).c_str(), Mass(), MotorLag(), k.k_rate, k.k_att, worst);
    EXPECT_LT(worst, 0.1) << file;
    TearDown();
    m_ = nullptr;
    d_ = nullptr;
  }
}

// q and -q are one attitude: the controls are identical, bit for bit.
TEST_F(GeometricTest, QuaternionSignGivesTheSameControls) {
  Load("quadrotor.xml");
  const std::array<double, 4> attitudes[] = {
      {1, 0, 0, 0}, {0.9, 0.3, -0.2, 0.1}, {0.1, 0.7, 0.7, 0.1}, {-0.2, 0.3, 0.9, -0.2}};
  for (auto quat : attitudes) {
    const double n =
        std::sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
    for (double& c : quat) c /= n;
    VehicleState s;
    s.pos = {0, 0, 4};
    s.vel = {0.5, -0.2, 0.1};
    s.gyro = {0.3, -0.1, 0.2};
    s.quat = quat;
    VehicleState flipped = s;
    for (double& c : flipped.quat) c = -c;
    Setpoint sp;
    sp.pos = {0, 0, 5};
    sp.acc = {1.5, -0.5, 0};
    sp.yaw = 0.4;
    Geometric a = MakeGeometric(), b = MakeGeometric();
    for (int step = 0; step < 3; ++step) {  // integrators too
      const auto ua = a.Update(s, sp, 0.001), ub = b.Update(flipped, sp, 0.001);
      for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(ua.ctrl[k], ub.ctrl[k]);
      for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(ua.attitude_error[i], ub.attitude_error[i]);
    }
  }
}

// Saturation: the geometric plugin's mixer keeps roll/pitch and moves the collective to make
// room, and gives up yaw first; the thrust-first mode (pd_cascade) loses roll at full thrust.
TEST(MixerPriorityTest, RollPitchFirstKeepsAttitudeAndGivesUpYawFirst) {
  std::array<attitude::RotorGeometry, 4> rotors;
  const double x[4] = {0.13, -0.13, 0.13, -0.13}, y[4] = {-0.22, 0.22, 0.22, -0.22};
  const double c[4] = {-0.06, -0.06, 0.06, 0.06};
  for (int k = 0; k < 4; ++k) {
    rotors[k].pos = {x[k], y[k], 0};
    rotors[k].gear = {0, 0, 1, 0, 0, c[k]};
    rotors[k].ctrl_max = 7;
  }
  const Mixer mixer(rotors);
  const auto delivered = [&](const Mixer::Result& r) -> Eigen::Vector4d {
    return mixer.allocation() * Eigen::Vector4d(r.ctrl[0], r.ctrl[1], r.ctrl[2], r.ctrl[3]);
  };
  // Full thrust plus a roll torque: thrust-first delivers no roll, roll/pitch-first all of it.
  const attitude::Wrench full(28, 0.8, 0, 0);
  const auto thrust_first = mixer.Mix(full, Mixer::Priority::kThrustFirst);
  const auto rp_first = mixer.Mix(full, Mixer::Priority::kRollPitchFirst);
  EXPECT_NEAR(delivered(thrust_first)[1], 0, 1e-9);
  EXPECT_NEAR(delivered(rp_first)[1], 0.8, 1e-9);
  EXPECT_DOUBLE_EQ(rp_first.roll_pitch_scale, 1);
  EXPECT_TRUE(rp_first.thrust_saturated);
  EXPECT_NEAR(delivered(rp_first)[0], rp_first.thrust, 1e-9);
  EXPECT_LT(rp_first.thrust, 28);
  EXPECT_GT(rp_first.thrust, 24);  // only as much as the roll torque needs
  // Roll plus too much yaw: roll and thrust kept, yaw cut (but kept in sign).
  const attitude::Wrench yaw_heavy(15, 0.5, 0, 2);
  const auto r = mixer.Mix(yaw_heavy, Mixer::Priority::kRollPitchFirst);
  const Eigen::Vector4d got = delivered(r);
  EXPECT_NEAR(got[0], 15, 1e-9);
  EXPECT_NEAR(got[1], 0.5, 1e-9);
  EXPECT_LT(r.yaw_scale, 1);
  EXPECT_GT(got[3], 0);
  // A roll/pitch torque beyond any collective: scaled down with its direction kept.
  const auto big = mixer.Mix(attitude::Wrench(15, 3, 2, 0), Mixer::Priority::kRollPitchFirst);
  const Eigen::Vector4d b = delivered(big);
  EXPECT_LT(big.roll_pitch_scale, 1);
  EXPECT_GT(big.roll_pitch_scale, 0);
  EXPECT_NEAR(b[1] / b[2], 1.5, 1e-6);
  for (double v : big.ctrl) {
    EXPECT_GE(v, 0);
    EXPECT_LE(v, 7);
  }
  // Within range: the same rotor commands as thrust-first.
  const attitude::Wrench easy(15, 0.1, -0.1, 0.02);
  const auto e1 = mixer.Mix(easy, Mixer::Priority::kThrustFirst);
  const auto e2 = mixer.Mix(easy, Mixer::Priority::kRollPitchFirst);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(e1.ctrl[k], e2.ctrl[k], 1e-12);
}

TEST(GeometricConfigTest, RefusesBadGainsWithTheReason) {
  std::array<attitude::RotorGeometry, 4> rotors;
  const double x[4] = {0.13, -0.13, 0.13, -0.13}, y[4] = {-0.22, 0.22, 0.22, -0.22};
  for (int k = 0; k < 4; ++k) {
    rotors[k].pos = {x[k], y[k], 0};
    rotors[k].gear = {0, 0, 1, 0, 0, k < 2 ? -0.06 : 0.06};
    rotors[k].ctrl_max = 7;
  }
  Geometric::Vehicle v;
  v.mass = 1.5;
  v.gravity = 9.81;
  v.inertia = {0.03, 0.03, 0.05};
  v.motor_lag = 0.025;
  EXPECT_NO_THROW(Geometric(Geometric::Gains{}, v, rotors));
  const auto message = [&](const Geometric::Gains& g, const Geometric::Vehicle& veh) {
    try {
      Geometric controller(g, veh, rotors);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  Geometric::Gains g;
  g.tilt_max = 1.6;
  EXPECT_NE(message(g, v).find("tilt_max"), std::string::npos);
  g = {};
  g.rate_bw = 60;  // 60 x 0.025 = 1.5 > 1
  EXPECT_NE(message(g, v).find("beyond the motors"), std::string::npos) << message(g, v);
  g = {};
  g.att_bw = 20;  // > rate_bw / 2 = 16.7
  EXPECT_NE(message(g, v).find("att_bw"), std::string::npos) << message(g, v);
  g = {};
  g.z_bw = 9;  // > att_bw = 8.3
  EXPECT_NE(message(g, v).find("z_bw"), std::string::npos) << message(g, v);
  g = {};
  g.yaw_bw = -1;
  EXPECT_NE(message(g, v).find("yaw_bw"), std::string::npos);
  g = {};
  g.rate_ki = 0.8;
  EXPECT_NE(message(g, v).find("rate_ki"), std::string::npos);
  Geometric::Vehicle heavy = v;
  heavy.mass = 3;  // 28 N x 0.9 < 1.05 x 29.4 N
  EXPECT_NE(message(Geometric::Gains{}, heavy).find("cannot hover"), std::string::npos);
}

}  // namespace
}  // namespace mjf::test
