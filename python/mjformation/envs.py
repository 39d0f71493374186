# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Learning environments over any experiment file (docs/PYTHON.md, "Environments").

    from mjformation.envs import FormationParallelEnv, FormationEnv
    env = FormationParallelEnv("experiments/exp2.toml")      # PettingZoo: agents = followers
    obs, infos = env.reset(seed=0)
    obs, rewards, terminations, truncations, infos = env.step(env.law_actions())

Both fly the runner's own simulation (mjformation.Simulation after reset(seed)): the same
vehicles, attitude plugins, sensors, network, wind and safety events as `mjformation run`;
stepped with the formation law's own commands they fly the runner's flight bit for bit.
gymnasium and pettingzoo are pyproject.toml's "envs" extra (pinned in requirements.txt, which
scripts/setup.sh installs into the project's .venv); only this module imports them.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Mapping
from typing import Callable

import numpy as np

try:
    import gymnasium
    from gymnasium import spaces
    from pettingzoo import ParallelEnv
except ModuleNotFoundError as missing:
    # The rest of mjformation runs without them (Debian's python3 imports it), so say what to
    # install rather than leave a bare "No module named 'gymnasium'".
    raise ImportError(
        f"mjformation.envs needs gymnasium and pettingzoo, and {sys.executable} cannot import "
        f"{missing.name!r}: install the \"envs\" extra (pip install '.[envs]' from the source "
        "tree: gymnasium, pettingzoo and their dependencies, pinned in pyproject.toml), or run "
        "the project's .venv/bin/python, which bash scripts/setup.sh fills from "
        "requirements.txt") from missing

from . import (STATE_COLUMNS, Simulation, SimulationError, _experiment_file, _overrides,
               _proportionate_window)

STATE = len(STATE_COLUMNS)  # 13
OFFSET = 6  # f_i(t): px py vx vy ax ay
NEIGHBOUR = STATE + OFFSET + 1  # a neighbour's state, its offset, heard (1) or not (0)
# The runner's safety event kinds (kSafetyEventKinds, runner/config experiment.hpp): what
# Simulation.events reports and [run] stop_on takes, so what terminate_on may name.
SAFETY_EVENTS = ("flip", "ground_impact", "collision", "near_miss", "left_region")
TERMINATE_ON = ("flip", "ground_impact", "collision")
ACTIONS = ("acceleration", "thrust_moment")


def observation_layout(max_neighbours: int) -> dict:
    """Where each part of a follower's observation vector lies (slices)."""
    own, offset = slice(0, STATE), slice(STATE, STATE + OFFSET)
    lead = STATE + OFFSET
    layout = {"own": own, "offset": offset, "leader": slice(lead, lead + STATE),
              "leader_heard": slice(lead + STATE, lead + STATE + 1)}
    start = lead + STATE + 1
    layout["neighbours"] = slice(start, start + NEIGHBOUR * max_neighbours)
    layout["size"] = start + NEIGHBOUR * max_neighbours
    return layout


def terminate_kinds(terminate_on) -> tuple:
    """terminate_on as a tuple of safety event kinds: one kind (a str) or an iterable of kinds,
    () for none. A str is one kind, not iterated (its letters would name no event), and every
    kind must be one of SAFETY_EVENTS: a misspelt kind matches no event, and the episode would
    never end on it."""
    if isinstance(terminate_on, str):
        kinds = (terminate_on,)
    elif isinstance(terminate_on, Iterable):
        kinds = tuple(terminate_on)
    else:
        raise TypeError(f"terminate_on={terminate_on!r}: a safety event kind or an iterable of "
                        f"kinds (() for none), from {', '.join(SAFETY_EVENTS)}")
    for kind in kinds:
        if not isinstance(kind, str) or kind not in SAFETY_EVENTS:
            raise ValueError(f"terminate_on: {kind!r} is not a safety event kind; the kinds are "
                             f"{', '.join(SAFETY_EVENTS)}")
    return kinds


def refuse_render_mode(render_mode) -> None:
    """render_mode: None only. The environments draw nothing themselves; a Gymnasium wrapper
    asking for frames (RecordVideo) is told where pictures come from rather than handed None."""
    if render_mode is not None:
        raise ValueError(f"render_mode={render_mode!r}: the environments render nothing "
                         "(render_modes is empty); for pictures, mjformation.run(...) writes "
                         "snapshots and video (docs/PYTHON.md), and an exported scene flies in "
                         "MuJoCo's viewer (docs/PLUGINS.md)")


class _Swarm:
    """What both environments share: the simulation, the per-follower observation vectors, the
    reward and the episode's end."""

    def __init__(self, caller, experiment, set=None, plugin_path=None, action_steps=None,
                 accel_max=5.0, vertical_max=2.0, terminate_on=TERMINATE_ON,
                 crash_penalty=10.0, velocity_weight=0.1, truth=False, action="acceleration"):
        if action not in ACTIONS:
            raise ValueError(f"action={action!r}: one of {ACTIONS}")
        self.terminate_on = terminate_kinds(terminate_on)
        experiment = _experiment_file(experiment)
        # A shorter run.duration alone scales the file's metric_window, as mjformation.run does;
        # done here so that the warning names the environment and the user's line (stacklevel 4:
        # past this and the environment's __init__), and the Simulation finds the window given.
        overrides = _overrides(set)
        overrides += _proportionate_window(experiment, overrides, f"mjformation.envs.{caller}",
                                           stacklevel=4)
        self.sim = Simulation(experiment, set=overrides, plugin_path=plugin_path, driven=True)
        self.n = self.sim.n_vehicles - 1
        self.action = action
        # Thrust and moments replace the attitude loop, which runs every physics step.
        self._action_steps = action_steps or (1 if action == "thrust_moment" else None)
        self.crash_penalty = float(crash_penalty)
        self.velocity_weight = float(velocity_weight)
        self.truth = truth
        adjacency = self.sim.graph.adjacency
        hears = [np.flatnonzero(adjacency[i] > 0) for i in range(self.n)]
        self.max_neighbours = max([len(h) for h in hears] + [0])
        self.neighbours = np.full((self.n, self.max_neighbours), -1, dtype=np.int64)
        for i, h in enumerate(hears):
            self.neighbours[i, :len(h)] = h
        self.layout = observation_layout(self.max_neighbours)
        self.observation_space = spaces.Box(-np.inf, np.inf, (self.layout["size"],), np.float64)
        if action == "thrust_moment":
            low, high, self.hover = self.sim.thrust_moment_bounds()
            self.action_spaces = [spaces.Box(low[i], high[i], (4,), np.float64)
                                  for i in range(self.n)]
        else:
            bound = np.array([accel_max, accel_max, vertical_max], dtype=np.float64)
            self.action_spaces = [spaces.Box(-bound, bound, (3,), np.float64)] * self.n
        self.events_seen = 0
        self.steps = 0
        # An episode starts with reset(seed) (the Simulation above stands at t = 0 already, but
        # with the file's seed) and ends as `ended` says: no step is flown outside one.
        self.started = False
        self.ended = None

    @property
    def action_steps(self) -> int:
        return self._action_steps or self.sim.action_steps

    def reset(self, seed: int) -> dict:
        self.sim.reset(seed)
        self.events_seen = 0
        self.steps = 0
        self.started, self.ended = True, None
        return self.sim.observe(truth=self.truth)

    def require_episode(self, what: str) -> None:
        """RuntimeError before the first reset() and after the episode ended: what a step
        returned then would belong to no episode (and, before reset, self._obs is None)."""
        if not self.started:
            raise RuntimeError(f"{what} called before reset(): call reset() before {what}")
        if self.ended is not None:
            raise RuntimeError(f"{what} called after the episode ended ({self.ended}): call "
                               "reset() to start a new episode")

    def vectors(self, obs: dict) -> np.ndarray:
        """(N, size): each follower's observation (observation_layout)."""
        out = np.zeros((self.n, self.layout["size"]))
        out[:, self.layout["own"]] = obs["own"]
        out[:, self.layout["offset"]] = obs["offsets"]
        out[:, self.layout["leader"]] = obs["heard"][:, 0]
        out[:, self.layout["leader_heard"]] = obs["heard_mask"][:, :1]
        if self.max_neighbours:
            idx = np.maximum(self.neighbours, 0)
            rows = np.arange(self.n)[:, None]
            valid = (self.neighbours >= 0).astype(float)
            block = np.concatenate([obs["heard"][rows, idx + 1] * valid[..., None],
                                    obs["offsets"][idx] * valid[..., None],
                                    (obs["heard_mask"][rows, idx + 1] * valid)[..., None]],
                                   axis=2)
            out[:, self.layout["neighbours"]] = block.reshape(self.n, -1)
        return out

    def rewards(self) -> np.ndarray:
        """-(|slot error| + velocity_weight |slot velocity error|), true states, horizontal."""
        x = self.sim.states
        f = self.sim.offsets()
        e_p = x[1:, 0:2] - x[0, 0:2] - f[:, 0:2]
        e_v = x[1:, 3:5] - x[0, 3:5] - f[:, 2:4]
        return -(np.linalg.norm(e_p, axis=1) + self.velocity_weight * np.linalg.norm(e_v, axis=1))

    def checked(self, i: int, action) -> np.ndarray:
        """Follower i's action as float64 of the action space's shape, finite; ValueError
        naming the follower otherwise."""
        a = np.asarray(action, dtype=np.float64)
        shape = self.action_spaces[i].shape
        if a.shape != shape:
            raise ValueError(f"the action of uav{i + 1} (follower {i}) has shape {a.shape}, "
                             f"expected {shape}: {self.meaning()}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"the action of uav{i + 1} (follower {i}) is not finite: {a}")
        return a

    def meaning(self) -> str:
        if self.action == "thrust_moment":
            return "collective thrust (N), body moments x, y, z (N m)"
        return "acceleration x, y and vertical feedforward (m/s^2, world frame)"

    def hover_actions(self) -> np.ndarray:
        """(N, 4): each follower's weight as thrust, no moments (action="thrust_moment")."""
        out = np.zeros((self.n, 4))
        out[:, 0] = self.hover
        return out

    def fly(self, actions: np.ndarray, given=None, commands=None):
        """One environment step of the simulation: accelerations (N, 3), or wrenches (N, 4) for
        the followers `given` (the others fly `commands`, default the law's)."""
        if self.action == "thrust_moment":
            return self.sim.step(actions, steps=self.action_steps, action="thrust_moment",
                                 given=given, commands=commands)
        return self.sim.step(actions, steps=self.action_steps)

    def advance(self, actions: np.ndarray, given=None, commands=None):
        """Flies one environment step; returns (obs or None, rewards, terminated, truncated,
        info)."""
        info = {}
        try:
            obs = self.fly(actions, given, commands)
        except SimulationError as e:
            info["error"] = str(e)
            self.ended = f"stopped by an error at t = {self.sim.time:.3f} s: {e}"
            return None, np.full(self.n, -self.crash_penalty * (1 + self.steps_left())), True, \
                False, info
        self.steps += 1
        rewards = self.rewards()
        events = self.sim.events
        fresh, self.events_seen = events[self.events_seen:], len(events)
        ending = [e for e in fresh if e["kind"] in self.terminate_on]
        if ending:
            # The steps the flight will not fly are charged at this step's reward: otherwise an
            # early crash, which ends the sum of negative rewards, would pay better than flying on.
            rewards = rewards * (1 + self.steps_left())
        for e in ending:
            for v in e["vehicles"]:
                if v > 0:
                    rewards[v - 1] -= self.crash_penalty
        if fresh:
            info["events"] = fresh
        truncated = self.sim.step_index >= self.sim.total_steps
        if ending:
            kinds = ", ".join(sorted({e["kind"] for e in ending}))
            self.ended = f"terminated at t = {self.sim.time:.3f} s by {kinds}"
        elif truncated:
            self.ended = f"truncated at t = {self.sim.time:.3f} s, the [run] duration"
        return obs, rewards, bool(ending), truncated, info

    def steps_left(self) -> int:
        """Environment steps from now to the end of [run] duration."""
        left = max(0, self.sim.total_steps - self.sim.step_index)
        return -(-left // self.action_steps)


class FormationParallelEnv(ParallelEnv):
    """PettingZoo ParallelEnv over an experiment: one agent per follower ("uav1".."uavN", the
    timeseries.csv names), every agent's action its acceleration command (x, y, vertical
    feedforward; m/s^2, world frame), held for action_steps physics steps (default: the
    formation law's sample period, else one step); with action="thrust_moment" its collective
    thrust (N) and body moments (N m), its attitude plugin bypassed (default one physics step).
    terminate_on: the safety event kind (a str) or kinds ending an episode, of SAFETY_EVENTS.
    `agents` is empty until reset() and after the episode's end; step() outside an episode
    raises RuntimeError. See docs/PYTHON.md for the observation, reward, termination and
    truncation."""

    metadata = {"name": "mjformation_formation_v0", "render_modes": []}

    def __init__(self, experiment, set=None, plugin_path=None, action_steps=None, accel_max=5.0,
                 vertical_max=2.0, terminate_on=TERMINATE_ON, crash_penalty=10.0,
                 velocity_weight=0.1, truth=False, action="acceleration", render_mode=None):
        refuse_render_mode(render_mode)
        self.swarm = _Swarm("FormationParallelEnv", experiment, set, plugin_path, action_steps,
                            accel_max, vertical_max, terminate_on, crash_penalty,
                            velocity_weight, truth, action)
        self.possible_agents = [f"uav{i + 1}" for i in range(self.swarm.n)]
        # PettingZoo: reset() sets the live agents; none is live before it (nor after the end).
        self.agents = []
        self.render_mode = None
        self._rng = np.random.default_rng()
        self._obs = None

    def observation_space(self, agent):
        return self.swarm.observation_space

    def action_space(self, agent):
        return self.swarm.action_spaces[self.possible_agents.index(agent)]

    @property
    def sim(self) -> Simulation:
        return self.swarm.sim

    def _observations(self, obs: dict) -> tuple[dict, dict]:
        self._obs = obs
        vectors = self.swarm.vectors(obs)
        info = {"time": obs["time"]}
        if "truth" in obs:
            info["truth"] = obs["truth"]
        return ({a: vectors[i] for i, a in enumerate(self.possible_agents)},
                {a: dict(info) for a in self.possible_agents})

    def reset(self, seed=None, options=None):
        """seed: the run's [run] seed; None: one drawn from the generator the last seed set."""
        if seed is not None:
            self._rng = np.random.default_rng(seed)
        run_seed = int(seed) if seed is not None else int(self._rng.integers(0, 2**31))
        self.agents = list(self.possible_agents)
        return self._observations(self.swarm.reset(run_seed))

    def law_actions(self) -> dict:
        """The experiment's formation law's commands for this tick, per agent (float64)."""
        if self._obs is None:
            raise RuntimeError("law_actions() called before reset(): call reset() first")
        law = self._obs["law_actions"]
        return {a: law[i].copy() for i, a in enumerate(self.possible_agents)}

    def hover_actions(self) -> dict:
        """action="thrust_moment": each agent's weight m g as thrust, zero moments."""
        hover = self.swarm.hover_actions()
        return {a: hover[i] for i, a in enumerate(self.possible_agents)}

    def step(self, actions: dict):
        """actions: {agent: action} of live agents (ValueError for any other key); an agent
        left out flies the law's command."""
        self.swarm.require_episode("step()")
        if not isinstance(actions, Mapping):
            raise TypeError(f"step(actions): actions is a dict {{agent: action}}, not "
                            f"{type(actions).__name__}")
        # A key that is no live agent would be ignored: a typo or the leader's name would fly
        # the law's command in silence.
        unknown = [a for a in actions if a not in self.agents]
        if unknown:
            named = ", ".join(map(repr, unknown))
            verb = "is not a live agent" if len(unknown) == 1 else "are not live agents"
            leader = "; uav0 is the leader, which flies its own guidance" if "uav0" in unknown \
                else ""
            raise ValueError(f"step(actions): {named} {verb} (the live agents: "
                             f"{', '.join(self.agents)}{leader})")
        # An agent without an action flies the law's command through its attitude plugin.
        commands = self._obs["law_actions"].copy()
        given = [a in actions for a in self.possible_agents]
        if self.swarm.action == "thrust_moment":
            wrenches = np.zeros((self.swarm.n, 4))
            for i, a in enumerate(self.possible_agents):
                if given[i]:
                    wrenches[i] = self.swarm.checked(i, actions[a])
            obs, rewards, terminated, truncated, info = self.swarm.advance(wrenches, given)
        else:
            for i, a in enumerate(self.possible_agents):
                if given[i]:
                    commands[i] = self.swarm.checked(i, actions[a])
            obs, rewards, terminated, truncated, info = self.swarm.advance(commands)
        if obs is None:
            observations = {a: np.zeros(self.swarm.layout["size"]) for a in self.agents}
            infos = {a: dict(info) for a in self.agents}
        else:
            observations, infos = self._observations(obs)
            for a in infos:
                infos[a].update(info)
        agents = self.agents
        result = (observations, {a: float(rewards[i]) for i, a in enumerate(agents)},
                  {a: terminated for a in agents}, {a: truncated and not terminated for a in agents},
                  infos)
        if terminated or truncated:
            self.agents = []
        return result

    def render(self):
        return None

    def close(self):
        pass


class FormationEnv(gymnasium.Env):
    """Gymnasium Env over an experiment: one learning follower (`follower`, 0-based; agent
    "uav<follower + 1>"), the others flown by `others`: None (default) the experiment's own
    formation law (Exp 2's: smc_discrete, eq. (48)), or a callable others(obs) -> (N, 3)
    commands, obs being Simulation.observe()'s dict (the learner's row is replaced). The same
    observation, action (action="acceleration" or "thrust_moment"), reward, terminate_on and
    episode end as FormationParallelEnv, for that follower: step() before reset() or after the
    episode ended raises RuntimeError."""

    metadata = {"render_modes": []}

    def __init__(self, experiment, follower: int = 0, others: Callable | None = None, set=None,
                 plugin_path=None, action_steps=None, accel_max=5.0, vertical_max=2.0,
                 terminate_on=TERMINATE_ON, crash_penalty=10.0, velocity_weight=0.1, truth=False,
                 action="acceleration", render_mode=None):
        refuse_render_mode(render_mode)
        self.swarm = _Swarm("FormationEnv", experiment, set, plugin_path, action_steps, accel_max,
                            vertical_max, terminate_on, crash_penalty, velocity_weight, truth,
                            action)
        if not 0 <= follower < self.swarm.n:
            raise ValueError(f"follower={follower}: the experiment has followers 0..{self.swarm.n - 1}")
        self.follower = follower
        self.others = others
        self.observation_space = self.swarm.observation_space
        self.action_space = self.swarm.action_spaces[follower]
        self.render_mode = None
        self._obs = None

    @property
    def sim(self) -> Simulation:
        return self.swarm.sim

    def _info(self, obs: dict) -> dict:
        info = {"time": obs["time"]}
        if "truth" in obs:
            info["truth"] = obs["truth"]
        return info

    def reset(self, *, seed=None, options=None):
        """seed: the run's [run] seed; None: one drawn from the generator the last seed set."""
        super().reset(seed=seed)
        run_seed = int(seed) if seed is not None else int(self.np_random.integers(0, 2**31))
        self._obs = self.swarm.reset(run_seed)
        return self.swarm.vectors(self._obs)[self.follower], self._info(self._obs)

    def hover_action(self) -> np.ndarray:
        """action="thrust_moment": the learner's weight m g as thrust, zero moments."""
        return self.swarm.hover_actions()[self.follower]

    def law_action(self) -> np.ndarray:
        """The experiment's formation law's command for the learner at this tick."""
        if self._obs is None:
            raise RuntimeError("law_action() called before reset(): call reset() first")
        return self._obs["law_actions"][self.follower].copy()

    def step(self, action):
        self.swarm.require_episode("step()")
        if self.others is None:
            commands = self._obs["law_actions"].copy()
        else:
            commands = np.array(self.others(self._obs), dtype=np.float64).reshape(self.swarm.n, 3)
        mine = self.swarm.checked(self.follower, action)
        if self.swarm.action == "thrust_moment":
            wrenches = np.zeros((self.swarm.n, 4))
            wrenches[self.follower] = mine
            given = [i == self.follower for i in range(self.swarm.n)]
            obs, rewards, terminated, truncated, info = self.swarm.advance(wrenches, given,
                                                                           commands)
        else:
            commands[self.follower] = mine
            obs, rewards, terminated, truncated, info = self.swarm.advance(commands)
        reward = float(rewards[self.follower])
        if obs is None:
            return np.zeros(self.swarm.layout["size"]), reward, True, False, info
        self._obs = obs
        info.update(self._info(obs))
        return (self.swarm.vectors(obs)[self.follower], reward, terminated,
                truncated and not terminated, info)


# gymnasium.make("mjformation/Formation-v0", experiment=...) builds FormationEnv with the same
# keywords. No step limit or other wrapper is added: the episode's end is the experiment's own
# [run] duration (truncation) and its safety events (termination).
if "mjformation/Formation-v0" not in gymnasium.registry:
    gymnasium.register(id="mjformation/Formation-v0", entry_point=FormationEnv)
