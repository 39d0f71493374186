// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/partitioned_physics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "mjformation/config/source_location.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/scene/vehicle_binding.hpp"
#include "mjformation/sim/actuation.hpp"
#include "mjformation/sim/mujoco_errors.hpp"
#include "mjformation/sim/step_checks.hpp"

namespace mjf::runner {

// K - 1 worker threads that run one job per partition in lockstep with the caller, which runs
// partition 0. A phase is short (tens of microseconds to a millisecond), and so is the caller's
// work between two phases (the control tick, recording: about 0.4 ms per step at 1000 followers,
// a few ms on a recording step). Every wait (a worker's for the next phase, the caller's for the
// workers) spins briefly on the counter, then yields its core (sched_yield) for up to
// kYieldFor, then sleeps on a condition variable. Why the middle stage: a worker that slept
// through the control tick costs a futex wake and, on a virtual machine, the wake-up of an idle
// virtual CPU (tens of microseconds) at every phase, several per step, which is what kept the
// 2-thread speed-up below its Amdahl bound at 1000 followers (docs/PERFORMANCE.md); a yielding
// waiter sees the next phase within a microsecond. On a loaded machine a yield hands the core
// to whatever else is runnable and comes back only after it (a slice, about a millisecond): a
// waiter whose yield took longer than kBusyYield sleeps at once, so that it does not keep
// competing for a core with the thread it waits for. No allocation after construction.
class LockstepPool {
 public:
  using Job = void (*)(void* context, int partition);
  explicit LockstepPool(int workers) {
    for (int k = 1; k <= workers; ++k) threads_.emplace_back([this, k] { Work(k); });
  }
  ~LockstepPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
      generation_.fetch_add(1, std::memory_order_release);
    }
    start_.notify_all();
    for (auto& t : threads_) t.join();
  }
  LockstepPool(const LockstepPool&) = delete;
  LockstepPool& operator=(const LockstepPool&) = delete;

  // Runs job(context, k) for every partition k (0 here, the others on the workers) and returns
  // when all have finished. `job` must not throw.
  void Run(Job job, void* context) {
    job_ = job;
    context_ = context;
    pending_.store(static_cast<int>(threads_.size()), std::memory_order_relaxed);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      generation_.fetch_add(1, std::memory_order_release);
    }
    start_.notify_all();
    job(context, 0);
    Await(done_, [this] { return pending_.load(std::memory_order_acquire) == 0; });
  }

 private:
  static constexpr int kSpins = 1000;  // 4-50 us of pause instructions, by CPU generation
  // Longest a waiter yields before it sleeps: longer than the caller's work between phases at
  // 1000 followers (a recording step included), short against a run.
  static constexpr std::chrono::microseconds kYieldFor{5000};
  // A yield that returns later than this gave the core to another runnable thread: the machine
  // is busy (on an idle core sched_yield returns within a few microseconds).
  static constexpr std::chrono::microseconds kBusyYield{100};
  static void Pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }

  // Returns once ready() holds: spins, then yields the core, then sleeps on `cv` (whose
  // notifier changes what ready() reads under mutex_ or notifies after such a change).
  template <typename Ready>
  void Await(std::condition_variable& cv, Ready ready) {
    for (int s = 0; s < kSpins; ++s) {
      if (ready()) return;
      Pause();
    }
    auto now = std::chrono::steady_clock::now();
    const auto until = now + kYieldFor;
    while (!ready()) {
      std::this_thread::yield();
      const auto before = now;
      now = std::chrono::steady_clock::now();
      if (now >= until || now - before > kBusyYield) {
        std::unique_lock<std::mutex> lock(mutex_);
        cv.wait(lock, ready);
        return;
      }
    }
  }

  void Work(int k) {
    uint64_t seen = 0;
    for (;;) {
      Await(start_, [&] { return generation_.load(std::memory_order_acquire) != seen; });
      seen = generation_.load(std::memory_order_acquire);
      if (stop_) return;
      job_(context_, k);
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);
        done_.notify_one();
      }
    }
  }

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  bool stop_ = false;  // written under mutex_ with a generation change
  Job job_ = nullptr;
  void* context_ = nullptr;
};

namespace {
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
}  // namespace

// One partition: vehicles [first, first + count) in a model of their own.
struct Partition {
  int first = 0, count = 0;
  std::unique_ptr<mjModel, ModelDeleter> model;
  std::unique_ptr<mjData, DataDeleter> data;
  VehicleBindings bindings;  // vehicle i of the partition is vehicle first + i of the swarm
  std::unique_ptr<Actuation> actuation;
  std::vector<mjfVehicleState> truth;  // this partition's vehicles
  std::vector<double> controls;        // this partition's slice of the swarm's controls
  StateOffsets offsets;                // where it sits in the whole model
  int act_offset = 0;
  std::exception_ptr error;  // set by a failed phase
  bool integrated = false;   // Step2 got past mj_step2 (a failure was then the state check's)
  std::array<char, 512> message{};  // a range job's plugin messages
};

namespace {

std::string ThreadsWhere(const ExperimentConfig& c) {
  return OriginLocation(c.source_path, c.threads_origin, SectionKey("run", "threads")).Prefix();
}

// Vehicle geoms that can touch a copy of themselves on another vehicle: MuJoCo collides two
// geoms when (contype1 & conaffinity2) || (contype2 & conaffinity1); every vehicle is a copy of
// the same model, so vehicle 0's geoms tell for all.
std::string InterVehicleContact(const mjModel* m, int vehicle_body) {
  std::vector<int> geoms;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->body_rootid[m->geom_bodyid[g]] == vehicle_body) geoms.push_back(g);
  }
  for (int a : geoms) {
    for (int b : geoms) {
      if ((m->geom_contype[a] & m->geom_conaffinity[b]) ||
          (m->geom_contype[b] & m->geom_conaffinity[a])) {
        const char* na = mj_id2name(m, mjOBJ_GEOM, a);
        return fmt::format(
            "geom {} (contype {}, conaffinity {}) of one vehicle collides with geom "
            "{} of another (contype {}, conaffinity {})",
            na ? na : std::to_string(a), m->geom_contype[a], m->geom_conaffinity[a], b,
            m->geom_contype[b], m->geom_conaffinity[b]);
      }
    }
  }
  return "";
}

}  // namespace

void CheckPartitionable(const ExperimentConfig& config, const mjModel* whole,
                        const std::vector<int>& vehicle_bodies) {
  if (config.threads < 1) throw ConfigError(ThreadsWhere(config) + ": must be >= 1");
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  if (config.threads > 1 && cores > 0 && config.threads > cores) {
    std::fprintf(stderr,
                 "warning: %s: %d threads on a machine with %d cores: the partitions will take "
                 "turns on the cores (same results, slower)\n",
                 ThreadsWhere(config).c_str(), config.threads, cores);
  }
  if (config.threads == 1) return;
  if (config.threads > static_cast<int>(vehicle_bodies.size())) {
    throw ConfigError(ThreadsWhere(config) + ": " + std::to_string(config.threads) +
                      " partitions for " + std::to_string(vehicle_bodies.size()) +
                      " vehicles: at most one partition per vehicle");
  }
  if (whole->opt.disableflags & mjDSBL_CONTACT) return;
  const std::string contact = InterVehicleContact(whole, vehicle_bodies[0]);
  if (!contact.empty()) {
    throw ConfigError(ThreadsWhere(config) + ": = " + std::to_string(config.threads) +
                      " needs vehicles that do not touch each other through MuJoCo, but " +
                      contact + "; use threads = 1, or [vehicles] contacts = false");
  }
}

namespace {
// Partition k's first vehicle of n, out of k_parts contiguous ranges.
int FirstOfPartition(int n, int k, int k_parts) {
  return static_cast<int>(static_cast<int64_t>(n) * k / k_parts);
}
}  // namespace

PartitionModels ComposePartitions(int k_parts, const SceneRequest& request) {
  const int n = static_cast<int>(request.positions.size());
  PartitionModels models;
  for (int k = 0; k < k_parts; ++k) {
    const int first = FirstOfPartition(n, k, k_parts);
    const int last = FirstOfPartition(n, k + 1, k_parts);
    SceneRequest part = request;
    part.positions.assign(request.positions.begin() + first, request.positions.begin() + last);
    part.first_vehicle = first;
    part.write_text = false;
    models.push_back(ComposeScene(part, fmt::format("partition {} of the scene", k)).model);
  }
  return models;
}

PartitionedPhysics::PartitionedPhysics(const ExperimentConfig& config, const SceneRequest& request,
                                       PartitionModels models, const mjfPlugin& attitude,
                                       const std::string& vehicle_xml, const mjModel* whole) {
  const int n = static_cast<int>(request.positions.size());
  const int k_parts = config.threads;
  if (static_cast<int>(models.size()) != k_parts) {
    throw std::logic_error("PartitionedPhysics: " + std::to_string(models.size()) +
                           " partition models for " + std::to_string(k_parts) + " threads");
  }
  int nq = 0, nv = 0, na = 0, nu = 0;
  for (int k = 0; k < k_parts; ++k) {
    auto p = std::make_unique<Partition>();
    p->first = FirstOfPartition(n, k, k_parts);
    p->count = FirstOfPartition(n, k + 1, k_parts) - p->first;
    p->model = std::move(models[k]);
    p->data.reset(mj_makeData(p->model.get()));
    p->bindings = BindVehicles(p->model.get(), config, attitude, vehicle_xml, p->first, p->count);
    p->actuation = WithRotorFaults(
        MakeActuation(config.rotor_model, p->model.get(), p->bindings, config.timestep), config,
        p->bindings, p->first);
    p->truth.resize(p->count);
    p->controls.assign(static_cast<size_t>(p->count) * p->bindings.actuators_per_vehicle, 0.0);
    p->offsets = {nq, nv, nu};
    p->act_offset = na;
    nq += p->model->nq;
    nv += p->model->nv;
    na += p->model->na;
    nu += p->model->nu;
    parts_.push_back(std::move(p));
  }
  // Every degree of freedom exactly once: the scene itself has no moving bodies of its own
  // (they would be simulated once per partition), and the layout is the vehicles' in order.
  if (nq != whole->nq || nv != whole->nv || na != whole->na || nu != whole->nu) {
    throw ConfigError(ThreadsWhere(config) + ": the scene " + config.scene_path +
                      " has joints or actuator states of its own (besides the vehicles'), which "
                      "cannot be split between partitions; use threads = 1");
  }
  pool_ = std::make_unique<LockstepPool>(k_parts - 1);
}

PartitionedPhysics::~PartitionedPhysics() = default;

void PartitionedPhysics::RunPhase(Phase phase) {
  struct Ctx {
    PartitionedPhysics* self;
    Phase phase;
  } ctx{this, phase};
  pool_->Run(
      [](void* c, int k) {
        auto* x = static_cast<Ctx*>(c);
        x->self->RunPartition(k, x->phase);
      },
      &ctx);
  // The lowest failed partition's error: the same message whatever the threads' timing.
  for (auto& p : parts_) {
    if (p->error) {
      std::exception_ptr e = p->error;
      failed_after_integration_ = p->integrated;
      for (auto& q : parts_) q->error = nullptr;
      std::rethrow_exception(e);
    }
  }
}

void PartitionedPhysics::RunPartition(int k, Phase phase) {
  Partition& p = *parts_[k];
  const mjModel* m = p.model.get();
  mjData* d = p.data.get();
  try {
    if (phase == Phase::kStep1) {
      ClearMujocoWarning();
      mj_step1(m, d);
      ReadTrueStates(d, p.bindings, &p.truth);
      std::copy(p.truth.begin(), p.truth.end(), truth_->begin() + p.first);
      return;
    }
    if (phase == Phase::kRange) {
      range_job_(range_context_, p.first, p.count, p.message.data(), p.message.size());
      return;
    }
    const int per = p.bindings.actuators_per_vehicle;
    std::copy(controls_->begin() + static_cast<ptrdiff_t>(p.first) * per,
              controls_->begin() + static_cast<ptrdiff_t>(p.first + p.count) * per,
              p.controls.begin());
    // The whole-swarm order (simulation.cc): rotor wrenches, then external forces, into the
    // qfrc_passive of this partition's mj_step1.
    p.actuation->Apply(p.controls, d);
    if (forces_) {
      for (int i = 0; i < p.count; ++i) {
        const double* f = forces_->data() + 3 * static_cast<size_t>(p.first + i);
        const mjtNum wrench[6] = {f[0], f[1], f[2], 0, 0, 0};
        AddWrenchAtCentreOfMass(m, d, p.bindings.vehicles[i].body, wrench);
      }
    }
    p.integrated = false;
    mj_step2(m, d);
    p.integrated = true;
    p.actuation->Advance(p.controls);
    CheckStepState(m, d, time_after_, p.offsets);
  } catch (...) {
    p.error = std::current_exception();
  }
}

void PartitionedPhysics::Step1(std::vector<mjfVehicleState>* truth) {
  truth_ = truth;
  RunPhase(Phase::kStep1);
}

void PartitionedPhysics::ForEachRange(RangeJob job, void* context) {
  range_job_ = job;
  range_context_ = context;
  RunPhase(Phase::kRange);
}

void PartitionedPhysics::Step2(const std::vector<double>& controls,
                               const std::vector<double>* forces, double time_after) {
  controls_ = &controls;
  forces_ = forces;
  time_after_ = time_after;
  RunPhase(Phase::kStep2);
}

mjData* PartitionedPhysics::partition_data(int k) { return parts_.at(k)->data.get(); }

void PartitionedPhysics::VisitState(StateArchive& archive) {
  archive.Tag("partitions");
  for (const auto& p : parts_) {
    const mjModel* m = p->model.get();
    mjData* d = p->data.get();
    const size_t size = static_cast<size_t>(mj_stateSize(m, mjSTATE_INTEGRATION));
    std::vector<double> physics(size);
    if (!archive.loading()) mj_getState(m, d, physics.data(), mjSTATE_INTEGRATION);
    archive(physics);
    if (physics.size() != size) {
      throw StateArchiveError("the saved state's partition " + std::to_string(p->first) +
                              " holds " + std::to_string(physics.size()) +
                              " numbers where this configuration has " + std::to_string(size));
    }
    if (archive.loading()) mj_setState(m, d, physics.data(), mjSTATE_INTEGRATION);
    p->actuation->VisitState(archive);
  }
}

void PartitionedPhysics::CopyInto(const mjModel* whole, mjData* data) const {
  for (const auto& p : parts_) {
    const mjModel* m = p->model.get();
    const mjData* d = p->data.get();
    std::memcpy(data->qpos + p->offsets.qpos, d->qpos, sizeof(mjtNum) * m->nq);
    std::memcpy(data->qvel + p->offsets.dof, d->qvel, sizeof(mjtNum) * m->nv);
    if (m->na) std::memcpy(data->act + p->act_offset, d->act, sizeof(mjtNum) * m->na);
    data->time = d->time;
  }
  mj_kinematics(whole, data);
  mj_comPos(whole, data);
  mj_camlight(whole, data);
}

}  // namespace mjf::runner
