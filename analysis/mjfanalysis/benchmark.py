# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""`mjformation benchmark`: flies laws x scenarios x seeds (one `mjformation run` per cell and
seed, several at once), resumable, then writes the board (leaderboard.md, leaderboard.json,
leaderboard.png; docs/BENCHMARK.md).

Layout of --out: runs/<law>/<scenario>/seed<S>/ (a run directory plus benchmark_metrics.json,
written last: a run with it is done and is skipped when the benchmark is run again).
"""

from __future__ import annotations

import datetime
import json
import subprocess
import sys
import threading
import time
import tomllib
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path

from . import benchmark_metrics as bm
from . import leaderboard

BENCHMARK_VERSION = 1
REPO = Path(__file__).resolve().parents[2]
SCENARIO_DIR = REPO / "experiments" / "benchmark"
LAWS_FILE = SCENARIO_DIR / "laws.toml"
BASELINE = SCENARIO_DIR / "leaderboard.json"
# The runner's refusal of a law without a per-agent version in a per-agent scenario
# (runner/control/src/control_wiring.cc, FindAgentPlugin): such a cell is "not applicable".
NO_AGENT_VERSION = "has no per-agent version"
PYTHON_LAW_RUNNER = REPO / "analysis" / "benchmark_python_law.py"


def python_law(law: str) -> bool:
    """A Python law, FILE.py:NAME (flown through mjformation.run), not a plugin's name."""
    path, _, name = law.rpartition(":")
    return path.endswith(".py") and name.isidentifier()


@dataclass
class Plan:
    """What to fly: laws {name: inline [formation] table}, scenario names, seeds, and how."""
    mjformation: str
    laws: dict
    scenarios: list
    seeds: list
    out: Path
    sets: list = field(default_factory=list)
    plugin_path: list = field(default_factory=list)
    jobs: int = 2
    band: float = bm.DEFAULT_BAND_M


def known_laws(path=LAWS_FILE) -> dict:
    """{law: inline formation table} from experiments/benchmark/laws.toml, in file order."""
    with open(path, "rb") as f:
        return {name: entry["formation"] for name, entry in tomllib.load(f)["laws"].items()}


def known_scenarios(folder=SCENARIO_DIR) -> list:
    """Scenario names (file stems) of experiments/benchmark/*.toml but laws.toml, sorted."""
    return sorted(p.stem for p in folder.glob("*.toml") if p.name != LAWS_FILE.name)


def pick(names: str | None, known, what: str) -> list:
    """The comma-separated subset of known names (all when names is None); an unknown name is
    an error that lists the known ones."""
    if not names:
        return list(known)
    picked = [n.strip() for n in names.split(",") if n.strip()]
    for n in picked:
        if n not in known:
            raise SystemExit(f"benchmark: unknown {what} '{n}' (known: {', '.join(known)})")
    return picked


def run_dir(plan: Plan, law: str, scenario: str, seed: int) -> Path:
    return plan.out / "runs" / law / scenario / f"seed{seed}"


def done_metrics(d: Path) -> dict | None:
    """The cell's stored metrics when its run finished and was scored, else None."""
    try:
        return json.loads((d / bm.METRICS_FILE).read_text())
    except (OSError, json.JSONDecodeError):
        return None


def command(plan: Plan, law: str, scenario: str, seed: int) -> list:
    """The `mjformation run` command line of one cell and seed (for a Python law, that of
    benchmark_python_law.py, which flies it through mjformation.run)."""
    if python_law(plan.laws[law]):
        cmd = [sys.executable, str(PYTHON_LAW_RUNNER), plan.laws[law],
               str(SCENARIO_DIR / f"{scenario}.toml"), str(run_dir(plan, law, scenario, seed)),
               str(seed), "--mjformation", plan.mjformation]
        for s in plan.sets:
            cmd += ["--set", s]
        for p in plan.plugin_path:
            cmd += ["--plugin-path", p]
        return cmd
    cmd = [plan.mjformation, "run", str(SCENARIO_DIR / f"{scenario}.toml"),
           "--out", str(run_dir(plan, law, scenario, seed)), "--overwrite", "--no-render", "-q",
           "--set", f"formation={plan.laws[law]}", "--set", f"run.seed={seed}"]
    for s in plan.sets:
        cmd += ["--set", s]
    for p in plan.plugin_path:
        cmd += ["--plugin-path", p]
    return cmd


def fly(plan: Plan, law: str, scenario: str, seed: int, stop: threading.Event) -> dict | None:
    """Runs one cell and seed and scores it (None: not started, the board is stopping). A law
    the runner refuses for having no per-agent version (a per-agent scenario) is scored not
    applicable. Any other run that ends without summary.json (a bad experiment or law, not a bad
    flight) or is interrupted stops the benchmark."""
    if stop.is_set():
        return None
    d = run_dir(plan, law, scenario, seed)
    cmd = command(plan, law, scenario, seed)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if not (d / "summary.json").is_file() and NO_AGENT_VERSION in proc.stderr:
        return bm.write_metrics(d, bm.not_applicable(f"{law} {NO_AGENT_VERSION}"))
    if not (d / "summary.json").is_file():
        stop.set()
        raise SystemExit(f"benchmark: {law} on {scenario} (seed {seed}) wrote no summary.json "
                         f"(exit code {proc.returncode}): {proc.stderr.strip()[-800:]}\n"
                         f"command: {' '.join(cmd)}")
    if "interrupted_by_signal" in bm.read_summary(d / "summary.json"):
        # Stopped by the user, not by its flight: left unscored, so that it is flown again.
        stop.set()
        raise SystemExit(f"benchmark: interrupted ({d}); the same command resumes")
    return bm.write_run_metrics(d, plan.band)


class Progress:
    """One stderr line: runs done of total, the mean wall time per run and the ETA."""

    def __init__(self, total: int, skipped: int, jobs: int):
        self.total, self.skipped, self.jobs = total, skipped, jobs
        self.flown, self.start = 0, time.monotonic()

    def line(self) -> str:
        elapsed = time.monotonic() - self.start
        todo = self.total - self.skipped - self.flown
        per_run = elapsed / self.flown if self.flown else float("nan")
        eta = f"{todo * per_run:.0f} s" if self.flown else "?"
        return (f"benchmark: {self.skipped + self.flown}/{self.total} runs "
                f"({self.skipped} done before), {per_run * self.jobs:.1f} s per run, "
                f"elapsed {elapsed:.0f} s, ETA {eta}")

    def tick(self) -> None:
        self.flown += 1
        end = "\n" if self.skipped + self.flown == self.total else "\r"
        print(self.line(), end=end, file=sys.stderr, flush=True)


def fly_all(plan: Plan) -> list:
    """Every record of the plan, flying only the cells not done before."""
    keys = [(law, s, seed) for law in plan.laws for s in plan.scenarios for seed in plan.seeds]
    results = {k: done_metrics(run_dir(plan, *k)) for k in keys}
    todo = [k for k in keys if results[k] is None]
    progress = Progress(len(keys), len(keys) - len(todo), plan.jobs)
    if not todo:
        print(f"benchmark: all {len(keys)} runs done before ({plan.out})", file=sys.stderr)
    stop = threading.Event()
    with ThreadPoolExecutor(max_workers=plan.jobs) as pool:
        futures = {pool.submit(fly, plan, *k, stop): k for k in todo}
        try:
            for f in as_completed(futures):
                results[futures[f]] = f.result()
                progress.tick()
        except BaseException:
            stop.set()
            pool.shutdown(cancel_futures=True)  # start nothing more; finished runs stay done
            raise
    return [{"law": law, "scenario": s, "seed": seed, "metrics": results[(law, s, seed)]}
            for law, s, seed in keys]


def meta(plan: Plan, argv: list) -> dict:
    """The board's header: benchmark version, date, mjformation version, seeds, command."""
    version = subprocess.run([plan.mjformation, "--version"], capture_output=True,
                             text=True).stdout.strip().splitlines()
    return {"benchmark_version": BENCHMARK_VERSION,
            "date": datetime.date.today().isoformat(), "mjformation": version[0] if version else "unknown",
            "seeds": plan.seeds, "band_m": plan.band, "sets": plan.sets,
            "command": " ".join(["mjformation", "benchmark", *argv])}


# Written first into every benchmark folder, as `mjformation run` marks its run directory
# (.mjformation-run): a folder with it is the benchmark's, to resume and to write the board in.
MARKER = ".mjformation-benchmark"
BOARD_FILES = ("leaderboard.md", "leaderboard.json", "leaderboard.png")


def claim_out(out: Path, overwrite: bool = False) -> None:
    """Makes out the benchmark's folder before anything is flown: a new or empty folder gets the
    marker; a marked one is resumed; any other is refused (SystemExit, nothing written) unless
    overwrite, which lets the board replace its leaderboard files and marks it."""
    if out.exists() and not out.is_dir():
        raise SystemExit(f"benchmark: --out {out}: is a file, not a folder; nothing was run")
    marker = out / MARKER
    if marker.is_file() and not marker.is_symlink():
        return
    if out.exists() and any(out.iterdir()) and not overwrite:
        held = sorted(p.name for p in out.iterdir())
        mine = [f for f in BOARD_FILES if f in held]
        raise SystemExit(
            f"benchmark: --out {out}: exists, is not empty ({', '.join(held[:5])}"
            f"{', ...' if len(held) > 5 else ''}) and is not a benchmark folder (no {MARKER} "
            f"marker); the board would replace {', '.join(mine or BOARD_FILES)} there. Nothing "
            "was run or written: choose another --out, or pass --overwrite to write the board "
            "into it")
    out.mkdir(parents=True, exist_ok=True)
    marker.write_text("This folder is a mjformation benchmark folder: `mjformation benchmark "
                      "--out` resumes it\nand replaces its leaderboard files. Delete this file "
                      "to protect the folder from that.\n")


def write_board(records: list, info: dict, out: Path) -> dict:
    """leaderboard.json, leaderboard.md and leaderboard.png in out; returns the board."""
    board = leaderboard.build(records)
    out.mkdir(parents=True, exist_ok=True)
    leaderboard.write_json(board, out / "leaderboard.json", info, records)
    (out / "leaderboard.md").write_text(leaderboard.markdown(board, info))
    leaderboard.heatmap(board, out / "leaderboard.png")
    return board


def baseline_records(path=BASELINE) -> tuple[list, dict]:
    """The stored board's per-run records and header ([] and {} when there is none)."""
    try:
        stored = json.loads(Path(path).read_text())
    except OSError:
        return [], {}
    keys = ("benchmark_version", "date", "mjformation", "seeds", "band_m", "sets")
    return stored.get("runs", []), {k: stored.get(k) for k in keys}
