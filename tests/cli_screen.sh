#!/usr/bin/env bash
# gyrokit screen: bad sweep files give one line and exit status 2; shards merge
# to the unsharded table; a killed run resumes to the same file.
set -u
cli=$1
data=$(cd "$2" && pwd)
source "$(dirname "$0")/cli_lib.sh"


sweep() {   # sweep NAME PARAMETER-LINES [EXTRA]
    cat > "$dir/$1.toml" <<END
scene = "$data/centrifuge.toml"
$2
[operating]
from = 25.0
to = 35.0
count = 11
[criteria.pervasive]
damping = ["total"]
${3:-}
END
}

good='[[parameter]]
name = "model.c_R"
values = [50.0, 60.0, 74.1333, 90.0, 100.0]
[[parameter]]
name = "model.d_G"
from = 1.0
to = 4.0
count = 4'

sweep ok "$good"
sweep unknown '[[parameter]]
name = "model.c_X"
values = [1.0]'
sweep empty '[[parameter]]
name = "model.c_R"
from = 70.0
to = 60.0
count = 3'
sweep emptyvalues '[[parameter]]
name = "model.c_R"
values = []'
sweep notmodel '[[parameter]]
name = "speeds.to"
values = [1.0]'
sweep balancer "$good" '[criteria.balancer]
limit_speed_ratio = 1.2'
sweep dofs "$good" '[criteria.response]
max_amplitude = 1e-3
dofs = ["z"]'
sweep lhsvalues '[sampling]
method = "lhs"
samples = 10
[[parameter]]
name = "model.c_R"
values = [1.0]'
sweep probeunits "$good" '[criteria.response]
max_amplitude = 1e-3
probes = [{ name = "P", dof_x = "x", dof_y = "psi", angle = 45.0 }]'
sweep probenode "$good" '[criteria.response]
max_amplitude = 1e-3
probes = [{ name = "P", node = 1, angle = 45.0 }]'
sweep logdec "$good" '[criteria.stability]
min_log_dec = -0.1'
printf 'scene = "%s/centrifuge.toml"\n[operating]\nfrom = 1.0\nto = 2.0\n' "$data" > "$dir/nocrit.toml"
sed 's/eps = 1.0e-3/eps = 0.0/' "$data/centrifuge.toml" > "$dir/nounbalance_scene.toml"
printf 'scene = "nounbalance_scene.toml"\n[operating]\nfrom = 1.0\nto = 2.0\n[criteria.response]\nmax_amplitude = 1.0\n' > "$dir/nounbalance.toml"

expect "unknown key 'c_X'" screen "$dir/unknown.toml"
expect "empty range" screen "$dir/empty.toml"
expect "is empty" screen "$dir/emptyvalues.toml"
expect "a path to a numeric value of the scene's [model]" screen "$dir/notmodel.toml"
# Paths into the elements of an FE rotor: what exists is named.
for bad in 'model.bearing[7].kxx|model.bearing has 2 entries; allowed: model.bearing[0] to model.bearing[1], or model.bearing[*]' \
           'model.material|model.material is not a number in the scene' \
           'model.shaft[2].length|[model.shaft[2]] length = -1: out of range'; do
    printf 'scene = "%s/three_disk_rotor.toml"\n[[parameter]]\nname = "%s"\nvalues = [-1.0]\n[operating]\nfrom = 100.0\nto = 200.0\n[criteria.stability]\nup_to = 300.0\n' \
        "$data" "${bad%%|*}" > "$dir/path.toml"
    expect "${bad#*|}" screen "$dir/path.toml"
done
expect "no balancer model in scene" screen "$dir/balancer.toml"
expect "'z' is not a DOF" screen "$dir/dofs.toml"
expect "needs from and to" screen "$dir/lhsvalues.toml"
expect "[criteria.response.probes[0]] dof_x = 'x' (m) and dof_y = 'psi' (rad): allowed: two DOFs of one unit" \
    screen "$dir/probeunits.toml"
expect "[criteria.response.probes[0]] node = 1: the model has no nodes on an axis" screen "$dir/probenode.toml"
expect "[criteria.stability] min_log_dec = -0.1: out of range; allowed: > 0" screen "$dir/logdec.toml"
expect "no criteria" screen "$dir/nocrit.toml"
expect "needs an unbalance" screen "$dir/nounbalance.toml"
expect "sweep file not found" screen "$dir/missing.toml"
expect "--shard '3/3'" screen "$dir/ok.toml" --shard 3/3
expect "--jobs -1" screen "$dir/ok.toml" --jobs -1
expect "allowed values: table, csv, json" screen "$dir/ok.toml" --format xml
expect "unsupported extension" screen "$dir/ok.toml" --plot "$dir/x.pdf"
printf 'design,foo\n' > "$dir/foreign.csv"
expect "no study identity on the first line" screen "$dir/ok.toml" --resume "$dir/foreign.csv"

# Unsharded, sharded and merged, resumed after a kill: the same file.
"$cli" screen "$dir/ok.toml" --jobs 1 --out "$dir/all.csv" 2> /dev/null || { echo "FAIL: unsharded run"; fail=1; }
[ "$(wc -l < "$dir/all.csv")" -eq 22 ] || { echo "FAIL: expected the identity, the header and 20 rows"; fail=1; }
for k in 0 1 2; do
    "$cli" screen "$dir/ok.toml" --shard "$k/3" --jobs 2 --out "$dir/s$k.csv" 2> /dev/null || { echo "FAIL: shard $k"; fail=1; }
done
"$cli" screen "$dir/ok.toml" --merge "$dir/s0.csv" "$dir/s1.csv" "$dir/s2.csv" --out "$dir/merged.csv" 2> /dev/null
cmp -s "$dir/all.csv" "$dir/merged.csv" || { echo "FAIL: merged shards differ from the unsharded run"; fail=1; }
# The same by plain concatenation, as a job array would do it.
{ head -n 2 "$dir/s0.csv"; tail -q -n +3 "$dir/s0.csv" "$dir/s1.csv" "$dir/s2.csv" | sort -t, -k1,1n; } > "$dir/cat.csv"
cmp -s "$dir/all.csv" "$dir/cat.csv" || { echo "FAIL: concatenated shards differ from the unsharded run"; fail=1; }

"$cli" screen "$dir/ok.toml" --jobs 1 --resume "$dir/resumed.csv" 2> /dev/null &
pid=$!
for _ in $(seq 1 400); do
    [ -f "$dir/resumed.csv" ] && [ "$(wc -l < "$dir/resumed.csv")" -ge 4 ] && break
    sleep 0.01
done
kill -KILL "$pid" 2> /dev/null
wait "$pid" 2> /dev/null
printf '17,90,3' >> "$dir/resumed.csv"   # a row cut short
"$cli" screen "$dir/ok.toml" --jobs 2 --resume "$dir/resumed.csv" 2> /dev/null || { echo "FAIL: resume"; fail=1; }
cmp -s "$dir/all.csv" "$dir/resumed.csv" || { echo "FAIL: resumed file differs from the uninterrupted run"; fail=1; }

# An output that is one of the run's inputs is refused, and the input is left whole.
cp "$dir/ok.toml" "$dir/keep.toml"
expect "that file is an input of this run" screen "$dir/ok.toml" --out "$dir/ok.toml"
cmp -s "$dir/ok.toml" "$dir/keep.toml" || { echo "FAIL: --out on the sweep file changed it"; fail=1; }
cp "$data/centrifuge.toml" "$dir/scene_copy.toml"
sed "s|$data/centrifuge.toml|$dir/scene_copy.toml|" "$dir/ok.toml" > "$dir/own_scene.toml"
expect "that file is an input of this run" screen "$dir/own_scene.toml" --out "$dir/scene_copy.toml"
cmp -s "$data/centrifuge.toml" "$dir/scene_copy.toml" || { echo "FAIL: --out on the base scene changed it"; fail=1; }
expect "that file is an input of this run" screen "$dir/ok.toml" --merge "$dir/s0.csv" "$dir/s1.csv" --out "$dir/s1.csv"
expect "that file is an input of this run" screen "$dir/ok.toml" --resume "$dir/./ok.toml"

# A second writer of a result file another run holds (the same flock as a run
# takes, here held by flock(1)) is refused, and the file is left as it was.
cp "$dir/all.csv" "$dir/held.csv"
flock -x "$dir/held.csv" -c "touch '$dir/ready'; while [ ! -f '$dir/release' ]; do sleep 0.05; done" &
holder=$!
for _ in $(seq 1 500); do [ -f "$dir/ready" ] && break; sleep 0.01; done
expect "another run is writing this result file" screen "$dir/ok.toml" --jobs 1 --resume "$dir/held.csv"
expect "another run is writing this result file" screen "$dir/ok.toml" --jobs 1 --out "$dir/held.csv"
expect "another run is writing this result file" screen "$dir/ok.toml" --merge "$dir/s0.csv" "$dir/s1.csv" "$dir/s2.csv" --out "$dir/held.csv"
touch "$dir/release"
wait "$holder" 2> /dev/null
cmp -s "$dir/all.csv" "$dir/held.csv" || { echo "FAIL: a refused writer changed the held file"; fail=1; }

expect "/dev/zero: is not a regular file" screen "$dir/ok.toml" --merge /dev/zero
expect "is a directory" screen "$dir/ok.toml" --merge "$dir"

# A 1e8-design grid with --limit 2 costs two designs, not memory per design (1.8 GB before).
sed -e 's/^count = 4$/count = 10000/' -e 's/^values = \[50.0, 60.0, 74.1333, 90.0, 100.0\]$/from = 50.0\nto = 100.0\ncount = 10000/' "$dir/ok.toml" > "$dir/huge.toml"
grep -q "count = 10000" "$dir/huge.toml" || { echo "FAIL: could not write the 1e8-design sweep"; fail=1; }
peak_kb=$(python3 -c 'import resource, subprocess, sys
subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)' "$cli" screen "$dir/huge.toml" --limit 2 --jobs 2 --out "$dir/huge.csv") ||
    { echo "FAIL: the 1e8-design sweep with --limit 2"; fail=1; peak_kb=0; }
[ "$(wc -l < "$dir/huge.csv")" -eq 4 ] || { echo "FAIL: --limit 2 wrote $(wc -l < "$dir/huge.csv") lines"; fail=1; }
[ "$peak_kb" -lt 500000 ] || { echo "FAIL: the 1e8-design sweep with --limit 2 peaked at $peak_kb KB"; fail=1; }

# A result file of another study (the base scene or a criterion changed since) is refused by
# --resume and --merge: its rows are not this study's answers.
cp "$data/centrifuge.toml" "$dir/study_scene.toml"
sed "s|$data/centrifuge.toml|$dir/study_scene.toml|" "$dir/ok.toml" > "$dir/study.toml"
"$cli" screen "$dir/study.toml" --jobs 2 --limit 5 --resume "$dir/study.csv" 2> /dev/null || { echo "FAIL: study run"; fail=1; }
head -n 1 "$dir/study.csv" | grep -q "^# study [0-9a-f]\{16\} " || { echo "FAIL: no study identity line"; fail=1; }
sed -i 's/^eps = 1.0e-3/eps = 2.0e-3/' "$dir/study_scene.toml"
grep -q "eps = 2.0e-3" "$dir/study_scene.toml" || { echo "FAIL: could not change the scene"; fail=1; }
expect "written by another study" screen "$dir/study.toml" --resume "$dir/study.csv"
expect "written by another study" screen "$dir/study.toml" --merge "$dir/study.csv"
cp "$data/centrifuge.toml" "$dir/study_scene.toml"
"$cli" screen "$dir/study.toml" --jobs 2 --resume "$dir/study.csv" 2> /dev/null || { echo "FAIL: the study resumed on its own scene"; fail=1; }
printf '[criteria.stability]\nup_to = 30.0\n' >> "$dir/study.toml"
expect "written by another study" screen "$dir/study.toml" --resume "$dir/study.csv"
# A stability margin set since is another study too.
"$cli" screen "$dir/study.toml" --jobs 2 --limit 2 --resume "$dir/margin.csv" 2> /dev/null || { echo "FAIL: margin study run"; fail=1; }
printf 'min_log_dec = 0.1\n' >> "$dir/study.toml"
expect "written by another study" screen "$dir/study.toml" --resume "$dir/margin.csv"

# A file the base scene names (a bearing table) is part of the study: edited, the old rows are refused.
mkdir -p "$dir/tabled/bearings"
cp "$data/fe_rotor.toml" "$dir/tabled/rotor.toml"
cp "$data"/bearings/*.csv "$dir/tabled/bearings/"
cat > "$dir/tabled/sweep.toml" <<END
scene = "rotor.toml"
[[parameter]]
name = "model.E"
values = [2.0e11, 2.1e11]
[operating]
from = 100.0
to = 200.0
count = 3
[criteria.separation]
margin_percent = 10.0
END
"$cli" screen "$dir/tabled/sweep.toml" --limit 1 --out "$dir/tabled/r.csv" > /dev/null 2>&1 || { echo "FAIL: tabled study run"; fail=1; }
# The same study run from its own folder (the table's path as written, not as resolved, counts).
cp "$dir/tabled/r.csv" "$dir/tabled/r2.csv"
cli_abs=$(cd "$(dirname "$cli")" && pwd)/$(basename "$cli")
(cd "$dir/tabled" && "$cli_abs" screen sweep.toml --resume r2.csv > /dev/null 2>&1) ||
    { echo "FAIL: the tabled study resumed from its own folder"; fail=1; }
sed -i '3s/^0,/0.0,/' "$dir/tabled/bearings/drive_end.csv"   # the same numbers, other bytes
expect "written by another study" screen "$dir/tabled/sweep.toml" --resume "$dir/tabled/r.csv"

# JSON on stdout: no NaN, one object per design.
"$cli" screen "$dir/ok.toml" --format json > "$dir/out.json" 2> /dev/null || { echo "FAIL: json run"; fail=1; }
if grep -qi 'nan' "$dir/out.json"; then echo "FAIL: NaN in JSON"; fail=1; fi
[ "$(grep -c '"design"' "$dir/out.json")" -eq 20 ] || { echo "FAIL: JSON rows"; fail=1; }

# Probes: the probe column is text, null in JSON where a design has none (an error row).
sweep probejson '[[parameter]]
name = "model.c_R"
values = [-5.0, 74.1333]' '[criteria.response]
max_amplitude = 1e-2
probes = [{ name = "rotor NE", dof_x = "x", dof_y = "y", angle = 45.0 }]'
"$cli" screen "$dir/probejson.toml" --format json > "$dir/probes.json" 2> /dev/null || { echo "FAIL: probes json run"; fail=1; }
grep -q '"max_amplitude_probe": null' "$dir/probes.json" || { echo "FAIL: no null probe in the error row"; fail=1; }
grep -q '"max_amplitude_probe": "rotor NE"' "$dir/probes.json" || { echo "FAIL: the probe is not named"; fail=1; }

exit $fail
