# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""analysis/ installs as a package (pyproject.toml) offline, and mjfanalysis then imports from
the installed location alone (no source tree on sys.path)."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

ANALYSIS = Path(__file__).resolve().parents[2] / "analysis"


def test_installs_offline_and_imports_without_the_source_tree(tmp_path):
    # Build from a copy: pip's in-tree build would leave build/ and *.egg-info in the sources.
    src = tmp_path / "src"
    src.mkdir()
    shutil.copy(ANALYSIS / "pyproject.toml", src)
    shutil.copytree(ANALYSIS / "mjfanalysis", src / "mjfanalysis",
                    ignore=shutil.ignore_patterns("__pycache__"))
    site = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                    "--no-deps", "--quiet", "--target", str(site), str(src)],
                   check=True, capture_output=True, text=True)
    shutil.rmtree(src)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    code = ("import mjfanalysis, sys; print(mjfanalysis.__file__); "
            "assert not any('analysis' == p.rstrip('/').split('/')[-1] for p in sys.path)")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, check=True,
                         capture_output=True, text=True)
    installed = Path(out.stdout.strip())
    assert installed.is_relative_to(site), installed
    for name in ("load_run", "load_sweep", "find_runs", "window_label"):
        assert hasattr(__import__("mjfanalysis"), name)
