// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A MuJoCo fixture for the vehicle tests: loads a file of mjcf/, reads the contract's sensors,
// resolves rotor geometry the way the runner does, and fails the test on any MuJoCo warning.
#ifndef MJFORMATION_TESTS_VEHICLE_FIXTURE_HPP_
#define MJFORMATION_TESTS_VEHICLE_FIXTURE_HPP_

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mjformation/attitude/mixer.hpp"
#include "mjformation/attitude/types.hpp"

namespace mjf::test {

class VehicleFixture : public ::testing::Test {
 protected:
  // file: a name in mjcf/, or an absolute path (test-only models).
  void Load(const std::string& file) {
    const std::string path =
        file.rfind('/', 0) == 0 ? file : std::string(MJF_MJCF_DIR) + "/" + file;
    char error[1024] = {0};
    m_ = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
    ASSERT_NE(m_, nullptr) << path << ": " << error;
    d_ = mj_makeData(m_);
    body_ = mj_name2id(m_, mjOBJ_BODY, "vehicle");
    ASSERT_GE(body_, 0);
    for (const char* name : {"pos", "vel", "quat", "gyro"}) {
      const int id = mj_name2id(m_, mjOBJ_SENSOR, name);
      ASSERT_GE(id, 0) << "sensor " << name;
      sensor_adr_.push_back(m_->sensor_adr[id]);
    }
    mj_forward(m_, d_);
  }

  void TearDown() override {
    if (d_) {
      for (int i = 0; i < mjNWARNING; ++i) {
        EXPECT_EQ(d_->warning[i].number, 0) << "MuJoCo warning " << i;
      }
      mj_deleteData(d_);
    }
    if (m_) mj_deleteModel(m_);
  }

  // Places a free-joint vehicle at pos with the given yaw (rad), at rest.
  void PlaceFree(const std::array<double, 3>& pos, double yaw = 0) {
    mj_resetData(m_, d_);
    for (int i = 0; i < 3; ++i) d_->qpos[i] = pos[i];
    d_->qpos[3] = std::cos(yaw / 2);
    d_->qpos[6] = std::sin(yaw / 2);
    mj_forward(m_, d_);
  }

  attitude::VehicleState State() const {
    attitude::VehicleState s;
    const double* sd = d_->sensordata;
    for (int i = 0; i < 3; ++i) {
      s.pos[i] = sd[sensor_adr_[0] + i];
      s.vel[i] = sd[sensor_adr_[1] + i];
      s.gyro[i] = sd[sensor_adr_[3] + i];
    }
    for (int i = 0; i < 4; ++i) s.quat[i] = sd[sensor_adr_[2] + i];
    return s;
  }

  // mj_step split as the runner does it: step1 (sensors of the current state), then the caller's
  // controls, then step2. Checks the warnings after each step.
  template <typename Control>
  void Step(Control control) {
    mj_step1(m_, d_);
    control(State());
    mj_step2(m_, d_);
    for (int i = 0; i < mjNWARNING; ++i) {
      ASSERT_EQ(d_->warning[i].number, 0) << "MuJoCo warning " << i << " at t = " << d_->time;
    }
  }

  // Rotor geometry as the runner fills mjfActuatorInfo: site relative to the body's centre of
  // mass in body axes, gear, ctrlrange.
  std::array<attitude::RotorGeometry, 4> Rotors() const {
    std::array<attitude::RotorGeometry, 4> rotors;
    for (int k = 0; k < 4; ++k) {
      const std::string name = "rotor" + std::to_string(k);
      const int a = mj_name2id(m_, mjOBJ_ACTUATOR, name.c_str());
      EXPECT_GE(a, 0) << name;
      const int site = m_->actuator_trnid[2 * a];
      double rel[3];
      mju_sub3(rel, d_->site_xpos + 3 * site, d_->xipos + 3 * body_);
      mju_mulMatTVec(rotors[k].pos.data(), d_->xmat + 9 * body_, rel, 3, 3);
      for (int i = 0; i < 6; ++i) rotors[k].gear[i] = m_->actuator_gear[6 * a + i];
      rotors[k].ctrl_min = m_->actuator_ctrlrange[2 * a];
      rotors[k].ctrl_max = m_->actuator_ctrlrange[2 * a + 1];
    }
    return rotors;
  }

  // Slowest rotor's first-order time constant (dyntype filter), s.
  double MotorLag() const {
    double lag = 0;
    for (int a = 0; a < m_->nu; ++a) {
      if (m_->actuator_dyntype[a] == mjDYN_FILTER)
        lag = std::max(lag, m_->actuator_dynprm[mjNDYN * a]);
    }
    return lag;
  }

  double Mass() const { return m_->body_subtreemass[body_]; }
  double Gravity() const { return mju_norm3(m_->opt.gravity); }
  std::array<double, 3> Inertia() const {
    return {m_->body_inertia[3 * body_], m_->body_inertia[3 * body_ + 1],
            m_->body_inertia[3 * body_ + 2]};
  }

  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  int body_ = -1;
  std::vector<int> sensor_adr_;
};

}  // namespace mjf::test

#endif  // MJFORMATION_TESTS_VEHICLE_FIXTURE_HPP_
