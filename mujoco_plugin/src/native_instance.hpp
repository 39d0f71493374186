// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What a native plugin instance keeps outside plugin_state, and how it is found: the holder of
// its bridge's plugin instances (plugin_data is this cache, never the state), the table of
// which holder belongs to which mjData, and the names messages give an instance.
#ifndef MJFORMATION_MUJOCO_PLUGIN_NATIVE_INSTANCE_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_NATIVE_INSTANCE_HPP_

#include <mujoco/mujoco.h>

#include <cstdint>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace mjf::native {

// What an instance caches in plugin_data: its plugin instances and their initial state.
struct Holder {
  virtual ~Holder() = default;
  // One control tick for physics step `step` on the sensors of `d`; controls[actuator id], and
  // the forces besides the actuators' into `held` (held_size() doubles).
  virtual void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls,
                    double* held) = 0;
  // The forces besides the actuators' (SwarmHost::held_size; none for mjformation.attitude):
  // their block's size, adding them into d->qfrc_passive, and the commit of a step (motor lags).
  virtual size_t held_size() const { return 0; }
  virtual void AddForces(const mjModel*, mjData*, const double*) {}
  virtual void Advance(const mjModel*, double*) {}
  // The tick's state, fixed size (the blocks of plugin_state after the header).
  virtual size_t state_size() const = 0;
  virtual void GetState(double* out) const = 0;
  // GetState into the block it last got or set, writing only what changed.
  virtual void UpdateState(double* block) const { GetState(block); }
  virtual void SetState(const double* in) = 0;
  std::vector<double> initial;  // the state before the first tick (what a reset restores)
};

// Which holder belongs to which mjData. MuJoCo copies plugin_data raw in places (an unpickled
// MjData, mj_copyData before our copy callback runs), so a pointer found there is trusted only
// when this table says it is that mjData's own.
class Holders {
 public:
  static Holders& Get();  // process-wide: mjData pointers are
  Holder* Find(const mjData* d, int instance);
  // Takes `holder` as d's (the one it had before is freed) and returns it.
  Holder* Adopt(const mjData* d, int instance, std::unique_ptr<Holder> holder);
  std::unique_ptr<Holder> Release(const mjData* d, int instance);

 private:
  std::mutex mutex_;
  std::map<std::pair<const mjData*, int>, std::unique_ptr<Holder>> owned_;
};

// The instance's name in the model, or its index when it has none.
std::string InstanceName(const mjModel* m, int instance);
// "MJCF plugin 'PLUGIN' instance 'NAME'": where a message about an instance points.
std::string InstanceWhere(const char* plugin, const mjModel* m, int instance);

// Runs `make` on a thread of its own and returns what it made (or rethrows what it threw). A
// bridge may load a vehicle model (a compile of its own), and MuJoCo keeps the compiler's error
// jump per thread: a compile nested on the compiling thread would leave the outer compile's
// jump pointing into a finished frame.
template <typename Make>
auto OnOwnThread(Make make) -> decltype(make()) {
  decltype(make()) made;
  std::exception_ptr failure;
  std::thread builder([&] {
    try {
      made = make();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  builder.join();
  if (failure) std::rethrow_exception(failure);
  return made;
}

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_NATIVE_INSTANCE_HPP_
