# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The peers harness (docs/PEERS.md): mjformation beside RotorPy, PyFlyt and Crazyflow.

Pure Python with numpy only, so every peer's own virtual environment (numpy 1.x or 2.x) imports
it: the reference vehicle and its conversion to each peer's parameters (params), the two
workloads and the discrete SMC law in numpy (workload), statistics and the Markdown tables
(tables)."""
