#!/usr/bin/env bash
# Every analysis on a model above the dense limit: a finite-element rotor of
# 768 elements (3,076 DOFs) is screened, checked for pervasive damping and
# exported, and gives the verdicts, losses and critical speeds of the same
# rotor with 24 elements solved densely (and sparsely).
set -u
cli=$1
source "$(dirname "$0")/cli_lib.sh"

scene() {   # scene FILE ELEMENTS SOLVER [EXTRA BEARING LINES]
    cat > "$1" <<END
title = "FE shaft with two disks"
[model]
type = "fe_rotor"
E = 211e9
poisson = 0.3
density = 7810
[[model.shaft]]
length = 1.5
elements = $2
outer_diameter = 0.05
[[model.disk]]
z = 0.5
mass = 33.657
Id = 0.17831
Ip = 0.32985
unbalance = 1e-4
[[model.disk]]
z = 1.0
mass = 33.657
Id = 0.17831
Ip = 0.32985
[[model.bearing]]
z = 0.0
${4:-kxx = 1e7
kyy = 1.5e7
c = 400}
[[model.bearing]]
z = 1.5
${4:-kxx = 1e7
kyy = 1.5e7
c = 400}
${5:-}
[analysis]
solver = "$3"
modes = 6
END
}
sweep() {   # sweep FILE SCENE
    cat > "$1" <<END
scene = "$2"
[[parameter]]
name = "model.E"
values = [1.2e11, 2.11e11, 3e11]
[operating]
from = 150.0
to = 300.0
count = 11
[criteria.separation]
margin_percent = 15.0
whirl = "forward"
count = 61
[criteria.stability]
up_to = 600.0
count = 31
END
}

scene "$dir/small_dense.toml" 24 dense
scene "$dir/small_sparse.toml" 24 sparse
scene "$dir/large.toml" 768 auto
for s in small_dense small_sparse large; do
    sweep "$dir/sw_$s.toml" "$dir/$s.toml"
    "$cli" screen "$dir/sw_$s.toml" --jobs 2 --format csv > "$dir/$s.csv" 2> "$dir/$s.err" ||
        { echo "FAIL: screen $s"; cat "$dir/$s.err"; fail=1; }
    # design, E, verdict, failed
    cut -d, -f1,2,6,7 "$dir/$s.csv" > "$dir/$s.verdicts"
done
for s in small_sparse large; do
    cmp -s "$dir/small_dense.verdicts" "$dir/$s.verdicts" ||
        { echo "FAIL: screen verdicts of $s differ from the dense small model"; diff "$dir/small_dense.verdicts" "$dir/$s.verdicts"; fail=1; }
done
grep -q "^2,300000000000,.*,fail,separation" "$dir/large.csv" || { echo "FAIL: the stiffest design must fail separation"; fail=1; }
# The same study in other shapes: one job, three shards merged, a run cut by
# --limit and resumed. Dense: the same bytes. Sparse: the same verdicts, and
# numbers equal to 1e-9 (ARPACK restarts from its own random vectors, whose seed
# the process carries from call to call: docs/reliability.md).
for s in small_dense small_sparse; do
    "$cli" screen "$dir/sw_$s.toml" --jobs 1 --format csv 2>/dev/null | grep -v '^#' > "$dir/$s.j1.csv"
    for k in 0 1 2; do
        "$cli" screen "$dir/sw_$s.toml" --shard $k/3 --out "$dir/$s.s$k.csv" --format csv > /dev/null 2>&1
    done
    "$cli" screen "$dir/sw_$s.toml" --merge "$dir/$s.s0.csv" "$dir/$s.s1.csv" "$dir/$s.s2.csv" --format csv 2>/dev/null |
        grep -v '^#' > "$dir/$s.merged.csv"
    "$cli" screen "$dir/sw_$s.toml" --limit 1 --out "$dir/$s.part.csv" --format csv > /dev/null 2>&1
    "$cli" screen "$dir/sw_$s.toml" --resume "$dir/$s.part.csv" --format csv > /dev/null 2>&1
    grep -v '^#' "$dir/$s.part.csv" > "$dir/$s.resumed.csv"
done
for v in j1 merged resumed; do
    cmp -s "$dir/small_dense.csv" "$dir/small_dense.$v.csv" ||
        { echo "FAIL: dense screening, $v: other bytes than --jobs 2"; diff "$dir/small_dense.csv" "$dir/small_dense.$v.csv"; fail=1; }
done
python3 - "$dir" <<'PY' || fail=1
import csv, sys
d = sys.argv[1]
ref = list(csv.DictReader(open(f"{d}/small_sparse.csv")))
for v in ("j1", "merged", "resumed"):
    rows = list(csv.DictReader(open(f"{d}/small_sparse.{v}.csv")))
    if len(rows) != len(ref):
        sys.exit(f"FAIL: sparse screening, {v}: {len(rows)} rows, --jobs 2 gave {len(ref)}")
    for a, b in zip(ref, rows):
        for k in a:
            try:
                x, y = float(a[k]), float(b[k])
            except ValueError:
                if k != "reason" and a[k] != b[k]:
                    sys.exit(f"FAIL: sparse screening, {v}, design {a['design']}: {k} {b[k]} vs {a[k]}")
                continue
            if abs(x - y) > 1e-9 * max(abs(x), 1.0):
                sys.exit(f"FAIL: sparse screening, {v}, design {a['design']}: {k} {y} vs {x}")
PY
# Critical speeds of the fine mesh: within 1e-5 of the coarse one (mesh convergence,
# measured 2e-6), and the sparse and dense solvers on one mesh to 1e-8.
python3 - "$dir" <<'PY' || fail=1
import csv, sys
d = sys.argv[1]
rows = {s: list(csv.DictReader(open(f"{d}/{s}.csv"))) for s in ("small_dense", "small_sparse", "large")}
for s, tol in (("small_sparse", 1e-8), ("large", 1e-5)):
    for a, b in zip(rows["small_dense"], rows[s]):
        x, y = float(a["critical_speed_rad_s"]), float(b["critical_speed_rad_s"])
        if abs(x - y) > tol * x:
            sys.exit(f"FAIL: {s} design {a['design']}: critical speed {y} vs dense {x}")
PY

# Pervasive damping: a damper at mid-span (z = 0.75) on a symmetric rotor cannot
# reach the antisymmetric modes (a node there): lost at every speed, found alike
# on both meshes and by both solvers.
damper='[[model.bearing]]
z = 0.75
c = 400'
scene "$dir/d_dense.toml" 24 dense "k = 1e7" "$damper"
scene "$dir/d_sparse.toml" 24 sparse "k = 1e7" "$damper"
scene "$dir/d_large.toml" 768 auto "k = 1e7" "$damper"
for s in d_dense d_sparse d_large; do
    "$cli" pervasive "$dir/$s.toml" --speeds 0:600:7 --format csv > "$dir/$s.csv" 2> "$dir/$s.err" ||
        { echo "FAIL: pervasive $s"; cat "$dir/$s.err"; fail=1; }
    cut -d, -f1-3,5 "$dir/$s.csv" > "$dir/$s.losses"
done
[ "$(grep -c ',backward$\|,forward$' "$dir/d_dense.losses")" -eq 28 ] ||
    { echo "FAIL: expected 28 losses (2 modes x 7 speeds x bearings and total)"; cat "$dir/d_dense.losses"; fail=1; }
for s in d_sparse d_large; do
    cmp -s "$dir/d_dense.losses" "$dir/$s.losses" ||
        { echo "FAIL: pervasive losses of $s differ"; diff "$dir/d_dense.losses" "$dir/$s.losses"; fail=1; }
done

# Export of the large model: sparse files, no dense state matrix (a note says so).
"$cli" export "$dir/large.toml" --speed 100 --dir "$dir/mtx" 2> "$dir/export.err" ||
    { echo "FAIL: export of the large model"; cat "$dir/export.err"; fail=1; }
grep -q "state.mtx not written" "$dir/export.err" || { echo "FAIL: export gives no note on the state matrix"; fail=1; }
head -3 "$dir/mtx/M.mtx" | grep -q "^3076 3076 " || { echo "FAIL: M.mtx is not 3076 x 3076 sparse"; head -3 "$dir/mtx/M.mtx"; fail=1; }
for f in K G D C Kw pencil_A pencil_B; do
    [ -s "$dir/mtx/$f.mtx" ] || { echo "FAIL: export misses $f.mtx"; fail=1; }
done
exit $fail
