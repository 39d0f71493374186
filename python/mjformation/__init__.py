# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation from Python: run, sweep and read experiments, and fly a formation law written in
Python on the same vehicles, runner, recorders and summary as a C++ plugin (docs/PYTHON.md).

    import mjformation
    run = mjformation.run("experiments/exp2.toml", set={"formation.q": 3.0})
    run.summary["metrics"]["sigma_f_mean"], run.timeseries["sigma_f"]
"""

from __future__ import annotations

import ctypes
import errno
import json
import os
import shutil
import signal
import tempfile
import warnings
import weakref
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from mjfanalysis.io import Run, Sweep, load_run, load_sweep

from . import _laws
from ._laws import Graph, Neighbourhood

_HERE = Path(__file__).resolve().parent
# Installed: the prefix's models and plugins (lib/python3.X/dist-packages/mjformation -> prefix).
# In the build tree (build/python/mjformation) the runner's compiled-in paths serve instead.
# From a wheel (`pip install .`) the package folder itself is the prefix (bin/, lib/, share/).
_INSTALLED_PLUGINS = []
_PREFIX = None
if (_HERE / "share/mjformation/mjcf").is_dir():
    _PREFIX = _HERE
elif _HERE.parent.name in ("dist-packages", "site-packages") and len(_HERE.parents) > 3:
    _PREFIX = _HERE.parents[3]
if _PREFIX is not None:
    if (_PREFIX / "share/mjformation/mjcf").is_dir():
        os.environ.setdefault("MJF_MJCF_DIR", str(_PREFIX / "share/mjformation/mjcf"))
    _INSTALLED_PLUGINS = [str(p) for p in [_PREFIX / "lib/mjformation/plugins"] if p.is_dir()]

from . import _core  # noqa: E402  (after MJF_MJCF_DIR: the runner reads it at load time)
from ._core import SimulationError  # noqa: E402,F401

__all__ = [
    "run", "load", "load_sweep", "sweep", "plugins", "check", "Run", "Sweep", "Simulation", "FormationLaw",
    "AgentLaw", "Graph", "Neighbourhood", "SimulationError", "RunFailed", "version",
]

STATE_COLUMNS = ("px", "py", "pz", "vx", "vy", "vz", "qw", "qx", "qy", "qz", "gx", "gy", "gz")


def version() -> str:
    return _core.version()


def engine() -> dict:
    """The MuJoCo this process runs: {"version", "library" (the file), "sha256" (of it)}.

    The same library as the `mujoco` Python package of the project's environment (.venv), so
    `import mujoco, mjformation` share one engine and a scene of ours opens in MuJoCo's tools.
    """
    return dict(_core.engine())


# ---- formation laws in Python ----------------------------------------------------------------


@dataclass(frozen=True)
class FormationLaw:
    """A central formation law: function(t, states, offsets, graph) -> (N, 2) accelerations.

    t: s; states: (1 + N, 13) measured states, row 0 the leader, columns STATE_COLUMNS;
    offsets: (N, 6) desired offsets f_i(t) = (px, py, vx, vy, ax, ay) from the leader
    (Definition 1); graph: Graph. Called once per `period` seconds (None or 0: every physics
    step), its output held in between; returns each follower's horizontal acceleration u_i.
    """

    function: Callable
    period: float | None = None
    per_agent = False


@dataclass(frozen=True)
class AgentLaw:
    """A per-agent law ([execution] mode = "per_agent"): factory(neighbourhood) -> agent, one
    per follower; agent(t, me, messages, leader, offsets) -> (2,) acceleration.

    me: (13,) own measured state; messages: {neighbour j: (13,) state as received};
    leader: (13,) the leader's state as received, or None without a leader link;
    offsets: (N, 6) f(t) of every follower (mission data every vehicle carries).
    """

    function: Callable
    period: float | None = None
    per_agent = True


def _as_law(formation) -> FormationLaw | AgentLaw:
    if isinstance(formation, (FormationLaw, AgentLaw)):
        return formation
    if callable(formation):
        return FormationLaw(formation)
    raise TypeError(f"formation= takes a callable, FormationLaw or AgentLaw, not {formation!r}")


def _law_overrides(law, key: str, experiment) -> list[str]:
    """Replaces [formation] by the in-process plugin, keeping [formation.shape] (a section
    override replaces the whole table)."""
    plugin = "python_agent" if law.per_agent else "python"
    table = {"plugin": plugin, "law": key}
    if law.period:
        table["period"] = float(law.period)
    shape = _read_toml(experiment).get("formation", {}).get("shape")
    if shape is not None:
        table["shape"] = shape
    overrides = [f"formation={_toml_value(table)}"]
    if law.per_agent:
        overrides.append('execution.mode="per_agent"')
    return overrides


def _read_toml(path) -> dict:
    import tomllib

    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return {}  # the runner reports it, with its own message


class _LawInUse:
    """Registers a Python law for the duration of a run (with statement)."""

    def __init__(self, formation, experiment):
        self.law = None if formation is None else _as_law(formation)
        self.experiment = experiment
        self.key = None

    def __enter__(self) -> list[str]:
        if self.law is None:
            return []
        self.key = _laws.acquire(self.law)
        return _law_overrides(self.law, self.key, self.experiment)

    def __exit__(self, *exc):
        if self.key is not None:
            _laws.release(self.key)


# ---- overrides ---------------------------------------------------------------------------------


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float, np.integer, np.floating)):
        return repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} as a TOML value")


def _overrides(set) -> list[str]:
    """set={"formation.q": 3.0} or ["formation.q=3.0", ...] (the CLI's --set strings)."""
    if set is None:
        return []
    if isinstance(set, dict):
        return [f"{k}={_toml_value(v)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]


def _user_plugin_path(plugin_path) -> list[str]:
    """plugin_path= as folders: one (str or os.PathLike) or several. A folder that is not there
    raises FileNotFoundError, as the CLI's --plugin-path refuses it: a misspelt folder would
    otherwise be searched in silence and the plugin looked for in it never found there."""
    extra = [plugin_path] if isinstance(plugin_path, (str, os.PathLike)) else list(plugin_path or [])
    for folder in extra:
        if not os.path.isdir(folder):
            where = os.path.abspath(folder)
            raise FileNotFoundError(errno.ENOENT, f"plugin_path: {os.fspath(folder)} is not a "
                                    f"folder (looked at {where})", os.fspath(folder))
    return [str(p) for p in extra]


def _plugin_path(plugin_path) -> list[str]:
    return _user_plugin_path(plugin_path) + _INSTALLED_PLUGINS


def _override_value(overrides: list[str], key: str):
    """The value an override string "key=value" gives `key` (the last one wins), else None."""
    import tomllib

    value = None
    for o in overrides:
        name, _, text = o.partition("=")
        if name.strip() == key:
            try:
                value = tomllib.loads(f"v = {text}")["v"]
            except tomllib.TOMLDecodeError:
                return None  # the runner reports it, with its own message
    return value


def _proportionate_window(experiment, overrides: list[str], caller: str,
                          stacklevel: int = 3) -> list[str]:
    """A run.duration override without run.metric_window, on a file whose [run] metric_window
    would reach past the new duration: the window scaled with the duration (the file's
    [25, 40] s of 40 s become [2.5, 4] s of a 4 s run), added as an override and stated in a
    warning. Nothing otherwise (the runner's default window already follows the duration).
    stacklevel: the warning's, so that it names the user's line (3: the caller's caller)."""
    duration = _override_value(overrides, "run.duration")
    if not isinstance(duration, (int, float)) or isinstance(duration, bool) or duration <= 0:
        return []
    if _override_value(overrides, "run.metric_window") is not None:
        return []
    run = _read_toml(experiment).get("run", {})
    window, full = run.get("metric_window"), run.get("duration", 40.0)
    if not (isinstance(window, list) and len(window) == 2 and isinstance(full, (int, float))
            and full > 0 and all(isinstance(w, (int, float)) for w in window)):
        return []
    if window[1] <= duration + 1e-9:
        return []
    scaled = [window[0] * duration / full, window[1] * duration / full]
    warnings.warn(f"{caller}: {experiment}: run.duration = {duration:g} s ends before the file's "
                  f"[run] metric_window [{window[0]:g}, {window[1]:g}] s (of {full:g} s): averaging "
                  f"over the proportionate window [{scaled[0]:g}, {scaled[1]:g}] s; pass "
                  "run.metric_window to choose another", UserWarning, stacklevel=stacklevel)
    return [f"run.metric_window={_toml_value(scaled)}"]


# ---- runs --------------------------------------------------------------------------------------


def load(run_dir) -> Run:
    """A run directory written by `mjformation run` or mjformation.run (mjfanalysis's Run)."""
    path = Path(run_dir)
    if not (path / "config.toml").is_file():
        raise FileNotFoundError(f"{path}: not a run directory (no config.toml)")
    return load_run(path)


def _annotate_agent_summary(run_path: Path, key: str, law) -> None:
    """Per-agent runs: summary.json names the law (the runner lists no attributes there)."""
    path = run_path / "summary.json"
    if not path.is_file():
        return
    s = json.loads(path.read_text())
    formation = s.get("plugins", {}).get("formation", {})
    formation["attributes"] = {"law": key, "period": str(float(law.period or 0))}
    tmp = path.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(s, indent=2) + "\n")
    tmp.replace(path)


class RunFailed(RuntimeError):
    """A run that stopped early (run(..., raise_on_failure=True)): `run` is its Run (what was
    recorded is kept), the message its summary's error."""

    def __init__(self, message: str, run):
        super().__init__(message)
        self.run = run


def run(experiment, set=None, out=None, render=False, formation=None, overwrite=False,
        record=True, plugin_path=None, raise_on_failure=False) -> Run:
    """Runs an experiment (the GIL released while it simulates) and returns its Run.

    set: overrides as {"section.key": value} or ["section.key=value", ...] (the CLI's --set);
    out: the run directory (None: a temporary one, removed with the Run object); the Run is
    mjfanalysis.io.Run, the loader the analysis uses;
    formation: a Python formation law (callable, FormationLaw or AgentLaw) flown in place of
    the experiment's [formation] plugin. A bad configuration raises ValueError (FILE:LINE:
    [section] key: reason); Ctrl-C ends the run, marked incomplete, and raises KeyboardInterrupt.
    A run that stops early (a plugin or law error, a non-finite state, [run] stop_on) returns
    its Run with complete False and warns (RuntimeWarning, with the reason); with
    raise_on_failure=True it raises RunFailed instead.
    render=False (the default) renders nothing and skips [render]'s checks (snapshot times
    inside the duration), as the CLI's --no-render. A shorter run.duration alone scales the
    file's metric_window with it (a UserWarning states the window used).
    """
    experiment = _experiment_file(experiment)
    temporary = out is None
    out = Path(tempfile.mkdtemp(prefix="mjformation_")) / "run" if temporary else Path(out)
    in_use = _LawInUse(formation, experiment)
    with in_use as law_overrides:
        overrides = _overrides(set)
        overrides += _proportionate_window(experiment, overrides, "mjformation.run")
        result = _core.run(str(experiment), law_overrides + overrides,
                           _plugin_path(plugin_path), str(out), overwrite, render, record)
        if in_use.law is not None and in_use.law.per_agent:
            _annotate_agent_summary(out, in_use.key, in_use.law)
    result["summary"] = json.loads(result["summary"])
    if result["signal"] == signal.SIGINT:  # a partial run is kept, even a temporary one
        raise KeyboardInterrupt(f"mjformation.run interrupted; partial run kept in {out}")
    r = load_run(out)
    r.result = result
    if temporary:
        weakref.finalize(r, shutil.rmtree, out.parent, ignore_errors=True)
    if not result["complete"]:
        message = (f"mjformation.run: {experiment}: the run stopped early at t = "
                   f"{result['summary'].get('sim_time_s', float('nan')):g} s: "
                   f"{result['error'] or result['summary'].get('error')}")
        if raise_on_failure:
            raise RunFailed(message, r)
        warnings.warn(message, RuntimeWarning, stacklevel=2)
    return r


def check(experiment, set=None, formation=None, plugin_path=None, render=True) -> dict:
    """Validates an experiment (config, model, plugins, topology) without running it; with
    render=False, not [render]'s checks (as run(render=False) and the CLI's --no-render)."""
    experiment = _experiment_file(experiment)
    with _LawInUse(formation, experiment) as law_overrides:
        overrides = _overrides(set)
        overrides += _proportionate_window(experiment, overrides, "mjformation.check")
        return _core.check(str(experiment), law_overrides + overrides,
                           _plugin_path(plugin_path), bool(render))


def _experiment_file(experiment) -> str:
    """The experiment file's path, or FileNotFoundError (an OSError, as open() raises) saying
    where it was looked for: a relative path is read from the working folder."""
    if not isinstance(experiment, (str, os.PathLike)):
        raise TypeError(f"experiment= takes a file's path (str or os.PathLike), not {experiment!r}")
    path = os.fspath(experiment)
    if not os.path.isfile(path):
        where = os.path.abspath(path)
        what = "is a folder, not an experiment file" if os.path.isdir(path) else "does not exist"
        raise FileNotFoundError(errno.ENOENT, f"{path}: {what} (looked at {where}; the working "
                                f"folder is {os.getcwd()})", path)
    return path


def _require_bool(name: str, value) -> bool:
    """A yes/no argument: bool("no") is True, so anything but a bool is refused, as run does."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}= takes True or False, not {value!r}")
    return bool(value)


def _require_path(name: str, value) -> str:
    """A folder argument: str(None) would be the folder ./None."""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name}= takes a folder (str or os.PathLike), not {value!r}")
    return os.fspath(value)


def export(experiment, out, overwrite=False, set=None, plugin_path=None) -> Path:
    """Writes OUT/scene.xml: the experiment as a MuJoCo scene whose controllers are the native
    plugins of native_plugin_library() (docs/PLUGINS.md), and beside it a copy of every file the
    scene names (vehicle model, data files), named relative to it: OUT can be moved. After
    `import mjformation`, mujoco.MjModel.from_xml_path(OUT/scene.xml) flies it. What the native
    path cannot carry is refused naming the key; what is not carried (e.g. [render]) is said in
    a UserWarning (warnings.filterwarnings silences it). overwrite=True replaces scene.xml and the files export wrote, no other file.
    out: a folder (str or os.PathLike); overwrite: True or False (anything else: TypeError);
    set and plugin_path: as for run() (the CLI's --set and --plugin-path)."""
    # The user's folders only: an export carries them, and the native library finds the
    # installed plugins from its own place (a folder of this machine would not travel).
    scene, notes = _core.export(_experiment_file(experiment), _require_path("out", out),
                                _require_bool("overwrite", overwrite), _overrides(set),
                                _user_plugin_path(plugin_path))
    for note in notes:
        warnings.warn(f"mjformation.export: {note}", UserWarning, stacklevel=2)
    return Path(scene)


def native_plugin_library() -> str:
    """libmjformation_mujoco.so, the native MuJoCo plugins: the installed one (<prefix>/lib)
    when this package is installed, else the build tree's. `import mjformation` has loaded it
    already (so mujoco.MjModel.from_xml_path flies an export); mujoco.mj_loadPluginLibrary of it
    is then harmless."""
    if _PREFIX is not None:
        for lib in ("lib", "lib64", "lib/x86_64-linux-gnu"):
            if (_PREFIX / lib / "libmjformation_mujoco.so").is_file():
                return str(_PREFIX / lib / "libmjformation_mujoco.so")
    return _core.native_plugin_library()


def plugins(plugin_path=None) -> list[dict]:
    """Every plugin found: name, kind, doc, library, attributes {key: {default, doc}}."""
    return _core.plugins(_plugin_path(plugin_path))


# ---- step-level access -------------------------------------------------------------------------


class Simulation:
    """One simulation, stepped from Python: step(n), time, states, measured, slots, graph; and,
    after reset(seed), driven by your commands: step(actions) (docs/PYTHON.md, "Drive it
    yourself").

    Built by the constructor, it always stands at a control tick: states / measured / setpoints
    / slots / controls are those of `time`, as the timeseries.csv row at that time records them.
    step(n) integrates n physics steps, each followed by the next tick (sensors, plugins or the
    Python law). After reset() it stands inside the tick, before the attitude plugins: the
    formation law's commands are on the bus (law_actions) and step(actions) replaces them.
    set: as for run(); a shorter run.duration alone scales the file's metric_window with it (a
    UserWarning states the window used), as run() does.
    """

    def __init__(self, experiment, set=None, formation=None, plugin_path=None, driven=False,
                 seed=None):
        experiment = _experiment_file(experiment)
        # A shorter run.duration alone scales the file's metric_window, as run() does: the runner
        # refuses a configuration whose window reaches past its duration.
        overrides = _overrides(set)
        overrides += _proportionate_window(experiment, overrides, "mjformation.Simulation")
        self._law = _LawInUse(formation, experiment)
        self._stopped = None  # why the simulation stopped (a SimulationError), once it has
        self._experiment = str(experiment)
        self._plugin_path = _plugin_path(plugin_path)
        self._overrides = self._law.__enter__() + overrides
        self.driven = False
        try:
            if driven:
                self.reset(seed)
            else:
                self._sim = _core.Simulation(self._experiment, self._overrides, self._plugin_path)
        except BaseException:
            self._law.__exit__()
            raise

    def __del__(self):
        self._sim = None
        law = getattr(self, "_law", None)
        if law is not None:
            law.__exit__()

    def reset(self, seed: int | None = None) -> dict:
        """Back to t = 0 as a new simulation of the same experiment, driven by step(actions);
        seed: [run] seed (every seeded source: sensors, wind, network, start jitter); None keeps
        the experiment's. The same seed gives the same flight, bit for bit. Returns observe()."""
        overrides = list(self._overrides)
        if seed is not None:
            if int(seed) < 0:
                raise ValueError(f"reset(seed={seed}): the seed is an integer >= 0")
            overrides.append(f"run.seed={int(seed)}")
        self._sim = None  # the old simulation's plugins go before the new one's are made
        self._sim = _core.DrivenSimulation(self._experiment, overrides, self._plugin_path)
        self._stopped = None
        self.driven = True
        return self.observe()

    def step(self, actions=1, steps: int | None = None, action: str = "acceleration",
             given=None, commands=None):
        """step(n): n >= 0 physics steps flown by the experiment's own laws (fewer at the end of
        the experiment); returns the Simulation. step(actions), after reset(): the followers'
        acceleration commands, an (N, 3) array (x, y and the vertical feedforward on the
        altitude hold, m/s^2, world frame; (N, 2): no feedforward) held for `steps` physics
        steps (default action_steps, the law's sample period); returns observe().
        The GIL is released while it flies.

        action="thrust_moment": the lower level. actions is (N, 4), each follower's collective
        thrust along its body z (N) and body moments about x, y, z (N m); its attitude plugin is
        bypassed and its allocation turns the wrench into actuator controls, clipped to their
        ranges (thrust_moment_bounds()). given (N,) bool, default all: the followers so driven;
        the others fly `commands` ((N, 3) accelerations, default the law's) through their
        attitude plugins.

        Once a step has failed (a law's exception, a non-finite state or command:
        SimulationError), the simulation stays where it stopped and every later step raises
        SimulationError again: a failed tick left its setpoints half made.
        """
        if self._stopped is not None:
            raise SimulationError(f"this Simulation stopped at t = {self.time:.3f} s "
                                  f"({self._stopped}); reset() or create a new one to run again")
        by_count = isinstance(actions, (int, np.integer)) and not isinstance(actions, bool)
        if not by_count and not self.driven:
            raise RuntimeError("step(actions) drives a Simulation after reset(): one made by "
                               "the constructor has already flown its law's commands at t")
        try:
            if by_count and not self.driven:
                self._sim.step(int(actions))
                return self
            if by_count:
                if actions < 0:
                    raise ValueError(f"step(n): n is a number of physics steps >= 0, got {actions}")
                self._sim.act(None, int(actions))
                return self
            n = self.action_steps if steps is None else int(steps)
            if action == "thrust_moment":
                mask = [True] * (self.n_vehicles - 1) if given is None else \
                    [bool(g) for g in given]
                self._sim.act_thrust_moment(
                    None if commands is None else np.asarray(commands, dtype=np.float64),
                    np.asarray(actions, dtype=np.float64), mask, n)
            elif action == "acceleration":
                self._sim.act(np.asarray(actions, dtype=np.float64), n)
            else:
                raise ValueError(f'step(action={action!r}): "acceleration" or "thrust_moment"')
        except SimulationError as e:
            self._stopped = e
            raise
        return self.observe()

    def get_state(self) -> bytes:
        """Everything the next step depends on, as bytes: MuJoCo's integration state (with
        plugin_state), the control tick's setpoint bus and every plugin instance's ABI state,
        the actuation's rotor lags, this tick's outputs and (driven) the safety events so far;
        the same serialisation as `mjformation run --checkpoint-every`. set_state(state) on a
        Simulation of the same experiment and set (this one or a new one) flies on bit for bit
        as from where it was taken. A Python formation law's own objects are not in it (keep
        them yourself). Raises ValueError naming the stage and key for what is not saved yet
        ([sensors], [estimator], [wind], per-agent execution, threads > 1)."""
        return self._sim.get_state()

    def set_state(self, state: bytes) -> "Simulation":
        """Back to a state of get_state() (ValueError: another experiment or set, or a state of a
        driven Simulation into an undriven one or back); a stopped Simulation runs again."""
        self._sim.set_state(bytes(state))
        self._stopped = None
        return self

    @property
    def action_steps(self) -> int:
        """Physics steps a step(actions) holds its commands by default: the formation law's
        sample period T when it reports one (Exp 2: 0.05 s = 50 steps), else 1."""
        period = self._sim.law_period if self.driven else float("nan")
        if np.isfinite(period) and period > 0:
            return max(1, round(period / self._sim.timestep))
        return 1

    def thrust_moment_bounds(self) -> tuple:
        """(low, high, hover) of step(action="thrust_moment") (driven): low and high (N, 4), the
        range of each follower's collective thrust (N) and body moments x, y, z (N m) over its
        actuator ranges (each component alone); hover (N,) its weight m g (N). ValueError for a
        vehicle without four actuators (the point mass)."""
        if not self.driven:
            raise RuntimeError("thrust_moment_bounds() needs a driven Simulation: call reset()")
        return self._sim.thrust_moment_bounds()

    def observe(self, truth: bool = False) -> dict:
        """What the followers know at `time` (driven simulations), followers 0..N-1:
        own (N, 13): each one's measured state (STATE_COLUMNS; the [sensors] model applied);
        offsets (N, 6): f_i(t) = px py vx vy ax ay from the leader (mission data);
        heard (N, N + 1, 13), heard_mask (N, N + 1): what follower i holds of vehicle v (0 the
        leader, v = j + 1 follower j): central execution, the measured states of the vehicles it
        hears in [topology] (an ideal network); per-agent execution, the newest messages that
        reached it through [network] (delay, loss, range); zeros where mask is 0;
        law_actions (N, 3): the experiment's formation law's commands for this tick;
        truth (V, 13), only with truth=True: the true states, vehicle 0 the leader.
        """
        if not self.driven:
            raise RuntimeError("observe() needs a driven Simulation: call reset() first")
        heard, mask = self._sim.heard()
        obs = {"time": self._sim.time, "own": self._sim.measured[1:],
               "offsets": self._sim.offsets(self._sim.time), "heard": heard, "heard_mask": mask,
               "law_actions": self.law_actions}
        if truth:
            obs["truth"] = self._sim.states
        return obs

    def offsets(self, t: float | None = None) -> np.ndarray:
        """(N, 6) the desired offsets f_i(t) = px py vx vy ax ay from the leader (Definition 1)
        at t (default: now); zeros without a [formation.shape] (driven)."""
        return self._sim.offsets(self.time if t is None else float(t))

    law_actions = property(lambda self: self._sim.setpoints[1:, 0:3],
                           doc="(N, 3) the formation law's commands of this tick (driven)")
    events = property(lambda self: self._sim.events if self.driven else [],
                      doc="safety events so far (driven): dicts kind, time, vehicles, value, text")
    time = property(lambda self: self._sim.time, doc="s, simulated time")
    step_index = property(lambda self: self._sim.step_index)
    total_steps = property(lambda self: self._sim.total_steps)
    n_vehicles = property(lambda self: self._sim.n_vehicles)
    states = property(lambda self: self._sim.states, doc="(V, 13) true states, STATE_COLUMNS")
    measured = property(lambda self: self._sim.measured, doc="(V, 13) what the plugins saw")
    setpoints = property(lambda self: self._sim.setpoints,
                         doc="(V, 14): acc 3, pos 3, vel 3, yaw, sliding 2 (the setpoint bus)")
    slots = property(lambda self: self._sim.slots, doc="(V, 2) desired x, y of each vehicle")
    scene_xml = property(lambda self: self._sim.scene_xml,
                         doc="the composed MJCF (scene.xml): loads in the `mujoco` package alone")

    @property
    def controls(self):
        """(V, actuators) the controls of this tick (not for a driven Simulation, whose tick
        stands before its attitude plugins)."""
        if self.driven:
            raise RuntimeError("a driven Simulation stands before this tick's attitude plugins: "
                               "its controls are made by the next step")
        return self._sim.controls

    @property
    def graph(self) -> Graph:
        g = self._sim.graph
        return Graph(leader_weight=g["leader_weight"], adjacency=g["adjacency"])


from ._sweep import sweep  # noqa: E402

_NATIVE_PLUGINS = []


def _register_native_plugins() -> None:
    """Loads native_plugin_library(), whose constructor registers mjformation.swarm and
    mjformation.attitude with the engine this process shares with the `mujoco` package
    (engine()): after `import mjformation`, a plain mujoco.MjModel.from_xml_path of an exported
    scene flies. A wheel's `import mujoco` loads the same file (its mujoco.plugins entry point);
    a second load of one file only counts a reference, it registers nothing twice."""
    path = native_plugin_library()
    try:
        _NATIVE_PLUGINS.append(ctypes.CDLL(path))
    except OSError as e:
        warnings.warn(f"mjformation: the native MuJoCo plugins were not loaded ({e}); "
                      "mujoco.mj_loadPluginLibrary(PATH) loads them by hand", RuntimeWarning,
                      stacklevel=2)


_register_native_plugins()
