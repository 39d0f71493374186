# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Driving the simulation from outside (Simulation.reset / step(actions)) and the learning
environments of mjformation.envs: the runner's flight bit for bit under the law's own commands,
determinism under reset(seed), what a follower knows, the episode's end, the API checkers."""

import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

import mjformation
from conftest import short
from mjformation.envs import SAFETY_EVENTS, FormationEnv, FormationParallelEnv

FOLLOWERS = "uav1, uav2, uav3, uav4, uav5, uav6"  # Exp 2's agents


def noisy(duration):
    """A short Exp 2 with seeded sensor noise: the seed matters."""
    return {**short(duration), "sensors.preset": "typical"}


def test_the_laws_own_commands_fly_the_runners_flight_bit_for_bit(exp2, tmp_path):
    # Given the runner's own loop (Simulation stepped by its law) and a driven one, with noise
    overrides = noisy(0.5)
    runner = mjformation.Simulation(exp2, set=overrides)
    driven = mjformation.Simulation(exp2, set=overrides, driven=True)
    assert driven.action_steps == 50  # smc_discrete's T = 0.05 s
    assert np.array_equal(driven.states, runner.states)
    # When the driven one flies the law's commands each step (T held)
    while driven.step_index < driven.total_steps:
        driven.step(driven.law_actions)
        runner.step(driven.step_index - runner.step_index)
        # Then every state and setpoint is the runner's, bit for bit
        assert np.array_equal(driven.states, runner.states), driven.time
        assert np.array_equal(driven.measured, runner.measured), driven.time
        assert np.array_equal(driven.setpoints, runner.setpoints, equal_nan=True), driven.time
    # And the CLI's run records the same flight (its 9-digit rows)
    ts = mjformation.run(exp2, set=overrides, out=tmp_path / "r").timeseries
    for v in range(7):
        for k, col in enumerate(("px", "py", "vx")):
            assert driven.states[v, [0, 1, 3][k]] == pytest.approx(ts[f"uav{v}_{col}"][-1],
                                                                 rel=1e-8, abs=1e-9)


def test_reset_with_a_seed_repeats_the_flight_and_another_seed_does_not(exp2):
    sim = mjformation.Simulation(exp2, set=noisy(0.3), driven=True)
    push = np.tile([0.5, -0.2, 0.0], (6, 1))

    def fly(seed):
        sim.reset(seed=seed)
        out = []
        for _ in range(4):
            out.append(sim.step(push, steps=25)["own"])
        return np.array(out)

    first = fly(3)
    assert np.array_equal(first, fly(3))
    assert not np.array_equal(first, fly(4))  # the sensors' noise is seeded by [run] seed


def test_a_follower_knows_what_the_graph_lets_it_hear(exp2):
    # Exp 2: follower 0 hears the leader and followers 1 and 5 (0-based); follower 3 hears 2, 4
    sim = mjformation.Simulation(exp2, set=short(0.2), driven=True)
    obs = sim.observe()
    assert obs["heard_mask"][0].tolist() == [1, 0, 1, 0, 0, 0, 1]
    assert obs["heard_mask"][3].tolist() == [0, 0, 0, 1, 0, 1, 0]
    assert np.array_equal(obs["heard"][3, 3], sim.measured[3])
    assert not obs["heard"][3, 0].any()
    assert "truth" not in obs and np.array_equal(sim.observe(truth=True)["truth"], sim.states)
    assert np.array_equal(obs["own"], sim.measured[1:])


def test_per_agent_execution_observes_the_messages_of_the_network(exp2):
    # Given per-agent execution over a network whose messages take 20 ms
    overrides = {**short(0.2), "execution.mode": "per_agent", "network.latency": 0.02}
    sim = mjformation.Simulation(exp2, set=overrides, driven=True)
    sim.step(sim.law_actions, steps=100)
    obs = sim.observe()
    # Then what follower 3 holds of follower 2 is older than follower 2's own measurement
    assert obs["heard_mask"][3].tolist() == [0, 0, 0, 1, 0, 1, 0]
    assert not np.array_equal(obs["heard"][3, 3], sim.measured[3])


def test_commands_are_checked_and_a_made_simulation_is_not_driven(exp2):
    sim = mjformation.Simulation(exp2, set=short(0.2))
    with pytest.raises(RuntimeError, match="reset"):
        sim.step(np.zeros((6, 3)))
    sim.reset(seed=1)
    with pytest.raises(ValueError, match=r"shape \(6, 4\), expected \(6, 3\)"):
        sim.step(np.zeros((6, 4)))
    bad = np.zeros((6, 3))
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="follower 2"):
        sim.step(bad)


def test_a_ground_impact_ends_the_episode(exp2):
    env = FormationParallelEnv(exp2, set=short(4.0))
    env.reset(seed=0)
    actions = env.law_actions()
    actions["uav2"] = np.array([0.0, 0.0, -30.0])  # the vertical feedforward cuts its thrust
    for _ in range(80):
        _, rewards, terminations, truncations, infos = env.step(actions)
        if terminations["uav2"]:
            break
    assert terminations["uav2"] and not truncations["uav2"] and env.agents == []
    kinds = {e["kind"] for e in infos["uav2"]["events"]}
    assert kinds & {"ground_impact", "flip", "collision"}
    assert rewards["uav2"] < rewards["uav1"] - 5  # the crash penalty


def cut_thrust_of_uav2(env, steps=80):
    """Flies the law but for uav2, whose vertical feedforward cuts its thrust (a ground impact
    at 2.97 s); returns uav2's termination and truncation at the end."""
    env.reset(seed=0)
    actions = env.law_actions()
    actions["uav2"] = np.array([0.0, 0.0, -30.0])
    for _ in range(steps):
        _, _, terminations, truncations, _ = env.step(actions)
        if terminations["uav2"] or truncations["uav2"]:
            break
    return terminations["uav2"], truncations["uav2"]


def test_terminate_on_takes_one_kind_as_a_string(exp2):
    # A string is one kind, not its letters: "ground_impact" ends the flight at the impact ...
    env = FormationParallelEnv(exp2, set=short(4.0), terminate_on="ground_impact")
    assert env.swarm.terminate_on == ("ground_impact",)
    assert cut_thrust_of_uav2(env) == (True, False) and env.sim.time < 3.1
    # ... and "collision" alone lets the same flight run to its end
    env = FormationParallelEnv(exp2, set=short(4.0), terminate_on="collision")
    assert cut_thrust_of_uav2(env) == (False, True) and env.sim.time == pytest.approx(4.0)


def test_terminate_on_refuses_what_is_no_safety_event_kind(exp2):
    kinds = re.escape("the kinds are flip, ground_impact, collision, near_miss, left_region")
    for env in (FormationEnv, FormationParallelEnv):
        for bad, named in ((["colision"], "'colision'"), ("flip,collision", "'flip,collision'"),
                           (("flip", 3), "3")):
            with pytest.raises(ValueError, match=f"terminate_on: {re.escape(named)} is not a "
                                                 f"safety event kind; {kinds}"):
                env(exp2, set=short(0.2), terminate_on=bad)
        with pytest.raises(TypeError, match=r"terminate_on=None: .*\(\(\) for none\)"):
            env(exp2, set=short(0.2), terminate_on=None)
    assert FormationEnv(exp2, set=short(0.2), terminate_on=()).swarm.terminate_on == ()


def test_the_safety_event_kinds_are_the_runners(source):
    """terminate_on is checked against SAFETY_EVENTS: the runner's list, as its header has it."""
    header = (source / "runner/config/include/mjformation/config/experiment.hpp").read_text()
    listed = re.search(r"kSafetyEventKinds\[\] = \{([^}]*)\}", header).group(1)
    assert SAFETY_EVENTS == tuple(re.findall(r'"([a-z_]+)"', listed))


def test_step_refuses_a_key_that_is_no_live_agent(exp2):
    env = FormationParallelEnv(exp2, set=short(0.2))
    env.reset(seed=0)
    law = env.law_actions()
    for key in ("uav9", "uav0", "UAV1"):
        with pytest.raises(ValueError, match=rf"step\(actions\): '{key}' is not a live agent "
                                             rf"\(the live agents: {FOLLOWERS}"):
            env.step({**law, key: np.zeros(3)})
    with pytest.raises(ValueError, match="uav0 is the leader"):
        env.step({"uav0": np.zeros(3)})
    with pytest.raises(TypeError, match=r"a dict \{agent: action\}, not ndarray"):
        env.step(np.zeros((6, 3)))
    assert env.sim.step_index == 0  # nothing flew
    # A live agent left out still flies the law's command (PettingZoo's partial action dict)
    env.step({"uav1": law["uav1"]})
    assert env.sim.step_index == env.swarm.action_steps


def test_step_outside_an_episode_raises_and_says_to_reset(exp2):
    before = re.escape("step() called before reset(): call reset() before step()")
    ended = re.escape("step() called after the episode ended (truncated at t = 0.100 s, the "
                      "[run] duration): call reset() to start a new episode")
    # The parallel env: no live agent before reset, as PettingZoo's environments
    env = FormationParallelEnv(exp2, set=short(0.1))
    assert env.agents == [] and env.possible_agents == FOLLOWERS.split(", ")
    with pytest.raises(RuntimeError, match=before):
        env.step({})
    with pytest.raises(RuntimeError, match=re.escape("law_actions() called before reset()")):
        env.law_actions()
    env.reset(seed=0)
    while env.agents:
        env.step(env.law_actions())
    with pytest.raises(RuntimeError, match=ended):
        env.step({})
    obs, _ = env.reset(seed=0)  # a new episode steps again
    assert env.agents == env.possible_agents and env.step(env.law_actions())[0].keys() == obs.keys()
    # The gymnasium env
    env = FormationEnv(exp2, set=short(0.1))
    with pytest.raises(RuntimeError, match=before):
        env.step(np.zeros(3))
    with pytest.raises(RuntimeError, match=re.escape("law_action() called before reset()")):
        env.law_action()
    env.reset(seed=0)
    done = False
    while not done:
        _, _, terminated, truncated, _ = env.step(env.law_action())
        done = terminated or truncated
    with pytest.raises(RuntimeError, match=ended):
        env.step(env.law_action())
    env.reset(seed=0)
    env.step(env.law_action())


def test_a_terminated_episode_says_how_it_ended(exp2):
    env = FormationParallelEnv(exp2, set=short(4.0))
    assert cut_thrust_of_uav2(env) == (True, False)
    with pytest.raises(RuntimeError, match=r"ended \(terminated at t = 3\.000 s by "
                                           r"ground_impact\)"):
        env.step({})


def test_a_shorter_duration_alone_scales_the_metric_window_in_both_envs(exp2):
    # exp2.toml averages over [25, 40] s of 40 s: the runner refuses that window in a 0.4 s run
    for env_class in (FormationEnv, FormationParallelEnv):
        with pytest.warns(UserWarning, match=rf"mjformation\.envs\.{env_class.__name__}: .*"
                                             r"proportionate window \[0\.25, 0\.4\] s") as caught:
            env = env_class(exp2, set={"run.duration": 0.4})
        assert [w.filename for w in caught if "proportionate" in str(w.message)] == [__file__]
        env.reset(seed=0)
        assert env.sim.total_steps == 400


def test_without_gymnasium_the_import_says_what_to_install():
    # As in Debian's python3, which runs mjformation but has no gymnasium
    code = "import sys; sys.modules['gymnasium'] = None; import mjformation.envs"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: mjformation.envs needs gymnasium and pettingzoo"), last
    assert "cannot import 'gymnasium'" in last and "pip install '.[envs]'" in last, last
    assert ".venv/bin/python" in last, last


def test_a_crash_is_charged_the_steps_it_does_not_fly(exp2):
    """A learner that holds still is rammed within a second: the step that ends the episode
    charges its reward for every step left to the horizon, so ending early is not a way out of
    the sum of negative rewards."""
    env = FormationEnv(exp2, follower=0, set=short(6.0))
    env.reset(seed=3)
    while True:
        _, reward, terminated, truncated, _ = env.step(np.zeros(3))
        if terminated or truncated:
            break
    assert terminated
    left = env.swarm.steps_left()
    assert left > 50  # rammed in the first second of six, 0.05 s steps
    base = env.swarm.rewards()[0]
    assert reward == pytest.approx(base * (1 + left) - env.swarm.crash_penalty, rel=1e-12)


def test_the_parallel_env_flown_by_the_law_is_the_runners_flight(exp2):
    env = FormationParallelEnv(exp2, set=noisy(0.3))
    runner = mjformation.Simulation(exp2, set=noisy(0.3))
    obs, _ = env.reset(seed=1)  # the experiment's own seed
    assert np.array_equal(obs["uav1"][:13], runner.measured[1])
    done = False
    while not done:
        _, _, terminations, truncations, _ = env.step(env.law_actions())
        runner.step(env.sim.step_index - runner.step_index)
        assert np.array_equal(env.sim.states, runner.states)
        done = truncations["uav1"] or terminations["uav1"]
    assert truncations["uav1"] and env.sim.time == pytest.approx(0.3)


def test_the_gymnasium_env_passes_its_checker(exp2):
    from gymnasium.utils.env_checker import check_env

    env = FormationEnv(exp2, follower=2, set=short(0.5))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    # What docs/PYTHON.md says it prints: the action Box is in physical units, the observation
    # Box unbounded; nothing of the float64 dtype
    said = [str(w.message) for w in caught if "gymnasium" in w.filename]
    expected = ("we recommend using a symmetric and normalized space (range=[-1, 1] or [0, 1])",
                "A Box observation space minimum value is -infinity",
                "A Box observation space maximum value is infinity")
    assert len(said) == len(expected), said
    assert all(any(e in message for message in said) for e in expected), said
    obs, _ = env.reset(seed=5)
    obs2, reward, terminated, truncated, info = env.step(env.law_action())
    assert obs.shape == env.observation_space.shape and reward < 0 and not terminated


def test_gymnasium_make_builds_the_env_and_flies_the_runners_flight(exp2):
    import gymnasium

    env = gymnasium.make("mjformation/Formation-v0", experiment=exp2, follower=1,
                         set=short(0.2))
    direct = FormationEnv(exp2, follower=1, set=short(0.2))
    assert isinstance(env.unwrapped, FormationEnv)
    obs, _ = env.reset(seed=3)
    obs_direct, _ = direct.reset(seed=3)
    assert np.array_equal(obs, obs_direct)
    obs, *_ = env.step(env.unwrapped.law_action())
    obs_direct, *_ = direct.step(direct.law_action())
    assert np.array_equal(obs, obs_direct)


def test_a_render_mode_is_refused_saying_where_pictures_come_from(exp2):
    for make in (lambda: FormationEnv(exp2, set=short(0.2), render_mode="rgb_array"),
                 lambda: FormationParallelEnv(exp2, set=short(0.2), render_mode="human")):
        with pytest.raises(ValueError, match="render nothing.*snapshots and video"):
            make()
    FormationEnv(exp2, set=short(0.2), render_mode=None)  # Gymnasium's default is accepted


def test_the_parallel_env_passes_pettingzoos_api_test(exp2):
    from pettingzoo.test import parallel_api_test

    parallel_api_test(FormationParallelEnv(exp2, set=short(0.5)), num_cycles=20)


def test_the_random_search_example_trains_and_compares_with_the_law(source, tmp_path):
    """examples/python/train_random_search.py, one short iteration: it runs end to end, reports
    the learned policy beside the SMC law and draws both flights."""
    import subprocess
    import sys
    done = subprocess.run(
        [sys.executable, str(source / "examples/python/train_random_search.py"),
         "--iterations", "1", "--directions", "1", "--seconds", "1",
         "--plot", str(tmp_path / "flights.png")],
        capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "iteration  1/1: return" in done.stdout
    assert "learned" in done.stdout and "SMC law (eq. 48)" in done.stdout
    assert (tmp_path / "flights.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
