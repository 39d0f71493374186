// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Header-only C++ helpers for writing plugins against include/mjformation/plugin.h: typed
// attribute parsing with messages that name the key, a wrapper that turns C++ exceptions
// thrown by a controller's constructor into the ABI's "NULL + error string" convention, and what
// every formation law reads of its input (the planar state, a per-agent law's inbox).
#ifndef MJFORMATION_PLUGIN_UTIL_HPP_
#define MJFORMATION_PLUGIN_UTIL_HPP_

#include <mjformation/plugin.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mjformation/plugin_state.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mjf::plugin {

// Thrown by the helpers below; create() turns it into ctx->error.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Read-only view of the attributes handed to create(), with typed getters.
class Attributes {
 public:
  explicit Attributes(const mjfCreateContext* ctx) : ctx_(ctx) {}

  // The raw string value of a declared key; throws if the key was not declared.
  std::string String(const char* key) const {
    for (int i = 0; i < ctx_->n_attributes; ++i) {
      if (std::strcmp(ctx_->keys[i], key) == 0) return ctx_->values[i];
    }
    throw ConfigError(std::string("attribute '") + key + "' is not declared by this plugin");
  }

  // A finite real number.
  double Number(const char* key) const {
    const std::string text = String(key);
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE ||
        !std::isfinite(value)) {
      throw ConfigError(std::string("attribute '") + key + "': expected a finite number, got '" +
                        text + "'");
    }
    return value;
  }

  // A whitespace-separated list of finite numbers; size checked when expected_size >= 0.
  std::vector<double> Numbers(const char* key, int expected_size = -1) const {
    const std::string text = String(key);
    std::istringstream in(text);
    std::vector<double> values;
    std::string token;
    while (in >> token) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(value)) {
        throw ConfigError(std::string("attribute '") + key + "': '" + token +
                          "' is not a finite number");
      }
      values.push_back(value);
    }
    if (expected_size >= 0 && static_cast<int>(values.size()) != expected_size) {
      throw ConfigError(std::string("attribute '") + key + "': expected " +
                        std::to_string(expected_size) + " numbers, got " +
                        std::to_string(values.size()) + " ('" + text + "')");
    }
    return values;
  }

  // One of a fixed set of words.
  std::string Choice(const char* key, const std::vector<std::string>& allowed) const {
    const std::string text = String(key);
    for (const auto& a : allowed) {
      if (a == text) return text;
    }
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("'" + a + "'");
    throw ConfigError(std::string("attribute '") + key + "': '" + text + "' is not one of " + list);
  }

 private:
  const mjfCreateContext* ctx_;
};

// Throws ConfigError("attribute 'key' must satisfy <condition> (got value)") unless ok.
inline void Require(bool ok, const char* key, const char* condition, double value) {
  if (!ok) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.17g", value);
    throw ConfigError(std::string("attribute '") + key + "' must satisfy " + condition + " (got " +
                      buf + ")");
  }
}

// Runs make() and returns its result, or writes the exception's message to ctx->error and
// returns nullptr: the ABI's way of refusing a configuration.
template <typename Make>
void* CreateOrExplain(const mjfCreateContext* ctx, Make make) {
  try {
    return make();
  } catch (const std::exception& e) {
    if (ctx->error && ctx->error_size > 0) {
      std::snprintf(ctx->error, ctx->error_size, "%s", e.what());
    }
    return nullptr;
  }
}

// Writes a one-line reason for a failed compute() into ctx->error and returns `code` (nonzero):
//   if (!ok) return mjf::plugin::Fail(ctx, "thrust allocation is singular");
inline int Fail(const mjfStepContext* ctx, const char* reason, int code = 1) {
  if (ctx->error && ctx->error_size > 0) std::snprintf(ctx->error, ctx->error_size, "%s", reason);
  return code;
}

// Runs step() (returning 0 or a code) and turns a C++ exception into a failure with its message:
// no exception ever crosses the C ABI.
template <typename Step>
int ComputeOrExplain(const mjfStepContext* ctx, Step step) {
  try {
    return step();
  } catch (const std::exception& e) {
    return Fail(ctx, e.what());
  } catch (...) {
    return Fail(ctx, "unknown C++ exception");
  }
}

// The horizontal position and velocity a formation law reads of a vehicle: pv = (px, py, vx, vy).
inline void ReadPlanarPv(const mjfVehicleState& state, double* pv) {
  pv[0] = state.pos[0];
  pv[1] = state.pos[1];
  pv[2] = state.vel[0];
  pv[3] = state.vel[1];
}

// The per-agent formation payload (mjfMessage.payload) every per-agent law sends: [0..3] the
// law's own, [4..7] the leader's (px, py, vx, vy) as the sender knows it, relayed one hop per
// sample for the followers without a leader link.
inline constexpr int kPayloadLeader = 4;
inline constexpr int kPayloadUsed = 8;

// What a per-agent formation law has heard: each neighbour's message this call and the leader's
// state (own link, else a neighbour's relay; kept from call to call once heard). Gather()
// allocates nothing.
class NeighbourInbox {
 public:
  NeighbourInbox() = default;
  // neighbours: the follower indices j (0-based) whose messages the law needs.
  explicit NeighbourInbox(std::vector<int> neighbours)
      : neighbours_(std::move(neighbours)), found_(neighbours_.size(), nullptr) {}

  // Finds each neighbour's message (sender j + 1) in `in` and the leader's state; false while
  // something the law needs has not arrived: a neighbour's message, or the leader's own when
  // leader_weight (a_i0) > 0 (otherwise the leader's state only feeds the reference slots).
  bool Gather(const mjfAgentInput& in, double leader_weight) {
    std::fill(found_.begin(), found_.end(), nullptr);
    for (int k = 0; k < in.n_messages; ++k) {
      for (size_t m = 0; m < neighbours_.size(); ++m) {
        if (in.messages[k].sender == neighbours_[m] + 1) found_[m] = &in.messages[k];
      }
    }
    if (in.leader) {
      ReadPlanarPv(in.leader->state, leader_pv_);
      knows_leader_ = true;
    } else {
      for (const mjfMessage* m : found_) {
        if (m && m->n_payload >= kPayloadUsed) {
          std::copy(m->payload + kPayloadLeader, m->payload + kPayloadUsed, leader_pv_);
          knows_leader_ = true;
          break;
        }
      }
    }
    for (const mjfMessage* m : found_) {
      if (!m) return false;
    }
    return leader_weight <= 0.0 || in.leader != nullptr;
  }

  const std::vector<int>& neighbours() const { return neighbours_; }
  // Neighbour m's message of the last Gather(), null when none came (all non-null after a
  // Gather() that returned true).
  const mjfMessage* message(size_t m) const { return found_[m]; }
  bool knows_leader() const { return knows_leader_; }
  // The leader's (px, py, vx, vy) last heard; zeros until knows_leader().
  const double* leader_pv() const { return leader_pv_; }
  // What a Gather() leaves for the next: the leader's state as last heard (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(leader_pv_, knows_leader_);
  }

 private:
  std::vector<int> neighbours_;
  std::vector<const mjfMessage*> found_;  // [m]: neighbour m's message this call
  double leader_pv_[4] = {0, 0, 0, 0};
  bool knows_leader_ = false;
};

}  // namespace mjf::plugin

// Defines the exported entry point returning the given descriptors (pointers to mjfPlugin).
#define MJF_EXPORT_PLUGINS(...)                                                               \
  extern "C" __attribute__((visibility("default"))) const mjfPlugin* const* mjf_plugin_entry( \
      int* count) {                                                                           \
    static const mjfPlugin* const kPlugins[] = {__VA_ARGS__};                                 \
    *count = static_cast<int>(sizeof(kPlugins) / sizeof(kPlugins[0]));                        \
    return kPlugins;                                                                          \
  }

#endif  // MJFORMATION_PLUGIN_UTIL_HPP_
