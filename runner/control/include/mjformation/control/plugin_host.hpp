// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Finds plugin libraries on a search path, dlopen()s them, checks the ABI version, and wraps
// plugin instances (attribute checking, create/compute/reset/destroy). One registry per
// simulation: nothing here is global, so simulations on several threads do not interfere.
#ifndef MJFORMATION_CONTROL_PLUGIN_HOST_HPP_
#define MJFORMATION_CONTROL_PLUGIN_HOST_HPP_

#include <mjformation/plugin.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mjformation/config/experiment.hpp"

namespace mjf::runner {

class PluginError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const char* KindName(mjfKind kind);

struct LoadedPlugin {
  const mjfPlugin* descriptor = nullptr;
  std::string library;  // the .so it came from
};

class PluginRegistry {
 public:
  // Loads every lib*.so in the folders (first folder wins on duplicate names). Libraries that
  // are not mjformation plugins or speak another ABI are noted in problems(), not fatal.
  explicit PluginRegistry(const std::vector<std::string>& search_path);
  ~PluginRegistry();
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  // The plugin called `name`; throws PluginError (prefixed with `where`) listing the plugins of
  // that kind that were found, or naming the library whose ABI does not match.
  const LoadedPlugin& Find(const std::string& name, const std::string& where) const;

  const std::vector<LoadedPlugin>& plugins() const { return plugins_; }
  const std::vector<std::string>& problems() const { return problems_; }
  const std::vector<std::string>& search_path() const { return search_path_; }

 private:
  std::vector<std::string> search_path_;
  std::vector<void*> handles_;
  std::vector<LoadedPlugin> plugins_;
  std::vector<std::string> problems_;
  void AddInProcessPlugins();
};

// One live plugin instance.
class PluginInstance {
 public:
  // Checks the section's attributes against the declaration (unknown key, missing required
  // one), fills defaults, and calls create(). `base` carries everything but the attributes and
  // the error buffer. Throws PluginError as "FILE:LINE: [section] ...: message".
  PluginInstance(const LoadedPlugin& plugin, const PluginSection& section,
                 const std::string& config_path, mjfCreateContext base);
  ~PluginInstance();
  PluginInstance(const PluginInstance&) = delete;
  PluginInstance& operator=(const PluginInstance&) = delete;

  int Compute(const mjfStepContext& ctx) { return descriptor_->compute(instance_, &ctx); }
  void Reset() {
    if (descriptor_->reset) descriptor_->reset(instance_);
  }
  std::vector<std::pair<std::string, double>> Report() const;

  // The instance's declared state (ABI 4): its size in doubles (0 for a plugin without state),
  // fixed at create(), and the calls that write and read it.
  size_t state_size() const { return state_size_; }
  bool declares_state() const { return descriptor_->state_size != nullptr; }
  void GetState(double* out) const {
    if (state_size_ > 0) descriptor_->get_state(instance_, out);
  }
  void SetState(const double* in) {
    if (state_size_ > 0) descriptor_->set_state(instance_, in);
  }

  const mjfPlugin& descriptor() const { return *descriptor_; }
  // Every declared attribute with the value in use (given or default), declaration order.
  const std::vector<std::pair<std::string, std::string>>& attributes() const { return attributes_; }

 private:
  const mjfPlugin* descriptor_;
  void* instance_ = nullptr;
  size_t state_size_ = 0;
  std::vector<std::pair<std::string, std::string>> attributes_;
};

// In-process plugins: descriptors compiled into the embedding program (e.g. the Python module's
// formation law that calls back into Python), not loaded from a library. Every registry created
// afterwards lists them after the libraries of its search path, with `origin` as their library.
// The descriptor must live as long as the process; same ABI check as a library's. Thread-safe.
void RegisterInProcessPlugin(const mjfPlugin* plugin, const std::string& origin);

// "FILE:LINE: [section] key" at the section's plugin key, or "--set section={...}: [section]
// key" when the command line gave it: where a plugin's refusals point.
std::string PluginWhere(const PluginSection& section, const std::string& config_path,
                        const std::string& key);

// The attribute checks of PluginInstance alone (also used by `mjformation check`).
std::vector<std::pair<std::string, std::string>> ResolveAttributes(const mjfPlugin& plugin,
                                                                   const PluginSection& section,
                                                                   const std::string& config_path);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_PLUGIN_HOST_HPP_
