# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The varied values of a sweep as sweep.json writes them. Its own module so that both the
readers (io.py) and the sweep plot (sweep_plot.py) use it without importing each other."""

from __future__ import annotations

import json


def axis_value(v):
    """A varied value as written in sweep.json: numbers stay numbers; TOML text such as
    '"none"' or '{preset = "typical"}' is decoded where it is JSON, else kept as text."""
    if isinstance(v, str):
        try:
            return json.loads(v)
        except ValueError:
            return v
    return v
