// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the formation laws taken from the literature (vs_tracking, super_twisting,
// adaptive_tracking, observer_tracking, terminal_smc) share: a positive-gain check that names the
// attribute, signed powers, and the clock that turns the host's step times into the dt their
// integrators need. Each law is written for double integrators tracking a leader and extended to
// a time-varying formation in the standard way: p_i -> p_i - f_ip, v_i -> v_i - f_iv,
// u_i -> u_i - f_ia, so the neighbour sums become e_i of eq. (16) of Wang et al. (AST 2021).
#ifndef MJFORMATION_FORMATION_LITERATURE_LAWS_HPP_
#define MJFORMATION_FORMATION_LITERATURE_LAWS_HPP_

#include <cmath>
#include <limits>

namespace mjf::formation {

// Throws std::invalid_argument "attribute '<key>': <key> > 0 is required by <source> (got v)"
// unless value is finite and > 0.
void RequirePositive(double value, const char* key, const char* source);

// sig(x)^a = sgn(x) |x|^a: the odd power x^(p/q) of p, q odd, for any real exponent a > 0.
inline double SignedPower(double x, double a) {
  return x > 0.0 ? std::pow(x, a) : (x < 0.0 ? -std::pow(-x, a) : 0.0);
}

// The step between two calls of a law that integrates a state (adaptive gain, observer,
// super-twisting integral): 0 on the first call after construction or Reset(), then the
// difference of the host's times (never negative).
class StepClock {
 public:
  double Advance(double time) {
    const double dt = std::isnan(last_time_) || time < last_time_ ? 0.0 : time - last_time_;
    last_time_ = time;
    return dt;
  }
  void Reset() { last_time_ = std::numeric_limits<double>::quiet_NaN(); }
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(last_time_);
  }

 private:
  double last_time_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_LITERATURE_LAWS_HPP_
