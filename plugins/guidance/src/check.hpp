// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Private to mjf_guidance_core: how the laws format numbers and refuse a bad configuration
// (std::invalid_argument naming the attribute, which the plugin adapters turn into a message).
#ifndef MJFORMATION_GUIDANCE_SRC_CHECK_HPP_
#define MJFORMATION_GUIDANCE_SRC_CHECK_HPP_

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance::check {

inline std::string Num(double v) {
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

[[noreturn]] inline void Refuse(const std::string& message) {
  throw std::invalid_argument(message);
}

// "attribute 'key' must be finite": the leaders' wording, keyed by the plugin attribute.
inline void RequireFiniteAttribute(double v, const char* key) {
  if (!std::isfinite(v)) Refuse(std::string("attribute '") + key + "' must be finite");
}

// The PD gains and the constant references of a law that tracks a reference (leaders' wording).
inline void ValidateTracking(const TrackingGains& g, double altitude, double yaw) {
  if (!(g.kp >= 0) || !(g.kd >= 0) || !std::isfinite(g.kp) || !std::isfinite(g.kd)) {
    Refuse("attributes 'kp', 'kd' must be finite and >= 0");
  }
  RequireFiniteAttribute(altitude, "altitude");
  RequireFiniteAttribute(yaw, "yaw");
}

// The circle's and hover's wording (they predate the attribute-keyed messages).
inline void RequireGains(const TrackingGains& g) {
  if (!(g.kp >= 0) || !(g.kd >= 0) || !std::isfinite(g.kp) || !std::isfinite(g.kd)) {
    throw std::invalid_argument("guidance gains kp, kd must be finite and >= 0");
  }
}

inline void RequireFinite(double v, const char* what) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be finite");
}

}  // namespace mjf::guidance::check

#endif  // MJFORMATION_GUIDANCE_SRC_CHECK_HPP_
