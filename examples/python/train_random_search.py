# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Trains one follower's formation policy with basic random search (docs/PYTHON.md,
"Environments"), in mjformation.envs.FormationEnv over Exp 2: follower 1 learns, the other five
fly the paper's discrete SMC law (eq. (48)) through the same sensors and attitude plugins.

The policy is linear in the learner's slot error as its observation vector carries it (own
state, desired offset f_1(t) and the leader's state: Definition 1's e_1 = x_1 - x_0 - f_1):
    a = clip(W [e_px, e_py, e_vx, e_vy, e_z, e_vz]^T + [f_ax, f_ay, 0]),
W a 3 x 6 matrix, started at a weak PD law on the slot error (--start-gain k: a = -k e_p - 1.5 k
e_v per axis; 0 starts from a follower that only follows its slot's acceleration, which Exp 2's
start sends into follower 4 within a second, whatever the search tries). The
method is the basic random search of Mania, Guy and Recht (NeurIPS 2018, "Simple random search
provides a competitive approach to reinforcement learning", their BRS, version V1): each
iteration draws `--directions` Gaussian directions, flies W + s d and W - s d for one short
episode each (same seed), and steps W along the return differences. It needs numpy alone.
It prints each iteration's return on a held-out evaluation seed, then the starting, the learned
and the SMC law's return on that seed: a few minutes on 2 cores. With --plot FILE it draws the return of each iteration
and, on the evaluation seed, the learner's distance to its slot over time under the starting, the
learned and the SMC policy (matplotlib, Debian's, seen by the project's venv).

    PYTHONPATH=build/python .venv/bin/python examples/python/train_random_search.py
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from mjformation.envs import FormationEnv

EXP2 = Path(__file__).resolve().parents[2] / "experiments/exp2.toml"
EVALUATION_SEED = 10_000  # the seed every policy is compared on; no update ever flies it


def features(env: FormationEnv, obs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The learner's slot error (6) and its slot's feed-forward acceleration (3)."""
    layout = env.swarm.layout
    own, offset, leader = obs[layout["own"]], obs[layout["offset"]], obs[layout["leader"]]
    e_p = own[0:2] - leader[0:2] - offset[0:2]
    e_v = own[3:5] - leader[3:5] - offset[2:4]
    e_z = np.array([own[2] - leader[2], own[5] - leader[5]])
    return np.concatenate([e_p, e_v, e_z]), np.array([offset[4], offset[5], 0.0])


def episode(env: FormationEnv, weights: np.ndarray | None, seed: int,
            trace: list | None = None) -> float:
    """The return of one episode; weights None: the SMC law's own command for the learner.
    env.ended_at holds when a safety event ended it (None: it flew to the end). `trace`, when
    given, receives (time, distance of the learner to its slot in the plane) at each step."""
    env.ended_at = None
    obs, _ = env.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        if trace is not None:
            trace.append((env.swarm.sim.time, float(np.hypot(*features(env, obs)[0][0:2]))))
        if weights is None:
            action = env.law_action()
        else:
            error, feed_forward = features(env, obs)
            action = np.clip(weights @ error + feed_forward, env.action_space.low,
                             env.action_space.high)
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        if terminated:
            env.ended_at = info["time"]
        done = terminated or truncated
    return total


def pd_start(k: float) -> np.ndarray:
    """W of a PD law on the slot error: a = -k e_p - 1.5 k e_v on each axis."""
    weights = np.zeros((3, 6))
    for axis, (p, v) in enumerate(((0, 2), (1, 3), (4, 5))):
        weights[axis, p], weights[axis, v] = -k, -1.5 * k
    return weights


def train(env: FormationEnv, args, returns: list) -> np.ndarray:
    """Basic random search (BRS, V1); prints each iteration's return and appends it to
    `returns`."""
    rng = np.random.default_rng(args.seed)
    weights = pd_start(args.start_gain)
    for iteration in range(args.iterations):
        start = time.perf_counter()
        deltas = rng.standard_normal((args.directions, 3, 6))
        seed = int(rng.integers(1 << 30))
        plus = np.array([episode(env, weights + args.noise * d, seed) for d in deltas])
        minus = np.array([episode(env, weights - args.noise * d, seed) for d in deltas])
        spread = np.concatenate([plus, minus]).std() or 1.0  # ARS's scaling by the returns' std
        weights += args.step / (args.directions * spread) * np.einsum(
            "k,kij->ij", plus - minus, deltas)
        # Progress on the held-out evaluation seed (never used by the update): the training
        # seeds differ from iteration to iteration, so their returns are not comparable.
        now = episode(env, weights, EVALUATION_SEED)
        returns.append(now)
        print(f"iteration {iteration + 1:2d}/{args.iterations}: return {now:9.2f} "
              f"(directions {plus.mean():8.2f} / {minus.mean():8.2f}, "
              f"{time.perf_counter() - start:4.1f} s)", flush=True)
    return weights


def plot(path: Path, returns: list, traces: dict, results: dict) -> None:
    """The return per iteration (0: the starting policy), and each policy's distance to the slot on the evaluation seed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.4))
    left.plot(range(len(returns)), returns, "o-")
    left.set(xlabel="iteration", ylabel="return on the evaluation seed",
             title="basic random search")
    for name, trace in traces.items():
        t, distance = np.array(trace).T
        ended = results[name][1]
        right.plot(t, distance, label=name + (f" (safety event at {ended:.2f} s)" if ended else ""))
        if ended:
            right.plot(t[-1], distance[-1], "kx")
    right.set(xlabel="t (s)", ylabel="|e_p| of follower 1 (m)", title="evaluation seed")
    right.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"figure: {path}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--iterations", type=int, default=10)
    parser.add_argument("--directions", type=int, default=4)
    parser.add_argument("--noise", type=float, default=0.3, help="exploration std of W")
    parser.add_argument("--step", type=float, default=0.2, help="step size of W")
    parser.add_argument("--seconds", type=float, default=6.0, help="episode length, s")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--start-gain", type=float, default=0.5, help="k of the starting PD law")
    parser.add_argument("--plot", type=Path, help="write the returns and the flights as a PNG")
    args = parser.parse_args(argv)
    for name in ("iterations", "directions"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} {getattr(args, name)}: give a whole number >= 1")
    if not (args.seconds > 0 and args.noise > 0 and args.step > 0):
        parser.error("--seconds, --noise and --step take positive numbers")
    short = {"run.duration": args.seconds, "run.metric_window": [0.0, args.seconds],
             "render.snapshots": []}
    env = FormationEnv(EXP2, follower=0, set=short)
    traces = {name: [] for name in ("untrained", "learned", "SMC law (eq. 48)")}
    results = {"untrained": episode(env, pd_start(args.start_gain), EVALUATION_SEED,
                                    traces["untrained"])}
    results["untrained"] = (results["untrained"], env.ended_at)
    returns = [results["untrained"][0]]  # iteration 0: the starting policy
    weights = train(env, args, returns)
    for name, w in (("learned", weights), ("SMC law (eq. 48)", None)):
        results[name] = (episode(env, w, EVALUATION_SEED, traces[name]), env.ended_at)
    print("evaluation seed: " + ", ".join(
        f"{name} {total:.2f}" + (f" (ended by a safety event at {t:.2f} s)" if t else "")
        for name, (total, t) in results.items()))
    print("learned W (rows: a_x, a_y, a_z; columns: e_px e_py e_vx e_vy e_z e_vz):")
    print(np.array2string(weights, precision=2, suppress_small=True))
    if args.plot:
        plot(args.plot, returns, traces, results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
