// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "native_instance.hpp"

namespace mjf::native {

Holders& Holders::Get() {
  static Holders holders;
  return holders;
}

Holder* Holders::Find(const mjData* d, int instance) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = owned_.find({d, instance});
  return it == owned_.end() ? nullptr : it->second.get();
}

Holder* Holders::Adopt(const mjData* d, int instance, std::unique_ptr<Holder> holder) {
  std::unique_ptr<Holder> old;  // freed after the lock is released
  std::lock_guard<std::mutex> lock(mutex_);
  std::unique_ptr<Holder>& slot = owned_[{d, instance}];
  old = std::move(slot);
  slot = std::move(holder);
  return slot.get();
}

std::unique_ptr<Holder> Holders::Release(const mjData* d, int instance) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = owned_.find({d, instance});
  if (it == owned_.end()) return nullptr;
  std::unique_ptr<Holder> holder = std::move(it->second);
  owned_.erase(it);
  return holder;
}

std::string InstanceName(const mjModel* m, int instance) {
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  return name && name[0] ? name : std::to_string(instance);
}

std::string InstanceWhere(const char* plugin, const mjModel* m, int instance) {
  return std::string("MJCF plugin '") + plugin + "' instance '" + InstanceName(m, instance) + "'";
}

}  // namespace mjf::native
