# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Analysis of mjformation run directories: reading, metrics, figures, the report.

The run directory layout, the timeseries.csv columns and the summary.json keys are the contract
of docs/ARCHITECTURE.md; this package reads nothing else.
"""

from .io import (  # noqa: F401
    Run,
    Sweep,
    find_runs,
    load_run,
    load_sweep,
    read_config,
    read_summary,
    read_timeseries,
    window_label,
)
from .metrics import (  # noqa: F401
    PAPER_SIGMA_F,
    final_slot_errors,
    formation_deviation,
    paper_experiment,
    sigma_f_recomputed,
    slot_radius,
    vehicle_ids,
    window_mean,
)
