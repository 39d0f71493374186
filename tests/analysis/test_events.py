# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Safety events (summary.json "events") are marked in the figures and in Table 1: a crashed
run's sigma_f is never shown as a plain result."""
import matplotlib.image as mpimg
import numpy as np
from conftest import make_run

from mjfanalysis import plots, report
from mjfanalysis.io import load_run

FLIP = [("flip", 12.5, [3]), ("near_miss", 5.0, [1, 2])]


def _event_red(path) -> int:
    """Pixels of the events' pure red (the figures use it for nothing else)."""
    img = mpimg.imread(str(path))[:, :, :3]
    return int(((img[:, :, 0] > 0.94) & (img[:, :, 1] < 0.12) & (img[:, :, 2] < 0.12)).sum())


def test_time_figures_mark_events_with_a_labelled_line(tmp_path):
    clean = load_run(make_run(tmp_path / "a", "exp2", exp=2, a=5.0, tau=4.0, c=0.2)[0])
    flipped = load_run(make_run(tmp_path / "b", "exp2", exp=2, a=5.0, tau=4.0, c=0.2,
                                events=FLIP)[0])
    assert [e["kind"] for e in plots.marked_events(flipped)] == ["flip"]  # near misses unmarked
    for key in ("sigma_f", "pitch_roll", "yaw", "sliding", "trajectories"):
        fn = dict(plots.FIGURES)[key]
        a = fn(clean, tmp_path / f"clean_{key}.png")
        b = fn(flipped, tmp_path / f"flip_{key}.png")
        assert _event_red(a) < 5, key
        assert _event_red(b) > 100, f"{key}: no event mark"


def test_event_label_and_title(tmp_path):
    import matplotlib.pyplot as plt

    run = load_run(make_run(tmp_path, "exp2", exp=2, events=FLIP)[0])
    fig, ax = plt.subplots()
    assert plots._mark_events_in_time(ax, run) == 1
    texts = [t.get_text() for t in ax.texts]
    assert "F3 flip 12.50 s" in texts, texts
    assert any(abs(line.get_xdata()[0] - 12.5) < 1e-9 for line in ax.lines)
    plt.close(fig)
    assert "2 SAFETY EVENTS" in plots._title(run, "x", 0)


def _results(root):
    res = root / "results"
    make_run(res, "exp2", exp=2, c=0.5, events=FLIP)
    make_run(res, "exp3", exp=3, c=0.5, events=[("near_miss", 7.0, [0, 4])])
    make_run(res, "exp1_printed", exp=1, c=0.2)
    return res


def _row(text, name):
    for line in text.splitlines():
        if line.startswith(f"| `{name}` |"):
            return [c.strip() for c in line.strip("|").split("|")]
    raise AssertionError(f"no table row for {name}")


def test_table1_marks_runs_with_events(tmp_path):
    res = _results(tmp_path)
    text = report.write_report(res, tmp_path / "out").read_text()
    crashed = _row(text, "exp2")
    # In parentheses, footnoted, without a ratio: not a plain result.
    assert crashed[4].startswith("(") and "†1" in crashed[4], crashed
    assert crashed[6] == "—", crashed
    near = _row(text, "exp3")
    assert "†2" in near[4] and not near[4].startswith("("), near
    assert near[6] != "—", near
    plain = _row(text, "exp1_printed")
    assert "†" not in plain[4] and not plain[4].startswith("("), plain
    note1 = next(line for line in text.splitlines() if line.startswith("†1 "))
    assert "`exp2`" in note1 and "2 safety events" in note1 and "follower 3 flip" in note1
    assert "not a result" in note1
    note2 = next(line for line in text.splitlines() if line.startswith("†2 "))
    assert "`exp3`" in note2 and "near misses only" in note2
    assert "**2 SAFETY EVENTS** — σ_f is not a result" in text


def test_crashed_run_stays_out_of_comparisons(tmp_path):
    res = tmp_path / "results"
    make_run(res, "exp2", exp=2, c=0.5, events=FLIP)
    make_run(res, "exp3", exp=3, c=0.9)
    text = report.write_report(res, tmp_path / "out").read_text()
    assert "**Exp. 2 vs Exp. 3** (quadrotor): mean σ_f" not in text
    assert np.isnan(report.analyse(load_run(res / "exp2")).ratio)
