// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// trajectory: a CSV interpolated smoothly through its rows; bad files refused with the line and
// the reason.
#include "mjformation/guidance/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "guidance_util.hpp"

namespace mjf::guidance {
namespace {

using test::Fly;
using test::Stats;
using test::WriteTemp;

TEST(TrajectoryTest, CsvInterpolatedSmoothlyThroughItsRows) {
  const std::string path =
      WriteTemp("traj_ok.csv", "t,x,y,z\n# a comment\n0,0,0,4\n2,2,0,4\n4,4,2,5\n\n6,4,4,5\n");
  const TrajectoryTable table = ReadTrajectoryCsv(path);
  ASSERT_EQ(table.t.size(), 4u);
  EXPECT_TRUE(table.has_z);
  TrajectoryGuidance::Config c;
  const TrajectoryGuidance law(c, table);
  for (size_t k = 0; k < table.t.size(); ++k) {
    const GuidanceOutput r = law.Reference(table.t[k]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.pos[i], table.pos[k][i], 1e-12) << k;
  }
  const GuidanceOutput mid = law.Reference(1.0);
  EXPECT_GT(mid.pos[0], 0.0);
  EXPECT_LT(mid.pos[0], 2.0);
  EXPECT_EQ(law.Reference(100).pos[1], 4.0);  // holds the last row
  const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                      {0, 0, 5}, 0.01, 10.0);
  EXPECT_GE(s.a_min[0], -1.0);
  EXPECT_LE(s.a_max[0], 1.0);
  // Without z the altitude attribute is used.
  const TrajectoryTable flat = ReadTrajectoryCsv(WriteTemp("traj_flat.csv", "0,1,2\n1,2,3\n"));
  EXPECT_FALSE(flat.has_z);
  c.altitude = 7;
  EXPECT_EQ(TrajectoryGuidance(c, flat).Reference(0.5).pos[2], 7.0);
}

TEST(TrajectoryTest, BadFilesRefusedWithLineAndReason) {
  auto refused = [](const std::string& name, const std::string& text, const std::string& what) {
    const std::string path = WriteTemp(name, text);
    try {
      ReadTrajectoryCsv(path);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'file'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused("back.csv", "t,x,y\n0,0,0\n1,1,1\n1,2,2\n", ":4: t = 1 is not after");
  refused("nan.csv", "0,0,0\n1,nan,1\n", ":2: a value is not finite");
  refused("one.csv", "t,x,y\n0,0,0\n", "at least two rows");
  refused("cols.csv", "0,0\n1,1\n", "columns");
  refused("mixed.csv", "0,0,0\n1,1,1,1\n", "columns like the first row");
  refused("text.csv", "t,x,y\n0,0,0\n1,a,1\n", ":3: expected numbers");
  try {
    ReadTrajectoryCsv("/nonexistent/leader.csv");
    ADD_FAILURE() << "unreadable file accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::guidance
