// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation._core: the runner library for Python (docs/PYTHON.md). The Python package
// (python/mjformation/) wraps it; this file only converts. Every call that simulates releases the
// GIL; input errors become ValueError with the runner's FILE:LINE: [section] key message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "driven.hpp"
#include "mjformation/app/cli.hpp"
#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/export/export.hpp"
#include "mjformation/formation/shape.hpp"
#include "mjformation/record/engine_identity.hpp"
#include "mjformation/record/output.hpp"
#include "mjformation/run/interrupt.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/sim/simulation.hpp"
#include "python_law.hpp"

namespace py = pybind11;
namespace rn = mjf::runner;

namespace {

// The runner's SIGINT/SIGTERM/SIGHUP handling for as long as some run or sweep is under way
// (several may run on Python threads at once), then Python's own handlers again. A Ctrl-C thus
// ends every run cleanly (marked incomplete) and the caller raises KeyboardInterrupt.
class SignalScope {
 public:
  SignalScope() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (active_++ > 0) return;
    rn::ClearInterrupt();
    sigaction(SIGINT, nullptr, &old_int_);
    sigaction(SIGTERM, nullptr, &old_term_);
    sigaction(SIGHUP, nullptr, &old_hup_);
    sigaction(SIGXFSZ, nullptr, &old_xfsz_);
    rn::InstallInterruptHandlers();
  }
  ~SignalScope() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (--active_ > 0) return;
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    sigaction(SIGHUP, &old_hup_, nullptr);
    sigaction(SIGXFSZ, &old_xfsz_, nullptr);
  }
  SignalScope(const SignalScope&) = delete;
  SignalScope& operator=(const SignalScope&) = delete;

 private:
  static inline std::mutex mutex_;
  static inline int active_ = 0;
  static inline struct sigaction old_int_ { }, old_term_{}, old_hup_{}, old_xfsz_{}; };

// `render`: whether [render]'s snapshot times and sizes are checked; a run that renders nothing
// skips them, as the CLI's --no-render does (a short run needs no snapshot-time override).
rn::ExperimentConfig Load(const std::string& path, const std::vector<std::string>& overrides,
                          const std::vector<std::string>& plugin_path, bool render = true) {
  rn::ExperimentConfig config =
      rn::LoadExperiment(path, overrides, rn::ExperimentChecks::Rendering(render));
  for (const auto& p : plugin_path) config.plugin_path.push_back(p);
  return config;
}

py::dict RunResultDict(const rn::RunResult& r) {
  py::dict d;
  d["complete"] = r.complete;
  d["error"] = r.error;
  d["signal"] = r.signal;
  d["summary_error"] = r.summary_error;
  d["wall_time_s"] = r.wall_time_s;
  d["sim_time_s"] = r.sim_time_s;
  d["steps"] = r.steps;
  d["summary"] = r.summary.dump();
  return d;
}

py::dict Run(const std::string& path, const std::vector<std::string>& overrides,
             const std::vector<std::string>& plugin_path, const std::string& out, bool overwrite,
             bool render, bool record) {
  const rn::ExperimentConfig config = Load(path, overrides, plugin_path, render);
  rn::RunOptions options;
  options.out_dir = out;
  options.overwrite = overwrite;
  options.render = render;
  options.record = record;
  rn::RunResult result;
  {
    py::gil_scoped_release nogil;
    SignalScope signals;
    result = rn::RunExperiment(config, options);
  }
  return RunResultDict(result);
}

// `mjformation <args>` in-process (the sweep and check commands), with the GIL released.
int CommandLine(const std::vector<std::string>& args) {
  std::vector<const char*> argv{"mjformation"};
  for (const auto& a : args) argv.push_back(a.c_str());
  py::gil_scoped_release nogil;
  SignalScope signals;
  const int code = rn::RunCommandLine(static_cast<int>(argv.size()), argv.data());
  std::fflush(stdout);
  return code;
}

py::dict Check(const std::string& path, const std::vector<std::string>& overrides,
               const std::vector<std::string>& plugin_path, bool render) {
  const rn::ExperimentConfig config = Load(path, overrides, plugin_path, render);
  std::unique_ptr<rn::Simulation> sim;
  {
    py::gil_scoped_release nogil;
    sim = std::make_unique<rn::Simulation>(config);
  }
  py::dict d;
  d["experiment"] = config.name;
  d["followers"] = config.followers;
  d["model"] = config.model_path;
  d["bodies"] = sim->model()->nbody;
  d["leader"] = config.leader.plugin;
  d["formation"] = config.formation.plugin;
  d["attitude"] = config.attitude.plugin;
  d["vehicle_notes"] = sim->vehicle_notes();
  return d;
}

py::list Plugins(const std::vector<std::string>& plugin_path) {
  rn::PluginRegistry registry(rn::PluginSearchPath(plugin_path));
  py::list out;
  for (const auto& p : registry.plugins()) {
    const mjfPlugin& d = *p.descriptor;
    py::dict attributes;
    for (int k = 0; k < d.n_attributes; ++k) {
      const mjfAttribute& a = d.attributes[k];
      attributes[a.key] =
          py::dict(py::arg("default") = a.default_value ? py::object(py::str(a.default_value))
                                                        : py::object(py::none()),
                   py::arg("doc") = a.doc ? a.doc : "");
    }
    out.append(py::dict(py::arg("name") = d.name, py::arg("kind") = rn::KindName(d.kind),
                        py::arg("doc") = d.doc ? d.doc : "", py::arg("library") = p.library,
                        py::arg("attributes") = attributes));
  }
  return out;
}

std::string ReadFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw py::value_error(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string text(static_cast<size_t>(file.tellg()), '\0');
  file.seekg(0);
  file.read(text.data(), static_cast<std::streamsize>(text.size()));
  return text;
}

std::vector<std::string> CsvHeader(const std::string& text, size_t eol) {
  std::vector<std::string> header;
  for (size_t start = 0;;) {
    const size_t comma = text.find(',', start);
    const size_t end = comma == std::string::npos || comma > eol ? eol : comma;
    std::string name = text.substr(start, end - start);
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    header.push_back(name);
    if (end == eol) return header;
    start = end + 1;
  }
}

// The rows after the header, row-major; a row with the wrong number of cells (a truncated
// last line) is dropped. from_chars: exact, locale-free and faster than strtod.
std::vector<double> CsvRows(const char* p, const char* stop, size_t columns) {
  std::vector<double> values, row(columns);
  while (p < stop) {
    size_t k = 0;
    bool ok = true;
    for (;; ++k) {
      double v = std::numeric_limits<double>::quiet_NaN();  // an empty cell
      const char* end = std::from_chars(p, stop, v).ptr;
      while (end < stop && *end != ',' && *end != '\n') ++end;
      if (k < columns)
        row[k] = v;
      else
        ok = false;
      p = end;
      if (p >= stop || *p == '\n') break;
      ++p;  // the comma
    }
    if (ok && k + 1 == columns && p < stop) values.insert(values.end(), row.begin(), row.end());
    ++p;  // the newline; a last line without one was cut short and is not kept
  }
  return values;
}

// timeseries.csv (or any numeric CSV with a header) as (header, columns x rows float array):
// one C++ pass with the GIL released, each column contiguous.
py::tuple ReadCsv(const std::string& path) {
  std::vector<std::string> header;
  std::vector<double> columns_major;
  size_t rows = 0;
  {
    py::gil_scoped_release nogil;
    const std::string text = ReadFile(path);
    const size_t eol = text.find('\n');
    // A C++ exception object only: Python sees it once the GIL is back (end of this scope).
    if (eol == std::string::npos) throw py::value_error(path + ": no header line");
    header = CsvHeader(text, eol);
    const std::vector<double> values =
        CsvRows(text.data() + eol + 1, text.data() + text.size(), header.size());
    rows = values.size() / header.size();
    columns_major.resize(values.size());
    for (size_t r = 0; r < rows; ++r) {
      for (size_t c = 0; c < header.size(); ++c)
        columns_major[c * rows + r] = values[r * header.size() + c];
    }
  }
  py::array_t<double> data(
      {static_cast<py::ssize_t>(header.size()), static_cast<py::ssize_t>(rows)});
  std::memcpy(data.mutable_data(), columns_major.data(), columns_major.size() * sizeof(double));
  return py::make_tuple(header, data);
}

py::array_t<double> States(const std::vector<mjfVehicleState>& states) {
  py::array_t<double> out({static_cast<py::ssize_t>(states.size()), py::ssize_t{13}});
  std::memcpy(out.mutable_data(), states.data(), states.size() * sizeof(mjfVehicleState));
  return out;
}

// Desired x, y of every vehicle (the leader's setpoint, then leader + f_i), as the recorders see
// them: the setpoints' reference positions.
py::array_t<double> Slots(const rn::Simulation& sim) {
  py::array_t<double> out({static_cast<py::ssize_t>(sim.n_vehicles()), py::ssize_t{2}});
  for (int v = 0; v < sim.n_vehicles(); ++v) {
    out.mutable_at(v, 0) = sim.setpoints()[v].pos[0];
    out.mutable_at(v, 1) = sim.setpoints()[v].pos[1];
  }
  return out;
}

py::array_t<double> Setpoints(const rn::Simulation& sim) {
  const auto& sp = sim.setpoints();
  constexpr py::ssize_t kSize = sizeof(mjfSetpoint) / sizeof(double);  // acc pos vel yaw sliding
  py::array_t<double> out({static_cast<py::ssize_t>(sp.size()), kSize});
  std::memcpy(out.mutable_data(), sp.data(), sp.size() * sizeof(mjfSetpoint));
  return out;
}

// The Python Simulation is always at a control tick: its states, setpoints and slots are those of
// time(), as a timeseries.csv row at that time records them. step(n): integrate, then the tick.
void Step(rn::Simulation& sim, int64_t n) {
  if (n < 0)
    throw py::value_error("step(n): n is a number of physics steps >= 0, got " + std::to_string(n));
  py::gil_scoped_release nogil;
  for (int64_t k = 0; k < n && sim.step_index() < sim.total_steps(); ++k) {
    sim.Integrate();
    sim.ComputeControls();
  }
}

// leader_weight[i] = a_i0, adjacency[i, j] = a_ij (edge j -> i), followers 0-based.
py::dict GraphDict(const rn::Simulation& sim) {
  const rn::ExperimentConfig& c = sim.config();
  const py::ssize_t n = c.followers;
  py::array_t<double> leader({n}), adjacency({n, n});
  std::memcpy(leader.mutable_data(), c.leader_weight.data(), n * sizeof(double));
  std::fill(adjacency.mutable_data(), adjacency.mutable_data() + n * n, 0.0);
  for (const auto& e : c.edges) adjacency.mutable_at(e.to, e.from) = e.weight;
  py::dict d;
  d["leader_weight"] = leader;
  d["adjacency"] = adjacency;
  return d;
}

void BindSimulation(py::module_& m) {
  py::class_<rn::Simulation>(m, "Simulation")
      .def(py::init([](const std::string& path, const std::vector<std::string>& overrides,
                       const std::vector<std::string>& plugin_path) {
             const rn::ExperimentConfig config =
                 Load(path, overrides, plugin_path, /*render=*/false);  // it renders nothing
             py::gil_scoped_release nogil;
             auto sim = std::make_unique<rn::Simulation>(config);
             sim->ComputeControls();  // the tick at t = 0
             return sim;
           }),
           py::arg("experiment"), py::arg("overrides"), py::arg("plugin_path"))
      .def("step", &Step, py::arg("n") = 1)
      .def_property_readonly("time", &rn::Simulation::time)
      .def_property_readonly("step_index", &rn::Simulation::step_index)
      .def_property_readonly("total_steps", &rn::Simulation::total_steps)
      .def_property_readonly("n_vehicles", &rn::Simulation::n_vehicles)
      .def_property_readonly("states", [](const rn::Simulation& s) { return States(s.states()); })
      .def_property_readonly("measured",
                             [](const rn::Simulation& s) { return States(s.measured()); })
      .def_property_readonly("setpoints", &Setpoints)
      .def_property_readonly("slots", &Slots)
      .def_property_readonly(
          "controls",
          [](const rn::Simulation& s) {
            const auto& c = s.controls();
            py::array_t<double> out({static_cast<py::ssize_t>(s.n_vehicles()),
                                     static_cast<py::ssize_t>(s.actuators_per_vehicle())});
            std::memcpy(out.mutable_data(), c.data(), c.size() * sizeof(double));
            return out;
          })
      .def_property_readonly("graph", &GraphDict)
      .def_property_readonly("scene_xml", &rn::Simulation::scene_xml)
      .def("get_state",
           [](rn::Simulation& s) { return py::bytes(mjf::python::SimulationState(s, nullptr)); })
      .def(
          "set_state",
          [](rn::Simulation& s, const py::bytes& state) {
            mjf::python::RestoreSimulationState(s, nullptr, std::string(state));
          },
          py::arg("state"));
}

// Checks the followers' commands: an (N, 3) array of finite numbers (acceleration x, y and the
// vertical feedforward, m/s^2) or an (N, 2) one (no feedforward); returns them [follower][3].
std::vector<double> Commands(const rn::Simulation& sim, const py::array_t<double>& actions) {
  const py::ssize_t n = sim.n_followers();
  const auto columns = actions.ndim() == 2 ? actions.shape(1) : -1;
  if (actions.ndim() != 2 || actions.shape(0) != n || (columns != 2 && columns != 3)) {
    std::string shape;
    for (py::ssize_t k = 0; k < actions.ndim(); ++k)
      shape += (k ? ", " : "") + std::to_string(actions.shape(k));
    throw py::value_error("step(actions): actions has shape (" + shape + "), expected (" +
                          std::to_string(n) + ", 3): each follower's acceleration x, y, z, m/s^2");
  }
  std::vector<double> out(3 * static_cast<size_t>(n), 0.0);
  for (py::ssize_t i = 0; i < n; ++i) {
    for (py::ssize_t k = 0; k < columns; ++k) {
      const double a = actions.at(i, k);
      if (!std::isfinite(a))
        throw py::value_error("step(actions): the command of follower " + std::to_string(i) +
                              " (0-based) is not finite");
      out[3 * i + k] = a;
    }
  }
  return out;
}

// act(actions or None, steps) -> physics steps done; the GIL released while it flies.
int64_t Act(mjf::python::DrivenSimulation& d, const std::optional<py::array_t<double>>& actions,
            int64_t steps) {
  if (steps < 0) throw py::value_error("steps is a number of physics steps >= 0");
  std::vector<double> commands;
  if (actions) commands = Commands(d.sim(), *actions);
  py::gil_scoped_release nogil;
  return d.Act(actions ? commands.data() : nullptr, steps);
}

// Checks the followers' wrenches: an (N, 4) array, finite where `given` (collective thrust N,
// body moments N m); returns them [follower][4].
std::vector<double> Wrenches(const rn::Simulation& sim, const py::array_t<double>& actions,
                             const std::vector<unsigned char>& given) {
  const py::ssize_t n = sim.n_followers();
  if (actions.ndim() != 2 || actions.shape(0) != n || actions.shape(1) != 4) {
    std::string shape;
    for (py::ssize_t k = 0; k < actions.ndim(); ++k)
      shape += (k ? ", " : "") + std::to_string(actions.shape(k));
    throw py::value_error("step(actions, action=\"thrust_moment\"): actions has shape (" + shape +
                          "), expected (" + std::to_string(n) +
                          ", 4): each follower's collective thrust (N) and body moments x, y, "
                          "z (N m)");
  }
  std::vector<double> out(4 * static_cast<size_t>(n), 0.0);
  for (py::ssize_t i = 0; i < n; ++i) {
    for (py::ssize_t k = 0; given[i] && k < 4; ++k) {
      const double w = actions.at(i, k);
      if (!std::isfinite(w))
        throw py::value_error("step(actions, action=\"thrust_moment\"): the " +
                              std::string(k == 0 ? "thrust" : "moment") + " of follower " +
                              std::to_string(i) + " (0-based) is not finite");
      out[4 * i + k] = w;
    }
  }
  return out;
}

// act_thrust_moment(commands or None, wrenches, given, steps) -> physics steps done.
int64_t ActThrustMoment(mjf::python::DrivenSimulation& d,
                        const std::optional<py::array_t<double>>& commands,
                        const py::array_t<double>& wrenches, const std::vector<bool>& given,
                        int64_t steps) {
  if (steps < 0) throw py::value_error("steps is a number of physics steps >= 0");
  if (!d.allocation_error().empty())
    throw py::value_error("action=\"thrust_moment\" needs four actuators a wrench maps onto: " +
                          d.allocation_error() + "; fly accelerations instead");
  const size_t n = static_cast<size_t>(d.sim().n_followers());
  if (given.size() != n)
    throw py::value_error("given has " + std::to_string(given.size()) + " entries, expected " +
                          std::to_string(n));
  const std::vector<unsigned char> mask(given.begin(), given.end());
  const std::vector<double> w = Wrenches(d.sim(), wrenches, mask);
  std::vector<double> accel;
  if (commands) accel = Commands(d.sim(), *commands);
  py::gil_scoped_release nogil;
  return d.ActThrustMoment(commands ? accel.data() : nullptr, w.data(), mask.data(), steps);
}

// (low, high): each follower's (N, 4) range of thrust and moments over its actuator ranges,
// and (N,) its hover thrust m g.
py::tuple ThrustMomentBounds(const mjf::python::DrivenSimulation& d) {
  if (!d.allocation_error().empty()) throw py::value_error(d.allocation_error());
  const py::ssize_t n = d.sim().n_followers();
  py::array_t<double> low({n, py::ssize_t{4}}), high({n, py::ssize_t{4}}), hover(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    d.allocation(static_cast<int>(i)).Bounds(low.mutable_data(i, 0), high.mutable_data(i, 0));
    const mjfVehicleInfo& info = d.sim().binding(static_cast<int>(i) + 1).info;
    hover.mutable_at(i) = info.mass * info.gravity;
  }
  return py::make_tuple(low, high, hover);
}

// f_i(t) of every follower, (N, 6): px py vx vy ax ay (Definition 1); zeros without a shape.
py::array_t<double> Offsets(const rn::Simulation& sim, double t) {
  const py::ssize_t n = sim.n_followers();
  py::array_t<double> out({n, py::ssize_t{6}});
  std::fill(out.mutable_data(), out.mutable_data() + 6 * n, 0.0);
  if (sim.shape() != nullptr) sim.shape()->Evaluate(t, out.mutable_data());
  return out;
}

py::tuple Heard(const mjf::python::DrivenSimulation& d) {
  const py::ssize_t n = d.sim().n_followers();
  py::array_t<double> states({n, n + 1, py::ssize_t{13}}), heard({n, n + 1});
  d.Heard(states.mutable_data(), heard.mutable_data());
  return py::make_tuple(states, heard);
}

py::list Events(const mjf::python::DrivenSimulation& d) {
  py::list out;
  for (const rn::SafetyEvent& e : d.events()) {
    out.append(py::dict(py::arg("kind") = e.kind, py::arg("time") = e.time_s,
                        py::arg("vehicles") = e.vehicles, py::arg("value") = e.value,
                        py::arg("text") = rn::DescribeEvent(e)));
  }
  return out;
}

// The same read-only view as Simulation's, over the driven simulation.
template <typename Class>
void BindViews(Class& c) {
  using D = mjf::python::DrivenSimulation;
  c.def_property_readonly("time", [](const D& d) { return d.sim().time(); })
      .def_property_readonly("step_index", [](const D& d) { return d.sim().step_index(); })
      .def_property_readonly("total_steps", [](const D& d) { return d.sim().total_steps(); })
      .def_property_readonly("timestep", [](const D& d) { return d.sim().config().timestep; })
      .def_property_readonly("n_vehicles", [](const D& d) { return d.sim().n_vehicles(); })
      .def_property_readonly("states", [](const D& d) { return States(d.sim().states()); })
      .def_property_readonly("measured", [](const D& d) { return States(d.sim().measured()); })
      .def_property_readonly("setpoints", [](const D& d) { return Setpoints(d.sim()); })
      .def_property_readonly("slots", [](const D& d) { return Slots(d.sim()); })
      .def_property_readonly("graph", [](const D& d) { return GraphDict(d.sim()); })
      .def_property_readonly("scene_xml", [](const D& d) { return d.sim().scene_xml(); })
      .def_property_readonly("per_agent", [](const D& d) { return d.sim().channel() != nullptr; })
      .def_property_readonly("law_period", [](const D& d) {
        return d.sim().contracts().law.period;  // NaN: the law does not say
      });
}

void BindDriven(py::module_& m) {
  using D = mjf::python::DrivenSimulation;
  py::class_<D> c(m, "DrivenSimulation");
  c.def(py::init([](const std::string& path, const std::vector<std::string>& overrides,
                    const std::vector<std::string>& plugin_path) {
          const rn::ExperimentConfig config = Load(path, overrides, plugin_path, false);
          py::gil_scoped_release nogil;
          return std::make_unique<D>(config);
        }),
        py::arg("experiment"), py::arg("overrides"), py::arg("plugin_path"))
      .def("act", &Act, py::arg("actions"), py::arg("steps"))
      .def("act_thrust_moment", &ActThrustMoment, py::arg("commands"), py::arg("wrenches"),
           py::arg("given"), py::arg("steps"))
      .def("thrust_moment_bounds", &ThrustMomentBounds)
      .def(
          "offsets", [](const D& d, double t) { return Offsets(d.sim(), t); }, py::arg("t"))
      .def("heard", &Heard)
      .def("get_state", [](D& d) { return py::bytes(d.GetState()); })
      .def(
          "set_state", [](D& d, const py::bytes& state) { d.SetState(std::string(state)); },
          py::arg("state"))
      .def_property_readonly("events", &Events);
  BindViews(c);
}

void RegisterExceptions(py::module_& m) {
  static py::exception<rn::SimulationError> simulation_error(m, "SimulationError",
                                                             PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rn::ConfigError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const rn::PluginError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const rn::ExportError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const rn::SceneError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const rn::StateArchiveError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const rn::OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const rn::SimulationError& e) {
      PyErr_SetString(simulation_error.ptr(), e.what());
    }
  });
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "mjformation's runner library (use the mjformation package, not this module)";
  rn::RegisterInProcessPlugin(&mjf::python::CentralLawPlugin(), "in-process (mjformation Python)");
  rn::RegisterInProcessPlugin(&mjf::python::AgentLawPlugin(), "in-process (mjformation Python)");
  RegisterExceptions(m);
  m.def("run", &Run, py::arg("experiment"), py::arg("overrides"), py::arg("plugin_path"),
        py::arg("out"), py::arg("overwrite"), py::arg("render"), py::arg("record"));
  m.def("command_line", &CommandLine, py::arg("args"));
  m.def(
      "export",
      [](const std::string& experiment, const std::string& out, bool overwrite,
         const std::vector<std::string>& overrides, const std::vector<std::string>& plugin_path) {
        rn::ExportOptions options;
        options.overrides = overrides;
        options.plugin_path = plugin_path;
        options.overwrite = overwrite;
        const rn::ExportResult r = rn::ExportExperiment(experiment, out, options);
        return py::make_tuple(r.scene_path, r.notes);
      },
      py::arg("experiment"), py::arg("out"), py::arg("overwrite"), py::arg("overrides"),
      py::arg("plugin_path"));
  m.def("native_plugin_library", [] { return std::string(MJF_NATIVE_PLUGIN_LIBRARY); });
  m.def("check", &Check, py::arg("experiment"), py::arg("overrides"), py::arg("plugin_path"),
        py::arg("render") = true);
  m.def("plugins", &Plugins, py::arg("plugin_path"));
  m.def("read_csv", &ReadCsv, py::arg("path"));
  m.def("version", &rn::VersionString);
  m.def("engine", [] {
    const rn::EngineIdentity& e = rn::RunningEngine();
    py::dict d;
    d["version"] = e.version;
    d["library"] = e.library_path;
    d["sha256"] = e.library_sha256;
    return d;
  });
  BindSimulation(m);
  BindDriven(m);
}
