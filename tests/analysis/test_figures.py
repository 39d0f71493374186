# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
import subprocess
import sys

from conftest import ANALYSIS, make_run

from mjfanalysis import plots
from mjfanalysis.io import load_run

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def test_figures_cli_writes_all(fake_run, tmp_path):
    d = fake_run[0]
    out = tmp_path / "figs"
    r = subprocess.run([sys.executable, str(ANALYSIS / "figures.py"), str(d), "--out", str(out)],
                       capture_output=True, text=True, env={"MPLBACKEND": "Agg", "PATH": ""})
    assert r.returncode == 0, r.stderr
    for name in plots.FIGURE_NAMES.values():
        p = out / name
        assert p.is_file(), name
        data = p.read_bytes()
        assert data.startswith(PNG_MAGIC) and len(data) > 5000, name


def test_figures_without_sliding_and_incomplete(tmp_path):
    d, _, _ = make_run(tmp_path, "consensus_baseline", exp=0, sliding=False, complete=False,
                       t_end=20.0)
    figs = plots.run_figures(load_run(d), tmp_path / "out")
    assert all(p.stat().st_size > 1000 for p in figs.values())


def test_figures_deterministic(fake_run, tmp_path):
    run = load_run(fake_run[0])
    a = plots.run_figures(run, tmp_path / "a")
    b = plots.run_figures(load_run(fake_run[0]), tmp_path / "b")
    for key in a:
        assert a[key].read_bytes() == b[key].read_bytes(), key


def test_radius_falls_back_to_slots(fake_run):
    run = load_run(fake_run[0])
    run.summary.pop("shape")
    run.summary["plugins"]["formation"]["attributes"] = {}
    run.config = None
    assert abs(plots.formation_radius(run) - 10.0) < 1e-6


def test_figures_cli_missing_dir(tmp_path):
    r = subprocess.run([sys.executable, str(ANALYSIS / "figures.py"), str(tmp_path / "nope")],
                       capture_output=True, text=True)
    assert r.returncode != 0


def test_sigma_f_zoom_is_a_panel_that_covers_nothing(tmp_path, monkeypatch):
    # sigma_f(0) some hundred times the window's: the window is zoomed on, in a panel of its
    # own below the whole series, so that no part of the transient is hidden behind it.
    d, _, _ = make_run(tmp_path, "exp2", exp=2, a=20.0, tau=4.0, c=0.05)
    drawn = []
    saved = plots.save_figure
    monkeypatch.setattr(plots, "save_figure",
                        lambda fig, path: drawn.append(fig) or saved(fig, path))
    plots.fig_sigma_f(load_run(d), tmp_path / "sigma_f.png")
    (fig,) = drawn
    whole, zoom = fig.axes
    assert zoom.get_title().startswith("zoom on the window")
    a, b = whole.get_position(), zoom.get_position()
    assert a.y0 > b.y1, (a, b)  # one above the other: nothing of `whole` is covered
    assert zoom.get_xlim()[1] <= 40.0 + 1.0 and zoom.get_xlim()[0] > 20.0


def test_sigma_f_without_a_transient_has_one_panel(tmp_path, monkeypatch):
    d, _, _ = make_run(tmp_path, "exp2", exp=2, a=0.0, c=0.05)
    drawn = []
    saved = plots.save_figure
    monkeypatch.setattr(plots, "save_figure",
                        lambda fig, path: drawn.append(fig) or saved(fig, path))
    plots.fig_sigma_f(load_run(d), tmp_path / "sigma_f.png")
    assert len(drawn[0].axes) == 1


def test_run_overwrite_knows_every_figure_name():
    # `mjformation run --overwrite` deletes from RUN_DIR/figures only the files named here;
    # a figure it does not know would be refused as the user's.
    output_cc = (ANALYSIS.parent / "runner" / "record" / "src" / "output.cc").read_text()
    for name in plots.FIGURE_NAMES.values():
        assert f'"{name}"' in output_cc, name
