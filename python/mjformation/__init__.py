# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""mjformation from Python: run, sweep and read experiments, and fly a formation law written in
Python on the same vehicles, runner, recorders and summary as a C++ plugin (docs/PYTHON.md).

    import mjformation
    run = mjformation.run("experiments/exp2.toml", set={"formation.q": 3.0})
    run.summary["metrics"]["sigma_f_mean"], run.timeseries["sigma_f"]
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import sys
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


def _plugin_path(plugin_path) -> list[str]:
    extra = [plugin_path] if isinstance(plugin_path, (str, os.PathLike)) else list(plugin_path or [])
    return [str(p) for p in extra] + _INSTALLED_PLUGINS


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
    inside the duration), as the CLI's --no-render.
    """
    temporary = out is None
    out = Path(tempfile.mkdtemp(prefix="mjformation_")) / "run" if temporary else Path(out)
    in_use = _LawInUse(formation, experiment)
    with in_use as law_overrides:
        result = _core.run(str(experiment), law_overrides + _overrides(set),
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


def check(experiment, set=None, formation=None, plugin_path=None) -> dict:
    """Validates an experiment (config, model, plugins, topology) without running it."""
    with _LawInUse(formation, experiment) as law_overrides:
        return _core.check(str(experiment), law_overrides + _overrides(set),
                           _plugin_path(plugin_path))


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


def export(experiment, out, overwrite=False) -> Path:
    """Writes OUT/scene.xml: the experiment as a MuJoCo scene whose controllers are the native
    plugins of native_plugin_library() (docs/PLUGINS.md). What the native path cannot carry is
    refused naming the key; notes on what is not carried (e.g. [render]) go to stderr.
    out: a folder (str or os.PathLike); overwrite: True or False (anything else: TypeError)."""
    scene, notes = _core.export(str(experiment), _require_path("out", out),
                                _require_bool("overwrite", overwrite))
    for note in notes:
        print(f"note: {note}", file=sys.stderr)
    return Path(scene)


def native_plugin_library() -> str:
    """libmjformation_mujoco.so, for mujoco.mj_loadPluginLibrary before loading an export: the
    installed one (<prefix>/lib) when this package is installed, else the build tree's."""
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
    """One simulation, stepped from Python: step(n), time, states, measured, slots, graph.

    It always stands at a control tick: states / measured / setpoints / slots / controls are
    those of `time`, as the timeseries.csv row at that time records them. step(n) integrates n
    physics steps, each followed by the next tick (sensors, plugins or the Python law).
    """

    def __init__(self, experiment, set=None, formation=None, plugin_path=None):
        self._law = _LawInUse(formation, experiment)
        self._stopped = None  # why the simulation stopped (a SimulationError), once it has
        overrides = self._law.__enter__() + _overrides(set)
        try:
            self._sim = _core.Simulation(str(experiment), overrides, _plugin_path(plugin_path))
        except BaseException:
            self._law.__exit__()
            raise

    def __del__(self):
        self._sim = None
        law = getattr(self, "_law", None)
        if law is not None:
            law.__exit__()

    def step(self, n: int = 1) -> "Simulation":
        """n >= 0 physics steps (fewer at the end of the experiment); the GIL is released.

        Once a step has failed (a law's exception, a non-finite state: SimulationError), the
        simulation stays where it stopped and every later step raises SimulationError again: a
        failed tick left its setpoints half made, and stepping on would fly them.
        """
        if self._stopped is not None:
            raise SimulationError(f"this Simulation stopped at t = {self.time:.3f} s "
                                  f"({self._stopped}); create a new one to run again")
        try:
            self._sim.step(int(n))
        except SimulationError as e:
            self._stopped = e
            raise
        return self

    time = property(lambda self: self._sim.time, doc="s, simulated time")
    step_index = property(lambda self: self._sim.step_index)
    total_steps = property(lambda self: self._sim.total_steps)
    n_vehicles = property(lambda self: self._sim.n_vehicles)
    states = property(lambda self: self._sim.states, doc="(V, 13) true states, STATE_COLUMNS")
    measured = property(lambda self: self._sim.measured, doc="(V, 13) what the plugins saw")
    setpoints = property(lambda self: self._sim.setpoints,
                         doc="(V, 14): acc 3, pos 3, vel 3, yaw, sliding 2 (the setpoint bus)")
    slots = property(lambda self: self._sim.slots, doc="(V, 2) desired x, y of each vehicle")
    controls = property(lambda self: self._sim.controls, doc="(V, actuators) the controls")
    scene_xml = property(lambda self: self._sim.scene_xml,
                         doc="the composed MJCF (scene.xml): loads in the `mujoco` package alone")

    @property
    def graph(self) -> Graph:
        g = self._sim.graph
        return Graph(leader_weight=g["leader_weight"], adjacency=g["adjacency"])


from ._sweep import sweep  # noqa: E402
