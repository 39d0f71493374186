// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjcf/pointmass.xml with PointMassDirect: an exact double integrator.
#include "mjformation/attitude/pointmass_direct.hpp"

#include <cmath>
#include <cstdio>

#include "vehicle_fixture.hpp"

namespace mjf::test {
namespace {

using attitude::PointMassDirect;
using attitude::Setpoint;
using attitude::VehicleState;

class PointMassTest : public VehicleFixture {
 protected:
  void SetUp() override { Load("pointmass.xml"); }
};

TEST_F(PointMassTest, ModelFollowsTheContract) {
  EXPECT_EQ(m_->nu, 3);
  EXPECT_NEAR(Mass(), 1.0, 1e-12);
  for (const char* name : {"fx", "fy", "fz"}) EXPECT_GE(mj_name2id(m_, mjOBJ_ACTUATOR, name), 0);
  EXPECT_EQ(m_->actuator_trntype[0], mjTRN_JOINT);
}

TEST_F(PointMassTest, AccelerationEqualsTheCommand) {
  mj_resetData(m_, d_);
  const double z0 = m_->body_pos[3 * body_ + 2];
  PointMassDirect controller(PointMassDirect::Gains{}, Mass(), Gravity());
  double worst = 0;
  VehicleState previous;
  Setpoint previous_sp;
  bool have_previous = false;
  for (int i = 0; i < 3000; ++i) {
    const double t = d_->time;
    Setpoint sp;
    sp.acc = {std::sin(1.3 * t) + 0.5, -0.7 * std::cos(0.9 * t), 0.2 * std::sin(2 * t)};
    sp.pos = {0, 0, z0 + 1};
    sp.vel = {0, 0, 0.1};
    Step([&](const VehicleState& s) {
      if (have_previous) {
        // Finite difference of the velocity sensor vs what the previous command asked for.
        for (int j = 0; j < 3; ++j) {
          const double measured = (s.vel[j] - previous.vel[j]) / m_->opt.timestep;
          double expected = previous_sp.acc[j];
          if (j == 2) {
            expected += 6 * (previous_sp.pos[2] - previous.pos[2]) +
                        5 * (previous_sp.vel[2] - previous.vel[2]);
          }
          worst =
              std::max(worst, std::abs(measured - expected) / std::max(1.0, std::abs(expected)));
        }
      }
      const auto force = controller.Update(s, sp);
      for (int j = 0; j < 3; ++j) d_->ctrl[j] = force[j];
      previous = s;
      previous_sp = sp;
      have_previous = true;
    });
  }
  std::printf("point mass: max relative |a - a_cmd| = %.3e\n", worst);
  EXPECT_LT(worst, 1e-6);
  const VehicleState s = State();
  EXPECT_NEAR(s.quat[0], 1, 1e-12);
  EXPECT_NEAR(s.gyro[0], 0, 1e-12);
}

TEST_F(PointMassTest, HoldsAltitudeUnderGravity) {
  mj_resetData(m_, d_);
  PointMassDirect controller(PointMassDirect::Gains{}, Mass(), Gravity());
  Setpoint sp;
  sp.pos = {0, 0, 3};
  for (int i = 0; i < 5000; ++i) {
    Step([&](const VehicleState& s) {
      const auto force = controller.Update(s, sp);
      for (int j = 0; j < 3; ++j) d_->ctrl[j] = force[j];
    });
  }
  EXPECT_NEAR(State().pos[2], 3, 1e-3);
  EXPECT_NEAR(State().pos[0], 0, 1e-12);
}

TEST(PointMassDirectTest, RefusesBadConfiguration) {
  EXPECT_THROW(PointMassDirect(PointMassDirect::Gains{}, 0, 9.81), std::invalid_argument);
  EXPECT_THROW(PointMassDirect(PointMassDirect::Gains{-1, 0}, 1, 9.81), std::invalid_argument);
}

}  // namespace
}  // namespace mjf::test
