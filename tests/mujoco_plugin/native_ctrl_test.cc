// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// ctrl as an input (docs/PLUGINS.md, "Actuation"): d->ctrl of a driven rotor is an additive
// trim on the controllers' command, clamped with it to ctrlrange, read at every evaluation.
// ctrl = 0 flies the runner's bits (ctest NativeFlight.*, NativeState.*); here a trim acts on
// its own vehicle, through the plant, as mjd_transitionFD's B says, and within ctrlrange.
// MuJoCo's C API alone flies the exported Exp 2.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/export/export.hpp"
#include "native_fixture.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::LoadNativePluginsOnce;
using mjf::testing::NativeExperimentText;
using mjf::testing::Scratch;

struct MujocoRaised : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void Raise(const char* message) { throw MujocoRaised(message); }

// The vehicle (root body) actuator a moves: the rotors act at sites of the vehicle.
int VehicleOfActuator(const mjModel* m, int a) {
  EXPECT_EQ(m->actuator_trntype[a], mjTRN_SITE) << "actuator " << a;
  return m->body_rootid[m->site_bodyid[m->actuator_trnid[2 * a]]];
}

// The vehicles whose qpos, qvel or act differ in any bit between a and b.
std::set<int> VehiclesThatDiffer(const mjModel* m, const mjData* a, const mjData* b) {
  std::set<int> differ;
  for (int j = 0; j < m->njnt; ++j) {
    const int vehicle = m->body_rootid[m->jnt_bodyid[j]];
    const int nq = (j + 1 < m->njnt ? m->jnt_qposadr[j + 1] : m->nq) - m->jnt_qposadr[j];
    const int nv = (j + 1 < m->njnt ? m->jnt_dofadr[j + 1] : m->nv) - m->jnt_dofadr[j];
    const size_t qpos = sizeof(mjtNum) * nq, qvel = sizeof(mjtNum) * nv;
    if (std::memcmp(a->qpos + m->jnt_qposadr[j], b->qpos + m->jnt_qposadr[j], qpos) != 0 ||
        std::memcmp(a->qvel + m->jnt_dofadr[j], b->qvel + m->jnt_dofadr[j], qvel) != 0) {
      differ.insert(vehicle);
    }
  }
  for (int u = 0; u < m->nu; ++u) {
    const int adr = m->actuator_actadr[u];
    if (adr < 0) continue;
    const size_t n = sizeof(mjtNum) * m->actuator_actnum[u];
    if (std::memcmp(a->act + adr, b->act + adr, n) != 0) differ.insert(VehicleOfActuator(m, u));
  }
  return differ;
}

// The vehicle each row of mjd_transitionFD's state (dq, qvel, act) belongs to.
std::vector<int> VehicleOfRow(const mjModel* m) {
  std::vector<int> rows;
  for (int pass = 0; pass < 2; ++pass) {
    for (int v = 0; v < m->nv; ++v) rows.push_back(m->body_rootid[m->dof_bodyid[v]]);
  }
  for (int u = 0; u < m->nu; ++u) {
    for (int i = 0; i < std::max(0, m->actuator_actnum[u]); ++i) {
      rows.push_back(VehicleOfActuator(m, u));
    }
  }
  return rows;
}

class NativeCtrl : public ::testing::Test {
 protected:
  void SetUp() override {
    LoadNativePluginsOnce();
    mju_user_error = Raise;
    std::ofstream(dir_ / "exp2.toml") << NativeExperimentText("exp2.toml");
    ExportExperiment(dir_ / "exp2.toml", dir_ / "export", {{}, {}, /*overwrite=*/true});
    char error[2048] = {0};
    m_ = mj_loadXML((dir_ / "export/scene.xml").c_str(), nullptr, error, sizeof(error));
    ASSERT_NE(m_, nullptr) << error;
    ASSERT_GT(m_->nu, 4);
    rotor_ = m_->nu / 2;  // a rotor of a vehicle in the middle of the formation
  }
  void TearDown() override {
    for (mjData* d : datas_) mj_deleteData(d);
    if (m_) mj_deleteModel(m_);
  }
  mjData* Make() { return datas_.emplace_back(mj_makeData(m_)); }
  mjData* Copy(const mjData* d) { return datas_.emplace_back(mj_copyData(nullptr, m_, d)); }
  void Step(mjData* d, int steps) {
    for (int k = 0; k < steps; ++k) mj_step(m_, d);
  }

  Scratch dir_{"ctrl"};
  mjModel* m_ = nullptr;
  int rotor_ = 0;
  std::vector<mjData*> datas_;
};

// A constant trim on one rotor changes its vehicle's flight and, for the first steps (until the
// formation law has seen it), no other vehicle's.
TEST_F(NativeCtrl, TrimOnOneRotorMovesItsVehicleFirst) {
  const int vehicle = VehicleOfActuator(m_, rotor_);
  mjData* plain = Make();
  mjData* trimmed = Make();
  trimmed->ctrl[m_->actuator_ctrladr[rotor_]] = 0.5;  // N, a tenth of the rotor's range
  for (int k = 1; k <= 2; ++k) {
    Step(plain, 1);
    Step(trimmed, 1);
    EXPECT_EQ(VehiclesThatDiffer(m_, plain, trimmed), std::set<int>{vehicle}) << "step " << k;
  }
  Step(plain, 500);
  Step(trimmed, 500);
  const mjtNum* p = plain->xpos + 3 * vehicle;
  const mjtNum* t = trimmed->xpos + 3 * vehicle;
  EXPECT_GT(mju_dist3(p, t), 1e-4) << "the trim moved the vehicle too little to see";
}

// mjd_transitionFD's B: non-zero in every driven rotor's column, and only in the rows of that
// rotor's vehicle; a column equals a finite difference taken by hand over copies.
TEST_F(NativeCtrl, TransitionFdBIsTheTrimsThroughThePlant) {
  mjData* d = Make();
  Step(d, 1000);
  const int nx = 2 * m_->nv + m_->na, nu = m_->nu;
  const mjtNum eps = 1e-6;
  std::vector<mjtNum> B(nx * nu);
  mjd_transitionFD(m_, d, eps, 0, nullptr, B.data(), nullptr, nullptr);
  const std::vector<int> row_vehicle = VehicleOfRow(m_);
  ASSERT_EQ(static_cast<int>(row_vehicle.size()), nx);
  for (int u = 0; u < nu; ++u) {
    const int vehicle = VehicleOfActuator(m_, u);
    bool nonzero = false;
    for (int r = 0; r < nx; ++r) {
      if (B[r * nu + u] == 0) continue;
      nonzero = true;
      EXPECT_EQ(row_vehicle[r], vehicle) << "control " << u << " moves row " << r;
    }
    EXPECT_TRUE(nonzero) << "control " << u << " has no effect";
  }
  // By hand: one step with the trim nudged, one without, from copies of d.
  mjData* base = Copy(d);
  mjData* nudged = Copy(d);
  nudged->ctrl[m_->actuator_ctrladr[rotor_]] += eps;
  Step(base, 1);
  Step(nudged, 1);
  std::vector<mjtNum> column(nx);
  mj_differentiatePos(m_, column.data(), eps, base->qpos, nudged->qpos);
  for (int v = 0; v < m_->nv; ++v) column[m_->nv + v] = (nudged->qvel[v] - base->qvel[v]) / eps;
  for (int i = 0; i < m_->na; ++i) column[2 * m_->nv + i] = (nudged->act[i] - base->act[i]) / eps;
  for (int r = 0; r < nx; ++r) {
    EXPECT_NEAR(B[r * nu + rotor_], column[r], 1e-9 * (1 + std::fabs(column[r]))) << "row " << r;
  }
}

// A trim past ctrlrange is clamped with the command: the motor lag heads for the range's end.
// A bad control zeroes every trim.
TEST_F(NativeCtrl, TrimPastCtrlrangeIsClamped) {
  mjData* d = Make();
  Step(d, 500);
  const int c = m_->actuator_ctrladr[rotor_];
  const int adr = m_->actuator_actadr[rotor_];
  ASSERT_TRUE(m_->actuator_ctrllimited[c]);
  ASSERT_GE(adr, 0);
  const mjtNum tau = mju_max(mjMINVAL, m_->actuator_dynprm[mjNDYN * rotor_]);
  for (const mjtNum trim : {1e3, 1e6, -1e3}) {
    mjData* trimmed = Copy(d);
    trimmed->ctrl[c] = trim;
    mj_forward(m_, trimmed);
    const mjtNum end = m_->actuator_ctrlrange[2 * c + (trim > 0 ? 1 : 0)];
    EXPECT_EQ(trimmed->act_dot[adr], (end - trimmed->act[adr]) / tau) << "trim " << trim;
  }
  // A bad control elsewhere (MuJoCo's mjWARN_BADCTRL zeroes every control) zeroes the trim too.
  mjData* plain = Copy(d);
  mjData* bad = Copy(d);
  bad->ctrl[c] = 1e3;
  bad->ctrl[m_->actuator_ctrladr[(rotor_ + 1) % m_->nu]] = std::nan("");
  mj_forward(m_, plain);
  mj_forward(m_, bad);
  EXPECT_EQ(bad->act_dot[adr], plain->act_dot[adr]);
}

}  // namespace
}  // namespace mjf::runner
