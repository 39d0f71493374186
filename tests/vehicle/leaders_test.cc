// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Maneuvering leaders (leaders.hpp) on an ideal double integrator: the command never leaves
// [a_min, a_max] over long seeded runs, the speed limit and the area hold, same seed same
// commands, and bad input is refused naming the attribute.
#include "mjformation/guidance/leaders.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mjf::guidance {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Stats {
  std::array<double, 2> a_min{1e9, 1e9}, a_max{-1e9, -1e9};
  std::array<double, 2> p_min{1e9, 1e9}, p_max{-1e9, -1e9};
  double speed_max = 0;    // largest |v| on any axis
  double max_jump = 0;     // largest |a(k+1) - a(k)| on any axis
  std::vector<double> ax;  // the x command per step
};

// Integrates p, v exactly over steps of dt with the law's command held (zero-order hold).
Stats Fly(const std::function<GuidanceOutput(double, const Vec3&, const Vec3&)>& law, Vec3 pos,
          double dt, double duration) {
  Stats s;
  Vec3 vel{0, 0, 0};
  std::array<double, 2> last{0, 0};
  const long steps = std::lround(duration / dt);
  for (long k = 0; k < steps; ++k) {
    const GuidanceOutput out = law(k * dt, pos, vel);
    for (int i = 0; i < 2; ++i) {
      const double a = out.acc[i];
      s.a_min[i] = std::min(s.a_min[i], a);
      s.a_max[i] = std::max(s.a_max[i], a);
      if (k > 0) s.max_jump = std::max(s.max_jump, std::abs(a - last[i]));
      last[i] = a;
      pos[i] += dt * vel[i] + 0.5 * dt * dt * a;
      vel[i] += dt * a;
      s.p_min[i] = std::min(s.p_min[i], pos[i]);
      s.p_max[i] = std::max(s.p_max[i], pos[i]);
      s.speed_max = std::max(s.speed_max, std::abs(vel[i]));
    }
    s.ax.push_back(out.acc[0]);
  }
  return s;
}

RandomAccelGuidance::Config RandomConfig(uint64_t seed) {
  RandomAccelGuidance::Config c;
  c.bounds = {-0.8, 1.2};  // asymmetric on purpose
  c.envelope.speed_max = 3.0;
  c.envelope.area_min = {-30, -20};
  c.envelope.area_max = {30, 20};
  c.seed = seed;
  return c;
}

TEST(RandomAccelTest, StaysInsideBoundsSpeedAndAreaOverLongSeededRuns) {
  for (uint64_t seed : {1u, 2u, 3u, 42u, 1234u}) {
    const RandomAccelGuidance law(RandomConfig(seed));
    const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                        {0, 0, 5}, 0.01, 3000.0);
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(s.a_min[i], -0.8) << "seed " << seed;
      EXPECT_LE(s.a_max[i], 1.2) << "seed " << seed;
      // It fills the bounds: over 1500 knots both ends are approached.
      EXPECT_LT(s.a_min[i], -0.7) << "seed " << seed;
      EXPECT_GT(s.a_max[i], 1.1) << "seed " << seed;
    }
    EXPECT_GE(s.p_min[0], -30.0);
    EXPECT_LE(s.p_max[0], 30.0);
    EXPECT_GE(s.p_min[1], -20.0);
    EXPECT_LE(s.p_max[1], 20.0);
    // It uses the room: a random walk confined by the envelope reaches near the walls.
    EXPECT_GT(s.p_max[0] - s.p_min[0], 40.0) << "seed " << seed;
    // The speed may pass the limit by at most the ramp (the envelope's band) plus one step.
    EXPECT_LE(s.speed_max, 3.0 + 0.3 + 0.02) << "seed " << seed;
    // Band-limited: the cosine blend's slope is at most pi (a_max - a_min) / (2 tau) per second;
    // the envelope adds at most its own ramp slope (bounds / ramp x |dv| per step).
    const double signal_slope = kPi * 2.0 / (2 * 2.0);
    const double envelope_step = 2.0 / 0.3 * 1.2 * 0.01 + 2.0 / 0.3 * 0.01 * 3.0 / 0.05;
    EXPECT_LE(s.max_jump, signal_slope * 0.01 + envelope_step) << "seed " << seed;
  }
}

TEST(RandomAccelTest, SameSeedSameCommandsOtherSeedOtherCommands) {
  const RandomAccelGuidance a(RandomConfig(7)), b(RandomConfig(7)), c(RandomConfig(8));
  auto fly = [](const RandomAccelGuidance& law) {
    return Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
               {1, 2, 5}, 0.01, 200.0)
        .ax;
  };
  const auto xa = fly(a), xb = fly(b), xc = fly(c);
  EXPECT_EQ(xa, xb);  // bit for bit
  EXPECT_NE(xa, xc);
  // A pure function of time: evaluating out of order gives the same values.
  EXPECT_EQ(a.Signal(0, 17.3), a.Signal(0, 17.3));
  const double late = a.Signal(1, 99.0);
  (void)a.Signal(1, 3.0);
  EXPECT_EQ(a.Signal(1, 99.0), late);
}

TEST(RandomAccelTest, BadInputRefusedNamingTheKey) {
  auto refused = [](RandomAccelGuidance::Config c, const std::string& key) {
    try {
      RandomAccelGuidance law(c);
      ADD_FAILURE() << "accepted, expected a complaint about " << key;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  auto c = RandomConfig(1);
  c.bounds = {1.0, 1.0};
  refused(c, "a_min");  // a_min >= a_max
  c.bounds = {0.5, 1.0};
  refused(c, "a_min");  // cannot brake
  c = RandomConfig(1);
  c.correlation_time = 0;
  refused(c, "correlation_time");
  c = RandomConfig(1);
  c.envelope.area_max = {-29.9, 20};
  refused(c, "area");
  c = RandomConfig(1);
  c.envelope.speed_max = 0.1;
  refused(c, "speed_max");
}

BangBangGuidance::Config BangConfig(uint64_t seed) {
  BangBangGuidance::Config c;
  c.bounds = {-1.0, 1.0};
  c.dwell_min = 0.5;
  c.dwell_max = 3.0;
  c.envelope.speed_max = 3.0;
  c.envelope.area_min = {-40, -40};
  c.envelope.area_max = {40, 40};
  c.seed = seed;
  return c;
}

TEST(BangBangTest, AlwaysAtABoundAndInsideSpeedAndArea) {
  for (uint64_t seed : {1u, 5u, 99u}) {
    BangBangGuidance law(BangConfig(seed));
    const double dt = 0.001;
    const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                        {0, 0, 5}, dt, 1000.0);
    int switches = 0, at_min = 0;
    for (size_t k = 0; k < s.ax.size(); ++k) {
      ASSERT_TRUE(s.ax[k] == -1.0 || s.ax[k] == 1.0) << s.ax[k] << " at step " << k;
      if (k > 0 && s.ax[k] != s.ax[k - 1]) ++switches;
      at_min += s.ax[k] < 0;
    }
    // Dwell times average 1.75 s: about 570 switches in 1000 s (envelope switches add some).
    EXPECT_GT(switches, 300) << "seed " << seed;
    EXPECT_LT(switches, 2000) << "seed " << seed;
    EXPECT_GT(at_min, static_cast<int>(0.3 * s.ax.size()));
    EXPECT_LT(at_min, static_cast<int>(0.7 * s.ax.size()));
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(s.p_min[i], -40.0);
      EXPECT_LE(s.p_max[i], 40.0);
    }
    EXPECT_LE(s.speed_max, 3.0 + 2 * dt) << "seed " << seed;  // switches as the limit is reached
  }
}

TEST(BangBangTest, DeterministicResetAndTimeMustNotGoBack) {
  BangBangGuidance a(BangConfig(3)), b(BangConfig(3));
  auto fly = [](BangBangGuidance& law) {
    return Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
               {0, 0, 5}, 0.01, 300.0)
        .ax;
  };
  const auto first = fly(a);
  EXPECT_EQ(first, fly(b));
  EXPECT_THROW(a.Update(1.0, {0, 0, 5}, {0, 0, 0}), std::invalid_argument);
  a.Reset();
  EXPECT_EQ(first, fly(a));
  BangBangGuidance c(BangConfig(4));
  EXPECT_NE(first, fly(c));
}

TEST(BangBangTest, BadDwellAndBoundsRefused) {
  auto refused = [](BangBangGuidance::Config c, const std::string& key) {
    try {
      BangBangGuidance law(c);
      ADD_FAILURE() << "accepted, expected a complaint about " << key;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  auto c = BangConfig(1);
  c.dwell_min = 0;
  refused(c, "dwell");
  c.dwell_min = -1;
  refused(c, "dwell");
  c = BangConfig(1);
  c.dwell_max = 0.1;  // < dwell_min
  refused(c, "dwell");
  c = BangConfig(1);
  c.bounds = {2.0, -2.0};
  refused(c, "a_max");
}

TEST(LemniscateTest, FigureEightInsideBoundsAndTooFastRefused) {
  LemniscateGuidance::Config c;
  c.half_width = 20;
  c.omega = 0.15;  // peak 2 A w^2 = 0.9
  const LemniscateGuidance law(c);
  // On the reference the command is the reference acceleration; it crosses the centre twice.
  const GuidanceOutput r = law.Reference(kPi / 2 / 0.15);
  EXPECT_NEAR(r.pos[0], 20.0, 1e-9);
  EXPECT_NEAR(r.pos[1], 0.0, 1e-9);
  EXPECT_NEAR(r.acc[0], -20 * 0.15 * 0.15, 1e-12);
  const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                      {0, -10, 5}, 0.01, 300.0);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GE(s.a_min[i], -1.0);
    EXPECT_LE(s.a_max[i], 1.0);
  }
  EXPECT_NEAR(s.p_max[0], 20.0, 0.5);  // converged onto the figure-eight
  c.omega = 0.2;                       // 2 A w^2 = 1.6 > 1
  try {
    LemniscateGuidance fast(c);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("omega"), std::string::npos) << e.what();
  }
}

TEST(WaypointTest, SmoothPathThroughThePointsWithinBounds) {
  WaypointGuidance::Config c;
  c.points = {{20, 0}, {0, 20}, {-20, 0}, {0, -20}};
  c.speed = 2.0;
  c.loop = true;
  const WaypointGuidance law(c);
  const HermitePath& path = law.path();
  const double leg = std::hypot(20.0, 20.0) / 2.0;  // s per segment
  EXPECT_NEAR(path.duration(), 4 * leg, 1e-9);
  for (int k = 0; k <= 4; ++k) {  // through each point at its time, and around again
    const GuidanceOutput at = path.Evaluate(k * leg);
    EXPECT_NEAR(at.pos[0], c.points[k % 4][0], 1e-9) << k;
    EXPECT_NEAR(at.pos[1], c.points[k % 4][1], 1e-9) << k;
  }
  // C1: velocity continuous across a knot; acceleration inside the bounds everywhere (dense).
  const GuidanceOutput before = path.Evaluate(leg - 1e-7), after = path.Evaluate(leg + 1e-7);
  EXPECT_NEAR(before.vel[0], after.vel[0], 1e-5);
  EXPECT_NEAR(before.vel[1], after.vel[1], 1e-5);
  for (double t = 0; t < 2 * path.duration(); t += 0.01) {
    const GuidanceOutput r = path.Evaluate(t);
    ASSERT_LE(std::abs(r.acc[0]), 1.0 + 1e-12) << t;
    ASSERT_LE(std::abs(r.acc[1]), 1.0 + 1e-12) << t;
  }
  const auto hi = path.max_acc(), lo = path.min_acc();
  EXPECT_LE(hi[0], 1.0);
  EXPECT_GE(lo[0], -1.0);
  const Stats s = Fly([&](double t, const Vec3& p, const Vec3& v) { return law.Update(t, p, v); },
                      {20, 0, 5}, 0.01, 200.0);
  EXPECT_GE(s.a_min[0], -1.0);
  EXPECT_LE(s.a_max[1], 1.0);
}

TEST(WaypointTest, TooCloseForTheBoundsOrCoincidentRefused) {
  WaypointGuidance::Config c;
  c.points = {{0, 0}, {1, 0}, {1, 1}};  // 1 m legs at 4 m/s need ~ 16 m/s^2
  c.speed = 4.0;
  c.loop = false;
  try {
    WaypointGuidance law(c);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("points"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("too close"), std::string::npos) << e.what();
  }
  c.speed = 0.5;  // slow enough: 6 (1 m) / (2 s)^2 = 1.5 ... still above 1
  EXPECT_THROW(WaypointGuidance{c}, std::invalid_argument);
  c.speed = 0.3;
  EXPECT_NO_THROW(WaypointGuidance{c});
  c.points = {{0, 0}, {0, 0}};
  EXPECT_THROW(WaypointGuidance{c}, std::invalid_argument);
}

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

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

// The tracking leaders are functions of (t, state): two instances from the same configuration
// give the same commands bit for bit.
TEST(TrackingLeadersTest, SameConfigurationSameCommands) {
  LemniscateGuidance::Config lc;
  WaypointGuidance::Config wc;
  wc.points = {{20, 0}, {0, 20}, {-20, 0}, {0, -20}};
  wc.loop = true;
  const TrajectoryTable table =
      ReadTrajectoryCsv(WriteTemp("traj_det.csv", "0,0,0\n3,2,1\n6,5,1\n9,5,4\n"));
  const std::vector<std::function<GuidanceOutput(double, const Vec3&, const Vec3&)>> pairs[] = {
      {[l = LemniscateGuidance(lc)](double t, const Vec3& p, const Vec3& v) {
         return l.Update(t, p, v);
       },
       [l = LemniscateGuidance(lc)](double t, const Vec3& p, const Vec3& v) {
         return l.Update(t, p, v);
       }},
      {[w = WaypointGuidance(wc)](double t, const Vec3& p, const Vec3& v) {
         return w.Update(t, p, v);
       },
       [w = WaypointGuidance(wc)](double t, const Vec3& p, const Vec3& v) {
         return w.Update(t, p, v);
       }},
      {[g = TrajectoryGuidance({}, table)](double t, const Vec3& p, const Vec3& v) {
         return g.Update(t, p, v);
       },
       [g = TrajectoryGuidance({}, table)](double t, const Vec3& p, const Vec3& v) {
         return g.Update(t, p, v);
       }},
  };
  for (const auto& pair : pairs) {
    EXPECT_EQ(Fly(pair[0], {3, -2, 5}, 0.01, 60.0).ax, Fly(pair[1], {3, -2, 5}, 0.01, 60.0).ax);
  }
}

TEST(HashUniformTest, UniformAndIndependentOfCallOrder) {
  double sum = 0, lo = 1, hi = 0;
  for (uint64_t k = 0; k < 100000; ++k) {
    const double u = HashUniform(9, 0, k);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(sum / 100000, 0.5, 0.005);  // 5 standard errors of the mean (0.0009)
  EXPECT_LT(lo, 1e-3);
  EXPECT_GT(hi, 1 - 1e-3);
  EXPECT_NE(HashUniform(9, 0, 5), HashUniform(9, 1, 5));
  EXPECT_NE(HashUniform(9, 0, 5), HashUniform(10, 0, 5));
}

}  // namespace
}  // namespace mjf::guidance
