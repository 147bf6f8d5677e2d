"""Design screening from Python against `gyrokit screen`: 1,000 centrifuge designs (a 40 x 25
grid of cage stiffness c_G and cage damping d_G, the criteria of data/screen_centrifuge.toml).

Rows: the CLI on 1 and all cores; gyrokit.screen on the sweep file and on the same designs as a
list of dicts (all cores); a plain Python loop calling gyrokit.screen once per design (one core).
Columns: wall time, time per design, ratio to the CLI on the same cores, and whether every
verdict equals the CLI's. The loop's overhead per design is its time per design minus that of
one gk.screen call of all designs on one core (the same process, the same work).

    PYTHONPATH=build/python /usr/bin/python3 apps/bench/bench_screen_python.py --cli build/apps/gyrokit [--designs 1000]
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile
import time

import gyrokit as gk


def sweep_file(directory, data, n_c, n_d):
    base = open(os.path.join(data, "screen_centrifuge.toml")).read()
    base = base.replace('scene = "centrifuge.toml"', f'scene = "{os.path.join(data, "centrifuge.toml")}"')
    base = base.replace("from = 150.0\nto = 600.0\ncount = 6", f"from = 150.0\nto = 600.0\ncount = {n_c}")
    base = base.replace("values = [0.0, 1.0, 4.0, 10.0]", f"from = 0.0\nto = 10.0\ncount = {n_d}")
    path = os.path.join(directory, "family.toml")
    open(path, "w").write(base)
    return path


def timed(f):
    t = time.perf_counter()
    out = f()
    return time.perf_counter() - t, out


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cli", required=True)
    p.add_argument("--data", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data"))
    p.add_argument("--designs", type=int, default=1000, help="40 x 25 = 1000 by default; any multiple of 25")
    a = p.parse_args()
    cores = os.cpu_count() or 1
    n_d = 25
    n_c = max(1, a.designs // n_d)
    with tempfile.TemporaryDirectory() as d:
        path = sweep_file(d, os.path.abspath(a.data), n_c, n_d)

        def cli(jobs):
            out = subprocess.run([a.cli, "screen", path, "--jobs", str(jobs), "--format", "csv"], check=True,
                                 capture_output=True, text=True).stdout
            return [r["verdict"] for r in csv.DictReader(io.StringIO(out))], list(csv.DictReader(io.StringIO(out)))

        t_cli1, (v_cli, rows) = timed(lambda: cli(1))
        t_clin, _ = timed(lambda: cli(cores))
        n = len(v_cli)
        designs = [{"model.c_G": float(r["model.c_G"]), "model.d_G": float(r["model.d_G"])} for r in rows]
        t_file, r_file = timed(lambda: gk.screen(path, jobs=cores))
        t_list, r_list = timed(lambda: gk.screen(path, designs, jobs=cores))
        t_list1, r_list1 = timed(lambda: gk.screen(path, designs, jobs=1))

        def loop():
            return [gk.screen(path, [x], jobs=1).verdict[0] for x in designs]

        t_loop, v_loop = timed(loop)
    table = [
        ("gyrokit screen (CLI)", 1, t_cli1, t_cli1, True),
        ("gyrokit screen (CLI)", cores, t_clin, t_clin, True),
        ("gk.screen(sweep file)", cores, t_file, t_clin, r_file.verdict == v_cli),
        ("gk.screen(list of dicts)", cores, t_list, t_clin, r_list.verdict == v_cli),
        ("gk.screen(list of dicts)", 1, t_list1, t_cli1, r_list1.verdict == v_cli),
        ("Python loop, gk.screen per design", 1, t_loop, t_cli1, v_loop == v_cli),
    ]
    print(f"Screening {n} centrifuge designs (criteria of data/screen_centrifuge.toml), {cores} cores")
    print(f"{'call':36s} {'cores':>5s} {'seconds':>9s} {'ms/design':>10s} {'vs CLI':>7s}  same verdicts")
    for name, c, t, ref, same in table:
        print(f"{name:36s} {c:5d} {t:9.3f} {1e3 * t / n:10.3f} {t / ref:7.2f}  {'yes' if same else 'NO'}")
    print(f"loop overhead per design: {1e3 * (t_loop - t_list1) / n:.3f} ms (the loop minus one gk.screen call of all "
          f"designs on one core)")
    return 0 if all(row[4] for row in table) else 1


if __name__ == "__main__":
    sys.exit(main())
