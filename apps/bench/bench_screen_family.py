"""Screening a family of finite-element rotors: data/screen_three_disk.toml, bearing support
stiffness (a tied parameter: both bearings, kxx and kyy) x mid-section diameter, 3 x 3 designs of
data/three_disk_rotor.toml (100 DOFs), API 684 separation and stability.

Rows: `gyrokit screen` on 1 and 2 jobs; gyrokit.screen with threads; on a process pool; on a Dask
LocalCluster of two worker processes (if python3-distributed is installed). Columns: wall time,
time per design, ratio to the CLI on 2 jobs, and whether every row (verdict, reason, quantities)
equals the CLI's to the last printed digit (every run, the Python module included: the same numbers).
It exits 1 if one does not.

    PYTHONPATH=build/python /usr/bin/python3 apps/bench/bench_screen_family.py --cli build/apps/gyrokit [--quick]
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import gyrokit as gk


def timed(f):
    t = time.perf_counter()
    out = f()
    return time.perf_counter() - t, out


def cli_rows(cli, sweep, jobs):
    out = subprocess.run([cli, "screen", sweep, "--jobs", str(jobs), "--format", "csv"], check=True,
                         capture_output=True, text=True).stdout
    return [r for r in csv.reader(io.StringIO(out)) if r and not r[0].startswith("#")][1:]


def py_rows(r):
    return [(r.verdict[k], r.reason[k], tuple(float(v[k]) for v in r.quantities.values()))
            for k in range(len(r.verdict))]


def as_cli(rows, n_params, quantities):
    out = []
    for row in rows:
        q = tuple(float(x) if x != "" else float("nan") for x in row[1 + n_params:1 + n_params + quantities])
        out.append((row[1 + n_params + quantities], row[-1], q))
    return out


def same(a, b, rel=0.0):
    """Verdicts and reasons equal; numbers equal (rel = 0) or within `rel` relative."""
    def close(u, v):
        return (u == v) or (u != u and v != v) or abs(u - v) <= rel * max(abs(u), abs(v))
    return len(a) == len(b) and all(x[0] == y[0] and x[1] == y[1] and all(close(u, v) for u, v in zip(x[2], y[2]))
                                    for x, y in zip(a, b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data"))
    ap.add_argument("--quick", action="store_true", help="the CLI on 2 jobs and gk.screen with threads only")
    a = ap.parse_args()
    sweep = os.path.join(a.data, "screen_three_disk.toml")
    t_ref, ref = timed(lambda: cli_rows(a.cli, sweep, 2))
    n = len(ref)
    probe = gk.screen(sweep, [{"k_bearing": 1e7, "model.shaft[2].outer_diameter": 0.1}])
    n_params, n_q = len(probe.parameters), len(probe.quantities)
    reference = as_cli(ref, n_params, n_q)
    runs = [("`gyrokit screen` (CLI)", 2, t_ref, True)]
    if not a.quick:
        t, rows = timed(lambda: cli_rows(a.cli, sweep, 1))
        runs.append(("`gyrokit screen` (CLI)", 1, t, same(as_cli(rows, n_params, n_q), reference)))
    t, r = timed(lambda: gk.screen(sweep, jobs=2))
    runs.append(("`gk.screen`, threads", 2, t, same(py_rows(r), reference)))
    if not a.quick:
        with ProcessPoolExecutor(max_workers=2) as pool:
            t, r = timed(lambda: gk.screen(sweep, executor=pool))
        runs.append(("`gk.screen`, process pool", 2, t, same(py_rows(r), reference)))
        try:
            import distributed
            with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                          dashboard_address=None) as cluster, distributed.Client(cluster) as client:
                t, r = timed(lambda: gk.screen(sweep, executor=client.get_executor()))
            runs.append(("`gk.screen`, Dask LocalCluster", 2, t, same(py_rows(r), reference)))
        except ImportError:
            print("python3-distributed is not installed: no Dask row", file=sys.stderr)
    print(f"{n} designs of data/screen_three_disk.toml (100-DOF FE rotor)\n")
    print("| run | workers | wall s | s per design | ratio to CLI (2 jobs) | rows equal the CLI's |")
    print("|---|---:|---:|---:|---:|---|")
    for name, w, t, ok in runs:
        print(f"| {name} | {w} | {t:.2f} | {t / n:.2f} | {t / t_ref:.2f} | {'yes' if ok else 'NO'} |")
    return 0 if all(ok for *_, ok in runs) else 1


if __name__ == "__main__":
    sys.exit(main())
