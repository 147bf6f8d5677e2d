#!/usr/bin/env python3
"""Every command's CSV is one table and its JSON uses stable snake_case keys.

For each command (and each table it can select), `--format csv` is read with
Python's csv module: one header, every row as long as the header, no blank line,
at least one row; `--format json` is parsed and every key (table keys, column
names) must be a snake_case identifier (screening's parameter columns keep the
scene key paths the sweep names, e.g. model.c_G). Usage: cli_one_table.py GYROKIT DATA_DIR
"""
import csv
import io
import json
import os
import re
import subprocess
import sys
import tempfile

gyrokit, data = sys.argv[1], os.path.abspath(sys.argv[2])
snake = re.compile(r"^[a-z][a-z0-9_]*$")
failures = []
# Screening columns named after the sweep's parameters keep the scene's key paths.
parameters = {"model.c_G", "model.d_G"}


def run(args):
    p = subprocess.run([gyrokit] + args, capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        failures.append(f"{' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
        return None
    return p.stdout


def check_csv(args):
    out = run(args + ["--format", "csv"])
    if out is None:
        return
    rows = list(csv.reader(io.StringIO(out)))
    where = " ".join(args)
    if len(rows) < 2:
        failures.append(f"{where}: CSV has no data row")
        return
    header = rows[0]
    if not all(snake.match(h) or h in parameters for h in header):
        failures.append(f"{where}: CSV header not snake_case: {header}")
    for i, r in enumerate(rows[1:], start=2):
        if len(r) != len(header):
            failures.append(f"{where}: CSV line {i} has {len(r)} fields, the header {len(header)}: {r}")
            return


def check_keys(value, where):
    if isinstance(value, dict):
        for k, v in value.items():
            if not snake.match(k) and k not in parameters:
                failures.append(f"{where}: JSON key {k!r} is not snake_case")
                return
            check_keys(v, where)
    elif isinstance(value, list):
        for v in value[:3]:
            check_keys(v, where)


def check_json(args):
    out = run(args + ["--format", "json"])
    if out is None:
        return
    try:
        check_keys(json.loads(out), " ".join(args))
    except json.JSONDecodeError as e:
        failures.append(f"{' '.join(args)}: JSON does not parse: {e}")


tmp = tempfile.mkdtemp()
sweep = os.path.join(tmp, "sweep.toml")
with open(os.path.join(data, "screen_centrifuge.toml")) as f:
    text = f.read()
with open(sweep, "w") as f:
    f.write(re.sub(r'^scene = "(.*)"', lambda m: f'scene = "{os.path.join(data, m.group(1))}"', text, flags=re.M))

c, fe = f"{data}/centrifuge.toml", f"{data}/fe_rotor.toml"
cases = [
    ["eig", c, "--speed", "20"],
    ["model", c],
    ["model", fe],
    ["modes", c, "--speed", "100"],
    ["modes", fe, "--speed", "100", "--modes", "2"],
    ["modes", c, "--speed", "100", "--per", "dof"],
    ["campbell", c, "--speeds", "0:100:11"],
    ["critical", c],
    ["stability", f"{data}/../docs/examples/circ.toml", "--speeds", "0:1000:201"],
    ["pervasive", c, "--speeds", "0:50:6"],
    ["response", c, "--speeds", "0:30:4"],
    ["response", c, "--extrema"],
    ["fluid", f"{data}/fluid_N1.toml"],
    ["fluid", f"{data}/fluid_N1.toml", "--table", "sloshing_modes"],
    ["fluid", f"{data}/fluid_N1.toml", "--table", "liquid"],
    ["fluid", f"{data}/fluid_N1.toml", "--fill", "0.05:0.08:3"],
    ["balancer", f"{data}/balancer_table1.toml"],
    ["balancer", f"{data}/balancer_table1.toml", "--table", "balancing_ranges"],
    ["sommerfeld", f"{data}/sommerfeld_rotor.toml", "--table", "summary"],
    ["balancer", f"{data}/balancer_bild7.toml", "--simulate", "--duration", "2"],
    ["balancer", f"{data}/balancer_bild7.toml", "--simulate", "--duration", "2", "--history"],
    ["balancer", f"{data}/balancer_bild7.toml", "--simulate", "--duration", "2", "--history", "--table", "final_state"],
    ["sommerfeld", f"{data}/sommerfeld_rotor.toml"],
    ["sommerfeld", f"{data}/sommerfeld_rotor.toml", "--table", "folds"],
    ["sommerfeld", f"{data}/sommerfeld_rotor.toml", "--table", "summary"],
    ["screen", sweep, "--limit", "4"],
    ["transient", fe, "--speed", "300", "--duration", "0.05"],
    ["transient", fe, "--run-up", "100:300", "--acceleration", "2000"],
]
for case in cases:
    check_csv(case)
    check_json(case)
for f in failures:
    print("FAIL:", f)
print(f"{len(cases)} commands, {len(failures)} failures")
sys.exit(1 if failures else 0)
