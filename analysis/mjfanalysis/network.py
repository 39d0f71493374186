# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The simulated network of a per-agent run (summary.json "network"): a few lines of
text and one figure (per link: delivered and lost messages, measured latency; per follower: the
age of the information it acts on), for the report's per-run section.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .io import Run  # noqa: E402
from .plots import STYLE, save_figure  # noqa: E402

FIGURE_NAME = "network.png"


def protocol_suffix(summary: dict | None) -> str:
    """' — per-agent, coupling jacobi (4 rounds/step)' for a per-agent run, '' otherwise."""
    net = (summary or {}).get("network")
    if not net or net.get("execution") != "per_agent":
        return ""
    return (f" — per-agent, coupling {net.get('coupling', '?')} "
            f"({net.get('rounds_per_step', '?')} rounds/step)")


def _totals(links: list[dict]) -> dict:
    keys = ("sent", "delivered", "lost", "stale_dropped", "out_of_range", "round_messages_sent",
            "round_messages_lost")
    return {k: sum(int(link.get(k, 0)) for link in links) for k in keys}


def lines(summary: dict | None) -> list[str]:
    """Markdown bullet lines about the run's network; [] when the run had none."""
    net = (summary or {}).get("network")
    if not net:
        return []
    links = net.get("links") or []
    t = _totals(links)
    arrived = [link for link in links if link.get("delivered", 0) > 0]
    mean_latency = (sum(link["latency_mean_s"] * link["delivered"] for link in arrived)
                    / max(1, sum(link["delivered"] for link in arrived)))
    ages = net.get("age_of_information") or []
    worst_age = max(ages, key=lambda a: a.get("max_s", 0.0)) if ages else None
    sent = max(1, t["sent"])
    out = [f"- network: {len(links)} links, coupling {net.get('coupling')}, "
           f"{net.get('rounds_per_step')} rounds per step, Jacobi spectral radius "
           f"rho((D + H)^-1 A) = {net.get('jacobi_spectral_radius', float('nan')):.4g}",
           f"- messages: {t['sent']} sent, {t['delivered']} delivered "
           f"({100 * t['delivered'] / sent:.1f} %), {t['lost']} lost "
           f"({100 * t['lost'] / sent:.1f} %), {t['stale_dropped']} dropped as older than the "
           f"one held, {t['out_of_range']} not sent (out of range); Jacobi round messages "
           f"{t['round_messages_sent']} sent, {t['round_messages_lost']} lost; measured latency "
           f"{1000 * mean_latency:.3g} ms (mean over delivered messages)"]
    if worst_age:
        mean_age = sum(a.get("mean_s", 0.0) for a in ages) / len(ages)
        out.append(f"- age of information acted on: {1000 * mean_age:.3g} ms on average over the "
                   f"followers; the largest, {1000 * worst_age['max_s']:.3g} ms, at follower "
                   f"{worst_age['follower']}")
    out.append(f"- topology: {net.get('topology_switches', 0)} link switches (range limits), "
               f"{net.get('time_without_spanning_tree_s', 0.0):.3g} s without a spanning tree"
               + (f"; {net['central_solve_skipped_samples']} samples without a central solve"
                  if net.get("central_solve_skipped_samples") else ""))
    return out


def figure(run: Run, out_path) -> Path | None:
    """Per link delivered / lost counts and measured latency; per follower age of information."""
    net = (run.summary or {}).get("network")
    if not net or not net.get("links"):
        return None
    links = net["links"]
    labels = [f"{link['from']}→{link['to']}" for link in links]
    x = range(len(links))
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(3, 1, figsize=(max(7.0, 0.35 * len(links)), 8.0))
        ax = axes[0]
        ax.bar(x, [link["delivered"] for link in links], label="delivered", color="tab:green")
        ax.bar(x, [link["lost"] for link in links], bottom=[link["delivered"] for link in links],
               label="lost", color="tab:red")
        ax.set_ylabel("messages")
        ax.set_xticks(list(x), labels, fontsize=7, rotation=90)
        ax.legend()
        ax.set_title(f"{run.name}: network per link (sender→receiver; 0 = leader)", fontsize=10)
        ax = axes[1]
        ax.bar(x, [1000 * link["latency_mean_s"] for link in links], label="mean",
               color="tab:blue")
        ax.plot(list(x), [1000 * link["latency_max_s"] for link in links], "k_", ms=10,
                label="max")
        ax.set_ylabel("measured latency (ms)")
        ax.set_xticks(list(x), labels, fontsize=7, rotation=90)
        ax.legend()
        ax = axes[2]
        ages = net.get("age_of_information") or []
        followers = [a["follower"] for a in ages]
        ax.bar(followers, [1000 * a["mean_s"] for a in ages], label="mean", color="tab:purple")
        ax.plot(followers, [1000 * a["max_s"] for a in ages], "k_", ms=12, label="max")
        ax.set_xlabel("follower")
        ax.set_ylabel("age of information (ms)")
        ax.legend()
        fig.tight_layout()
        return save_figure(fig, out_path)
