#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The robustness map (experiment x tilt_max x attitude plugin) as Markdown and CSV.

Usage: /usr/bin/python3 analysis/robustness_map.py MAP_DIR   (writes MAP_DIR/map.md, map_compact.md, map.csv)
MAP_DIR holds one `mjformation sweep` folder per <experiment>__<plugin> (scripts/robustness_map.sh).
"""

import argparse
import sys
from pathlib import Path

from mjfanalysis import robustness


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("map_dir", type=Path)
    args = ap.parse_args(argv)
    cells = robustness.read_map(args.map_dir)
    if not cells:
        print(f"robustness_map.py: no sweep folder in {args.map_dir}", file=sys.stderr)
        return 2
    (args.map_dir / "map.md").write_text("\n".join(robustness.markdown(cells)) + "\n")
    (args.map_dir / "map_compact.md").write_text(
        "\n".join(robustness.compact_markdown(cells)) + "\n")
    robustness.write_csv(cells, args.map_dir / "map.csv")
    print(f"robustness_map.py: wrote {args.map_dir / 'map.md'} and map.csv ({len(cells)} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
