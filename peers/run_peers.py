#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""The peers harness (issue 37, docs/PEERS.md): mjformation beside RotorPy, PyFlyt and Crazyflow.

  /usr/bin/python3 peers/run_peers.py --build build            # everything -> peers/out/PEERS.md
  /usr/bin/python3 peers/run_peers.py --build build --doc      # ... and the tracked docs/PEERS.md
  /usr/bin/python3 peers/run_peers.py --build build --sizes 7 --repeats 3 --batch-worlds 0   # quicker
  /usr/bin/python3 peers/run_peers.py --build build --sizes 1000 --peers crazyflow --workloads W1 \
      --duration 10 --skip-dynamics --batch-worlds 0 --merge --doc --doc-section   # add cells

Installs each peer into its own virtual environment (peers/.envs/NAME) from its pinned lock
(peers/locks/NAME.txt), runs each in its own process (peers/workers/worker_NAME.py) with
single-threaded BLAS/XLA, times mjformation's runner (BUILD/runner/mjformation) on the same
workloads in the same invocation, runs the dynamics tiers, writes OUT/results.json (OUT:
--out, default peers/out), the report OUT/PEERS.md and its divergence figure beside it (with --doc,
docs/PEERS.md and docs/peers_divergence.png instead). --merge keeps the cells of OUT/results.json
that this invocation does not measure again; --doc-section writes only this invocation's sizes into
the report, as a section between markers, and leaves the rest of the file as it is. Not part of CI:
it installs from a registry."""

import argparse
import datetime
import hashlib
import json
import os
import platform
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

from peerlib import experiments as E  # noqa: E402
from peerlib import params as P  # noqa: E402
from peerlib import workload as W  # noqa: E402

PEERS = {
    "rotorpy": {"lock": "rotorpy.txt", "worker": "worker_rotorpy.py", "hosts_law": True},
    "pyflyt": {"lock": "pyflyt.txt", "worker": "worker_pyflyt.py", "hosts_law": False},
    "crazyflow": {"lock": "crazyflow.txt", "worker": "worker_crazyflow.py", "hosts_law": True},
}
THREADS_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
               "NUMBA_NUM_THREADS": "1",
               "XLA_FLAGS": "--xla_cpu_multi_thread_eigen=false intra_op_parallelism_threads=1",
               "JAX_PLATFORMS": "cpu", "PYTHONDONTWRITEBYTECODE": "1"}


def log(msg):
    print(f"[peers {time.strftime('%H:%M:%S')}] {msg}", flush=True)


def ensure_env(name, python, envs):
    """peers/.envs/NAME from locks/NAME.txt (exact pins); reinstalled when the lock changes.
    Returns (python path or None, error text or None)."""
    lock = HERE / "locks" / f"{name}.txt"
    env = envs / name
    stamp = env / ".lock-sha256"
    digest = hashlib.sha256(lock.read_bytes()).hexdigest()
    py = env / "bin" / "python"
    if py.exists() and stamp.exists() and stamp.read_text() == digest:
        return str(py), None
    log(f"installing {name} from {lock.name}")
    if env.exists():
        shutil.rmtree(env)
    cmds = [[python, "-m", "venv", str(env)],
            ["nice", "-n", "10", str(py), "-m", "pip", "install", "-q", "--disable-pip-version-check",
             "--no-deps", "-r", str(lock)]]
    for cmd in cmds:
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return None, f"`{' '.join(cmd[-4:])}` exit {r.returncode}: {(r.stderr or r.stdout).strip()[-1500:]}"
    stamp.write_text(digest)
    return str(py), None


def run_worker(py, worker, task, out, timeout):
    tf, rf = out / f"task_{task['peer']}_{task['tag']}.json", out / f"result_{task['peer']}_{task['tag']}.json"
    tf.write_text(json.dumps(task))
    env = dict(os.environ, **THREADS_ENV)
    t0 = time.perf_counter()
    try:
        r = subprocess.run([py, str(HERE / "workers" / worker), str(tf), str(rf)], capture_output=True,
                           text=True, timeout=timeout, env=env, cwd=str(HERE / "workers"))
        err = None if r.returncode == 0 else f"exit {r.returncode}: {r.stderr.strip()[-1500:]}"
    except subprocess.TimeoutExpired:
        err = f"timed out after {timeout:.0f} s"
    res = json.loads(rf.read_text()) if rf.exists() else {"jobs": []}
    res["process_error"], res["process_wall_s"] = err, time.perf_counter() - t0
    return res


def read_positions(run_dir, n):
    """(t, positions (k, n, 3)) from a run's timeseries.csv."""
    import numpy as np
    d = np.genfromtxt(run_dir / "timeseries.csv", delimiter=",", names=True)
    pos = np.stack([np.stack([d[f"uav{i}_p{c}"] for c in "xyz"], axis=1) for i in range(n)], axis=1)
    return d["t"], pos


def mjformation_speed(binary, toml, out, workload, n, repeats, sets=()):
    """Runs of the runner (no render; `sets`: its --set overrides); wall = summary.json's
    timing.wall_time_s (the stepping loop); setup = the process's wall time less that."""
    n_run = max(n, 2)
    runs = []
    overrides = [word for value in sets for word in ("--set", value)]
    for k in range(repeats):
        rd = out / f"mjf_{workload}_n{n}_{k}"
        t0 = time.perf_counter()
        r = subprocess.run([binary, "run", str(toml), "--out", str(rd), "--no-render", "--overwrite", "-q"]
                           + overrides, capture_output=True, text=True)
        proc = time.perf_counter() - t0
        if not (rd / "summary.json").exists():
            return {"error": f"exit {r.returncode}: {r.stderr.strip()[-800:]}", "runs": runs}
        s = json.loads((rd / "summary.json").read_text())
        tm = s.get("timing", {})
        t, pos = read_positions(rd, n_run)
        win = (t >= 25.0) & (t <= 40.0 + 1e-9)
        if workload == "W1":
            errs = [W.hover_error(pos[i], n_run) for i in range(len(t)) if win[i]]
        else:
            errs = [W.slot_error(t[i], pos[i], n_run - 1) for i in range(len(t)) if win[i]]
        final = W.hover_error(pos[-1], n_run) if workload == "W1" else W.slot_error(t[-1], pos[-1], n_run - 1)
        runs.append({"wall_s": tm.get("wall_time_s"), "sim_s": float(s.get("sim_time_s") or t[-1]),
                     "physics_steps": int(s.get("steps") or round(float(t[-1]) * 1000)), "setup_s": proc - (tm.get("wall_time_s") or 0),
                     "warmup_s": None, "error_mean_25_40": sum(errs) / len(errs) if errs else None, "error_final": final,
                     "complete": s.get("complete"), "events": (s.get("events") or {}).get("by_kind")})
        if k > 0:
            shutil.rmtree(rd, ignore_errors=True)
    return {"runs": runs, "physics_hz": 1000.0, "n_run": n_run}


def batch_cell(binary, crazyflow_py, model, out, args):
    """40-s W2 runs (N = 7) per hour on both cores: Crazyflow's batch of worlds (XLA on 2 threads)
    against mjformation's sweep with 2 workers, over the same number of runs."""
    worlds = args.batch_worlds
    log(f"batched: Crazyflow {worlds} worlds, mjformation sweep of {worlds} runs on 2 workers")
    toml = out / "W2_n7_batch.toml"
    toml.write_text(E.experiment("W2", 7, str(model), duration=40.0))
    t0 = time.perf_counter()
    r = subprocess.run([binary, "sweep", str(toml), "--seeds", str(worlds), "--jobs", "2", "--no-render",
                        "-o", str(out / "mjf_sweep"), "--overwrite"], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    ours = {"runs": worlds, "wall_s": wall, "runs_per_hour": worlds * 3600.0 / wall,
            "error": None if r.returncode == 0 else f"exit {r.returncode}: {r.stderr.strip()[-500:]}"}
    task = {"peer": "crazyflow", "tag": "batch",
            "jobs": [{"kind": "batch", "n": 7, "worlds": worlds, "duration": args.batch_duration}]}
    env_flags = THREADS_ENV["XLA_FLAGS"]
    THREADS_ENV["XLA_FLAGS"] = "--xla_cpu_multi_thread_eigen=true intra_op_parallelism_threads=2"
    try:
        res = run_worker(crazyflow_py, PEERS["crazyflow"]["worker"], task, out, 3600)
    finally:
        THREADS_ENV["XLA_FLAGS"] = env_flags
    j = res["jobs"][0] if res.get("jobs") else {"error": res.get("process_error")}
    if "wall_s" in j:   # scale the stepping to a 40-s run; setup and compilation once
        j["runs_per_hour_40s"] = worlds * 3600.0 / (j["setup_s"] + j["warmup_s"] + j["wall_s"] * 40.0 / j["sim_s"])
    return {"mjformation": ours, "crazyflow": j}


def machine():
    def sh(cmd):
        try:
            return subprocess.run(cmd, shell=True, capture_output=True, text=True).stdout.strip()
        except OSError:
            return ""
    return {"cpu": sh("lscpu | sed -n 's/^Model name: *//p'"), "nproc": os.cpu_count(),
            "python": platform.python_version(), "os": sh(". /etc/os-release; echo $PRETTY_NAME"),
            "loadavg": os.getloadavg()}


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"), help="mjformation build folder (BUILD/runner/mjformation)")
    ap.add_argument("--binary", help="the runner itself (overrides --build)")
    ap.add_argument("--peers", default="rotorpy,pyflyt,crazyflow")
    ap.add_argument("--sizes", default="1,7,49", help="vehicles in all, comma separated")
    ap.add_argument("--workloads", default="W1,W2", help="speed workloads, comma separated (W1, W2)")
    ap.add_argument("--mjf-set", action="append", default=[], metavar="KEY=VALUE",
                    help="an override for mjformation's speed runs (its `run --set`), e.g. "
                         "'vehicles.rotor_model=\"wrench\"'; repeatable; stated in the report")
    ap.add_argument("--repeats", type=int, default=5, help="runs per cell (median and range reported)")
    ap.add_argument("--repeats-other", type=int, default=0,
                    help="runs per cell for sizes other than 7 (0: --repeats)")
    ap.add_argument("--duration", type=float, default=40.0, help="simulated seconds per run")
    ap.add_argument("--warmup-periods", type=int, default=1,
                    help="a peer's first control periods timed apart from the stepping (JIT compilation; "
                         "Crazyflow compiles its step again in its second period)")
    ap.add_argument("--wall-budget", type=float, default=120.0, help="stop a peer run after this many wall seconds")
    ap.add_argument("--python", default="/usr/bin/python3", help="interpreter the virtual environments are made from")
    ap.add_argument("--out", default=str(HERE / "out"), help="folder of results.json, PEERS.md and the figure")
    ap.add_argument("--doc", nargs="?", const=str(ROOT / "docs" / "PEERS.md"),
                    help="write the report to this file instead of OUT/PEERS.md (no FILE: the tracked "
                         "docs/PEERS.md)")
    ap.add_argument("--batch-worlds", type=int, default=8, help="Crazyflow worlds in the batched 2-core cell (0: skip)")
    ap.add_argument("--batch-duration", type=float, default=10.0, help="simulated seconds of the batched cell")
    ap.add_argument("--skip-speed", action="store_true")
    ap.add_argument("--skip-dynamics", action="store_true")
    ap.add_argument("--report-only", action="store_true", help="rewrite the report from OUT/results.json")
    ap.add_argument("--merge", action="store_true",
                    help="keep the cells of an existing OUT/results.json that this invocation does not "
                         "measure again (same simulator, work, N and controller: replaced)")
    ap.add_argument("--doc-section", action="store_true",
                    help="write only this invocation's sizes (--sizes) into the report, as a section between "
                         "markers (replaced when there, else placed before the dynamics), leaving the rest "
                         "of the file as it is")
    return ap.parse_args(argv)


def fail(message):
    """One line on stderr naming the argument or file and what to do; exit status 2."""
    return SystemExit(f"run_peers.py: {message}")


def writable_folder(path, option):
    """Creates `path` and checks that a file can be written in it."""
    try:
        path.mkdir(parents=True, exist_ok=True)
        probe = path / ".write-check"
        probe.write_text("")
        probe.unlink()
    except OSError as error:
        raise fail(f"{option} {path}: cannot write there ({error.strerror}); name a writable folder") from None
    return path


WORKLOADS = ("W1", "W2")


def checked_sizes(text):
    """The --sizes list as whole numbers, in the order given, or a one-line refusal."""
    sizes = []
    for word in (w for w in text.split(",") if w.strip()):
        if not word.strip().isdigit() or int(word) < 1:
            raise fail(f"--sizes: '{word}' is not a number of vehicles; give whole numbers >= 1, e.g. --sizes 1,7,49")
        sizes.append(int(word))
    if not sizes:
        raise fail("--sizes: no size given; give whole numbers >= 1, e.g. --sizes 1,7,49")
    return sizes


def checked_workloads(text):
    """The --workloads list (W1, W2), or a one-line refusal."""
    workloads = [w.strip() for w in text.split(",") if w.strip()]
    unknown = [w for w in workloads if w not in WORKLOADS]
    if unknown or not workloads:
        raise fail(f"--workloads: unknown workload '{(unknown or [text])[0]}'; the harness knows "
                   f"{', '.join(WORKLOADS)}, e.g. --workloads W1")
    return workloads


def checked_inputs(args):
    """(runner, peers, sizes, workloads) from the arguments, or a one-line refusal before anything
    is installed."""
    sizes = checked_sizes(args.sizes)
    if args.warmup_periods < 1:
        raise fail(f"--warmup-periods: {args.warmup_periods} is below 1; the first control period is always "
                   "timed apart, e.g. --warmup-periods 2")
    workloads = checked_workloads(args.workloads)
    if args.doc_section and not args.doc:
        raise fail("--doc-section: names no report to write into; add --doc (docs/PEERS.md) or --doc FILE")
    peers = [p for p in args.peers.split(",") if p]
    unknown = [p for p in peers if p not in PEERS]
    if unknown:
        raise fail(f"--peers: unknown peer '{unknown[0]}'; the harness knows {', '.join(PEERS)}")
    binary = args.binary or str(Path(args.build) / "runner" / "mjformation")
    if not (os.path.isfile(binary) and os.access(binary, os.X_OK)):
        where = "--binary" if args.binary else f"--build {args.build}:"
        raise fail(f"{where} no runner at {binary}; build it (cmake --build build --target mjf_product) "
                   "or name it with --binary FILE")
    return binary, peers, sizes, workloads


def load_results(out):
    """OUT/results.json of an earlier invocation, or a one-line refusal."""
    path = out / "results.json"
    try:
        results = json.loads(path.read_text())
    except FileNotFoundError:
        raise fail(f"{path}: no results to report; run the harness without --report-only first") from None
    except json.JSONDecodeError as error:
        raise fail(f"{path}: line {error.lineno}: not valid JSON ({error.msg}); run the harness again "
                   "to rewrite it") from None
    missing = [k for k in ("speed", "dynamics", "machine", "install", "command") if k not in results]
    if not isinstance(results, dict) or missing:
        raise fail(f"{path}: not a results file of this harness (no '{(missing or ['speed'])[0]}'); "
                   "run the harness again to rewrite it")
    return results


def write_report(results, args, out):
    import report
    doc = Path(args.doc) if args.doc else out / "PEERS.md"
    try:
        if args.doc_section:
            report.write_section(results, doc, checked_sizes(args.sizes))
        else:
            report.write(results, doc, out)
    except OSError as error:
        raise fail(f"{doc}: cannot write the report ({error.strerror}); name a writable file with --doc") from None
    log(f"wrote {doc}")


def take_lock(envs):
    """The harness's lock, or None when another invocation holds it."""
    import fcntl
    guard = open(envs / ".harness-lock", "w")
    try:   # two invocations at once would rebuild the same environments under each other
        fcntl.flock(guard, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        log(f"another run_peers.py holds {envs / '.harness-lock'}: wait for it to finish")
        return None
    return guard


KEPT_PINS = ("pyflyt", "rotorpy", "crazyflow", "drone_models", "mujoco", "numpy", "jax", "pybullet", "scipy")


def install_all(peers, args, envs, results):
    """{name: python} for every peer (and the mujoco reference) that installed."""
    pys = {}
    for name in peers + ([] if args.skip_dynamics else ["mujoco"]):   # mujoco: the dynamics tiers' reference
        py, err = ensure_env(name, args.python, envs)
        pins = [line for line in (HERE / "locks" / f"{name}.txt").read_text().split()
                if line.split("==")[0].lower() in KEPT_PINS + (name,)]
        results["install"][name] = {"ok": py is not None, "error": err, "pins": pins}
        if py:
            pys[name] = py
        else:
            log(f"{name}: install failed: {err}")
    return pys


def dynamics_tiers(binary, model, peers, pys, out, results):
    """Tiers (a)-(c): mjformation's composed scene in stock MuJoCo beside each peer."""
    log("dynamics tiers")
    toml = out / "dyn_w1.toml"
    toml.write_text(E.experiment("W1", 2, str(model), duration=0.1))
    rd = out / "mjf_scene"
    subprocess.run([binary, "run", str(toml), "--out", str(rd), "--no-render", "--overwrite", "-q"],
                   capture_output=True, text=True)
    scene = rd / "scene.xml"
    if "mujoco" in pys:
        results["dynamics"]["mjformation"] = run_worker(
            pys["mujoco"], "worker_mujoco.py", {"peer": "mjformation", "tag": "dyn",
                                                "model": str(scene) if scene.exists() else None}, out, 600)
    for name in peers:
        if name in pys:
            task = {"peer": name, "tag": "dyn", "jobs": [{"kind": "dynamics"}, {"kind": "dynamics", "bare": True}]}
            results["dynamics"][name] = run_worker(pys[name], PEERS[name]["worker"], task, out, 1200)


def stamp(cell, args, when=None):
    """The cell with what it was measured under: the simulated seconds asked for, when it began
    and the load average then (`when`: those of an earlier moment)."""
    cell.update({"duration": args.duration}, **(when or {"measured": now(), "load": list(os.getloadavg())}))
    return cell


def peer_speed_cells(name, workload, n, reps, pys, out, args):
    """The speed cells of one peer on one workload and size (its own controller, and the SMC law
    where it takes an acceleration reference)."""
    cells = []
    ctrls = ["own"] + (["smc"] if workload == "W2" and PEERS[name]["hosts_law"] and n > 1 else [])
    for ctrl in ctrls:
        log(f"{workload} N={n}: {name} ({ctrl})")
        job = {"kind": "speed", "workload": workload, "n": n, "controller": ctrl,
               "duration": args.duration, "repeats": reps, "wall_budget": args.wall_budget,
               "warmup_periods": args.warmup_periods}
        res = run_worker(pys[name], PEERS[name]["worker"],
                         {"peer": name, "tag": f"{workload}_{n}_{ctrl}", "jobs": [job]}, out,
                         reps * (args.wall_budget + 120) + 300)
        j = res["jobs"][0] if res["jobs"] else {}
        cells.append({"sim": name, "workload": workload, "n": n, "controller": ctrl,
                      "runs": j.get("runs", []), "physics_hz": j.get("physics_hz"),
                      "error": j.get("error") or res.get("process_error"), "duration": args.duration,
                      "warmup_periods": args.warmup_periods})
    return cells


def speed_tiers(binary, model, peers, sizes, workloads, pys, out, args, results, previous):
    """The workloads at every size: mjformation's runner, then each installed peer."""
    for n in sizes:
        reps = args.repeats if (n == 7 or not args.repeats_other) else args.repeats_other
        for workload in workloads:
            toml = out / f"{workload}_n{n}.toml"
            toml.write_text(E.experiment(workload, n, str(model), duration=args.duration))
            results["machine"].setdefault("load_during", []).append(os.getloadavg())
            log(f"{workload} N={n}: mjformation")
            cell = stamp({"sim": "mjformation", "workload": workload, "n": n,
                          "controller": "smc (48)" if workload == "W2" else "hover", "sets": args.mjf_set}, args)
            cell.update(mjformation_speed(binary, toml, out, workload, n, reps, args.mjf_set))
            results["speed"].append(cell)
            for name in (p for p in peers if p in pys):
                began = {"measured": now(), "load": list(os.getloadavg())}
                cells = peer_speed_cells(name, workload, n, reps, pys, out, args)
                results["speed"] += [stamp(c, args, began) for c in cells]
            save(results, out, previous)


def cell_key(cell):
    return (cell["sim"], cell["workload"], cell["n"], cell["controller"])


def invocation(results):
    """When, how and under what load one invocation ran (its load average at the start and end)."""
    m = results.get("machine", {})
    return dict({k: results.get(k) for k in ("started", "finished", "command")},
                loadavg=m.get("loadavg"), loadavg_end=m.get("loadavg_end"))


def merge_results(old, new):
    """`new`'s results over `old`'s: a speed cell of `new` replaces `old`'s of the same simulator,
    work, N and controller, `old`'s other cells stay where they were; the dynamics and the batch
    cell likewise when `new` measured them. The header (started, command, machine) stays `old`'s;
    every invocation is listed under "invocations"."""
    if old is None:
        return new
    merged = dict(old)
    again = {cell_key(c) for c in new["speed"]}
    merged["speed"] = [c for c in old["speed"] if cell_key(c) not in again] + new["speed"]
    merged["dynamics"] = new["dynamics"] or old["dynamics"]
    if new.get("batch"):
        merged["batch"] = new["batch"]
    merged["install"] = {**old["install"], **new["install"]}
    merged["invocations"] = old.get("invocations", [invocation(old)]) + [invocation(new)]
    return merged


def save(results, out, previous=None):
    """OUT/results.json: this invocation's results, merged over `previous` (--merge) when given."""
    merged = merge_results(previous, results)
    (out / "results.json").write_text(json.dumps(merged, indent=1, default=float))
    return merged


def now():
    return datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")


def main(argv=None):
    args = parse_args(argv)
    out = writable_folder(Path(args.out), "--out")
    if args.report_only:
        write_report(load_results(out), args, out)
        return 0
    binary, peers, sizes, workloads = checked_inputs(args)
    previous = load_results(out) if args.merge and (out / "results.json").exists() else None
    envs = HERE / ".envs"
    if peers or not args.skip_dynamics:   # environments to make: one invocation at a time
        envs.mkdir(exist_ok=True)
        guard = take_lock(envs)
        if guard is None:
            return 2
    results = {"started": now(), "command": shlex.join([os.path.relpath(sys.argv[0], ROOT)] + sys.argv[1:]),
               "machine": machine(), "binary": binary, "reference": P.REFERENCE, "derived": P.derived(),
               "unmatched": P.unmatched(), "args": vars(args), "install": {}, "speed": [], "dynamics": {}}
    ver = subprocess.run([binary, "--version"], capture_output=True, text=True)
    results["mjformation_version"] = (ver.stdout or ver.stderr).strip().splitlines()[0]
    pys = install_all(peers, args, envs, results)
    model = out / "cfref.xml"
    model.write_text(P.mjcf())
    if not args.skip_dynamics:
        dynamics_tiers(binary, model, peers, pys, out, results)
        save(results, out, previous)
    if not args.skip_speed:
        speed_tiers(binary, model, peers, sizes, workloads, pys, out, args, results, previous)
    if not args.skip_speed and args.batch_worlds and "crazyflow" in pys:
        results["batch"] = batch_cell(binary, pys["crazyflow"], model, out, args)
        save(results, out, previous)
    results["finished"] = now()
    results["machine"]["loadavg_end"] = os.getloadavg()
    write_report(save(results, out, previous), args, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
