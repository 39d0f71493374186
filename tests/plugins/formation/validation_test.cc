// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Algorithms 1/2 and Theorems 1/2: every invalid parameter is refused, naming the key.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>
#include <mjformation/formation/continuous_smc.hpp>
#include <mjformation/formation/discrete_smc.hpp>
#include <mjformation/formation/linear_consensus.hpp>
#include <stdexcept>
#include <string>

#include "test_util.hpp"

namespace mjf::formation {
namespace {

void ExpectRefused(const std::function<void()>& make, const std::vector<std::string>& fragments) {
  try {
    make();
    ADD_FAILURE() << "expected std::invalid_argument containing '" << fragments.front() << "'";
  } catch (const std::invalid_argument& e) {
    for (const auto& fragment : fragments) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "message '" << e.what() << "' lacks '" << fragment << "'";
    }
  }
}

template <typename Smc, typename Params>
std::function<void()> Build(Params p) {
  return [p] { Smc(testing::PaperGraph(), p); };
}

TEST(ValidationTest, ContinuousParameters) {
  using C = ContinuousSmcParams;
  EXPECT_NO_THROW(Build<ContinuousSmc>(C{})());
  C p;
  p.gains.k1 = 0;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'k'", "k1 > 0", "k1 = 0"});
  p = C{};
  p.gains.k2 = -1;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'k'", "k2 = -1"});
  p = C{};
  p.rho = 0;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'rho'", "rho > 0", "Theorem 1"});
  p = C{};
  p.reaching = Reaching::kExponential;
  p.q = -2;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'q'", "q > 0", "got -2"});
  p.reaching = Reaching::kConstant;  // q unused then
  EXPECT_NO_THROW(Build<ContinuousSmc>(p)());
  p = C{};
  p.u_min = 2;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'u_min' with 'u_max'", "u_min <= u_max"});
  p = C{};
  p.sign = SignFunction::kSat;
  p.boundary_layer = 0;
  ExpectRefused(Build<ContinuousSmc>(p), {"attribute 'boundary_layer'", "'sat'", "> 0"});
  ExpectRefused([] { ParseCompensation("upper"); }, {"attribute 'compensation'", "'upper'"});
  ExpectRefused([] { ParseReaching("fast"); }, {"attribute 'reaching'"});
  ExpectRefused([] { ParseSignFunction("tanh"); }, {"attribute 'sign'", "'sgn', 'sat'"});
}

TEST(ValidationTest, DiscreteParameters) {
  using D = DiscreteSmcParams;
  EXPECT_NO_THROW(Build<DiscreteSmc>(D{})());
  D p;
  p.gains.k1 = -3;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'k'"});
  p = D{};
  p.eps = 0;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'eps'", "eps > 0", "Theorem 2"});
  p = D{};
  p.q = 0;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'q'", "q > 0", "Theorem 2"});
  p = D{};
  p.period = 0;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'period'", "period > 0"});
  p = D{};
  p.q = 30;
  ExpectRefused(Build<DiscreteSmc>(p),
                {"attribute 'q' with 'period': 1 - q*T > 0 is required by Theorem 2 (got q = 30, "
                 "T = 0.05)"});
  p = D{};
  p.period = 0.25;  // q T = 1.125
  ExpectRefused(Build<DiscreteSmc>(p), {"1 - q*T > 0", "T = 0.25"});
  p = D{};
  p.u_max = -2;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'u_min' with 'u_max'"});
  p = D{};
  p.eta0 = 0;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'eta0'"});
  p = D{};
  p.gains = {25.0, 1.0};  // T k1 / k2 = 1.25 with T = 0.05: fine; with T = 0.1: 2.5
  EXPECT_NO_THROW(Build<DiscreteSmc>(p)());
  p.period = 0.1;
  p.q = 4.5;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'k' with 'period'", "T*k1/k2 < 2"});
  p = D{};
  p.sign = SignFunction::kSat;
  p.boundary_layer = -1;
  ExpectRefused(Build<DiscreteSmc>(p), {"attribute 'boundary_layer'"});
}

TEST(ValidationTest, ConsensusParameters) {
  ExpectRefused([] { LinearConsensus(testing::PaperGraph(), {0.0, 1.0}); }, {"attribute 'kp'"});
  ExpectRefused([] { LinearConsensus(testing::PaperGraph(), {1.0, -1.0}); }, {"attribute 'kv'"});
}

TEST(ValidationTest, GraphWithoutSpanningTreeIsRefusedByEveryProtocol) {
  const Graph g(4, {0, 1, 0, 0}, {{1, 2}, {3, 0}});
  ExpectRefused([&] { ContinuousSmc(g, {}); }, {"Assumption 2", "followers 1, 4"});
  ExpectRefused([&] { DiscreteSmc(g, {}); }, {"Assumption 2", "followers 1, 4"});
  ExpectRefused([&] { LinearConsensus(g, {}); }, {"Assumption 2", "followers 1, 4"});
}

TEST(TheoremTwoTest, BandAndBoundFollowEquations) {
  DiscreteSmcParams p;  // T 0.05, eps 0.05, q 4.5, k [3 1], u in [-1, 1]
  const DiscreteSmc smc(testing::PaperGraph(), p);
  const double kb = 1.0 * 0.05;
  EXPECT_DOUBLE_EQ(smc.delta2(0), 0.05 * 0.05 + kb * 2.0);                         // eq. (50)
  EXPECT_DOUBLE_EQ(smc.delta1(0), (0.05 * 0.05 + kb * 2.0 + 1e-6) / (2 - 0.225));  // eq. (49)
  EXPECT_DOUBLE_EQ(smc.delta2(1), 0.05 * 0.05);                                    // a_20 = 0
  EXPECT_DOUBLE_EQ(smc.delta(), smc.delta2(0));
  // ||L_H^-1||_2 from L_H written out by hand for PaperGraph (edges j -> i: row i gets -a_ij,
  // the diagonal d_i + a_i0) and a dense SVD: independent of the protocol's own solver.
  Eigen::MatrixXd lh = Eigen::MatrixXd::Zero(6, 6);
  const int edges[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {0, 2}, {2, 4}, {5, 3}};
  for (const auto& e : edges) {
    lh(e[1], e[0]) -= 1.0;
    lh(e[1], e[1]) += 1.0;
  }
  lh(0, 0) += 1.0;  // a_10 = 1
  const double norm = Eigen::JacobiSVD<Eigen::MatrixXd>(lh.inverse()).singularValues()(0);
  EXPECT_NEAR(smc.norm_inv_lh(), norm, 1e-9 * norm);
  // eq. (47) as EQUATIONS.md reads it: ||L_H^-1|| sqrt(N) Delta / ((k1 + k2) sqrt(2)), k = [3 1].
  EXPECT_NEAR(smc.error_bound(), norm * std::sqrt(6.0) * smc.delta() / (4.0 * std::sqrt(2.0)),
              1e-9 * smc.error_bound());
}

}  // namespace
}  // namespace mjf::formation
