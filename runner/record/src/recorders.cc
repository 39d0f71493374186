// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "mjformation/record/estimation_metrics.hpp"
#include "mjformation/record/frame_view.hpp"
#include "mjformation/record/leader_acceleration.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/record/safety_events.hpp"
#include "mjformation/render.hpp"
#include "mjformation/sim/simulation.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {

void Recorder::VisitState(StateArchive&) {
  throw StateArchiveError("a recorder of this run does not save its state");
}

namespace {

// The leader's measured acceleration against Assumption 1 (summary.json "leader_acceleration").
class LeaderAccelerationRecorder final : public Recorder {
 public:
  explicit LeaderAccelerationRecorder(const Simulation& sim) : monitor_(sim) {}
  void OnStep(const Simulation& sim) override { monitor_.Step(sim); }
  bool Wants(int64_t) const override { return false; }
  void Record(const Frame&) override {}
  void Summarize(nlohmann::ordered_json* summary) const override {
    (*summary)["leader_acceleration"] = monitor_.Summary();
  }
  const LeaderAccelerationMonitor& monitor() const { return monitor_; }
  void VisitState(StateArchive& archive) override { archive(monitor_); }

 private:
  LeaderAccelerationMonitor monitor_;
};

// timeseries.csv at [run] record_rate, and always at the last step; with
// [run] record_leader_acceleration the leader's measured acceleration as two more columns.
class TimeseriesRecorder final : public Recorder {
 public:
  TimeseriesRecorder(const Simulation& sim, const RunDirectory& dir,
                     const LeaderAccelerationRecorder* leader, bool resume)
      : leader_(leader),
        writer_(dir.Path("timeseries.csv"), sim.n_vehicles(), sim.config().sensors.enabled(),
                sim.config().wind.enabled(),
                leader ? std::vector<std::string>{"leader_ax", "leader_ay"}
                       : std::vector<std::string>{},
                sim.estimation() != nullptr, resume),
        every_(NearestSteps(1.0 / sim.config().record_rate, sim.config().timestep)),
        last_(sim.total_steps()) {}
  bool Wants(int64_t step) const override { return step % every_ == 0 || step == last_; }
  void Record(const Frame& f) override {
    writer_.Write(f.sim, f.sigma_f, f.slots,
                  leader_ ? leader_->monitor().current().data() : nullptr);
  }
  void Finish() override { writer_.Close(); }
  // The file's length at the checkpoint; on resume the file is cut back to it.
  void VisitState(StateArchive& archive) override {
    uint64_t length = archive.loading() ? 0 : writer_.Checkpoint();
    archive(length);
    if (archive.loading()) resumed_length_ = length;
  }
  void ResumeFiles() override { writer_.Rewind(resumed_length_); }

 private:
  const LeaderAccelerationRecorder* leader_;  // owned by the same recorder list
  TimeseriesWriter writer_;
  int64_t every_, last_;
  uint64_t resumed_length_ = 0;  // the file's length in the checkpoint loaded
};

std::vector<Vec3> Positions(const Simulation& sim) {
  std::vector<Vec3> out;
  for (const auto& s : sim.states()) out.push_back({s.pos[0], s.pos[1], s.pos[2]});
  return out;
}

// The marks of the safety events seen so far (frame_view.hpp): written by the SafetyRecorder
// when an event is first seen, with the vehicles' positions of that step; read by the pictures.
using EventMarks = std::vector<render::EventMark>;

// The vehicles' recent paths, the desired slots and circle, the safety events: what snapshots
// and video draw, by the rules replay and the live viewer share (frame_view.hpp).
class Scenery {
 public:
  Scenery(const Simulation& sim, std::shared_ptr<const EventMarks> events)
      : every_(NearestSteps(0.1, sim.config().timestep)),
        trails_(sim.n_vehicles(), sim.config().render.trail_seconds,
                every_ * sim.config().timestep),
        bodies_(VehicleBodies(sim.model(), sim.n_vehicles())),
        events_(std::move(events)) {}
  // Called every step by the recorders that draw; keeps a point every 0.1 s.
  void Update(const Simulation& sim) {
    if (sim.step_index() % every_ != 0 || sim.step_index() == last_step_) return;
    last_step_ = sim.step_index();
    trails_.Add(Positions(sim));
  }
  int64_t every() const { return every_; }
  void VisitState(StateArchive& archive) { archive(trails_, last_step_); }
  render::Overlay Overlay(const Simulation& sim, const std::vector<double>& slots) const {
    std::vector<std::array<double, 2>> vehicle_slots;  // [vehicle]; the leader's is not drawn
    for (int i = 0; i < sim.n_vehicles(); ++i)
      vehicle_slots.push_back({slots[2 * i], slots[2 * i + 1]});
    const ExperimentConfig& c = sim.config();
    const double ring = sim.shape() && c.shape.type == ShapeType::kCircle ? c.shape.radius : 0.0;
    render::Overlay o = FrameOverlay(trails_, Positions(sim), vehicle_slots, c.altitude, ring,
                                     FrameLabel(c.name, sim.time()));
    o.vehicle_bodies = bodies_;
    if (events_) o.events = *events_;
    return o;
  }

 private:
  int64_t every_;
  TrailBuffer trails_;
  std::vector<int> bodies_;
  std::shared_ptr<const EventMarks> events_;
  int64_t last_step_ = -1;
};

// An offscreen view of the scene with its overlay, for snapshots and video.
const std::vector<unsigned char>& RenderFrame(render::OffscreenRenderer& renderer,
                                              const Scenery& scenery, const Frame& f) {
  const std::vector<Vec3> positions = Positions(f.sim);
  const Vec3 target = CameraTarget(f.sim.config().render, positions);
  return renderer.Render(f.sim.data(), FollowingCamera(f.sim.config().render, positions, target),
                         scenery.Overlay(f.sim, f.slots), target.data());
}

// snapshots/t<sss.ss>.png at the configured times.
class SnapshotRecorder final : public Recorder {
 public:
  SnapshotRecorder(const Simulation& sim, const RunDirectory& dir, std::shared_ptr<Scenery> scenery)
      : dir_(dir),
        scenery_(std::move(scenery)),
        renderer_(sim.model(), sim.config().render.width, sim.config().render.height,
                  sim.config().render.shadows) {
    for (double t : sim.config().render.snapshots) {
      steps_.push_back(NearestStep(t, sim.config().timestep));
    }
  }
  bool Wants(int64_t step) const override {
    return step % scenery_->every() == 0 ||
           std::find(steps_.begin(), steps_.end(), step) != steps_.end();
  }
  void Record(const Frame& f) override {
    scenery_->Update(f.sim);
    if (std::find(steps_.begin(), steps_.end(), f.step) == steps_.end()) return;
    const RenderConfig& r = f.sim.config().render;
    const std::string name = fmt::format("snapshots/t{:06.2f}.png", f.sim.time());
    render::WritePng(dir_.Path(name), RenderFrame(renderer_, *scenery_, f).data(), r.width,
                     r.height);
    files_.push_back(name);
  }
  void Summarize(nlohmann::ordered_json* summary) const override {
    (*summary)["snapshots"] = files_;
  }
  // The trails drawn so far and the files written (the pictures themselves stay on disk).
  void VisitState(StateArchive& archive) override {
    scenery_->VisitState(archive);
    archive(files_);
  }

 private:
  const RunDirectory& dir_;
  std::shared_ptr<Scenery> scenery_;
  render::OffscreenRenderer renderer_;
  std::vector<int64_t> steps_;
  std::vector<std::string> files_;
};

// video.mp4 through ffmpeg, at [render] video_fps.
class VideoRecorder final : public Recorder {
 public:
  VideoRecorder(const Simulation& sim, const RunDirectory& dir, std::shared_ptr<Scenery> scenery)
      : scenery_(std::move(scenery)),
        renderer_(sim.model(), sim.config().render.video_width, sim.config().render.video_height,
                  sim.config().render.video_shadows),
        writer_(dir.Path("video.mp4"), sim.config().render.video_width,
                sim.config().render.video_height, sim.config().render.video_fps),
        every_(NearestSteps(1.0 / sim.config().render.video_fps, sim.config().timestep)) {}
  bool Wants(int64_t step) const override {
    return step % every_ == 0 || step % scenery_->every() == 0;
  }
  void Record(const Frame& f) override {
    scenery_->Update(f.sim);
    if (f.step % every_ == 0) writer_.AddFrame(RenderFrame(renderer_, *scenery_, f).data());
  }
  void Finish() override { writer_.Close(); }

 private:
  std::shared_ptr<Scenery> scenery_;
  render::OffscreenRenderer renderer_;
  render::VideoWriter writer_;
  int64_t every_;
};

// Safety events (safety_events.hpp), checked every step; with [run] stop_on, an event of a
// listed kind ends the run (the exception becomes the run's error: exit 3).
class SafetyRecorder final : public Recorder {
 public:
  SafetyRecorder(const Simulation& sim, std::shared_ptr<EventMarks> marks)
      : monitor_(sim.config().safety, VehicleRadii(sim)), marks_(std::move(marks)) {}
  void OnStep(const Simulation& sim) override {
    const size_t fresh = Check(sim);
    const auto& stop_on = sim.config().safety.stop_on;
    const auto& events = monitor_.events();
    for (size_t k = events.size() - fresh; k < events.size(); ++k) Mark(sim, events[k]);
    for (size_t k = events.size() - fresh; k < events.size(); ++k) {
      if (std::find(stop_on.begin(), stop_on.end(), events[k].kind) != stop_on.end()) {
        throw std::runtime_error("stopped at a safety event ([run] stop_on): " +
                                 DescribeEvent(events[k]));
      }
    }
  }
  bool Wants(int64_t) const override { return false; }
  void Record(const Frame&) override {}
  // Only a run with an event gains "events", so event-free runs keep their summary as it was.
  void Summarize(nlohmann::ordered_json* summary) const override {
    if (!monitor_.events().empty()) (*summary)["events"] = monitor_.Summary();
  }
  // The events seen so far and their marks for the pictures.
  void VisitState(StateArchive& archive) override {
    archive(monitor_);
    size_t n = marks_ ? marks_->size() : 0;
    archive(n);
    if (!marks_) return;
    if (archive.loading()) marks_->resize(n);
    for (auto& mark : *marks_) archive(mark.pos, mark.label);
  }

 private:
  // The monitor's check of this step. With partitioned physics each partition's thread tests
  // its own vehicles and the pairs its sorted places start (every step, on the caller's thread
  // it was the largest per-vehicle cost left there); the events are the same, in the same order.
  size_t Check(const Simulation& sim) {
    if (sim.threads() == 1) return monitor_.Check(sim.time(), sim.states());
    monitor_.Begin(sim.states());
    struct Job {
      SafetyMonitor* monitor;
      const std::vector<mjfVehicleState>* states;
    } job{&monitor_, &sim.states()};
    sim.ForEachVehicleRange(
        [](void* context, int first, int count, char*, size_t) {
          const Job& j = *static_cast<Job*>(context);
          j.monitor->Scan(first, count, *j.states);
        },
        &job);
    return monitor_.Finish(sim.time(), sim.states());
  }

  // The event's mark for the pictures, at the vehicles' positions (their midpoint for a pair)
  // of this step.
  void Mark(const Simulation& sim, const SafetyEvent& e) {
    if (!marks_ || marks_->size() >= kMaxEventMarks || !MarkedEventKind(e.kind)) return;
    Vec3 at = {0, 0, 0};
    for (int v : e.vehicles) {
      for (int k = 0; k < 3; ++k) at[k] += sim.states()[v].pos[k] / e.vehicles.size();
    }
    marks_->push_back(MakeEventMark(e.kind, e.time_s, e.vehicles, at));
  }

  SafetyMonitor monitor_;
  std::shared_ptr<EventMarks> marks_;
};

}  // namespace

// Each vehicle's radius about its body's origin that holds every geom of its subtree
// (bounding spheres, geom_rbound), from the model's rest frames. One pass: bodies are in
// depth-first order, so a parent's frame (relative to its vehicle) is known before its
// children's.
std::vector<double> VehicleRadii(const Simulation& sim) {
  const mjModel* m = sim.model();
  std::vector<int> owner(m->nbody, -1);
  std::vector<std::array<mjtNum, 3>> pos(m->nbody, {0, 0, 0});
  std::vector<std::array<mjtNum, 4>> quat(m->nbody, {1, 0, 0, 0});
  for (int v = 0; v < sim.n_vehicles(); ++v) owner[sim.binding(v).body] = v;
  for (int k = 1; k < m->nbody; ++k) {
    const int parent = m->body_parentid[k];
    if (owner[k] >= 0 || owner[parent] < 0) continue;  // a vehicle's own body, or not in one
    owner[k] = owner[parent];
    mjtNum offset[3];
    mju_rotVecQuat(offset, m->body_pos + 3 * k, quat[parent].data());
    for (int a = 0; a < 3; ++a) pos[k][a] = pos[parent][a] + offset[a];
    mju_mulQuat(quat[k].data(), quat[parent].data(), m->body_quat + 4 * k);
  }
  std::vector<double> radii(sim.n_vehicles(), 0.0);
  for (int g = 0; g < m->ngeom; ++g) {
    const int k = m->geom_bodyid[g];
    if (owner[k] < 0) continue;
    mjtNum p[3];
    mju_rotVecQuat(p, m->geom_pos + 3 * g, quat[k].data());
    for (int a = 0; a < 3; ++a) p[a] += pos[k][a];
    radii[owner[k]] = std::max(radii[owner[k]], mju_norm3(p) + m->geom_rbound[g]);
  }
  return radii;
}

namespace {

// summary.json "estimation", with an [estimator] other than passthrough: the
// estimate against the truth on the record ticks of the metric window (the rows of
// timeseries.csv there), and the estimator plugin's fused / gated / too-old counts.
class EstimationRecorder final : public Recorder {
 public:
  explicit EstimationRecorder(const Simulation& sim)
      : sim_(sim),
        metrics_(sim.n_vehicles()),
        window_(sim.config().metric_window),
        every_(NearestSteps(1.0 / sim.config().record_rate, sim.config().timestep)),
        last_(sim.total_steps()) {}
  void OnStep(const Simulation& sim) override {
    const int64_t step = sim.step_index();
    const double t = sim.time();
    if ((step % every_ != 0 && step != last_) || t < window_[0] - 1e-9 || t > window_[1] + 1e-9)
      return;
    metrics_.Add(sim.estimation()->estimates(), sim.states());
  }
  bool Wants(int64_t) const override { return false; }
  void Record(const Frame&) override {}
  void VisitState(StateArchive& archive) override { archive(metrics_); }
  void Summarize(nlohmann::ordered_json* summary) const override {
    std::vector<std::array<double, 3>> counts;  // as the run ended
    for (const auto& plugin : sim_.estimation()->estimators()) counts.push_back(Counts(*plugin));
    nlohmann::ordered_json e;
    e["plugin"] = sim_.config().estimator.plugin;
    e["window_s"] = window_;
    const nlohmann::ordered_json block = metrics_.Summary(counts);
    for (const auto& [k, v] : block.items()) e[k] = v;
    (*summary)["estimation"] = e;
  }

 private:
  // {fused, gated, too_old} from the plugin's report(); NaN for a count it does not report.
  static std::array<double, 3> Counts(const PluginInstance& plugin) {
    std::array<double, 3> c;
    c.fill(std::numeric_limits<double>::quiet_NaN());
    static const char* const kKeys[] = {"fused", "gated", "too_old"};
    for (const auto& [k, v] : plugin.Report()) {
      for (int n = 0; n < 3; ++n) {
        if (k == kKeys[n]) c[n] = v;
      }
    }
    return c;
  }

  const Simulation& sim_;
  EstimationMetrics metrics_;
  std::array<double, 2> window_;
  int64_t every_, last_;
};

}  // namespace

std::vector<std::unique_ptr<Recorder>> MakeRecorders(const Simulation& sim, const RunDirectory* dir,
                                                     const RecorderOptions& options) {
  std::vector<std::unique_ptr<Recorder>> out;
  if (!dir) return out;
  auto leader = std::make_unique<LeaderAccelerationRecorder>(sim);
  const LeaderAccelerationRecorder* leader_columns =
      sim.config().record_leader_acceleration ? leader.get() : nullptr;
  out.push_back(std::move(leader));  // first: its OnStep runs before the CSV row is written
  auto marks = std::make_shared<EventMarks>();
  out.push_back(std::make_unique<SafetyRecorder>(sim, marks));
  if (sim.estimation()) out.push_back(std::make_unique<EstimationRecorder>(sim));
  if (options.record) {
    out.push_back(std::make_unique<TimeseriesRecorder>(sim, *dir, leader_columns, options.resume));
  }
  const RenderConfig& r = sim.config().render;
  auto scenery = std::make_shared<Scenery>(sim, marks);
  if (options.render && !r.snapshots.empty()) {
    out.push_back(std::make_unique<SnapshotRecorder>(sim, *dir, scenery));
  }
  if (options.render && r.video) out.push_back(std::make_unique<VideoRecorder>(sim, *dir, scenery));
  return out;
}

}  // namespace mjf::runner
