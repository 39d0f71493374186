# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""One benchmark cell flown with a Python formation law (docs/BENCHMARK.md, "Submitting a law"):
`mjformation benchmark --law FILE.py:NAME` runs this once per scenario and seed, in place of
`mjformation run`. NAME is a callable, FormationLaw or AgentLaw of FILE (docs/PYTHON.md), flown
through mjformation.run(formation=...) with the cell's seed and the board's overrides. A law the
runner refuses (a central law in a per-agent scenario) exits 1 with the runner's message.

    benchmark_python_law.py FILE.py:NAME SCENARIO.toml OUT SEED --mjformation BIN [--set K=V]...
        [--plugin-path DIR]...
"""

from __future__ import annotations

import argparse
import runpy
import sys
from pathlib import Path


def parse(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("law", help="FILE.py:NAME")
    p.add_argument("scenario")
    p.add_argument("out")
    p.add_argument("seed", type=int)
    p.add_argument("--mjformation", required=True, help="the runner the board flies with")
    p.add_argument("--set", dest="sets", action="append", default=[])
    p.add_argument("--plugin-path", dest="plugin_path", action="append", default=[])
    return p.parse_args(argv)


def import_mjformation(runner: str):
    """The mjformation package: installed, or the build tree's (BUILD/python beside
    BUILD/runner/mjformation) when the board flies a build tree's runner."""
    try:
        import mjformation
    except ImportError:
        sys.path.insert(0, str(Path(runner).resolve().parents[1] / "python"))
        import mjformation
    return mjformation


def load_law(spec: str):
    path, _, name = spec.rpartition(":")
    namespace = runpy.run_path(path)
    if name not in namespace:
        raise SystemExit(f"benchmark: {path} defines no '{name}'")
    return namespace[name]


def main(argv) -> int:
    args = parse(argv)
    mjformation = import_mjformation(args.mjformation)
    law = load_law(args.law)
    try:
        mjformation.run(args.scenario, set=[f"run.seed={args.seed}", *args.sets], out=args.out,
                        overwrite=True, render=False, formation=law,
                        plugin_path=args.plugin_path or None)
    except (ValueError, TypeError) as e:  # a configuration the runner refuses
        print(e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
