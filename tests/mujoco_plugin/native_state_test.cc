// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The controllers' state lives in MuJoCo's plugin_state (docs/PLUGINS.md, "The tick rule"):
// what a MuJoCo user does with a scene (copy it, checkpoint it, differentiate it, reset it,
// integrate it with RK4) gives the flight the plain mj_step loop gives, bit for bit. Each test
// flies the exported Exp 2 for a few seconds with MuJoCo's C API alone.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/export/export.hpp"
#include "native_fixture.hpp"

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;
using mjf::testing::LoadNativePluginsOnce;
using mjf::testing::NativeExperimentText;
using mjf::testing::Scratch;

// The plugin_state header of mujoco_plugin/src/native_plugins.cc.
constexpr int kCommitted = 1, kHeld = 2;

// MuJoCo's errors as exceptions (as the runner and Python have them), so that a refusal is
// seen by the test instead of ending the process.
struct MujocoRaised : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void Raise(const char* message) { throw MujocoRaised(message); }

// Exp 2 exported, [render] dropped; `vehicle`: a [vehicles] model to fly instead.
mjModel* LoadExp2(const Scratch& dir, const std::string& vehicle = "") {
  LoadNativePluginsOnce();
  mju_user_error = Raise;
  std::ofstream(dir / "exp2.toml") << NativeExperimentText("exp2.toml", vehicle);
  ExportExperiment(dir / "exp2.toml", dir / "export", {{}, {}, /*overwrite=*/true});
  char error[2048] = {0};
  mjModel* m = mj_loadXML((dir / "export/scene.xml").c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << error;
  return m;
}

void Step(const mjModel* m, mjData* d, int steps) {
  for (int k = 0; k < steps; ++k) mj_step(m, d);
}

// The physics and the controllers' state, every bit.
::testing::AssertionResult SameBits(const mjModel* m, const mjData* a, const mjData* b) {
  const struct {
    const char* name;
    const mjtNum *x, *y;
    mjtSize n;
  } fields[] = {{"time", &a->time, &b->time, 1},
                {"qpos", a->qpos, b->qpos, m->nq},
                {"qvel", a->qvel, b->qvel, m->nv},
                {"act", a->act, b->act, m->na},
                {"plugin_state", a->plugin_state, b->plugin_state, m->npluginstate}};
  for (const auto& f : fields) {
    if (std::memcmp(f.x, f.y, sizeof(mjtNum) * f.n) != 0) {
      return ::testing::AssertionFailure() << f.name << " differs at t = " << a->time << " s";
    }
  }
  return ::testing::AssertionSuccess();
}

class NativeState : public ::testing::Test {
 protected:
  void SetUp() override {
    m_ = LoadExp2(dir_);
    ASSERT_NE(m_, nullptr);
  }
  void TearDown() override {
    for (mjData* d : datas_) mj_deleteData(d);
    if (m_) mj_deleteModel(m_);
  }
  mjData* Make() { return datas_.emplace_back(mj_makeData(m_)); }
  mjData* Own(mjData* d) { return datas_.emplace_back(d); }
  // A flight of `steps` plain mj_step from the start: the reference.
  mjData* Reference(int steps) {
    mjData* d = Make();
    Step(m_, d, steps);
    return d;
  }

  Scratch dir_{"exp2"};
  mjModel* m_ = nullptr;
  std::vector<mjData*> datas_;
};

// A copy at 1 s flies on as the original does, and both as the uncopied flight (the copy used
// to restart the laws: 7.2 mm apart after 1 s).
TEST_F(NativeState, CopyAtOneSecondFliesOnAsTheOriginal) {
  const mjData* reference = Reference(2000);
  mjData* d = Make();
  Step(m_, d, 1000);
  mjData* copy = Own(mj_copyData(nullptr, m_, d));
  Step(m_, d, 1000);
  Step(m_, copy, 1000);
  EXPECT_TRUE(SameBits(m_, d, reference));
  EXPECT_TRUE(SameBits(m_, copy, reference));
}

// A copy into an mjData that has its own controllers keeps them (no leak, no rebuild), and
// 2000 copies cost little: the passive viewer copies every frame. Reports the figures.
TEST_F(NativeState, RepeatedCopiesReuseTheHolderAndLeakNothing) {
  mjData* d = Make();
  Step(m_, d, 500);
  mjData* dest = Make();
  auto start = std::chrono::steady_clock::now();
  constexpr int kCopies = 2000;
  for (int i = 0; i < kCopies; ++i) mj_copyData(dest, m_, d);
  const double per_copy =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kCopies;
  for (int i = 0; i < 50; ++i) mj_deleteData(mj_copyData(nullptr, m_, d));
  Step(m_, dest, 500);
  Step(m_, d, 500);
  EXPECT_TRUE(SameBits(m_, dest, d));
  start = std::chrono::steady_clock::now();
  Step(m_, d, 1000);
  const double per_step =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 1000;
  std::printf(
      "mj_copyData into an mjData with its controllers: %.2f us per copy; mj_step: %.2f "
      "us per step (%d vehicles)\n",
      per_copy * 1e6, per_step * 1e6, static_cast<int>(m_->nbody - 1));
  EXPECT_LT(per_copy, 1e-3);  // a rebuild costs milliseconds
}

// mj_getState / mj_setState: a checkpoint replayed gives the same bits (it was 1.9e-8 off).
TEST_F(NativeState, CheckpointReplayIsExact) {
  mjData* d = Make();
  Step(m_, d, 1000);
  const int spec = mjSTATE_INTEGRATION;
  std::vector<mjtNum> checkpoint(mj_stateSize(m_, spec));
  mj_getState(m_, d, checkpoint.data(), spec);
  Step(m_, d, 700);
  mjData* first = Own(mj_copyData(nullptr, m_, d));
  mj_setState(m_, d, checkpoint.data(), spec);
  Step(m_, d, 700);
  EXPECT_TRUE(SameBits(m_, d, first));
}

// Finite differences evaluate the step again and again from one state: the flight after them
// is the flight without them (ten FD calls used to move it 1.54 m).
TEST_F(NativeState, TransitionFdLeavesTheFlightUnchanged) {
  const mjData* reference = Reference(1600);
  mjData* d = Make();
  Step(m_, d, 1000);
  const int nx = 2 * m_->nv + m_->na;
  std::vector<mjtNum> A(nx * nx), B(nx * m_->nu);
  mjd_transitionFD(m_, d, 1e-6, 1, A.data(), B.data(), nullptr, nullptr);
  Step(m_, d, 600);
  EXPECT_TRUE(SameBits(m_, d, reference));
}

// mj_resetData, then the same flight again, from the controllers' initial state.
TEST_F(NativeState, ResetThenFlyAgainIsTheFirstFlight) {
  const mjData* reference = Reference(800);
  mjData* d = Make();
  Step(m_, d, 1500);
  mj_resetData(m_, d);
  Step(m_, d, 800);
  EXPECT_TRUE(SameBits(m_, d, reference));
}

// RK4: the controllers tick once per step, at its first evaluation (the step's own sensors),
// never at an intermediate stage; repeated evaluations in between change nothing.
TEST_F(NativeState, Rk4TicksOncePerStepOnTheStepsSensors) {
  m_->opt.integrator = mjINT_RK4;
  mjData* plain = Make();
  mjData* probed = Make();
  const int adr = m_->plugin_stateadr[0];
  for (int k = 0; k < 600; ++k) {
    mj_step(m_, plain);
    mj_forward(m_, probed);  // the tick of step k runs here, on the step's sensors
    const std::vector<mjtNum> held(probed->plugin_state, probed->plugin_state + m_->npluginstate);
    mj_step(m_, probed);  // RK4's four stages reuse it
    EXPECT_EQ(probed->plugin_state[adr + kCommitted], k + 1);
    EXPECT_EQ(probed->plugin_state[adr + kHeld], k);
    // Controls (NaN for an actuator not driven) and state blocks, bit for bit.
    ASSERT_EQ(std::memcmp(held.data() + adr + 4, probed->plugin_state + adr + 4,
                          sizeof(mjtNum) * (held.size() - adr - 4)),
              0)
        << "a stage ticked again at step " << k;
  }
  EXPECT_TRUE(SameBits(m_, plain, probed));
  EXPECT_GT(std::fabs(plain->qpos[0] - m_->qpos0[0]) + std::fabs(plain->qpos[1] - m_->qpos0[1]),
            1e-3);
}

// Two mjData sharing one holder pointer (an unpickled MjData copies plugin_data raw): each
// flies with its own controllers, and freeing one leaves the other flying.
TEST_F(NativeState, ARawCopyOfPluginDataIsNeverTrusted) {
  const mjData* reference = Reference(1200);
  mjData* source = mj_makeData(m_);
  Step(m_, source, 600);
  mjData* pickled = Make();
  const int spec = mjSTATE_INTEGRATION;
  std::vector<mjtNum> state(mj_stateSize(m_, spec));
  mj_getState(m_, source, state.data(), spec);
  mj_setState(m_, pickled, state.data(), spec);
  std::memcpy(pickled->plugin_data, source->plugin_data, sizeof(uintptr_t) * m_->nplugin);
  mj_deleteData(source);  // the raw pointer now dangles
  Step(m_, pickled, 600);
  EXPECT_TRUE(SameBits(m_, pickled, reference));
}

// With the vehicle file gone, a reset and a copy still fly (nothing is read again per mjData:
// a failed rebuild used to leave the bridge half-built and the next mj_step segfaulted).
TEST(NativeStateFiles, ResetAndCopyReadNoFileAgain) {
  Scratch dir("files");
  fs::copy_file(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml", dir / "vehicle.xml");
  mjModel* m = LoadExp2(dir, dir / "vehicle.xml");
  ASSERT_NE(m, nullptr);
  mjData* reference = mj_makeData(m);
  Step(m, reference, 300);
  mjData* d = mj_makeData(m);
  Step(m, d, 700);
  fs::remove(dir / "vehicle.xml");
  mj_resetData(m, d);
  mjData* copy = mj_copyData(nullptr, m, d);
  Step(m, d, 300);
  Step(m, copy, 300);
  EXPECT_TRUE(SameBits(m, d, reference));
  EXPECT_TRUE(SameBits(m, copy, reference));
  for (mjData* x : {reference, d, copy}) mj_deleteData(x);
  mj_deleteModel(m);
}

// plugin_state that is not ours (garbage written over it) is refused with a message naming the
// plugin, never flown and never a crash.
TEST_F(NativeState, ForeignPluginStateIsRefused) {
  mjData* d = Make();
  Step(m_, d, 10);
  for (int i = 0; i < m_->npluginstate; ++i) d->plugin_state[i] = 7;
  d->plugin_state[kHeld] = -1;  // no controls held: the next evaluation reads the state
  try {
    mj_step(m_, d);
    ADD_FAILURE() << "stepped on a foreign plugin_state";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("mjformation.swarm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("layout"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::runner
