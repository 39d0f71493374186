// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <mjformation/formation/metrics.hpp>
#include <mjformation/formation/shape.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace mjf::formation {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string RefusalMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ShapeTest, PaperCircleValuesAndDerivatives) {
  const auto circle = MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);
  std::vector<double> f(36);
  circle->Evaluate(2.0, f.data());
  const double theta = 0.314 * 2.0 + 2 * kPi / 3;  // follower 3 (index 2): phase (3-1) pi/3
  EXPECT_NEAR(f[6 * 2 + kShapePx], 10 * std::cos(theta), 1e-12);
  EXPECT_NEAR(f[6 * 2 + kShapePy], 10 * std::sin(theta), 1e-12);
  EXPECT_NEAR(f[6 * 2 + kShapeVx], -0.314 * 10 * std::sin(theta), 1e-12);
  EXPECT_NEAR(f[6 * 2 + kShapeVy], 0.314 * 10 * std::cos(theta), 1e-12);
  EXPECT_NEAR(f[6 * 2 + kShapeAx], -0.314 * 0.314 * 10 * std::cos(theta), 1e-12);
  const mjfShape abi = ToAbi(*circle);
  std::vector<double> g(36);
  abi.evaluate(abi.self, 2.0, g.data());
  EXPECT_EQ(f, g);
  EXPECT_EQ(abi.n_followers, 6);
}

// EvaluateOne (and mjfShape.evaluate_one) gives follower i's entries of Evaluate bit for bit,
// for every shape type, inside and beyond a table: per-agent instances evaluate one follower at
// a time and must act on the same numbers as the swarm-level plugins.
TEST(ShapeTest, EvaluateOneIsEvaluateBitForBit) {
  std::vector<FollowerTerms> terms(3);
  for (int i = 0; i < 3; ++i) {
    terms[i].x.polynomial = {1.0 + i, 0.25, -0.125 * i};
    terms[i].x.sinusoids = {{0.5, 0.7, 0.1 * i}};
    terms[i].y.polynomial = {-2.0 * i};
  }
  std::vector<double> samples;
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 4; ++c) samples.push_back(0.3 * k + 1.7 * i - 0.9 * c + 0.01 * k * k);
    }
  }
  std::vector<std::unique_ptr<Shape>> shapes;
  shapes.push_back(MakeCircleShape(3, 10.0, 0.314, 0.2, kPi / 3));
  shapes.push_back(MakeTermsShape(terms));
  shapes.push_back(MakeSampledShape(3, {0.0, 1.5, 4.0}, samples));
  for (const auto& shape : shapes) {
    const mjfShape abi = ToAbi(*shape);
    mjfShape without_one = abi;
    without_one.evaluate_one = nullptr;  // a host that does not set it: AbiShape falls back
    const AbiShape fallback(without_one);
    for (double t : {-1.0, 0.0, 0.37, 1.5, 2.9, 4.0, 7.25}) {
      std::vector<double> all(18);
      shape->Evaluate(t, all.data());
      for (int i = 0; i < 3; ++i) {
        double one[6], through_abi[6], through_fallback[6];
        shape->EvaluateOne(t, i, one);
        abi.evaluate_one(abi.self, t, i, through_abi);
        fallback.EvaluateOne(t, i, through_fallback);
        for (int k = 0; k < 6; ++k) {
          EXPECT_EQ(one[k], all[6 * i + k]) << "t " << t << " follower " << i << " k " << k;
          EXPECT_EQ(through_abi[k], all[6 * i + k]);
          EXPECT_EQ(through_fallback[k], all[6 * i + k]);
        }
      }
    }
  }
}

TEST(ShapeTest, ConsistencyCheckAcceptsTheCircle) {
  const auto circle = MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);
  EXPECT_NO_THROW(CheckShapeConsistency(*circle, 0.0, 40.0, 0.01, 1e-4));
  EXPECT_NO_THROW(CheckShapeConsistency(*circle, 0.0, 40.0, 0.2, 1e-2));
}

// Algorithm 2's printed test f_ip(k+1) - f_ip(k) = T f_iv(k) is first order: the paper's own
// circle misses it by T r w^2 / 2 in m/s (0.0986 m/s for T = 0.2 s).
TEST(ShapeTest, PrintedForwardDifferenceFormRejectsThePapersCircleAtCoarseT) {
  const auto circle = MakeCircleShape(6, 10.0, 0.314, 0.0, kPi / 3);
  const std::string message = RefusalMessage([&] {
    CheckShapeConsistency(*circle, 0.0, 40.0, 0.2, 0.05, ConsistencyForm::kForwardDifference);
  });
  EXPECT_NE(message.find("f_ip' = f_iv"), std::string::npos) << message;
  EXPECT_NO_THROW(
      CheckShapeConsistency(*circle, 0.0, 40.0, 0.2, 0.1, ConsistencyForm::kForwardDifference));
}

TEST(ShapeTest, TermsShapeIsConsistentAndEvaluatesItsTerms) {
  FollowerTerms a;
  a.x.polynomial = {1.0, 0.5, -0.25};  // 1 + 0.5 t - 0.25 t^2
  a.y.sinusoids = {{2.0, 0.7, 0.3}};
  FollowerTerms b;
  b.x.polynomial = {-3.0};
  const auto shape = MakeTermsShape({a, b});
  std::vector<double> f(12);
  shape->Evaluate(2.0, f.data());
  EXPECT_NEAR(f[kShapePx], 1.0 + 1.0 - 1.0, 1e-12);
  EXPECT_NEAR(f[kShapeVx], 0.5 - 1.0, 1e-12);
  EXPECT_NEAR(f[kShapeAx], -0.5, 1e-12);
  EXPECT_NEAR(f[kShapePy], 2.0 * std::sin(1.7), 1e-12);
  EXPECT_NEAR(f[kShapeVy], 1.4 * std::cos(1.7), 1e-12);
  EXPECT_NEAR(f[6 + kShapePx], -3.0, 1e-12);
  EXPECT_NO_THROW(CheckShapeConsistency(*shape, 0.0, 10.0, 0.01, 1e-3));
}

TEST(ShapeTest, ConsistencyCheckRefusesAnInconsistentTableNamingFollowerAndTime) {
  // Follower 2's table moves 1 m per second in x but claims zero velocity from t = 1 s on.
  const std::vector<double> times = {0.0, 1.0, 2.0, 3.0};
  std::vector<double> samples;
  for (int k = 0; k < 4; ++k) {
    samples.insert(samples.end(), {5.0, 0.0, 0.0, 0.0});  // follower 1: still, consistent
    samples.insert(samples.end(), {1.0 * k, 0.0, k == 0 ? 1.0 : 0.0, 0.0});  // follower 2
  }
  const auto table = MakeSampledShape(2, times, samples);
  const std::string message =
      RefusalMessage([&] { CheckShapeConsistency(*table, 0.0, 3.0, 0.05, 0.05); });
  EXPECT_NE(message.find("follower 2"), std::string::npos) << message;
  EXPECT_NE(message.find("x axis"), std::string::npos) << message;
  EXPECT_NE(message.find("at t = "), std::string::npos) << message;
}

TEST(ShapeTest, SampledCircleTableIsConsistent) {
  const auto circle = MakeCircleShape(3, 10.0, 0.314, 0.0, 2 * kPi / 3);
  std::vector<double> times, samples, f(18);
  for (int k = 0; k <= 100; ++k) {
    times.push_back(0.2 * k);
    circle->Evaluate(0.2 * k, f.data());
    for (int i = 0; i < 3; ++i)
      samples.insert(samples.end(), f.begin() + 6 * i, f.begin() + 6 * i + 4);
  }
  const auto table = MakeSampledShape(3, times, samples);
  EXPECT_NO_THROW(CheckShapeConsistency(*table, 0.0, 20.0, 0.01, 2e-3));
  std::vector<double> g(18);
  table->Evaluate(7.3, g.data());
  circle->Evaluate(7.3, f.data());
  for (int k = 0; k < 18; ++k) EXPECT_NEAR(g[k], f[k], 5e-2) << k;
}

TEST(ShapeTest, BadShapeDefinitionsAreRefused) {
  EXPECT_THROW(MakeCircleShape(0, 10, 0.3, 0, 0), std::invalid_argument);
  EXPECT_THROW(MakeSampledShape(1, {0.0, 0.0}, std::vector<double>(8)), std::invalid_argument);
  EXPECT_THROW(MakeSampledShape(1, {0.0, 1.0}, std::vector<double>(7)), std::invalid_argument);
  FollowerTerms bad;
  bad.x.polynomial = {std::nan("")};
  EXPECT_THROW(MakeTermsShape({bad}), std::invalid_argument);
}

TEST(MetricsTest, FormationErrorIsEq68) {
  const double leader[] = {20, 0, 0, 3};
  const double shape[] = {10, 0, 0, 1, 0, 0, -10, 0, 0, -1, 0, 0};
  const double followers[] = {30, 0, 0, 4, 0, 1, 0, 2};  // follower 2: -10 m off in x, 1 in y
  EXPECT_DOUBLE_EQ(FormationError(2, followers, leader, shape), std::sqrt(10.0 * 10.0 + 1.0 * 1.0));
}

}  // namespace
}  // namespace mjf::formation
