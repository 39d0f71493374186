// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The controllers' state lives in MuJoCo's plugin_state (docs/PLUGINS.md, "The tick rule"):
// what a MuJoCo user does with a scene (copy it, checkpoint it, differentiate it, reset it,
// integrate it with RK4) gives the flight the plain mj_step loop gives, bit for bit. Each test
// flies the exported Exp 2 for a few seconds with MuJoCo's C API alone.
#include <gtest/gtest.h>
#include <malloc.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/export/export.hpp"
#include "mjformation/sim/mujoco_errors.hpp"
#include "mjformation/sim/simulation.hpp"
#include "native_fixture.hpp"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MJF_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define MJF_TEST_ASAN 1
#endif
#ifdef MJF_TEST_ASAN
#include <sanitizer/allocator_interface.h>
#endif

namespace mjf::runner {
namespace {

namespace fs = std::filesystem;
using mjf::testing::LoadNativePluginsOnce;
using mjf::testing::NativeExperimentText;
using mjf::testing::ReadFile;
using mjf::testing::Scratch;

// The plugin_state header of mujoco_plugin/src/actuator_plugin.hpp.
constexpr int kCommitted = 1, kHeld = 2, kHeader = 5;

// MuJoCo's errors as exceptions (as the runner and Python have them), so that a refusal is
// seen by the test instead of ending the process.
struct MujocoRaised : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void Raise(const char* message) { throw MujocoRaised(message); }

// `text` exported and loaded with MuJoCo's C API alone.
mjModel* LoadExported(const Scratch& dir, const std::string& text) {
  LoadNativePluginsOnce();
  mju_user_error = Raise;
  std::ofstream(dir / "exp2.toml") << text;
  ExportExperiment(dir / "exp2.toml", dir / "export", {{}, {}, /*overwrite=*/true});
  char error[2048] = {0};
  mjModel* m = mj_loadXML((dir / "export/scene.xml").c_str(), nullptr, error, sizeof(error));
  EXPECT_NE(m, nullptr) << error;
  return m;
}

// Exp 2 exported, [render] dropped; `vehicle`: a [vehicles] model to fly instead.
mjModel* LoadExp2(const Scratch& dir, const std::string& vehicle = "") {
  return LoadExported(dir, NativeExperimentText("exp2.toml", vehicle));
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

// Copies at 1, 7 and 20 s, one into a new mjData and one into an mjData with controllers of its
// own, fly on as the uncopied flight, bit for bit.
TEST_F(NativeState, CopiesAtOneSevenAndTwentySecondsFlyOnAsTheOriginal) {
  mjData* uncopied = Make();
  mjData* d = Make();
  mjData* dest = Make();
  Step(m_, dest, 300);  // its controllers hold a state of their own
  int done = 0;
  for (const int at : {1000, 7000, 20000}) {
    Step(m_, uncopied, at - done);
    Step(m_, d, at - done);
    done = at + 500;
    mjData* fresh = Own(mj_copyData(nullptr, m_, d));
    mj_copyData(dest, m_, d);
    for (mjData* x : {uncopied, d, fresh, dest}) Step(m_, x, 500);
    EXPECT_TRUE(SameBits(m_, fresh, uncopied));
    EXPECT_TRUE(SameBits(m_, dest, uncopied));
    EXPECT_TRUE(SameBits(m_, d, uncopied));
  }
}

// The heap in use, in bytes: the sanitizer's count under ASan (its allocator replaces malloc's).
size_t HeapInUse() {
#ifdef MJF_TEST_ASAN
  return __sanitizer_get_current_allocated_bytes();
#else
  return mallinfo2().uordblks;
#endif
}

// 10,000 copies (one in ten into a new mjData, then deleted; the rest into one mjData, as the
// passive viewer copies every frame) leave the heap where it was (a copy used to keep a second
// controller bridge: +150 kB each). LeakSanitizer checks the instrumented tree at exit too.
TEST_F(NativeState, TenThousandCopiesLeakNothing) {
  mjData* d = Make();
  Step(m_, d, 500);
  mjData* dest = Make();
  const auto copies = [&](int n) {
    for (int i = 0; i < n; ++i) {
      if (i % 10 == 0) {
        mj_deleteData(mj_copyData(nullptr, m_, d));
      } else {
        mj_copyData(dest, m_, d);
      }
    }
  };
  copies(100);  // caches that fill once (MuJoCo's, the allocator's) are full before the count
  const size_t before = HeapInUse();
  copies(10000);
  const size_t after = HeapInUse();
  std::printf("heap in use before 10,000 copies: %zu bytes, after: %zu\n", before, after);
  EXPECT_LT(after, before + 64 * 1024);
  Step(m_, dest, 10);
  Step(m_, d, 10);
  EXPECT_TRUE(SameBits(m_, dest, d));
}

// mj_copyData's cost per call into an mjData of the same model, averaged over `copies`.
double SecondsPerCopy(const mjModel* m, int copies) {
  mjData* src = mj_makeData(m);
  Step(m, src, 500);
  mjData* dest = mj_makeData(m);
  Step(m, dest, 1);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < copies; ++i) mj_copyData(dest, m, src);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  mj_deleteData(dest);
  mj_deleteData(src);
  return seconds / copies;
}

// Not a test (timing): `mujoco_plugin_test --gtest_also_run_disabled_tests
// --gtest_filter='*CopyCost*'` prints what one mj_copyData of the exported Exp 2 costs against
// the bare scene (the same scene.xml without <extension>: MuJoCo's actuators, no plugin).
TEST_F(NativeState, DISABLED_CopyCostAgainstTheBareScene) {
  std::string text = ReadFile(dir_ / "export/scene.xml");
  const size_t begin = text.find("<extension>");
  const std::string close = "</extension>";
  ASSERT_NE(begin, std::string::npos);
  text.erase(begin, text.find(close) + close.size() - begin);
  std::ofstream(dir_ / "export/bare.xml") << text;  // beside the files the scene names
  char error[1024] = {0};
  mjModel* bare = mj_loadXML((dir_ / "export/bare.xml").c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(bare, nullptr) << error;
  constexpr int kCopies = 20000;
  SecondsPerCopy(m_, kCopies / 10);  // warm caches
  const double exported = SecondsPerCopy(m_, kCopies), plain = SecondsPerCopy(bare, kCopies);
  std::printf("mj_copyData: exported Exp 2 %.3f us, bare scene %.3f us, ratio %.2f\n",
              exported * 1e6, plain * 1e6, exported / plain);
  mj_deleteModel(bare);
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

// Flies `steps` twice with m's integrator: plainly, and probed with mj_forward before each
// mj_step (the tick of step k runs there, on the step's own sensors). After every step the step
// ran exactly one tick (committed k + 1, held k, the held controls and blocks untouched by the
// integrator's evaluations); both flights are the same bits. Returns the plain flight.
mjData* FlyProbed(const mjModel* m, int steps) {
  mjData* plain = mj_makeData(m);
  mjData* probed = mj_makeData(m);
  const int adr = m->plugin_stateadr[0];
  for (int k = 0; k < steps; ++k) {
    mj_step(m, plain);
    mj_forward(m, probed);
    const std::vector<mjtNum> held(probed->plugin_state, probed->plugin_state + m->npluginstate);
    mj_step(m, probed);
    EXPECT_EQ(probed->plugin_state[adr + kCommitted], k + 1);
    EXPECT_EQ(probed->plugin_state[adr + kHeld], k);
    // Controls (NaN for an actuator not driven) and state blocks, bit for bit.
    if (std::memcmp(held.data() + adr + kHeader, probed->plugin_state + adr + kHeader,
                    sizeof(mjtNum) * (held.size() - adr - kHeader)) != 0) {
      ADD_FAILURE() << "an evaluation ticked again at step " << k;
      break;
    }
  }
  EXPECT_TRUE(SameBits(m, plain, probed));
  mj_deleteData(probed);
  return plain;
}

// How far the vehicles moved from their starting point (the flight is not a hover in place).
double Travelled(const mjModel* m, const mjData* d) {
  return std::fabs(d->qpos[0] - m->qpos0[0]) + std::fabs(d->qpos[1] - m->qpos0[1]);
}

// RK4: the controllers tick once per step, at its first evaluation (the step's own sensors),
// never at an intermediate stage; repeated evaluations in between change nothing.
TEST_F(NativeState, Rk4TicksOncePerStepOnTheStepsSensors) {
  m_->opt.integrator = mjINT_RK4;
  const mjData* plain = Own(FlyProbed(m_, 600));
  EXPECT_GT(Travelled(m_, plain), 1e-3);
}

// implicitfast (one evaluation per step, like Euler): the same tick rule, one tick per mj_step
// on the step's own sensors; the flight stays within the integrators' difference of Euler's.
TEST_F(NativeState, ImplicitFastTicksOncePerStepOnTheStepsSensors) {
  m_->opt.integrator = mjINT_IMPLICITFAST;
  const mjData* implicit = Own(FlyProbed(m_, 1000));
  m_->opt.integrator = mjINT_EULER;
  const mjData* euler = Reference(1000);
  EXPECT_GT(Travelled(m_, implicit), 1e-3);
  double apart = 0;
  for (int i = 0; i < m_->nq; ++i) {
    apart = std::max(apart, std::fabs(implicit->qpos[i] - euler->qpos[i]));
  }
  std::printf("implicitfast vs Euler after 1 s: %.3g m at most\n", apart);
  EXPECT_LT(apart, 1e-5);
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

// With the (exported) vehicle file gone, a reset and a copy still fly (nothing is read again per
// mjData: a failed rebuild used to leave the bridge half-built and the next mj_step segfaulted).
TEST(NativeStateFiles, ResetAndCopyReadNoFileAgain) {
  Scratch dir("files");
  fs::copy_file(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml", dir / "vehicle.xml");
  mjModel* m = LoadExp2(dir, dir / "vehicle.xml");
  ASSERT_NE(m, nullptr);
  mjData* reference = mj_makeData(m);
  Step(m, reference, 300);
  mjData* d = mj_makeData(m);
  Step(m, d, 700);
  fs::remove(dir / "export/vehicle/vehicle.xml");  // the copy the exported scene names
  mj_resetData(m, d);
  mjData* copy = mj_copyData(nullptr, m, d);
  Step(m, d, 300);
  Step(m, copy, 300);
  EXPECT_TRUE(SameBits(m, d, reference));
  EXPECT_TRUE(SameBits(m, copy, reference));
  for (mjData* x : {reference, d, copy}) mj_deleteData(x);
  mj_deleteModel(m);
}

// The files are read once per model: a model copied after its vehicle file is gone reads them
// again for its first mjData and cannot. mj_makeData raises (never a crash), and
// the original model's mjData still step.
TEST(NativeStateFiles, AnInitThatCannotReadItsFilesRaises) {
  Scratch dir("init");
  fs::copy_file(std::string(MJF_SOURCE_DIR) + "/mjcf/quadrotor.xml", dir / "vehicle.xml");
  mjModel* m = LoadExp2(dir, dir / "vehicle.xml");
  ASSERT_NE(m, nullptr);
  mjData* reference = mj_makeData(m);
  Step(m, reference, 300);
  fs::remove(dir / "export/vehicle/vehicle.xml");  // the copy the exported scene names
  mjModel* copy = mj_copyModel(nullptr, m);
  ClearMujocoWarning();
  try {
    mjData* d = mj_makeData(copy);
    ADD_FAILURE() << "an mjData made without its vehicle file";
    mj_deleteData(d);
  } catch (const std::exception& e) {
    // MuJoCo's error names the plugin's slot; the instance's own message, naming the file, is
    // the warning before it.
    EXPECT_NE(std::string(e.what()).find("plugin->init failed"), std::string::npos) << e.what();
    const std::string warning = LastMujocoWarning();  // the runner's handler keeps it
    EXPECT_NE(warning.find("vehicle.xml' not found"), std::string::npos) << warning;
  }
  mjData* d = mj_makeData(m);
  Step(m, d, 300);
  EXPECT_TRUE(SameBits(m, d, reference));
  for (mjData* x : {reference, d}) mj_deleteData(x);
  mj_deleteModel(copy);
  mj_deleteModel(m);
}

// experiments/<experiment> (NativeExperimentText) flown with [vehicles] rotor_model = "wrench".
std::string WithWrenchRotors(std::string text) {
  const size_t at = text.find("followers = 6");
  EXPECT_NE(at, std::string::npos) << "no [vehicles] followers = 6 to add the rotor model after";
  if (at != std::string::npos) text.insert(at + 13, "\nrotor_model = \"wrench\"");
  return text;
}

// The benchmark's b08 with its rotor fault moved from 15 s to 0.5 s, between the copies.
std::string RotorFaultAtHalfASecond() {
  const std::string text = NativeExperimentText("benchmark/b08_rotor_fault.toml");
  EXPECT_NE(text.find("\nat = 15.0"), std::string::npos) << "b08's fault is no longer at 15 s";
  return std::regex_replace(text, std::regex("\nat = 15.0"), "\nat = 0.5");
}

// A scene whose controllers draw random numbers and keep queues (sensor noise and latency
// buffers, a lossy network): the flights MuJoCo's tools give stay the uncopied flight.
class NativeStreamsState : public NativeState {
 protected:
  // Copies at 0.3 and 0.8 s (samples and messages taken, in flight and used), into a new
  // mjData and into one with controllers of its own, fly on as the uncopied flight, bit for bit.
  void CopiesAtTwoTimesFlyOnAsTheOriginal() {
    mjData* uncopied = Make();
    mjData* d = Make();
    mjData* dest = Make();
    Step(m_, dest, 100);  // its controllers and sensors hold a state of their own
    int done = 0;
    for (const int at : {300, 800}) {
      Step(m_, uncopied, at - done);
      Step(m_, d, at - done);
      done = at + 250;
      mjData* fresh = Own(mj_copyData(nullptr, m_, d));
      mj_copyData(dest, m_, d);
      for (mjData* x : {uncopied, d, fresh, dest}) Step(m_, x, 250);
      EXPECT_TRUE(SameBits(m_, fresh, uncopied));
      EXPECT_TRUE(SameBits(m_, dest, uncopied));
      EXPECT_TRUE(SameBits(m_, d, uncopied));
    }
    EXPECT_GT(Travelled(m_, d), 1e-3);
  }

  // mj_getState / mj_setState: a checkpoint replayed gives the same bits, in the same mjData
  // and in another that has flown a flight of its own.
  void CheckpointReplayIsExact() {
    mjData* d = Make();
    Step(m_, d, 500);
    const int spec = mjSTATE_INTEGRATION;
    std::vector<mjtNum> checkpoint(mj_stateSize(m_, spec));
    mj_getState(m_, d, checkpoint.data(), spec);
    Step(m_, d, 300);
    mjData* first = Own(mj_copyData(nullptr, m_, d));
    mj_setState(m_, d, checkpoint.data(), spec);
    Step(m_, d, 300);
    EXPECT_TRUE(SameBits(m_, d, first));
    mjData* other = Make();
    Step(m_, other, 50);
    mj_setState(m_, other, checkpoint.data(), spec);
    Step(m_, other, 300);
    EXPECT_TRUE(SameBits(m_, other, first));
  }

  // Finite differences and a reset leave the flight as it was: the random streams are restored
  // with the rest, and a reset starts them from their seeds.
  void TransitionFdAndResetLeaveTheFlightUnchanged() {
    const mjData* reference = Reference(600);
    mjData* d = Make();
    Step(m_, d, 400);
    const int nx = 2 * m_->nv + m_->na;
    std::vector<mjtNum> A(nx * nx), B(nx * m_->nu);
    mjd_transitionFD(m_, d, 1e-6, 1, A.data(), B.data(), nullptr, nullptr);
    Step(m_, d, 200);
    EXPECT_TRUE(SameBits(m_, d, reference));
    mj_resetData(m_, d);
    Step(m_, d, 600);
    EXPECT_TRUE(SameBits(m_, d, reference));
  }

  // What mujoco.rollout does over threads: batches set from states of one flight (0.1 to 0.4 s)
  // and stepped 0.15 s, on two threads each with its own mjData going from batch to batch, give
  // the bits of a serial loop that flies each batch on an mjData of its own.
  void BatchesOverTwoThreadsAreTheSerialLoop() {
    constexpr int kBatches = 4, kSpacing = 100, kSteps = 150;
    const int spec = mjSTATE_INTEGRATION;
    const auto state_of = [&](const mjData* d) {
      std::vector<mjtNum> state(mj_stateSize(m_, spec));
      mj_getState(m_, d, state.data(), spec);
      return state;
    };
    std::vector<std::vector<mjtNum>> initial;
    mjData* flight = Make();
    for (int b = 0; b < kBatches; ++b) {
      Step(m_, flight, kSpacing);
      initial.push_back(state_of(flight));
    }
    std::vector<std::vector<mjtNum>> serial;
    for (const std::vector<mjtNum>& state : initial) {
      mjData* d = Make();
      mj_setState(m_, d, state.data(), spec);
      Step(m_, d, kSteps);
      serial.push_back(state_of(d));
    }
    std::vector<std::vector<mjtNum>> threaded(kBatches);
    std::vector<mjData*> own = {Make(), Make()};
    Step(m_, own[1], 50);  // one of them holds a flight of its own before its first batch
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t) {
      threads.emplace_back([&, t] {
        for (int b = t; b < kBatches; b += 2) {
          mj_setState(m_, own[t], initial[b].data(), spec);
          Step(m_, own[t], kSteps);
          threaded[b] = state_of(own[t]);
        }
      });
    }
    for (std::thread& t : threads) t.join();
    for (int b = 0; b < kBatches; ++b) {
      EXPECT_EQ(
          std::memcmp(threaded[b].data(), serial[b].data(), sizeof(mjtNum) * serial[b].size()), 0)
          << "batch " << b;
      EXPECT_NE(std::memcmp(serial[b].data(), initial[b].data(), sizeof(mjtNum) * 8), 0)
          << "batch " << b << " did not fly";
    }
    // The serial loop continues the flight the states were taken from.
    Step(m_, flight, kSteps);  // `flight` stands at the last batch's start
    const std::vector<mjtNum> continued = state_of(flight);
    EXPECT_EQ(
        std::memcmp(continued.data(), serial.back().data(), sizeof(mjtNum) * continued.size()), 0);
  }

  // RK4 (four evaluations a step, no sensors at the inner stages): the controllers tick once per
  // step, so copies at two times still fly on as the uncopied RK4 flight.
  void Rk4CopiesFlyOnAsTheOriginal() {
    m_->opt.integrator = mjINT_RK4;
    CopiesAtTwoTimesFlyOnAsTheOriginal();
  }
};

// The benchmark's b05: GNSS-grade sensors (noise, bias walk, wander, rates, latency) and a
// Kalman filter per vehicle. Their state (random streams, latency buffers, the filters' state
// and covariance) lives in plugin_state with the rest, so MuJoCo's tools stay exact.
class NativeSensorState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, NativeExperimentText("benchmark/b05_gnss_kf.toml"));
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeSensorState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeSensorState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeSensorState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}
TEST_F(NativeSensorState, BatchesOverTwoThreadsAreTheSerialLoop) {
  BatchesOverTwoThreadsAreTheSerialLoop();
}
TEST_F(NativeSensorState, Rk4CopiesFlyOnAsTheOriginal) { Rk4CopiesFlyOnAsTheOriginal(); }

// The benchmark's b13: per-agent execution over a lossy network. Every link's random stream,
// its messages in flight and held, the ages and each follower's instance live in plugin_state.
class NativeNetworkState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, NativeExperimentText("benchmark/b13_lossy_network.toml"));
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeNetworkState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeNetworkState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeNetworkState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}
TEST_F(NativeNetworkState, BatchesOverTwoThreadsAreTheSerialLoop) {
  BatchesOverTwoThreadsAreTheSerialLoop();
}

// examples/vehicles/midge: a foreign thrust-and-moment model mapped onto the contract; the
// plugin adapts it once per model (as the runner does) and its state is the controllers' alone.
class NativeMappedState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, mjf::testing::MidgeExperimentText());
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeMappedState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeMappedState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }

// The benchmark's b08 with its rotor fault moved to 0.5 s: the copies at 0.3 and 0.8 s are taken
// before and after it; the fault is a function of the step alone, so they fly on faulted alike.
class NativeFaultState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, RotorFaultAtHalfASecond());
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeFaultState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}

// b08 with the wrench rotor model and its fault moved to 0.5 s: the faulted controls that drive
// the rotors' motor lags are held in plugin_state, so copies taken before and after the fault,
// a checkpoint and finite differences fly on as the uncopied flight.
class NativeWrenchFaultState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, WithWrenchRotors(RotorFaultAtHalfASecond()));
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeWrenchFaultState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeWrenchFaultState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeWrenchFaultState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}

// b13 with a range-limited link from follower 1 to 2 (kRange): up while they start 1.5 m apart,
// down once the reaching phase has spread them, between the copies at 0.3 and 0.8 s, inside the
// checkpoint's replay (0.5-0.8 s) and the steps after finite differences (0.4-0.6 s); the
// runner shows when below. Whether the link is up is in plugin_state, so all of them fly on as
// the uncopied flight across the change.
class NativeRangeLinkState : public NativeStreamsState {
 protected:
  static constexpr double kRange = 1.8;  // m: down at 0.534 s in the runner
  static std::string Text() {
    return NativeExperimentText("benchmark/b13_lossy_network.toml") +
           "\n[[network.link]]\nfrom = 1\nto = 2\nrange = " + std::to_string(kRange) + "\n";
  }
  void SetUp() override {
    m_ = LoadExported(dir_, Text());
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeRangeLinkState, TheLinkGoesDownBetweenTheCopies) {
  std::ofstream(dir_ / "runner.toml") << Text();
  Simulation runner(LoadExperiment(dir_ / "runner.toml", {}, ExperimentChecks::Rendering(false)));
  for (int k = 0; k < 800; ++k) {
    runner.ComputeControls();
    runner.Integrate();
  }
  ASSERT_NE(runner.channel(), nullptr);
  const auto& events = runner.channel()->network().events();
  ASSERT_FALSE(events.empty()) << "the link never went down";
  EXPECT_EQ(events[0].from, 1);
  EXPECT_EQ(events[0].to, 2);
  EXPECT_FALSE(events[0].up);
  EXPECT_GT(events[0].time, 0.3);
  EXPECT_LT(events[0].time, 0.8);
}
TEST_F(NativeRangeLinkState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeRangeLinkState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeRangeLinkState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}

// b13 with Jacobi's exchange rounds carried over its lossy, late links (a round timeout): the
// letters in flight, the exchanges waiting for them and their counts live in plugin_state, so
// the copies, a checkpoint and finite differences fly on as the uncopied flight.
class NativeRoundsState : public NativeStreamsState {
 protected:
  void SetUp() override {
    const std::string text = mjf::testing::RoundsOverTheLinksText();
    ASSERT_FALSE(text.empty()) << "b13 has no [execution] or [network] to add the rounds to";
    m_ = LoadExported(dir_, text);
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeRoundsState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeRoundsState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeRoundsState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}
TEST_F(NativeRoundsState, BatchesOverTwoThreadsAreTheSerialLoop) {
  BatchesOverTwoThreadsAreTheSerialLoop();
}
TEST_F(NativeRoundsState, Rk4CopiesFlyOnAsTheOriginal) { Rk4CopiesFlyOnAsTheOriginal(); }

// What b13's plugin_state holds (docs/PLUGINS.md quotes it): the swarm's doubles.
TEST_F(NativeNetworkState, StateSizeIsFixedAndPrinted) {
  ASSERT_EQ(m_->nplugin, 1);
  const int nstate = m_->npluginstate;
  std::printf("b13 exported: npluginstate = %d doubles (mj_stateSize INTEGRATION = %d)\n", nstate,
              static_cast<int>(mj_stateSize(m_, mjSTATE_INTEGRATION)));
  EXPECT_GT(nstate, 13 * 3 * 28) << "13 links' queues of 3 messages at the least";
}

// b06 shortened: a 3 m/s wind with moderate Dryden turbulence. The wind field's state (each
// vehicle's Dryden filters and random stream, the held samples) lives in plugin_state, and so
// does the drag of the step, added into qfrc_passive at every evaluation.
class NativeWindState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, NativeExperimentText("benchmark/b06_gusty_wind.toml"));
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeWindState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeWindState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeWindState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}

// With springs and dampers both disabled MuJoCo skips the passive stage, where the wind's drag
// goes: the step raises, naming the flags, instead of flying on without the wind. Either flag
// alone leaves the stage, and the flight, as it was.
TEST_F(NativeWindState, SpringsAndDampersBothDisabledAreRefused) {
  mjData* reference = Make();
  Step(m_, reference, 50);
  m_->opt.disableflags |= mjDSBL_SPRING;
  mjData* spring_off = Make();
  Step(m_, spring_off, 50);
  EXPECT_TRUE(SameBits(m_, spring_off, reference));
  m_->opt.disableflags |= mjDSBL_DAMPER;
  mjData* both_off = Make();
  try {
    Step(m_, both_off, 1);
    ADD_FAILURE() << "a step without the passive stage's forces";
  } catch (const std::exception& e) {  // MuJoCo's error, as the installed handler throws it
    EXPECT_NE(std::string(e.what()).find("springs and dampers are both disabled"),
              std::string::npos)
        << e.what();
  }
  m_->opt.disableflags &= ~(mjDSBL_SPRING | mjDSBL_DAMPER);
}

// B's columns are differenced with the velocity stage skipped, qfrc_passive kept from the
// evaluation before: the drag is in it once, never added again. A rotor's column equals a
// difference taken by hand over copies (each copy's step adds the drag once), and a second call
// gives the same B.
TEST_F(NativeWindState, TransitionFdBCountsTheDragOnce) {
  mjData* d = Make();
  Step(m_, d, 400);
  const int nx = 2 * m_->nv + m_->na, nu = m_->nu;
  const int rotor = nu / 2;
  const mjtNum eps = 1e-6;
  std::vector<mjtNum> B(nx * nu), again(nx * nu);
  mjd_transitionFD(m_, d, eps, 0, nullptr, B.data(), nullptr, nullptr);
  mjd_transitionFD(m_, d, eps, 0, nullptr, again.data(), nullptr, nullptr);
  EXPECT_EQ(B, again);
  mjData* base = Own(mj_copyData(nullptr, m_, d));
  mjData* nudged = Own(mj_copyData(nullptr, m_, d));
  nudged->ctrl[m_->actuator_ctrladr[rotor]] += eps;
  Step(m_, base, 1);
  Step(m_, nudged, 1);
  std::vector<mjtNum> column(nx);
  mj_differentiatePos(m_, column.data(), eps, base->qpos, nudged->qpos);
  for (int v = 0; v < m_->nv; ++v) column[m_->nv + v] = (nudged->qvel[v] - base->qvel[v]) / eps;
  for (int i = 0; i < m_->na; ++i) column[2 * m_->nv + i] = (nudged->act[i] - base->act[i]) / eps;
  double largest = 0;
  for (int r = 0; r < nx; ++r) {
    EXPECT_NEAR(B[r * nu + rotor], column[r], 1e-9 * (1 + std::fabs(column[r]))) << "row " << r;
    largest = std::max(largest, std::fabs(B[r * nu + rotor]));
  }
  EXPECT_GT(largest, 1e-3) << "the rotor's column is not seen";
}

// Exp 2 with the wrench rotor model: the tick's controls and the motor lags are in
// plugin_state; the rotors' wrenches are added into qfrc_passive at every evaluation.
class NativeWrenchState : public NativeStreamsState {
 protected:
  void SetUp() override {
    m_ = LoadExported(dir_, WithWrenchRotors(NativeExperimentText("exp2.toml")));
    ASSERT_NE(m_, nullptr);
  }
};

TEST_F(NativeWrenchState, CopiesAtTwoTimesFlyOnAsTheOriginal) {
  CopiesAtTwoTimesFlyOnAsTheOriginal();
}
TEST_F(NativeWrenchState, CheckpointReplayIsExact) { CheckpointReplayIsExact(); }
TEST_F(NativeWrenchState, TransitionFdAndResetLeaveTheFlightUnchanged) {
  TransitionFdAndResetLeaveTheFlightUnchanged();
}

// The scene's one actuator is the zero-gear tick actuator: its B column is zero, to the bit (a
// rotor wrench added a second time in the evaluations that skip the velocity stage would show
// here, as the whole wrench over eps). A's velocity columns, differenced with the velocity stage
// run, move the vehicles.
TEST_F(NativeWrenchState, TransitionFdSeesTheTickActuatorAsNoForce) {
  ASSERT_EQ(m_->nu, 1);
  ASSERT_STREQ(mj_id2name(m_, mjOBJ_ACTUATOR, 0), "mjformation_swarm_tick");
  mjData* d = Make();
  Step(m_, d, 400);
  const int nx = 2 * m_->nv + m_->na;
  std::vector<mjtNum> A(nx * nx), B(nx);
  mjd_transitionFD(m_, d, 1e-6, 0, A.data(), B.data(), nullptr, nullptr);
  for (int r = 0; r < nx; ++r) EXPECT_EQ(B[r], 0.0) << "row " << r;
  // d qpos(next) / d qvel of the leader's x velocity is the timestep.
  EXPECT_NEAR(A[0 * nx + m_->nv + 0], m_->opt.timestep, 1e-7);
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
