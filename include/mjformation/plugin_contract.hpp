// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The host-plugin contract: the attributes and report() keys the runner gives a meaning to, their
// units, and the typed values it reads from them. A plugin that declares one of these attributes
// or reports one of these keys gets the runner's use of it (the checks against a law's sample
// period, the predicted delay margin, the leader's acceleration against the law's bounds, the
// torque-authority check); any other key is the plugin's own, passed along untouched
// (summary.json "plugin_report"). The C ABI (plugin.h) carries attributes and reports as strings
// and (key, value) pairs; this header names the keys once and gives their values a type, for the
// plugin that writes them and for the runner that reads them (docs/PLUGINS.md, "The contract").
#ifndef MJFORMATION_PLUGIN_CONTRACT_HPP_
#define MJFORMATION_PLUGIN_CONTRACT_HPP_

#include <mjformation/plugin.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace mjf::plugin::contract {

// The keys. "attribute": declared in mjfPlugin.attributes; "report": emitted by report().
// A formation law (formation or per-agent formation plugin):
inline constexpr char kPeriod[] = "period";  // attribute and report: s, the sample period T
                                             // (0 or absent: every physics step)
inline constexpr char kQ[] = "q";            // report: 1/s, the reaching gain q of eq. (48)
inline constexpr char kDelta[] = "delta";    // report: m/s, the quasi-sliding band Delta, eq. (49)
inline constexpr char kUMin[] = "u_min";     // attribute: m/s^2, the leader input bounds the law
inline constexpr char kUMax[] = "u_max";     //   assumes (Assumption 1)
inline constexpr char kAccelLimit[] = "accel_limit";  // attribute: m/s^2, "none", or kFromVehicle
inline constexpr char kFromVehicle[] = "vehicle";     // accel_limit: the runner substitutes the
                                                      // vehicles' bound (their thrust and tilt)
// A guidance plugin flying the leader:
inline constexpr char kAMin[] = "a_min";  // attribute: m/s^2, the acceleration bounds it keeps
inline constexpr char kAMax[] = "a_max";
// An attitude plugin:
inline constexpr char kAttBw[] = "att_bw";  // report: 1/s, rate reference per rad of tilt error
inline constexpr char kAttBwUnlimited[] = "att_bw_unlimited";  // report: 1/s, before the plugin
                                                               // lowered it to the vehicle
inline constexpr char kTiltMax[] = "tilt_max";  // attribute and report: rad, the tilt limit
// The per-agent version of a formation law `name` is the plugin `name` + kAgentSuffix.
inline constexpr char kAgentSuffix[] = "_agent";

inline constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();

// What the runner reads of a formation law. kUnset (NaN): the law does not declare it.
struct Law {
  double period = kUnset;  // s (report)
  double q = kUnset;       // 1/s (report)
  double delta = kUnset;   // m/s (report)
  double u_min = kUnset;   // m/s^2 (attribute)
  double u_max = kUnset;
  // Law (48)'s predicted delay margin needs its T and q (docs/NETWORK.md "Delay margin").
  bool HasDelayMargin() const { return period > 0.0 && q > 0.0; }
  bool HasInputBounds() const { return std::isfinite(u_min) && std::isfinite(u_max); }
};

// What the runner reads of the leader's guidance plugin.
struct Guidance {
  double a_min = kUnset;  // m/s^2 (attribute)
  double a_max = kUnset;
  bool HasBounds() const { return std::isfinite(a_min) && std::isfinite(a_max); }
};

// What the runner reads of an attitude plugin.
struct Attitude {
  double att_bw = kUnset;            // 1/s (report)
  double att_bw_unlimited = kUnset;  // 1/s (report)
  double tilt_max = kUnset;          // rad (report)
};

// The name of the per-agent version of formation law `law`.
inline std::string AgentName(const std::string& law) { return law + kAgentSuffix; }

// An attribute's text as a finite number (the whole text); false otherwise.
inline bool ParseNumber(const char* text, double* value) {
  char* end = nullptr;
  const double x = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(x)) return false;
  *value = x;
  return true;
}

// The readers: each sets the field `key` names and returns true, or returns false when the key
// is not part of that plugin kind's contract. Report values are taken as given; attribute texts
// only when they are finite numbers.
inline bool SetReported(Law& law, const char* key, double value) {
  double* field = std::strcmp(key, kPeriod) == 0  ? &law.period
                  : std::strcmp(key, kQ) == 0     ? &law.q
                  : std::strcmp(key, kDelta) == 0 ? &law.delta
                                                  : nullptr;
  if (field) *field = value;
  return field != nullptr;
}
inline bool SetAttribute(Law& law, const char* key, const char* text) {
  double* field = std::strcmp(key, kUMin) == 0   ? &law.u_min
                  : std::strcmp(key, kUMax) == 0 ? &law.u_max
                                                 : nullptr;
  return field && ParseNumber(text, field);
}
inline bool SetAttribute(Guidance& guidance, const char* key, const char* text) {
  double* field = std::strcmp(key, kAMin) == 0   ? &guidance.a_min
                  : std::strcmp(key, kAMax) == 0 ? &guidance.a_max
                                                 : nullptr;
  return field && ParseNumber(text, field);
}
inline bool SetReported(Attitude& attitude, const char* key, double value) {
  double* field = std::strcmp(key, kAttBw) == 0            ? &attitude.att_bw
                  : std::strcmp(key, kAttBwUnlimited) == 0 ? &attitude.att_bw_unlimited
                  : std::strcmp(key, kTiltMax) == 0        ? &attitude.tilt_max
                                                           : nullptr;
  if (field) *field = value;
  return field != nullptr;
}

// The writer, for a law's report(): emits the fields it declares (not kUnset), period, q, delta.
inline void Emit(const Law& law, mjfReportFn emit, void* user) {
  if (!std::isnan(law.period)) emit(user, kPeriod, law.period);
  if (!std::isnan(law.q)) emit(user, kQ, law.q);
  if (!std::isnan(law.delta)) emit(user, kDelta, law.delta);
}

}  // namespace mjf::plugin::contract

#endif  // MJFORMATION_PLUGIN_CONTRACT_HPP_
