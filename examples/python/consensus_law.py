# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""A formation law in 30 lines of numpy: consensus_linear re-implemented in Python, flown on
Exp 2's quadrotors through the same runner, beside the C++ plugin (docs/PYTHON.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/consensus_law.py [--duration 40]
"""

import argparse
import tomllib
from pathlib import Path

import numpy as np

import mjformation

KP, KV = 1.0, 2.0  # consensus_linear's defaults: 1/s^2, 1/s


def consensus(t, states, offsets, graph):
    """u_i = f_ia - kp e_ip - kv e_iv, e_i = (L_H z)_i with z_i = x_i - f_i - x_0 (eq. (16))."""
    leader = states[0, [0, 1, 3, 4]]  # px, py, vx, vy
    z = states[1:, [0, 1, 3, 4]] - offsets[:, :4] - leader
    a = graph.adjacency  # a[i, j] = a_ij: i hears j
    e = graph.leader_weight[:, None] * z + (a[:, :, None] * (z[:, None, :] - z[None, :, :])).sum(1)
    return offsets[:, 4:6] - KP * e[:, :2] - KV * e[:, 2:4]


def consensus_agent(hood):
    """The same law, one callable per follower, from its own state and what it received."""

    def agent(t, me, messages, leader, offsets):
        i = hood.follower
        z_i = me[[0, 1, 3, 4]] - offsets[i, :4]
        e = np.zeros(4)
        if hood.leader_weight > 0:
            e += hood.leader_weight * (z_i - leader[[0, 1, 3, 4]])
        for j, a_ij in zip(hood.neighbours, hood.weights):
            e += a_ij * (z_i - (messages[j][[0, 1, 3, 4]] - offsets[j, :4]))
        return offsets[i, 4:6] - KP * e[:2] - KV * e[2:4]

    return agent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=40.0)
    parser.add_argument("--figure", default="consensus_python_vs_cpp.png")
    parser.add_argument("--experiment", default=str(Path(__file__).parents[2] / "experiments/exp2.toml"))
    args = parser.parse_args()
    short = {"run.duration": args.duration, "run.metric_window": [0.0, args.duration],
             "render.snapshots": []}
    shape = tomllib.loads(Path(args.experiment).read_text())["formation"]["shape"]
    cpp = mjformation.run(args.experiment, set={**short, "formation": {"plugin": "consensus_linear",
                                                                       "shape": shape}})
    py = mjformation.run(args.experiment, set=short, formation=consensus)
    diff = np.max(np.abs(cpp.timeseries["sigma_f"] - py.timeseries["sigma_f"]))
    print(f"consensus_linear (C++): mean sigma_f {cpp.summary['metrics']['sigma_f_mean']:.6f}")
    print(f"consensus in Python:    mean sigma_f {py.summary['metrics']['sigma_f_mean']:.6f}"
          f"  (summary names it: {py.summary['plugins']['formation']})")
    print(f"largest sigma_f difference over the run: {diff:.3g}")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.semilogy(cpp.timeseries["t"], cpp.timeseries["sigma_f"], lw=3, alpha=0.4,
                label="consensus_linear (C++ plugin)")
    ax.semilogy(py.timeseries["t"], py.timeseries["sigma_f"], "k--", lw=1,
                label=f"consensus in Python (largest difference {diff:.2g})")
    ax.set(xlabel="t [s]", ylabel="sigma_f [m] (68)", title="Exp 2 vehicles, linear consensus")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.figure, dpi=120)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()
