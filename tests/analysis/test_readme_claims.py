# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""README's figures are regenerated or dated: the Performance section's paragraph names a command
or a date beside its figures, and the claims found no longer true stay out."""
import re
from pathlib import Path

README = (Path(__file__).resolve().parents[2] / "README.md").read_text()


def _section(title: str) -> str:
    start = README.index(f"## {title}")
    end = README.find("\n## ", start + 1)
    return README[start:end if end > 0 else None]


def test_performance_figures_come_with_a_command_or_a_date():
    text = _section("Performance")
    figures = re.findall(r"\d+(?:\.\d+)?x\b", text)
    assert figures, "no figures found: the test would check nothing"
    assert re.search(r"20\d\d-\d\d-\d\d", text) and "`mjformation bench" in text
    assert "`mjformation run experiments/exp2.toml --no-render`" in text


def test_claims_found_untrue_are_gone():
    assert "pixel for pixel" not in README  # replay: a few pixels differ (replay_test.cc)
    assert "0.58x real time" not in README  # MuJoCo 2.2.2, one thread: superseded
    assert "with\n0.35 rad the quadrotors do not reach" not in README  # the constrained law does
