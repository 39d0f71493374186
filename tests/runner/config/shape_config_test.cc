// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [formation.shape]: fixed offsets and sampled tables, with the consistency check f_ip' = f_iv
// of Algorithms 1 and 2 applied before any step.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "mjformation/config/config.hpp"
#include "mjformation/formation/shape.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::TempDir;
using mjf::testing::WriteFile;
using ::testing::AllOf;
using ::testing::HasSubstr;

std::string PointMassFormation(const std::string& shape) {
  return "[run]\nduration = 20.0\n[vehicles]\nmodel = \"pointmass\"\nfollowers = 3\n"
         "altitude = 2.0\nleader_start = [0.0, 0.0]\n"
         "follower_start = [[-1.0, 1.0], [-1.0, -1.0], [-2.0, 0.0]]\n"
         "[topology]\nleader_links = [1]\nedges = [[1, 2], [2, 3], [3, 1]]\n"
         "[leader]\nplugin = \"hover\"\n[formation]\nplugin = \"smc_discrete\"\n"
         "[formation.shape]\n" +
         shape + "[attitude]\nplugin = \"pointmass_direct\"\n";
}

// Followers end at leader + offset.
void ExpectSlotsReached(Simulation& sim, const std::vector<std::array<double, 2>>& offsets) {
  for (int64_t k = 0; k < sim.total_steps(); ++k) {
    sim.ComputeControls();
    sim.Integrate();
  }
  sim.ComputeControls();
  for (int i = 1; i <= 3; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      EXPECT_NEAR(sim.states()[i].pos[axis], sim.states()[0].pos[axis] + offsets[i - 1][axis], 0.05)
          << "follower " << i << " axis " << axis;
    }
  }
}

TEST(ShapeConfigTest, FixedOffsetsAreReached) {
  const std::string dir = TempDir("shape");
  const std::string text =
      PointMassFormation("type = \"offsets\"\noffsets = [[3.0, 0.0], [0.0, 3.0], [-3.0, 0.0]]\n");
  Simulation sim(LoadExperiment(WriteFile(dir + "/e.toml", text)));
  ExpectSlotsReached(sim, {{3.0, 0.0}, {0.0, 3.0}, {-3.0, 0.0}});
}

TEST(ShapeConfigTest, ConsistentTableIsFlown) {
  // A table sampled from a 4 m circle turning at 0.2 rad/s: consistent, so it is accepted.
  const std::string dir = TempDir("table");
  std::ostringstream csv;
  csv << "t,f1_px,f1_py,f1_vx,f1_vy,f2_px,f2_py,f2_vx,f2_vy,f3_px,f3_py,f3_vx,f3_vy\n";
  for (int k = 0; k <= 250; ++k) {
    const double t = 0.1 * k;
    csv << t;
    for (int i = 0; i < 3; ++i) {
      const double a = 0.2 * t + 2 * M_PI * i / 3;
      csv << "," << 4 * std::cos(a) << "," << 4 * std::sin(a) << "," << -0.8 * std::sin(a) << ","
          << 0.8 * std::cos(a);
    }
    csv << "\n";
  }
  WriteFile(dir + "/shape.csv", csv.str());
  const std::string text =
      PointMassFormation("type = \"table\"\nfile = \"shape.csv\"\ntolerance = 0.01\n");
  Simulation sim(LoadExperiment(WriteFile(dir + "/e.toml", text)));
  std::vector<std::array<double, 2>> at_end;
  for (int i = 0; i < 3; ++i) {
    const double a = 0.2 * 20.0 + 2 * M_PI * i / 3;
    at_end.push_back({4 * std::cos(a), 4 * std::sin(a)});
  }
  ExpectSlotsReached(sim, at_end);
}

TEST(ShapeConfigTest, InconsistentTableIsRefusedBeforeRunning) {
  // Positions fixed but velocities claimed non-zero: f_ip' != f_iv.
  const std::string dir = TempDir("badtable");
  WriteFile(dir + "/shape.csv",
            "t,a,b,c,d,e,f,g,h,i,j,k,l\n0,1,0,0,0,0,1,0.5,0,-1,0,0,0\n"
            "30,1,0,0,0,0,1,0.5,0,-1,0,0,0\n");
  const std::string text = PointMassFormation("type = \"table\"\nfile = \"shape.csv\"\n");
  try {
    Simulation sim(LoadExperiment(WriteFile(dir + "/e.toml", text)));
    FAIL() << "accepted an inconsistent shape";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("[formation.shape]"), HasSubstr("follower 2")));
  }
  WriteFile(dir + "/short.csv", "t,a\n0,1\n");
  const std::string bad = PointMassFormation("type = \"table\"\nfile = \"short.csv\"\n");
  try {
    Simulation sim(LoadExperiment(WriteFile(dir + "/e2.toml", bad)));
    FAIL() << "accepted a malformed table";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("short.csv:2"), HasSubstr("expected 13 numbers")));
  }
}

}  // namespace
}  // namespace mjf::runner
