#!/usr/bin/env bash
# The large-model options of eig/campbell/critical/stability/response (--solver,
# --target, --modes, --lanczos, --dofs) on the finite-element scene with
# speed-dependent bearing tables, and their bad input: exit status 2 and one line;
# the Campbell diagram of the published example data/friswell_5_9_1.toml.
set -u
cli=$1
data=$2
source "$(dirname "$0")/cli_lib.sh"

run() {   # run ARGS...: must succeed
    if ! "$cli" "$@" > "$dir/out" 2> "$dir/err"; then
        echo "FAIL: gyrokit $* -> exit $?"; sed 's/^/    /' "$dir/err"; fail=1
    fi
}

# Sparse and dense Campbell diagrams of the same scene: the four lowest branches agree.
run campbell "$data/fe_rotor.toml" --solver dense --modes 4 --speeds 0:2000:11 --format csv
cp "$dir/out" "$dir/dense.csv"
run campbell "$data/fe_rotor.toml" --solver sparse --modes 6 --speeds 0:2000:11 --format csv --jobs 2
awk -F, 'NR == FNR { if (FNR > 1) d[$1 "," $2] = $4; next }
         FNR > 1 && ($1 "," $2) in d { n++; r = ($4 - d[$1 "," $2]) / d[$1 "," $2]; if (r < 0) r = -r;
                                       if (r > 1e-9) { print "FAIL: sparse vs dense at " $1 " mode " $2; bad = 1 } }
         END { if (n < 40) { print "FAIL: only " n " common points"; bad = 1 } exit bad }' \
    "$dir/dense.csv" "$dir/out" || fail=1

# Modes near a target frequency: the two nearest 450 rad/s.
run eig "$data/fe_rotor.toml" --speed 0 --solver sparse --target 450 --modes 2 --format csv
awk -F, 'NR > 1 { if ($4 < 440 || $4 > 470) bad = 1; n++ } END { exit (bad || n != 2) }' "$dir/out" \
    || { echo "FAIL: eig --target 450 --modes 2"; cat "$dir/out"; fail=1; }

# Response of two named DOFs through the sparse LU; critical speeds from sparse branches.
run response "$data/fe_rotor.toml" --solver sparse --dofs x8,y8 --speeds 100:1000:10 --format csv
[ "$(tail -n +2 "$dir/out" | wc -l)" -eq 20 ] || { echo "FAIL: response --dofs x8,y8 rows"; fail=1; }
run critical "$data/fe_rotor.toml" --solver sparse --modes 4 --speeds 0:1000:21 --format csv
grep -q '^1[0-9][0-9]\.' "$dir/out" || { echo "FAIL: sparse critical speeds"; cat "$dir/out"; fail=1; }
# Bearing tables cover 0..4000 rad/s: a wider range is reported, not refused.
run campbell "$data/fe_rotor.toml" --solver sparse --speeds 0:5000:3 --format csv
grep -q "held constant" "$dir/err" || { echo "FAIL: extrapolation not reported"; fail=1; }
# ... and at one speed (eig, modes, export) as well.
run eig "$data/fe_rotor.toml" --solver sparse --modes 2 --speed 5000
grep -q "the speed 5000 rad/s outside it uses its end row (held constant)" "$dir/err" ||
    { echo "FAIL: extrapolation at one speed not reported"; cat "$dir/err"; fail=1; }

# The published example (Friswell et al., Example 5.9.1): the Campbell diagram of the
# scene at 4000 rev/min gives the six published frequencies (rad/s, 8 decimals) within
# 1e-9 relative, lower of each pair backward, upper forward.
run campbell "$data/friswell_5_9_1.toml" --format csv
awk -F, 'BEGIN { split("85.389467 87.7958637 251.78460413 294.71333087 600.17936195 827.07536193", p, " ") }
         NR > 1 && $1 > 418.879 { n++; r = ($5 - p[$2]) / p[$2]; if (r < 0) r = -r
                                  w = ($2 % 2 == 1) ? "backward" : "forward"
                                  if (r > 1e-9 || $6 != w) { print "FAIL: friswell_5_9_1 mode " $2 ": " $5 " " $6; bad = 1 } }
         END { if (n != 6) { print "FAIL: friswell_5_9_1: " n " modes at 4000 rev/min"; bad = 1 } exit bad }' \
    "$dir/out" || fail=1
run campbell "$data/friswell_5_9_1.toml" --units rpm --plot "$dir/friswell.svg"
grep -q "<svg" "$dir/friswell.svg" || { echo "FAIL: friswell_5_9_1 Campbell plot"; fail=1; }

# Bad options.
expect "--solver 'fast': allowed: auto, dense, sparse" campbell "$data/fe_rotor.toml" --solver fast
expect "--lanczos -1" eig "$data/fe_rotor.toml" --speed 0 --lanczos -1
# The library names its option fields structurally; the command line writes its flags.
expect "--lanczos 3: must exceed 2 * modes + 3" eig "$data/fe_rotor.toml" --speed 0 --solver sparse --lanczos 3 --modes 6
expect "--motion 'sideways': allowed: lateral, all, axial, torsional" eig "$data/fe_rotor.toml" --speed 0 --motion sideways
expect "--motion 'all' does not apply to" eig "$data/centrifuge.toml" --speed 0 --motion all
# One parallelism rule: more jobs than cores are capped, with a note.
"$cli" campbell "$data/fe_rotor.toml" --jobs 100000 --speeds 0:100:3 2>&1 >/dev/null | grep -q "^note: --jobs 100000 capped to the" ||
    { echo "FAIL: campbell --jobs 100000 without the note on the cap"; fail=1; }
"$cli" screen "$data/screen_centrifuge.toml" --jobs 100000 --limit 1 --out "$dir/capped.csv" 2>&1 >/dev/null | grep -q "^note: --jobs 100000 capped to the" ||
    { echo "FAIL: screen --jobs 100000 without the note on the cap"; fail=1; }
expect "--dofs 'x99': 'x99' is not a DOF" response "$data/fe_rotor.toml" --dofs x99 --speeds 1:2:2

# Bearing tables: one speed, unsorted speeds, a DOF index out of range.
mkdir -p "$dir/b"
fe() {   # fe NAME TABLE-BODY: a scene whose first bearing uses the table
    printf 'speed,dof_x,dof_y,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy\n%b' "$2" > "$dir/b/$1.csv"
    sed "s#bearings/drive_end.csv#$dir/b/$1.csv#; s#bearings/non_drive_end.csv#$data/bearings/non_drive_end.csv#" \
        "$data/fe_rotor.toml" > "$dir/b/$1.toml"
}
fe one '0,0,1,1e7,0,0,1e7,0,0,0,0\n'
expect "1 speed row(s); allowed: at least 2" eig "$dir/b/one.toml" --speed 0
fe unsorted '0,0,1,1e7,0,0,1e7,0,0,0,0\n500,0,1,1e7,0,0,1e7,0,0,0,0\n400,0,1,1e7,0,0,1e7,0,0,0,0\n'
expect "speed 400 does not exceed the previous 500" eig "$dir/b/unsorted.toml" --speed 0
# A matrices scene: its tables name DOFs by index.
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 1\n' > "$dir/b/M.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 100\n2 2 100\n' > "$dir/b/K.mtx"
printf 'speed,dof_x,dof_y,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy\n0,0,2,1,0,0,1,0,0,0,0\n9,0,2,1,0,0,1,0,0,0,0\n' \
    > "$dir/b/range.csv"
printf '[model]\ntype = "matrices"\nM = "M.mtx"\nK = "K.mtx"\nbearings = ["range.csv"]\n' > "$dir/b/mat.toml"
expect "dof_y = 2 is out of range; allowed: a whole number from 0 to 1" eig "$dir/b/mat.toml" --speed 0
# A shift that is an eigenvalue: the free-free shaft has lambda = 0; the shift is moved and the move reported.
printf '[model]\ntype = "fe_rotor"\nE = 2e11\ndensity = 7800\n[[model.shaft]]\nlength = 1\nelements = 4\nouter_diameter = 0.05\n' \
    > "$dir/b/free.toml"
run eig "$dir/b/free.toml" --speed 0 --solver sparse --modes 2
grep -q "was moved" "$dir/err" && grep -q "rigid-body" "$dir/err" \
    || { echo "FAIL: free-free sparse eig: no note of the moved shift and the rigid-body modes"; cat "$dir/err"; fail=1; }
# Above the dense limit: the dense solver and the dense-only direct critical-speed method refuse
# (pervasive, export and screening run sparse: cli_sparse_models.sh).
printf '[model]\ntype = "fe_rotor"\nE = 2e11\ndensity = 7800\n[[model.shaft]]\nlength = 8\nelements = 800\nouter_diameter = 0.05\n[[model.bearing]]\nz = 0\nk = 1e8\n[[model.bearing]]\nz = 8\nk = 1e8\n' \
    > "$dir/b/large.toml"
expect "above the dense limit of 3000" eig "$dir/b/large.toml" --speed 0 --solver dense
expect "gyrokit critical --critical-method direct needs the dense model" critical "$dir/b/large.toml" --speeds 0:10:2 --critical-method direct
run eig "$dir/b/large.toml" --speed 100 --modes 3 --format csv
[ "$(tail -n +2 "$dir/out" | wc -l)" -eq 3 ] || { echo "FAIL: auto solver on 3204 DOFs"; fail=1; }
exit $fail
