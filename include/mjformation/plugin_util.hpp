// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Header-only C++ helpers for writing plugins against include/mjformation/plugin.h: typed
// attribute parsing with messages that name the key, and a wrapper that turns C++ exceptions
// thrown by a controller's constructor into the ABI's "NULL + error string" convention.
#ifndef MJFORMATION_PLUGIN_UTIL_HPP_
#define MJFORMATION_PLUGIN_UTIL_HPP_

#include <mjformation/plugin.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
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
