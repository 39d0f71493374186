// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "swarm_plugin.hpp"

#include <mujoco/mjplugin.h>

#include <mutex>

#include "attach_names.hpp"
#include "mjformation/scene/scene.hpp"
#include "scene_files.hpp"
#include "swarm_host.hpp"

namespace mjf::native {
namespace {

// What one model's swarm instances share (the files read, the libraries loaded), kept per
// model so that a new mjData, a copy or a reset reads nothing again. Keyed by the model's
// address and what the instance is made of (its configuration, sizes and timestep), so a later
// model at the same address is not mistaken for it.
class SwarmModels {
 public:
  static SwarmModels& Get() {
    static SwarmModels models;
    return models;
  }
  std::shared_ptr<const SwarmShared> For(const mjModel* m, int instance) {
    const std::string key = Key(m, instance);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const Entry& e : entries_) {
        if (e.model == m && e.instance == instance && e.key == key) return e.shared;
      }
    }
    const runner::ExperimentConfig config = SwarmPlugin::Config(m, instance);
    const runner::SceneNames names = SwarmPlugin::Names(m, instance, config);
    std::shared_ptr<const SwarmShared> shared =
        OnOwnThread([&] { return SwarmHost::Prepare(m, config, true, names); });
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back({m, instance, key, shared});
    if (entries_.size() > kKept) entries_.erase(entries_.begin());
    return shared;
  }

 private:
  static constexpr size_t kKept = 16;  // models alive at once in one process, generously
  static std::string Key(const mjModel* m, int instance) {
    std::string key =
        std::to_string(m->nu) + "/" + std::to_string(m->nsensor) + "/" + std::to_string(m->nbody) +
        "/" + std::to_string(m->opt.timestep) + "\n" +
        SceneFolder(m, instance);  // the same scene from another folder reads other files
    for (const std::string& section : CarriedSections()) {
      const char* value = mj_getPluginConfig(m, instance, section.c_str());
      key += "\n" + section + "=" + (value ? value : "");
    }
    return key;
  }
  struct Entry {
    const mjModel* model;
    int instance;
    std::string key;
    std::shared_ptr<const SwarmShared> shared;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
};

struct SwarmHolder final : Holder {
  std::unique_ptr<SwarmHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls,
            double* held) override {
    host->Tick(step, m, d, controls, held);
  }
  size_t held_size() const override { return host->held_size(); }
  void AddForces(const mjModel* m, mjData* d, const double* held) override {
    host->AddForces(m, d, held);
  }
  void Advance(const mjModel* m, double* held) override { host->Advance(m, held); }
  size_t state_size() const override { return host->state_size(); }
  void GetState(double* out) const override { host->GetState(out); }
  void UpdateState(double* block) const override { host->UpdateState(block); }
  void SetState(const double* in) override { host->SetState(in); }
};

}  // namespace

runner::ExperimentConfig SwarmPlugin::Config(const mjModel* m, int instance) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& key : CarriedSections()) {
    const char* value = mj_getPluginConfig(m, instance, key.c_str());
    pairs.emplace_back(key, value ? value : "");
  }
  return ConfigFromPairs(pairs, InstanceWhere(SwarmPlugin::kName, m, instance),
                         SceneFolder(m, instance));
}

std::vector<std::string> SwarmPlugin::Bodies(int followers) {
  std::vector<std::string> bodies;
  for (int i = 0; i <= followers; ++i) {
    bodies.push_back(runner::VehiclePrefix(i) + "vehicle");
  }
  return bodies;
}

runner::SceneNames SwarmPlugin::Names(const mjModel* m, int instance,
                                      const runner::ExperimentConfig& config) {
  return InstanceNames(m, instance, Bodies(config.followers), InstanceWhere(kName, m, instance));
}

std::unique_ptr<Holder> SwarmPlugin::Make(const mjModel* m, int instance) {
  auto holder = std::make_unique<SwarmHolder>();
  holder->host = std::make_unique<SwarmHost>(SwarmModels::Get().For(m, instance));
  return holder;
}

// runner::DescribeVehicles stands for the bindings while the model compiles.
size_t SwarmPlugin::StateSize(const mjModel* m, int instance) {
  const runner::ExperimentConfig config = SwarmPlugin::Config(m, instance);
  SwarmPlugin::Names(m, instance, config);
  const std::unique_ptr<SwarmHost> host = OnOwnThread(
      [&] { return std::make_unique<SwarmHost>(SwarmHost::Prepare(m, config, false)); });
  return host->held_size() + host->state_size();
}

const PluginKind kSwarmKind = {SwarmPlugin::kName, SwarmPlugin::Make, SwarmPlugin::StateSize};

void SwarmPlugin::Register() {
  static const std::vector<const char*> kAttributes = [] {
    std::vector<const char*> names;
    for (const std::string& key : CarriedSections()) names.push_back(key.c_str());
    return names;
  }();
  ActuatorPlugin<kSwarmKind>::Register(kAttributes);
}

}  // namespace mjf::native
