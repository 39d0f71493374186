#!/usr/bin/python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The robustness map under the acceleration limit as Markdown and CSV, 95 % CIs.

Usage: /usr/bin/python3 analysis/accel_limit_map.py MAP_DIR   (writes MAP_DIR/map.md, map_compact.md, map.csv)
MAP_DIR holds one `mjformation sweep` folder per <experiment>__<vehicle>__<law>
(scripts/robustness_map.sh).
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from mjfanalysis import accel_map  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    ap.add_argument("map_dir", type=Path)
    args = ap.parse_args(argv)
    cells = accel_map.read_map(args.map_dir)
    if not cells:
        print(f"accel_limit_map.py: no sweep folder in {args.map_dir}", file=sys.stderr)
        return 2
    (args.map_dir / "map.md").write_text("\n".join(accel_map.markdown(cells)) + "\n")
    (args.map_dir / "map_compact.md").write_text(
        "\n".join(accel_map.compact_markdown(cells)) + "\n")
    accel_map.write_csv(cells, args.map_dir / "map.csv")
    n = sum(len(c.runs) for c in cells)
    print(f"accel_limit_map.py: wrote {args.map_dir / 'map.md'} and map.csv ({n} runs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
