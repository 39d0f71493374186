# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The benchmark board from stored per-run records: intervals, ties, failed cells."""
import json
import math

import matplotlib.image as mpimg
import pytest

from mjfanalysis import leaderboard as lb

# Scores (rms_slot_error_m) per law and scenario, seeds 1..3. In A, x and y overlap (a tie), z
# lies above both; in B, y's seed 2 flipped.
SCORES = {("x", "A"): [1.0, 1.1, 0.9], ("y", "A"): [1.2, 1.3, 1.1], ("z", "A"): [3.0, 3.1, 2.9],
          ("x", "B"): [2.0, 2.0, 2.0], ("y", "B"): [1.0, 1.0, 1.0], ("z", "B"): [4.0, 4.0, 4.0]}


def _records():
    out = []
    for (law, scenario), scores in SCORES.items():
        for seed, v in enumerate(scores, start=1):
            failed = "safety: 1 flip" if (law, scenario, seed) == ("y", "B", 2) else None
            out.append({"law": law, "scenario": scenario, "seed": seed,
                        "metrics": {"rms_slot_error_m": v, "sigma_f_mean": 2 * v,
                                    "failed": failed}})
    return out


def test_interval_is_student_t():
    mean, lo, hi = lb.interval95([1.0, 1.1, 0.9])
    half = 4.3027 * 0.1 / math.sqrt(3)  # t_{0.975, 2} sd / sqrt(n)
    assert (mean, lo, hi) == pytest.approx((1.0, 1.0 - half, 1.0 + half))
    assert lb.interval95([2.5]) == (2.5, 2.5, 2.5)
    assert lb.interval95([0.1, 5.0])[1] == 0.0  # non-negative scores: cut at zero


def test_ties_ranks_and_failed_cells():
    board = lb.build(_records())
    cells = {(c["law"], c["scenario"]): c for c in board["cells"]}
    assert (cells[("x", "A")]["rank"], cells[("x", "A")]["tie"]) == (1, True)
    assert (cells[("y", "A")]["rank"], cells[("y", "A")]["tie"]) == (1, True)
    assert (cells[("z", "A")]["rank"], cells[("z", "A")]["tie"]) == (3, False)
    flipped = cells[("y", "B")]
    assert flipped["failed"] == "seed 2: safety: 1 flip"
    assert flipped["mean"] is None and flipped["rank"] is None
    # y's 1.0 in B is not the best: its cell failed, so x's 2.0 is
    assert cells[("x", "B")]["normalised"] == 1.0 and cells[("z", "B")]["normalised"] == 2.0
    # overall per seed: x (1.0, 1.1, 0.9)/1 + 1 over 2; z (3.0, 3.1, 2.9)/1 + 2 over 2
    overall = {o["law"]: o for o in board["overall"]}
    assert overall["x"]["mean"] == pytest.approx(1.0) and overall["x"]["rank"] == 1
    assert overall["z"]["mean"] == pytest.approx(2.5) and overall["z"]["rank"] == 2
    assert overall["y"]["failed_cells"] == ["B"] and overall["y"]["rank"] is None
    assert [o["law"] for o in board["overall"]] == ["x", "z", "y"]


def test_markdown_json_and_figure(tmp_path):
    records = _records()
    board = lb.build(records)
    meta = {"benchmark_version": 1, "date": "2026-12-07", "seeds": [1, 2, 3]}
    text = lb.markdown(board, meta)
    rows = {line.split("|")[1].strip(): line for line in lb.board_table(board)}
    assert all(line in text for line in rows.values())
    assert "#1=" in rows["`x`"] and "#3" in rows["`z`"]
    assert "**FAILED** (seed 2: safety: 1 flip)" in rows["`y`"]
    assert "**FAILED** in 1 scenario(s)" in rows["`y`"]
    lb.write_json(board, tmp_path / "leaderboard.json", meta, records)
    stored = json.loads((tmp_path / "leaderboard.json").read_text())
    assert stored["date"] == "2026-12-07" and len(stored["runs"]) == 18
    assert lb.build(stored["runs"])["overall"] == board["overall"]  # re-ranked from the file
    lb.heatmap(board, tmp_path / "board.png")
    img = mpimg.imread(str(tmp_path / "board.png"))[:, :, :3]
    grey = (abs(img[:, :, 0] - 0.8) < 0.02) & (abs(img[:, :, 1] - 0.8) < 0.02)
    assert grey.sum() > 200  # the failed cell's grey


def test_a_law_missing_a_scenario_gets_no_overall_score():
    records = [r for r in _records() if (r["law"], r["scenario"]) != ("z", "B")]
    board = lb.build(records)
    overall = {o["law"]: o for o in board["overall"]}
    assert overall["z"]["mean"] is None and overall["z"]["rank"] is None
    assert overall["x"]["rank"] == 1
    row = next(line for line in lb.board_table(board) if line.startswith("| `z`"))
    assert "n/a (not every scenario" in row and "not run" in row


def test_a_cell_not_applicable_is_shown_and_left_out_of_the_overall_score(tmp_path):
    records = _records() + [
        {"law": "x", "scenario": "C", "seed": seed,
         "metrics": {"not_applicable": "x has no per-agent version", "failed": None}}
        for seed in (1, 2, 3)] + [
        {"law": law, "scenario": "C", "seed": seed,
         "metrics": {"rms_slot_error_m": v, "failed": None, "messages_per_s": 200.0}}
        for law, v in (("y", 1.0), ("z", 2.0)) for seed in (1, 2, 3)]
    board = lb.build(records)
    cells = {(c["law"], c["scenario"]): c for c in board["cells"]}
    assert cells[("x", "C")]["rank"] is None and cells[("x", "C")]["failed"] is None
    assert cells[("y", "C")]["normalised"] == 1.0  # x is not counted in C
    assert cells[("z", "C")]["metrics_mean"]["messages_per_s"] == 200.0
    overall = {o["law"]: o for o in board["overall"]}
    # x over A and B only, as in test_ties_ranks_and_failed_cells
    assert overall["x"]["mean"] == pytest.approx(1.0) and overall["x"]["not_applicable"] == ["C"]
    row = next(line for line in lb.board_table(board) if line.startswith("| `x`"))
    assert "not applicable (x has no per-agent version)" in row
    assert "(without 1 not applicable)" in row
    lb.heatmap(board, tmp_path / "board.png")
    assert (tmp_path / "board.png").stat().st_size > 0
