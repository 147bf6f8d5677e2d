"""The engineer's analyses of one rotor, timed side by side: every `gyrokit` command on the 100-DOF
three-disk rotor (data/three_disk_rotor.toml) with its defaults, best of `--runs` runs, with what the
command vouches for its numbers, and the time as a ratio to `gyrokit campbell` (the core job) run in the
same sitting.

    /usr/bin/python3 apps/bench/bench_analyses.py --cli build/apps/gyrokit [--runs 3] [--quick]

--quick: one run each (the ctest smoke run). Exits 1 if a command fails.
"""
import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))   # apps/bench/ -> the root
SCENE = os.path.join(ROOT, "data", "three_disk_rotor.toml")


def static_check(out):
    rows = {r["quantity"]: r["value"] for r in json.loads(out)["static"]}
    return f"backward error {rows['backward error of the solve']}, deflection bound {rows['deflection error bound']}"


def map_check(out):
    d = json.loads(out)
    worst = max(r["backward_error"] for r in d["critical_map"])
    return f"{len(d['critical_map'])} critical speeds, largest backward error {worst:.1e}"


def pervasive_check(out):
    d = json.loads(out)
    rows = {r["quantity"]: r["value"] for r in d["pervasive_summary"]}
    return f"{rows['modes checked']}; {len(d['pervasive_damping'])} losses"


def rows_check(what):
    return lambda out: f"{len(json.loads(out))} {what}"


# (analysis, arguments after the scene, check of the JSON output)
CASES = [
    ("Campbell diagram (baseline)", ["campbell", "--format", "json"], rows_check("rows, each pair verified")),
    ("critical speeds, API 684 AF", ["critical", "--format", "json"], rows_check("critical speeds")),
    ("stability", ["stability", "--format", "json"], rows_check("stability changes")),
    ("pervasive damping (Hautus)", ["pervasive", "--format", "json"], pervasive_check),
    ("unbalance response", ["response", "--format", "json"], rows_check("rows (speed x DOF)")),
    ("static deflection", ["static", "--format", "json"], static_check),
    ("critical speed map", ["critical-map", "--format", "json"], map_check),
    ("FRF, 151 frequencies", ["frf", "--input", "y12", "--speed", "600", "--format", "json"],
     rows_check("rows; residual of each solve <= 1e-8")),
    ("transient, 1 s at 600 rad/s", ["transient", "--speed", "600", "--duration", "1", "--format", "json"],
     rows_check("envelope rows")),
    ("transient, run-up 0-15000 rpm at 3000 rpm/s", ["transient", "--run-up", "0:15000", "--acceleration", "3000",
                                                     "--units", "rpm", "--format", "json"],
     rows_check("envelope rows")),
]


def timed(cli, args):
    t0 = time.perf_counter()
    run = subprocess.run([cli, args[0], SCENE, *args[1:]], capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if run.returncode != 0:
        sys.exit(f"gyrokit {' '.join(args)} failed: {run.stderr.strip()}")
    return dt, run.stdout


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--cli", required=True)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
    runs = 1 if a.quick else a.runs
    results = []
    for name, args, check in CASES:
        best, out = min((timed(a.cli, args) for _ in range(runs)), key=lambda r: r[0])
        results.append((name, "gyrokit " + " ".join(x for x in args if x not in ("--format", "json")), best,
                        check(out)))
    base = results[0][2]
    print(f"{os.path.relpath(SCENE, ROOT)} (100 DOFs), best of {runs} run(s), one process each (2 cores)\n")
    print("| analysis | command | wall s | vs campbell | what the output vouches |")
    print("|---|---|---:|---:|---|")
    for name, cmd, t, check in results:
        print(f"| {name} | `{cmd}` | {t:.3f} | {t / base:.3f} | {check} |")


if __name__ == "__main__":
    main()
