# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The Python formation laws in use, by key (the in-process plugins' `law` attribute).

The C++ trampolines (python/src/python_law.cc) call resolve_central / resolve_agent from a
plugin's create(); everything else here runs on the caller's thread, under a lock.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field

import numpy as np

_lock = threading.Lock()
_laws: dict[str, list] = {}  # key -> [law object, users]


@dataclass(frozen=True)
class Graph:
    """The follower graph as a central law gets it (paper section 2; followers 0..N-1 here).

    leader_weight[i] = a_i0; adjacency[i, j] = a_ij, the weight of edge j -> i (i hears j).
    """

    leader_weight: np.ndarray
    adjacency: np.ndarray

    @property
    def n_followers(self) -> int:
        return len(self.leader_weight)

    @property
    def laplacian(self) -> np.ndarray:
        """L_H = D - A + H (eq. (16)'s matrix)."""
        a = self.adjacency
        return np.diag(a.sum(axis=1)) - a + np.diag(self.leader_weight)


@dataclass(frozen=True)
class Neighbourhood:
    """What one follower knows of the graph (per-agent mode): its own row of L_H."""

    follower: int  # 0-based (the paper's i = follower + 1; vehicle follower + 1)
    n_followers: int
    leader_weight: float  # a_i0 (0: this follower does not hear the leader)
    neighbours: tuple = field(default_factory=tuple)  # in-neighbours j (0-based followers)
    weights: tuple = field(default_factory=tuple)  # a_ij, same order


def _key(law) -> str:
    fn = getattr(law, "function", law)
    module = getattr(fn, "__module__", None) or "python"
    name = getattr(fn, "__qualname__", None) or type(fn).__name__
    return f"{module}.{name}"


def acquire(law) -> str:
    """Registers `law` (a FormationLaw or AgentLaw) while a run uses it; returns its key."""
    base = _key(law)
    with _lock:
        key, n = base, 1
        while key in _laws and _laws[key][0] is not law:
            n += 1
            key = f"{base}#{n}"  # another law of the same name is in use
        entry = _laws.setdefault(key, [law, 0])
        entry[1] += 1
        return key


def release(key: str) -> None:
    with _lock:
        entry = _laws.get(key)
        if entry is None:
            return
        entry[1] -= 1
        if entry[1] <= 0:
            del _laws[key]


def _find(key: str):
    with _lock:
        entry = _laws.get(key)
    if entry is None:
        raise KeyError(
            f"no Python formation law '{key}' is registered (the 'python' plugins run only "
            "through mjformation.run / Simulation with formation=...)"
        )
    return entry[0]


def resolve_central(key: str, info: dict):
    law = _find(key)
    if getattr(law, "per_agent", False):
        raise TypeError(f"law '{key}' is per-agent: it needs execution.mode = \"per_agent\"")
    graph = Graph(leader_weight=info["leader_weight"], adjacency=info["adjacency"])
    return law.function, graph


def resolve_agent(key: str, info: dict):
    law = _find(key)
    hood = Neighbourhood(
        follower=info["follower"],
        n_followers=info["n_followers"],
        leader_weight=info["leader_weight"],
        neighbours=tuple(info["neighbours"]),
        weights=tuple(info["weights"]),
    )
    if getattr(law, "per_agent", False):
        return law.function(hood)  # the factory: one callable per follower
    raise TypeError(f"law '{key}' is a central law; per-agent execution needs an AgentLaw")
