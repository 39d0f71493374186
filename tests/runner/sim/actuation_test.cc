// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/sim/src/actuation.cc: MuJoCo's actuators (d->ctrl) against the runner's wrench model
// (qfrc_passive) on a tiny model: the wrench model must give the generalized force MuJoCo's own
// site actuators give (qfrc_actuator), clamping and motor lag included; the wrench at the centre
// of mass against MuJoCo's mj_applyFT.
#include "mjformation/sim/actuation.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

// One tilted free body with two rotor sites (one turned about its own z) driving site actuators
// with force along z and a yaw torque; `dyn` adds first-order motor lag.
std::string TinyVehicle(bool lag) {
  const std::string dyn = lag ? " dyntype=\"filter\" dynprm=\"0.05\"" : "";
  return "<mujoco><option timestep=\"0.001\" gravity=\"0 0 -9.81\"/><worldbody>"
         "<body name=\"fixed\" pos=\"5 0 0\"><geom size=\"0.1\"/></body>"
         "<body name=\"vehicle\" pos=\"0.3 -0.2 1\" quat=\"0.96 0.1 -0.2 0.15\">"
         "<freejoint/><geom type=\"box\" size=\"0.2 0.1 0.03\" mass=\"1.3\" pos=\"0.02 0 0\"/>"
         "<site name=\"r0\" pos=\"0.2 0.05 0.01\"/>"
         "<site name=\"r1\" pos=\"-0.15 -0.1 0\" euler=\"0.1 0 0.5\"/></body></worldbody>"
         "<actuator><general name=\"a0\" site=\"r0\" gear=\"0 0 1 0 0 0.05\" ctrllimited=\"true\" "
         "ctrlrange=\"0 10\"" +
         dyn +
         "/>"
         "<general name=\"a1\" site=\"r1\" gear=\"0 0 1 0 0 -0.05\" ctrllimited=\"true\" "
         "ctrlrange=\"0 10\"" +
         dyn + "/></actuator></mujoco>";
}

struct Tiny {
  explicit Tiny(bool lag) {
    const std::string path = mjf::testing::TempDir("act") + "/tiny.xml";
    std::ofstream(path) << TinyVehicle(lag);
    char error[512] = "";
    m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
    EXPECT_NE(m, nullptr) << error;
    d = mj_makeData(m);
    mj_forward(m, d);
    // The binding BindVehicles would make of this one vehicle.
    VehicleBinding& b = bindings.vehicles.emplace_back();
    b.body = mj_name2id(m, mjOBJ_BODY, "vehicle");
    for (int a = 0; a < m->nu; ++a) {
      b.actuators.push_back(a);
      b.sites.push_back(m->actuator_trnid[2 * a]);
      mjfActuatorInfo info{};
      std::memcpy(info.gear, m->actuator_gear + 6 * a, sizeof(info.gear));
      info.ctrl_min = m->actuator_ctrlrange[2 * a];
      info.ctrl_max = m->actuator_ctrlrange[2 * a + 1];
      info.time_constant =
          m->actuator_dyntype[a] == mjDYN_FILTER ? m->actuator_dynprm[mjNDYN * a] : 0;
      b.actuator_info.push_back(info);
      bindings.wrench_gain.push_back(m->actuator_gainprm[mjNGAIN * a]);
    }
    bindings.actuators_per_vehicle = m->nu;
  }
  ~Tiny() {
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  // MuJoCo's generalized actuator force for these controls (and motor states).
  std::vector<double> MujocoForce(const std::vector<double>& ctrl,
                                  const std::vector<double>& act = {}) {
    mjData* e = mj_makeData(m);
    for (int a = 0; a < m->nu; ++a) e->ctrl[a] = ctrl[a];
    for (int a = 0; a < m->na; ++a) e->act[a] = act[a];
    mj_forward(m, e);
    std::vector<double> f(e->qfrc_actuator, e->qfrc_actuator + m->nv);
    mj_deleteData(e);
    return f;
  }
  mjModel* m = nullptr;
  mjData* d = nullptr;
  VehicleBindings bindings;
};

void ExpectNear(const double* got, const std::vector<double>& want, double tol) {
  for (size_t j = 0; j < want.size(); ++j) EXPECT_NEAR(got[j], want[j], tol) << "dof " << j;
}

TEST(ActuationTest, ActuatorModelWritesTheControlsToMujoco) {
  Tiny t(false);
  auto act = MakeActuation(RotorModel::kActuator, t.m, t.bindings, 0.001);
  act->Apply({3.0, 4.5}, t.d);
  EXPECT_EQ(t.d->ctrl[0], 3.0);
  EXPECT_EQ(t.d->ctrl[1], 4.5);
  for (int j = 0; j < t.m->nv; ++j) EXPECT_EQ(t.d->qfrc_passive[j], 0.0);
}

TEST(ActuationTest, WrenchModelGivesMujocosActuatorForce) {
  Tiny t(false);
  auto act = MakeActuation(RotorModel::kWrench, t.m, t.bindings, 0.001);
  for (const std::vector<double>& ctrl :
       {std::vector<double>{3.0, 4.5}, {0.0, 7.25}, {12.0, -1.0} /* clamped to [0, 10] */}) {
    mju_zero(t.d->qfrc_passive, t.m->nv);
    act->Apply(ctrl, t.d);
    ExpectNear(t.d->qfrc_passive, t.MujocoForce(ctrl), 1e-12);
    for (int a = 0; a < t.m->nu; ++a) EXPECT_EQ(t.d->ctrl[a], 0.0);  // no actuator touched
  }
  // A nonzero force at all (a test comparing zeros would pass on a no-op).
  double norm = 0;
  for (int j = 0; j < t.m->nv; ++j) norm += std::abs(t.d->qfrc_passive[j]);
  EXPECT_GT(norm, 1.0);
}

TEST(ActuationTest, WrenchModelMotorLagFollowsMujocosFilter) {
  Tiny t(true);
  auto act = MakeActuation(RotorModel::kWrench, t.m, t.bindings, 0.001);
  const std::vector<double> ctrl = {10.0, 4.0};
  // Motors start at rest: no force before the first Advance.
  act->Apply(ctrl, t.d);
  for (int j = 0; j < t.m->nv; ++j) EXPECT_EQ(t.d->qfrc_passive[j], 0.0);
  // act += dt (ctrl - act) / tau, as MuJoCo's Euler filter: 0.2 and 0.08 after one step.
  act->Advance(ctrl);
  mju_zero(t.d->qfrc_passive, t.m->nv);
  act->Apply(ctrl, t.d);
  ExpectNear(t.d->qfrc_passive, t.MujocoForce(ctrl, {0.2, 0.08}), 1e-12);
  act->Advance({20.0, 4.0});  // clamped to 10 before it enters the lag
  mju_zero(t.d->qfrc_passive, t.m->nv);
  act->Apply(ctrl, t.d);
  const double a0 = 0.2 + 0.001 * (10.0 - 0.2) / 0.05, a1 = 0.08 + 0.001 * (4.0 - 0.08) / 0.05;
  ExpectNear(t.d->qfrc_passive, t.MujocoForce(ctrl, {a0, a1}), 1e-12);
}

TEST(ActuationTest, WrenchAtTheCentreOfMassMatchesMjApplyFT) {
  Tiny t(false);
  const int body = mj_name2id(t.m, mjOBJ_BODY, "vehicle");
  const mjtNum wrench[6] = {1.5, -2.0, 9.0, 0.3, 0.1, -0.7};
  mju_zero(t.d->qfrc_passive, t.m->nv);
  AddWrenchAtCentreOfMass(t.m, t.d, body, wrench);
  std::vector<double> reference(t.m->nv, 0.0);
  mj_applyFT(t.m, t.d, wrench, wrench + 3, t.d->xipos + 3 * body, body, reference.data());
  ExpectNear(t.d->qfrc_passive, reference, 1e-12);
  // It adds to what is there.
  AddWrenchAtCentreOfMass(t.m, t.d, body, wrench);
  for (double& v : reference) v *= 2;
  ExpectNear(t.d->qfrc_passive, reference, 1e-12);
}

TEST(ActuationTest, NoDofsNoForce) {
  Tiny t(false);
  const mjtNum wrench[6] = {1, 2, 3, 4, 5, 6};
  mju_zero(t.d->qfrc_passive, t.m->nv);
  AddWrenchAtCentreOfMass(t.m, t.d, 0, wrench);                                     // the world
  AddWrenchAtCentreOfMass(t.m, t.d, mj_name2id(t.m, mjOBJ_BODY, "fixed"), wrench);  // welded
  for (int j = 0; j < t.m->nv; ++j) EXPECT_EQ(t.d->qfrc_passive[j], 0.0);
}

// The stage choice through a whole simulation: a hovering quadrotor flown by MuJoCo's
// actuators and by the wrench model stays the same to round-off.
TEST(ActuationTest, BothRotorModelsFlyTheSameQuadrotor) {
  const std::string text = mjf::testing::HoverExperiment(1, 0.05);
  ExperimentConfig actuator = mjf::testing::Parse(text);
  ExperimentConfig wrench = actuator;
  wrench.rotor_model = RotorModel::kWrench;
  Simulation a(actuator), w(wrench);
  for (int64_t step = 0; step < 50; ++step) {
    a.ComputeControls();
    w.ComputeControls();
    a.Integrate();
    w.Integrate();
  }
  a.ComputeControls();
  w.ComputeControls();
  for (int i = 0; i < a.n_vehicles(); ++i) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(a.states()[i].pos[k], w.states()[i].pos[k], 1e-9) << i << " " << k;
      EXPECT_NEAR(a.states()[i].vel[k], w.states()[i].vel[k], 1e-9) << i << " " << k;
    }
  }
  EXPECT_EQ(a.model()->nu, 8);  // two quadrotors' rotors
  EXPECT_EQ(w.model()->nu, 0);  // stripped: the rotors are wrenches
}

}  // namespace
}  // namespace mjf::runner
