#!/usr/bin/env python3
# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
"""Two engines and two rotor models in one window: `mjformation bench` of two runner builds.

    dev/engine_bench.py OLD_MJFORMATION NEW_MJFORMATION [--followers 6,200,1000] [--rounds 2]

For each rotor model (thrust actuators, wrench) and swarm size, the two binaries' benches run
alternately (old, new, old, new, ...), each point best of `bench`'s own three; the table gives
bare and full steps/s of each engine, new over old, and the full pipeline's real-time factor with
1 and 2 physics threads on the new engine (contacts off, as docs/PERFORMANCE.md's scaling runs).
"""
import argparse
import json
import subprocess
import tempfile

EXPERIMENT = "experiments/exp2.toml"
ROTORS = {"actuator": [], "wrench": ["--set", 'vehicles.rotor_model="wrench"']}
# Simulated seconds per point: the actuator path at large N is slow enough to need few steps.
DURATION = {("actuator", 6): 4.0, ("actuator", 200): 0.2, ("actuator", 1000): 0.02,
            ("wrench", 6): 4.0, ("wrench", 200): 1.0, ("wrench", 1000): 0.5}


def bench(binary, followers, rotor, threads):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        cmd = [binary, "bench", EXPERIMENT, "--followers", str(followers), "--duration",
               str(DURATION.get((rotor, followers), 1.0)), "--json", out.name,
               "--set", "vehicles.contacts=false", *ROTORS[rotor]]
        if threads:
            cmd += ["--threads", ",".join(map(str, threads))]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        return json.load(open(out.name))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--followers", default="6,200,1000")
    parser.add_argument("--rounds", type=int, default=2)
    args = parser.parse_args()
    sizes = [int(s) for s in args.followers.split(",")]
    print("| rotor model | followers | bare steps/s old | bare new | new/old | full steps/s old"
          " | full new | new/old | RTF full new, 1 thread | 2 threads |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for rotor in ROTORS:
        for n in sizes:
            old, new = [], []
            for _ in range(args.rounds):
                old.append(bench(args.old, n, rotor, None)["points"][0])
                new.append(bench(args.new, n, rotor, None)["points"][0])
            threaded = bench(args.new, n, rotor, [1, 2]) if n >= 200 else None
            steps = old[0]["steps"]
            bare_old = steps / min(p["bare_wall_s"] for p in old)
            bare_new = steps / min(p["bare_wall_s"] for p in new)
            full_old = steps / min(p["full_wall_s"] for p in old)
            full_new = steps / min(p["full_wall_s"] for p in new)
            rtf = ["", ""]
            if threaded:
                for p in threaded["points"]:
                    rtf[p.get("threads", 1) - 1] = f"{p['real_time_factor_full']:.2f}"
            print(f"| {rotor} | {n} | {bare_old:,.0f} | {bare_new:,.0f} | {bare_new / bare_old:.2f}"
                  f" | {full_old:,.0f} | {full_new:,.0f} | {full_new / full_old:.2f}"
                  f" | {rtf[0]} | {rtf[1]} |", flush=True)


if __name__ == "__main__":
    main()
