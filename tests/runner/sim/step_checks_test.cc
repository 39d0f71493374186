// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/sim/src/step_checks.cc: a state with any non-finite qpos or qvel throws, naming the
// first one (with the partition's offset into the whole model); large, tiny, negative-zero and
// subnormal values are finite and pass (the branch-free screen must not miss or invent one).
#include "mjformation/sim/step_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "mjformation/control/errors.hpp"

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

// Two free bodies: nq 14, nv 12.
class StepChecksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string path =
        ::testing::TempDir() + "step_checks_" + std::to_string(getpid()) + ".xml";
    std::ofstream(path) << "<mujoco><worldbody>"
                           "<body><freejoint/><geom size='0.1'/></body>"
                           "<body pos='1 0 0'><freejoint/><geom size='0.1'/></body>"
                           "</worldbody></mujoco>";
    char error[256] = "";
    m_ = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
    std::remove(path.c_str());
    ASSERT_NE(m_, nullptr) << error;
    d_ = mj_makeData(m_);
    mj_forward(m_, d_);
  }
  void TearDown() override {
    mj_deleteData(d_);
    mj_deleteModel(m_);
  }
  // The message CheckStepState throws, or "" when it passes.
  std::string Check(StateOffsets offsets = {}) {
    try {
      CheckStepState(m_, d_, 1.5, offsets);
    } catch (const SimulationError& e) {
      return e.what();
    }
    return "";
  }
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
};

TEST_F(StepChecksTest, FiniteExtremesPass) {
  ASSERT_EQ(m_->nq, 14);
  ASSERT_EQ(m_->nv, 12);
  const double finite[] = {std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::min(),
                           -0.0,
                           1e300,
                           -1e-300};
  for (double v : finite) {
    for (int i = 0; i < m_->nq; ++i) d_->qpos[i] = v;
    for (int i = 0; i < m_->nv; ++i) d_->qvel[i] = v;
    EXPECT_EQ(Check(), "") << v;
  }
}

TEST_F(StepChecksTest, EachNonFiniteValueIsNamedWithItsWholeModelIndex) {
  const double bad[] = {
      std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const StateOffsets offsets{100, 200, 0};
  for (double v : bad) {
    for (int i = 0; i < m_->nq; ++i) {
      const double kept = d_->qpos[i];
      d_->qpos[i] = v;
      EXPECT_EQ(Check(offsets), "t = 1.500 s: non-finite qpos[" + std::to_string(100 + i) + "]");
      d_->qpos[i] = kept;
    }
    for (int i = 0; i < m_->nv; ++i) {
      d_->qvel[i] = v;
      EXPECT_EQ(Check(offsets), "t = 1.500 s: non-finite qvel[" + std::to_string(200 + i) + "]");
      d_->qvel[i] = 0;
    }
  }
  // Two at once: the first qpos is named.
  d_->qpos[9] = NAN;
  d_->qpos[3] = INFINITY;
  d_->qvel[0] = NAN;
  EXPECT_THAT(Check(), HasSubstr("non-finite qpos[3]"));
}

}  // namespace
}  // namespace mjf::runner
