# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
import math
import re
import subprocess
import sys

import pytest
from conftest import ANALYSIS, make_run

PAPER = {1: 0.8397, 2: 1.4405, 3: 4.5250}


def _results(root):
    """exp1_printed (ratio 0.5), exp2 (ratio 2.0), exp3 incomplete, exp1_switching unfinished,
    exp1_exponential missing, a point-mass exp2 (ratio 1.25) and a baseline not in the paper."""
    res = root / "results"
    c = lambda target: target / math.sqrt(6)  # noqa: E731  constant offset c: sigma = sqrt(6) c
    make_run(res, "exp1_printed", exp=1, c=c(0.5 * PAPER[1]), video=True)
    make_run(res, "exp2", exp=2, c=c(2.0 * PAPER[2]), delta=0.1, error_bound=9.0)
    make_run(res, "exp2_pointmass", exp=2, c=c(1.25 * PAPER[2]), model="pointmass",
             snapshots=False)
    make_run(res, "exp3", exp=3, c=c(PAPER[3]), complete=False, t_end=30.0)
    make_run(res, "exp1_switching", exp=1, summary=False, t_end=10.0)
    make_run(res, "consensus_baseline", exp=0, sliding=False, c=0.9)
    (res / "discussion.md").write_text("The authors' paragraph, verbatim: *sigma* | pipes.\n")
    return res


def _report(res, out):
    return subprocess.run([sys.executable, str(ANALYSIS / "report.py"), str(res), "--out", str(out)],
                          capture_output=True, text=True)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    root = tmp_path_factory.mktemp("rep")
    res = _results(root)
    r = _report(res, root / "out1")
    assert r.returncode == 0, r.stderr
    return root, res, (root / "out1" / "report.md").read_text()


def _row(text, name):
    for line in text.splitlines():
        if line.startswith(f"| `{name}` |") and "Protocol" not in line:
            return [c.strip() for c in line.strip("|").split("|")]
    raise AssertionError(f"no table row for {name}")


def test_table_ratios(report):
    _, _, text = report
    assert "## Table 1, side by side with the paper" in text
    r = _row(text, "exp1_printed")
    assert r[1] == "1" and r[2] == "quadrotor" and r[3].startswith("smc_continuous")
    assert float(r[4]) == pytest.approx(0.5 * PAPER[1], abs=1e-4) and r[5] == "0.8397" and r[6] == "0.500"
    assert r[10] == "yes"
    r = _row(text, "exp2")
    assert float(r[4]) == pytest.approx(2.0 * PAPER[2], abs=1e-4) and r[5] == "1.4405" and r[6] == "2.000"
    assert r[7] == "0.1" and r[8] == "9"
    r = _row(text, "exp2_pointmass")
    assert r[2] == "pointmass" and r[6] == "1.250"
    r = _row(text, "consensus_baseline")
    assert r[1] == "—" and r[5] == "—" and r[6] == "—"


def test_incomplete_flagged(report):
    _, _, text = report
    r = _row(text, "exp3")
    assert "incomplete" in r[4] and r[4].startswith("(") and r[6] == "—"
    assert r[10] == "**NO** (incomplete)"
    r = _row(text, "exp1_switching")
    assert r[10] == "**NO** (unfinished)" and r[6] == "—"
    assert "> **INCOMPLETE** — not a result." in text
    assert "> **UNFINISHED** — not a result." in text
    assert re.search(r"Incomplete runs.*`exp3`.*`exp1_switching`|Incomplete runs.*`exp1_switching`"
                     r".*`exp3`", text)


def test_missing_runs(report):
    _, _, text = report
    line = next(x for x in text.splitlines() if x.startswith("**Missing runs**"))
    assert "`exp1_exponential`" in line and "`exp1_printed`" not in line
    assert "`exp1_printed_pointmass`" in line  # point-mass runs exist, so their set is expected
    assert "`exp2_pointmass`" not in line


def test_discussion_and_topology(report):
    _, _, text = report
    assert "The authors' paragraph, verbatim: *sigma* | pipes." in text
    assert "Formation achieved" in text and "`exp2`" in text
    # exp3 is incomplete: no Exp 2 vs Exp 3 verdict from it.
    assert "Exp. 2 vs Exp. 3** (quadrotor): cannot compare" in text
    assert "Exp. 1 vs Exp. 2** (quadrotor)" in text
    assert "Fig. 8" in text and "1→2" in text and "6→1" in text
    assert "yes (Assumption 2 holds)" in text
    assert "measured mean σ_f" in text and "bound 9" in text


def test_findings_first_commentary_and_detail_after(report):
    _, _, text = report
    headings = [line for line in text.splitlines() if line.startswith("## ")]
    assert headings[:2] == ["## Findings", "## Table 1, side by side with the paper"], headings
    order = [headings.index(h) for h in ("## Findings", "## Runs",
                                          "## Commentary from the experiment authors (`discussion.md`)",
                                          "## Runs in detail")]
    assert order == sorted(order), headings
    assert text.index("Formation achieved") < text.index("## Table 1")


def test_cross_check_agrees(report):
    _, _, text = report
    line = next(x for x in text.splitlines() if x.startswith("| `exp2` | [25, 40]"))
    assert line.rstrip().endswith("| yes |")


def test_figures_snapshots_video(report):
    root, _, text = report
    out = root / "out1"
    for link in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text):
        p = out / link
        assert p.is_file() and p.stat().st_size > 0, link
    assert "figures/sigma_f_all_runs.png" in text
    assert "snapshots/exp1_printed/t000.00.png" in text
    m = re.search(r"Video: \[[^\]]*\]\(([^)]+)\)", text)
    assert m and (out / m.group(1)).resolve() == (root / "results/exp1_printed/video.mp4")


def test_deterministic(report):
    root, res, text = report
    r = _report(res, root / "out2")
    assert r.returncode == 0, r.stderr
    assert (root / "out2" / "report.md").read_text() == text
    pngs = sorted(p.relative_to(root / "out1") for p in (root / "out1").rglob("*.png"))
    assert len(pngs) > 20
    for p in pngs:
        assert (root / "out1" / p).read_bytes() == (root / "out2" / p).read_bytes(), p


def test_empty_results_exit_nonzero(tmp_path):
    (tmp_path / "empty").mkdir()
    r = _report(tmp_path / "empty", tmp_path / "out")
    assert r.returncode != 0 and "no run directories" in r.stderr
    r = _report(tmp_path / "does_not_exist", tmp_path / "out")
    assert r.returncode != 0


def test_default_out_dir(tmp_path):
    res = tmp_path / "res"
    make_run(res, "exp2", exp=2)
    r = subprocess.run([sys.executable, str(ANALYSIS / "report.py"), str(res)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert (res / "report" / "report.md").is_file()
    # Re-running with the report folder inside the results folder still finds one run.
    r = subprocess.run([sys.executable, str(ANALYSIS / "report.py"), str(res)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "1 run directory" in (res / "report" / "report.md").read_text()


def test_per_agent_run_gets_its_network_lines_and_figure(tmp_path):
    links = [{"from": f, "to": t, "sent": 100, "delivered": 80, "lost": 20, "stale_dropped": 1,
              "out_of_range": 0, "latency_mean_s": 0.002, "latency_max_s": 0.003,
              "round_messages_sent": 10, "round_messages_lost": 2}
             for f, t in ((0, 1), (1, 2), (2, 1))]
    network = {"execution": "per_agent", "coupling": "jacobi", "rounds_per_step": 4,
               "central_solve_skipped_samples": 0, "jacobi_spectral_radius": 0.5,
               "links": links,
               "age_of_information": [{"follower": 1, "mean_s": 0.002, "max_s": 0.004},
                                      {"follower": 2, "mean_s": 0.004, "max_s": 0.009}],
               "topology_switches": 2, "topology_events": [],
               "time_without_spanning_tree_s": 1.5}
    res = tmp_path / "results"
    make_run(res, "exp2_network", exp=2, c=0.5, network=network)
    make_run(res, "exp2", exp=2, c=0.5)
    r = _report(res, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "out" / "report.md").read_text()
    assert _row(text, "exp2_network")[3].endswith("— per-agent, coupling jacobi (4 rounds/step)")
    assert "per-agent" not in _row(text, "exp2")[3]
    assert ("- messages: 300 sent, 240 delivered (80.0 %), 60 lost (20.0 %), 3 dropped as older "
            "than the one held, 0 not sent (out of range); Jacobi round messages 30 sent, 6 lost; "
            "measured latency 2 ms") in text
    assert "the largest, 9 ms, at follower 2" in text
    assert "- topology: 2 link switches (range limits), 1.5 s without a spanning tree" in text
    assert "![exp2_network network](figures/exp2_network/network.png)" in text
    assert (tmp_path / "out" / "figures" / "exp2_network" / "network.png").stat().st_size > 5000
    assert not (tmp_path / "out" / "figures" / "exp2" / "network.png").exists()
    # The paper's orderings compare its protocols as run centrally, not a networked variant.
    assert "σ_f(`exp2_network`)" not in text and "(`exp2_network`):" not in text


def test_a_violated_assumption_1_is_a_line_of_the_run(tmp_path):
    """Stock Exp 2's leader leaves Assumption 1's bounds in its start transient: the run's section
    says so with summary.json's own numbers; a run whose assumption holds gets no such line."""
    import json

    res = tmp_path / "results"
    make_run(res, "exp2", exp=2, c=0.3)
    make_run(res, "exp1_printed", exp=1, c=0.3)
    summary_path = res / "exp2" / "summary.json"
    summary = json.loads(summary_path.read_text())
    summary["leader_acceleration"] = {"bounds": [-1.0, 1.0], "fraction_outside": 0.023575,
                                      "first_violation_time_s": 0.073, "max_excess": 4.927,
                                      "assumption1_holds": False}
    summary_path.write_text(json.dumps(summary))
    r = _report(res, tmp_path / "out")
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "out" / "report.md").read_text()
    assert text.count("**Assumption 1 does not hold**") == 1
    assert ("the leader's measured acceleration left [-1, 1] m/s² on 2.36 % of the steps, first "
            "at t = 0.073 s, by up to 4.927 m/s²: Theorem 2's band is not guaranteed") in text
