// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/plugin_host.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>

#include "mjformation/config/nearest_word.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/config/source_location.hpp"

namespace mjf::runner {

const char* KindName(mjfKind kind) {
  switch (kind) {
    case MJF_KIND_GUIDANCE:
      return "guidance";
    case MJF_KIND_FORMATION:
      return "formation";
    case MJF_KIND_ATTITUDE:
      return "attitude";
    case MJF_KIND_FORMATION_AGENT:
      return "per-agent formation";
    case MJF_KIND_ESTIMATOR:
      return "estimator";
  }
  return "unknown";
}

namespace {

struct InProcessPlugins {
  std::mutex mutex;
  std::vector<LoadedPlugin> plugins;
};

// "was built for plugin ABI X, this runner speaks ABI Y; ...": what to do about it.
std::string AbiMismatch(uint32_t built) {
  std::string message = "was built for plugin ABI " + std::to_string(built) +
                        ", this runner speaks ABI " + std::to_string(MJF_ABI_VERSION) +
                        "; rebuild it against include/mjformation/plugin.h";
  if (built == 3 && MJF_ABI_VERSION == 4) {
    // The one step a plugin author takes by hand: declaring the instance's state.
    message +=
        " after adding state_size, get_state and set_state (docs/PLUGINS.md, \"Migrating from "
        "ABI 3\")";
  }
  return message;
}

InProcessPlugins& InProcess() {
  static InProcessPlugins registered;  // process-wide by design: the embedding program's own
  return registered;
}

}  // namespace

void RegisterInProcessPlugin(const mjfPlugin* plugin, const std::string& origin) {
  if (plugin == nullptr) return;
  InProcessPlugins& in_process = InProcess();
  std::lock_guard<std::mutex> lock(in_process.mutex);
  for (const LoadedPlugin& p : in_process.plugins) {
    if (p.descriptor == plugin) return;  // idempotent
  }
  in_process.plugins.push_back({plugin, origin});
}

void PluginRegistry::AddInProcessPlugins() {
  InProcessPlugins& in_process = InProcess();
  std::lock_guard<std::mutex> lock(in_process.mutex);
  for (const LoadedPlugin& p : in_process.plugins) {
    if (p.descriptor->abi_version != MJF_ABI_VERSION) {
      problems_.push_back(p.library + ": plugin '" + p.descriptor->name + "' " +
                          AbiMismatch(p.descriptor->abi_version));
      continue;
    }
    const bool duplicate = std::any_of(plugins_.begin(), plugins_.end(), [&](auto& q) {
      return std::strcmp(q.descriptor->name, p.descriptor->name) == 0;
    });
    if (duplicate) {
      problems_.push_back(p.library + ": plugin '" + p.descriptor->name +
                          "' shadowed by a library on the search path");
      continue;
    }
    plugins_.push_back(p);
  }
}

PluginRegistry::PluginRegistry(const std::vector<std::string>& search_path)
    : search_path_(search_path) {
  std::set<std::string> seen_files;
  for (const std::string& dir : search_path) {
    std::error_code ec;
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.size() > 6 && name.compare(0, 3, "lib") == 0 &&
          name.compare(name.size() - 3, 3, ".so") == 0) {
        files.push_back(name);
      }
    }
    if (ec) continue;                       // an absent folder on the search path is not an error
    std::sort(files.begin(), files.end());  // deterministic order
    for (const std::string& file : files) {
      const std::string path = dir + "/" + file;
      if (!seen_files.insert(file).second) continue;  // same library earlier on the path
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        problems_.push_back(path + ": cannot load: " + dlerror());
        continue;
      }
      auto entry = reinterpret_cast<mjfEntryFn>(dlsym(handle, MJF_ENTRY_SYMBOL));
      if (!entry) {
        problems_.push_back(path + ": not an mjformation plugin library (no " MJF_ENTRY_SYMBOL ")");
        dlclose(handle);
        continue;
      }
      handles_.push_back(handle);
      int count = 0;
      const mjfPlugin* const* list = entry(&count);
      for (int i = 0; list && i < count; ++i) {
        const mjfPlugin* p = list[i];
        if (!p) continue;
        // abi_version is the first field in every ABI version, so it is safe to read; the
        // rest of a foreign-ABI descriptor is not.
        if (p->abi_version != MJF_ABI_VERSION) {
          problems_.push_back(path + ": plugin #" + std::to_string(i) + " " +
                              AbiMismatch(p->abi_version));
          continue;
        }
        const bool duplicate = std::any_of(plugins_.begin(), plugins_.end(), [&](auto& q) {
          return std::strcmp(q.descriptor->name, p->name) == 0;
        });
        if (duplicate) {
          problems_.push_back(path + ": plugin '" + p->name +
                              "' shadowed by one earlier on the search path");
          continue;
        }
        plugins_.push_back({p, path});
      }
    }
  }
  AddInProcessPlugins();
}

PluginRegistry::~PluginRegistry() {
  for (void* h : handles_) dlclose(h);
}

const LoadedPlugin& PluginRegistry::Find(const std::string& name, const std::string& where) const {
  for (const auto& p : plugins_) {
    if (name == p.descriptor->name) return p;
  }
  std::vector<std::string> names;
  for (const auto& p : plugins_) names.push_back(p.descriptor->name);
  std::string message = where + ": unknown plugin '" + name + "'" + DidYouMean(name, names);
  std::string available;
  for (const auto& p : plugins_) {
    available += (available.empty() ? "" : ", ") + std::string(p.descriptor->name) + " (" +
                 KindName(p.descriptor->kind) + ")";
  }
  message += available.empty() ? "; no plugins found" : "; available: " + available;
  std::string folders;
  for (const auto& dir : search_path_) folders += (folders.empty() ? "" : ", ") + dir;
  message += "; searched: " + folders;
  for (const auto& problem : problems_) {
    if (problem.find("ABI") != std::string::npos) message += "; " + problem;
  }
  throw PluginError(message);
}

std::string PluginWhere(const PluginSection& section, const std::string& config_path,
                        const std::string& key) {
  return OriginLocation(config_path, {section.line, section.origin},
                        SectionKey(section.section, key))
      .Prefix();
}

std::vector<std::pair<std::string, std::string>> ResolveAttributes(const mjfPlugin& plugin,
                                                                   const PluginSection& section,
                                                                   const std::string& config_path) {
  auto where = [&](int line, const std::string& key) {
    return SourceLocation{config_path, line, SectionKey(section.section, key)}.Prefix();
  };
  std::vector<std::pair<std::string, std::string>> resolved;
  std::string declared;
  for (int i = 0; i < plugin.n_attributes; ++i) {
    declared += (declared.empty() ? "" : ", ") + std::string(plugin.attributes[i].key);
  }
  for (const auto& [key, value] : section.attributes) {
    bool known = false;
    for (int i = 0; i < plugin.n_attributes; ++i) known |= key == plugin.attributes[i].key;
    if (!known) {
      const std::string at = value.origin.empty()
                                 ? where(value.line, key)
                                 : value.origin + ": " + SectionKey(section.section, key);
      throw PluginError(at + ": plugin '" + plugin.name + "' has no attribute '" + key +
                        "' (its attributes: " + (declared.empty() ? "none" : declared) + ")");
    }
  }
  for (int i = 0; i < plugin.n_attributes; ++i) {
    const mjfAttribute& a = plugin.attributes[i];
    auto it = section.attributes.find(a.key);
    const auto derived = section.derived.find(a.key);
    if (it != section.attributes.end()) {
      resolved.emplace_back(a.key, it->second.text);
    } else if (derived != section.derived.end()) {
      resolved.emplace_back(a.key, derived->second);  // e.g. seed = [run] seed
    } else if (a.default_value) {
      resolved.emplace_back(a.key, a.default_value);
    } else {
      throw PluginError(PluginWhere(section, config_path, a.key) + ": plugin '" + plugin.name +
                        "' requires attribute '" + a.key + "' (" + (a.doc ? a.doc : "") + ")");
    }
  }
  return resolved;
}

namespace {

// Where a plugin's refusal points: at the attribute it names ("attribute 'a_max'" or
// "'a_max'"), when the file gives it, else at the `plugin =` line.
std::string RefusalWhere(const PluginSection& section, const std::string& config_path,
                         const std::string& error) {
  for (const auto& [key, value] : section.attributes) {
    if (error.find("'" + key + "'") == std::string::npos) continue;
    if (!value.origin.empty()) return value.origin + ": " + SectionKey(section.section, key);
    return SourceLocation{config_path, value.line, SectionKey(section.section, key)}.Prefix() +
           ": plugin";
  }
  return PluginWhere(section, config_path, "plugin");
}

}  // namespace

PluginInstance::PluginInstance(const LoadedPlugin& plugin, const PluginSection& section,
                               const std::string& config_path, mjfCreateContext base)
    : descriptor_(plugin.descriptor) {
  attributes_ = ResolveAttributes(*descriptor_, section, config_path);
  std::vector<const char*> keys, values;
  for (const auto& [k, v] : attributes_) {
    keys.push_back(k.c_str());
    values.push_back(v.c_str());
  }
  char error[1024] = {0};
  base.n_attributes = static_cast<int>(keys.size());
  base.keys = keys.data();
  base.values = values.data();
  base.error = error;
  base.error_size = sizeof(error);
  instance_ = descriptor_->create(&base);
  if (!instance_) {
    throw PluginError(RefusalWhere(section, config_path, error) + " '" + descriptor_->name + "' (" +
                      plugin.library +
                      ") refused its configuration: " + (error[0] ? error : "no reason given"));
  }
  if (descriptor_->state_size) {
    if (!descriptor_->get_state || !descriptor_->set_state) {
      if (descriptor_->destroy) descriptor_->destroy(instance_);
      throw PluginError(std::string("plugin '") + descriptor_->name + "' (" + plugin.library +
                        ") declares state_size without get_state and set_state: a plugin "
                        "sets all three or none (docs/PLUGINS.md, \"Plugin state\")");
    }
    state_size_ = descriptor_->state_size(instance_);
  }
}

PluginInstance::~PluginInstance() {
  if (instance_ && descriptor_->destroy) descriptor_->destroy(instance_);
}

std::vector<std::pair<std::string, double>> PluginInstance::Report() const {
  std::vector<std::pair<std::string, double>> out;
  if (!descriptor_->report) return out;
  descriptor_->report(
      instance_,
      [](void* user, const char* key, double value) {
        static_cast<std::vector<std::pair<std::string, double>>*>(user)->emplace_back(key, value);
      },
      &out);
  return out;
}

}  // namespace mjf::runner
