#!/usr/bin/env bash
# Bad input to the gyrokit CLI: exit status 2, exactly one line on stderr that
# names the offending key or value, nothing on stdout.
set -u
cli=$1
data=$(cd "${2:-$(dirname "$0")/../data}" && pwd)
source "$(dirname "$0")/cli_lib.sh"

good_model='type = "gyrostat"
A_G = 2.0
B_G = 2.0
A_R = 0.09
C_R = 0.1
m = 8.0
s = 0.25
eps = 1e-3
c_G = 300.0
c_T = 2000.0
c_R = 70.0'

scene() {   # scene NAME MODEL-LINES [EXTRA]
    printf '[model]\n%s\n%s\n' "$2" "${3:-}" > "$dir/$1.toml"
}


scene ok "$good_model" '[speeds]
from = 0.0
to = 40.0
count = 41'
scene missing "$(printf '%s\n' "$good_model" | grep -v '^c_T')"
scene negative "$(printf '%s\n' "$good_model" | sed 's/^m = 8.0/m = -1.0/')"
scene subnormal "$(printf '%s\n' "$good_model" | sed 's/^m = 8.0/m = 1e-310/')"
scene unknown "$good_model
c_X = 1.0"
scene badtype "$good_model
d_G = \"a lot\""
scene bothrigid "$good_model
shaft = \"rigid\"
housing = \"rigid\""
scene range "$good_model" '[speeds]
from = 50.0
to = 10.0
count = 11'
printf 'this is [not toml\n' > "$dir/syntax.toml"

printf '%%%%MatrixMarket matrix array real general\n2 3\n1\n0\n0\n1\n0\n0\n' > "$dir/M23.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n' > "$dir/M2.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1.0\n2 2 1.0\n3 3 1.0\n' > "$dir/K3.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 nan\n2 2 1.0\n' > "$dir/Knan.mtx"
printf '[model]\ntype = "matrices"\nM = "M23.mtx"\nK = "M2.mtx"\n' > "$dir/nonsquare.toml"
printf '[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "K3.mtx"\n' > "$dir/mismatch.toml"
printf '[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "Knan.mtx"\n' > "$dir/nan.toml"
printf '[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "missing.mtx"\n' > "$dir/nofile.toml"
printf '[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "M2.mtx"\n[speeds]\nfrom = 0.0\nto = 2.0\ncount = 5\n' > "$dir/nounbalance.toml"

expect "c_T" eig "$dir/missing.toml" --speed 1
expect "m = -1" eig "$dir/negative.toml" --speed 1
expect "m = 1e-310: a subnormal number" eig "$dir/subnormal.toml" --speed 1
expect "unknown key 'c_X'" eig "$dir/unknown.toml" --speed 1
expect "d_G is not a number" eig "$dir/badtype.toml" --speed 1
expect "no degree of freedom" eig "$dir/bothrigid.toml" --speed 1
expect "FROM = 50" campbell "$dir/range.toml"
expect "syntax.toml: line 1" eig "$dir/syntax.toml" --speed 1
expect "2x3" eig "$dir/nonsquare.toml" --speed 1
expect "matrix K is 3x3, expected 2x2" eig "$dir/mismatch.toml" --speed 1
expect "not a finite number" eig "$dir/nan.toml" --speed 1
expect "missing.mtx" eig "$dir/nofile.toml" --speed 1
expect "no unbalance" response "$dir/nounbalance.toml"
expect "scene file not found" eig "$dir/absent.toml" --speed 1
expect "FROM = 10 is greater than TO = 5" campbell "$dir/ok.toml" --speeds 10:5:11
expect "expected FROM:TO:N" campbell "$dir/ok.toml" --speeds 0:10
expect "did you mean '--speeds'" campbell "$dir/ok.toml" --speds 0:10:3
expect "did you mean '--units'" eig "$dir/ok.toml" --speed 1 --unit Hz
expect "did you mean 'campbell'" campbel "$dir/ok.toml"
expect "--speed '-3'" eig "$dir/ok.toml" --speed -3
expect "table format 'xml'" eig "$dir/ok.toml" --speed 1 --format xml
expect "--units" eig "$dir/ok.toml" --speed 1 --units furlong
expect "--method 'lu': allowed: auto, qz, qz-classic, state" eig "$dir/ok.toml" --speed 1 --method lu
expect "harmonics" critical "$dir/ok.toml" --harmonics 0
expect "--plot" campbell "$dir/ok.toml" --plot "$dir/x.pdf"
expect "--tolerance" pervasive "$dir/ok.toml" --tolerance 2
expect "--target-order -1: allowed" campbell "$dir/ok.toml" --solver sparse --target-order -1
expect "--target-order 'fast'" critical "$dir/ok.toml" --target-order fast
scene badorder "$good_model" '[analysis]
target_order = -0.5'
expect "target_order" eig "$dir/badorder.toml" --speed 1
scene badcut "$good_model" '[analysis]
f_cut = 0'
expect "f_cut" campbell "$dir/badcut.toml" --speeds 0:40:5
expect "--f-cut 0: allowed: a finite frequency > 0" critical "$dir/ok.toml" --f-cut 0
expect "--f-cut -5: allowed" stability "$dir/ok.toml" --f-cut -5
scene damped "$good_model
d_G = 1.0"
expect "needs an undamped system" critical "$dir/damped.toml" --speeds 0:40:41 --critical-method direct
expect "scene" eig
expect "--modes: Value -3 not in range 0 to 100000000" pervasive "$dir/ok.toml" --modes -3
expect "--modes: Value -1 not in range 0 to 100000000" response "$dir/ok.toml" --modes -1
# A mistyped command names the nearest one; an unknown one only itself.
expect "unknown command 'campbel'; did you mean 'campbell'?" campbel "$dir/ok.toml"
expect "unknown command 'xyzzy' (see --help)" xyzzy
# Conventions that succeed: --version, the command list without arguments, units in any case.
"$cli" --version | grep -qx "gyrokit [0-9.]*" || { echo "FAIL: --version"; fail=1; }
"$cli" | grep -q "campbell" || { echo "FAIL: gyrokit alone does not list the commands"; fail=1; }
"$cli" eig "$dir/ok.toml" --speed 3 --units hz | head -1 | grep -q "at 3 Hz" || { echo "FAIL: --units hz"; fail=1; }

# Speeds that repeat at double precision: one line, exit 2, no hang (each under a
# 20 s limit: a hang exits 124 and fails).
real_cli=$cli
printf '#!/bin/sh\nexec timeout 20 "%s" "$@"\n' "$real_cli" > "$dir/gk_limited"
chmod +x "$dir/gk_limited"
cli=$dir/gk_limited
for cmd in campbell critical stability response; do
    expect "keeps the 3 speeds distinct" "$cmd" "$dir/ok.toml" --speeds 1:1.0000000000000002:3
done
printf 'scene = "%s"\n[operating]\nfrom = 0\nto = 0\n[criteria.stability]\n' "$dir/ok.toml" > "$dir/zero_sweep.toml"
expect "[criteria.stability] up_to is missing" screen "$dir/zero_sweep.toml"
cli=$real_cli

# Response outputs by node or position: a node a support holds has no translation to report.
cat > "$dir/pinned.toml" <<'END'
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 1.0
elements = 4
outer_diameter = 0.05
[[model.disk]]
z = 0.5
outer_diameter = 0.2
width = 0.03
unbalance = 1e-4
[[model.support]]
z = 0.0
[[model.support]]
z = 1.0
[speeds]
from = 0
to = 1000
count = 11
END
expect "node 0 has no free lateral translation" response "$dir/pinned.toml" --nodes 0
expect "--at 0: node 0 has no free lateral translation" response "$dir/pinned.toml" --at 0
expect "--at 1.5: axial position 1.5 m is off the shaft; allowed: [0, 1] m" response "$dir/pinned.toml" --at 1.5
# In an mm scene positions are typed and read in mm: the same rotor, --at 500 is node 2.
cat > "$dir/pinned_mm.toml" <<'END'
[model]
type = "fe_rotor"
material = "steel"
length_unit = "mm"
[[model.shaft]]
length = 1000
elements = 4
outer_diameter = 50
[[model.disk]]
z = 500
outer_diameter = 200
width = 30
unbalance = 1e-4
[[model.support]]
z = 0
[[model.support]]
z = 1000
[speeds]
from = 0
to = 1000
count = 11
END
"$cli" response "$dir/pinned_mm.toml" --at 500 --format csv | cut -d, -f2 | sort -u | tr '\n' ' ' | grep -qx "dof x2 y2 " ||
    { echo "FAIL: --at 500 in an mm scene gives x2, y2"; fail=1; }
expect "--at 1500: axial position 1500 mm is off the shaft; allowed: [0, 1000] mm" response "$dir/pinned_mm.toml" --at 1500
expect "--probes '2@x': allowed: NODE@ANGLE items" response "$dir/pinned.toml" --probes 2@x
expect "--probes '2@400': allowed" response "$dir/pinned.toml" --probes 2@400
expect "--probes 0@45: node 0 has no free x and y translations" response "$dir/pinned.toml" --probes 0@45
expect "--probes: '2@45' is listed twice" frf "$dir/pinned.toml" --input y2 --probes 2@45,2@45
expect "--probes and --dofs, --nodes, --at: allowed: probes alone" response "$dir/pinned.toml" --probes 2@45 --dofs x2
"$cli" response "$dir/pinned.toml" --at 0.5 --format csv | cut -d, -f2 | sort -u | tr '\n' ' ' | grep -qx "dof x2 y2 " ||
    { echo "FAIL: --at 0.5 gives x2, y2"; fail=1; }
# The FRF, static and critical-map options: each bad value named with its allowed range.
three_disk="$data/three_disk_rotor.toml"
expect "--input 'q9': not a DOF of the model" frf "$three_disk" --input q9
expect "--frequencies '5:1:3': FROM = 5 is greater than TO = 1" frf "$three_disk" --input y12 --frequencies 5:1:3
expect "--speed -3: allowed: a finite number >= 0 (rpm)" frf "$three_disk" --input y12 --speed -3
expect "--load '12:x:1': allowed: NODE:FX:FY or NODE:FX:FY:MX:MY" static "$three_disk" --load 12:x:1
expect "load 0 at node 99; allowed: 0 to 24" static "$three_disk" --load 99:0:1
expect "static analysis: --gravity -1; allowed: 0 (no weight)" static "$three_disk" --gravity -1
expect "--modes: Value 0 not in range 1 to 1000" critical-map "$three_disk" --modes 0
expect "--stiffness '1e9:1e6:5': allowed: FROM:TO:N with 0 < FROM < TO" critical-map "$three_disk" --stiffness 1e9:1e6:5
expect "--units 'furlong' is unknown" critical-map "$three_disk" --units furlong
# Level I: the machine data missing or out of range, each named.
expect "the maximum continuous speed is missing; required: [api] mcs in the scene or --mcs (in rpm)" level1 "$data/compressor.toml"
expect "the anticipated cross-coupling is unknown" level1 "$data/compressor.toml" --mcs 10000
expect "--qa -5: allowed: a finite stiffness > 0 (N/m)" level1 "$three_disk" --mcs 10000 --qa -5
expect "--mcs 0: allowed: a finite speed > 0 (rpm)" level1 "$three_disk" --mcs 0 --qa 1e6
expect "--machine 'radial': allowed: centrifugal, axial" level1 "$three_disk" --mcs 10000 --qa 1e6 --machine radial
expect "--q-ratio 1: allowed: [2, 1000]" level1 "$three_disk" --mcs 10000 --qa 1e6 --q-ratio 1
expect "Level I needs an FE rotor" level1 "$data/centrifuge.toml" --mcs 10 --qa 1
expect "--station = 0 m: its node 0 does not move laterally" level1 "$dir/pinned.toml" --mcs 100 --qa 1e5 --station 0
expect "--station = 7 m: " level1 "$three_disk" --qa 1e5 --station 7
# The report: its file required, never over the scene, a count out of range.
expect "--out is required" report "$three_disk"
expect "--out $three_disk: that file is an input of this run" report "$three_disk" --out "$three_disk"
expect "--mode-shapes: Value 21 not in range 0 to 20" report "$three_disk" --out "$dir/r.html" --mode-shapes 21
# A film's tolerance band out of order, or half of it.
sed 's/^clearance_min = 50e-6.*/clearance_min = 70e-6/' "$data/three_disk_rotor_journal.toml" > "$dir/band_order.toml"
expect "clearance_min = 7e-05, clearance = 6e-05, clearance_max = 7.5e-05 (m); allowed: 0 < clearance_min <= clearance <= clearance_max" level1 "$dir/band_order.toml"
grep -v '^viscosity_max' "$data/three_disk_rotor_journal.toml" > "$dir/band_half.toml"
expect "viscosity_min is given without viscosity_max; allowed: both ends of the band or neither" level1 "$dir/band_half.toml"
expect "the maximum continuous speed is missing; required: [api] mcs in the scene or --mcs (in rpm)" api-unbalance "$data/compressor.toml"
expect "--min-speed 0: allowed: a finite speed > 0 (rpm)" api-unbalance "$three_disk" --min-speed 0
expect "--min-speed 12000: allowed: (0, 10000 rpm] (at most the mcs)" api-unbalance "$three_disk" --min-speed 12000
expect "--trip-speed 9000: allowed: at least the mcs, 10000 rpm" api-unbalance "$three_disk" --trip-speed 9000
expect "the API unbalance cases need an FE rotor" api-unbalance "$data/centrifuge.toml" --mcs 10
sed 's/^trip_speed = 10500/trip_speed = 9500/' "$three_disk" > "$dir/trip.toml"
expect "[api] trip_speed = 9500: out of range; allowed: at least the mcs, 10000 rpm" api-unbalance "$dir/trip.toml"
sed 's/^clearance = 0.25e-3/clearance = -1/' "$three_disk" > "$dir/clearance.toml"
expect "[api.clearance[0]] clearance = -1: out of range; allowed: > 0 (m)" api-unbalance "$dir/clearance.toml"
expect "--tolerance 0.7: allowed: (0, 0.5)" mesh "$three_disk" --tolerance 0.7
expect "--levels 1: allowed: [2, 8]" mesh "$three_disk" --levels 1
expect "mesh convergence refines an FE rotor's sections" mesh "$data/centrifuge.toml"
# Inputs that are not regular files, or nested beyond the parser's stack: one line, never a hang.
printf '[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "/dev/zero"\n' > "$dir/devzero.toml"
expect "/dev/zero: is not a regular file (a device, FIFO or socket); expected a Matrix Market file" eig "$dir/devzero.toml" --speed 1
expect "is a directory; expected a scene file" eig "$dir" --speed 1
expect "/dev/null: is not a regular file" eig /dev/null --speed 1
ln -s "$dir/loop.toml" "$dir/loop.toml"
expect "symbolic link that leads nowhere (or in a loop)" eig "$dir/loop.toml" --speed 1
python3 -c "print('[' + '.'.join(['x'] * 50000) + ']')" > "$dir/deep_header.toml"
expect "more than 64 levels deep" eig "$dir/deep_header.toml" --speed 1
python3 -c "print('.'.join(['x'] * 100000) + ' = 1')" > "$dir/deep_key.toml"
expect "a dotted key more than 64 levels deep" eig "$dir/deep_key.toml" --speed 1
python3 -c "print('x = ' + '[' * 100000 + ']' * 100000)" > "$dir/deep_array.toml"
expect "nested more than 64 levels deep" eig "$dir/deep_array.toml" --speed 1
# Dots inside strings and numbers are no levels.
printf 'title = "%s"\n[model]\ntype = "matrices"\nM = "M2.mtx"\nK = "M2.mtx"\nx = 1.5\n' "$(python3 -c "print('.' * 1000)")" > "$dir/dotted_title.toml"
expect "unknown key 'x'" eig "$dir/dotted_title.toml" --speed 1

# A bearing table naming a column twice; options listing a value twice; a speed beyond double precision.
printf 'speed,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy,kxx\n0,1e7,0,0,1e7,100,0,0,100,2e7\n1000,1e7,0,0,1e7,100,0,0,100,2e7\n' > "$dir/dupcol.csv"
cat > "$dir/dupcol.toml" <<END
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 1.0
elements = 4
outer_diameter = 0.05
[[model.bearing]]
z = 0.0
table = "dupcol.csv"
[[model.bearing]]
z = 1.0
k = 1e7
[speeds]
from = 0
to = 1000
count = 3
END
expect "the header names 'kxx' twice (columns 2 and 10)" eig "$dir/dupcol.toml" --speed 1
expect "--harmonics '1,1': 1 is listed twice" critical "$data/centrifuge.toml" --harmonics 1,1
expect "--dofs 'x,x': 'x' is listed twice" response "$data/centrifuge.toml" --dofs x,x
"$cli" eig "$data/centrifuge.toml" --speed 1e150 > "$dir/out" 2> "$dir/err"
rc=$?
if [ "$rc" -ne 3 ] || [ -s "$dir/out" ] || ! grep -q "the eigensolver cannot vouch for this pencil" "$dir/err"; then
    echo "FAIL: eig at 1e150 rad/s -> exit $rc, expected a solver error (3) and no table"; fail=1
fi

# A DOF of 1e20 N/m beside kilograms: its 4.47e9 rad/s mode is printed (QZ), never
# dropped as infinite; the state-matrix method says it cannot resolve it (exit 3).
printf '%%%%MatrixMarket matrix coordinate real general\n4 4 4\n1 1 5\n2 2 5\n3 3 0.02\n4 4 0.02\n' > "$dir/M20.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n4 4 4\n1 1 1\n2 2 1e20\n3 3 1\n4 4 1\n' > "$dir/K20.mtx"
printf '[model]\ntype = "matrices"\nM = "M20.mtx"\nK = "K20.mtx"\n' > "$dir/stiff20.toml"
"$cli" eig "$dir/stiff20.toml" --speed 0 > "$dir/out" 2> "$dir/err"
rc=$?
if [ "$rc" -ne 0 ] || ! grep -q " 4 .*4\.47214e+09" "$dir/out" || grep -q "infinite" "$dir/out"; then
    echo "FAIL: eig of the 1e20 N/m DOF -> exit $rc, expected its 4.47214e+09 rad/s mode and no infinite one"
    sed 's/^/    /' "$dir/out" "$dir/err"; fail=1
fi
"$cli" eig "$dir/stiff20.toml" --speed 0 --method state > "$dir/out" 2> "$dir/err"
rc=$?
if [ "$rc" -ne 3 ] || [ -s "$dir/out" ] || ! grep -q "M is invertible" "$dir/err"; then
    echo "FAIL: eig --method state of the 1e20 N/m DOF -> exit $rc, expected a solver error (3) naming M invertible"
    sed 's/^/    /' "$dir/err"; fail=1
fi

# A file that is not what it should be is named, never quoted; a huge key is cut.
printf 'root:secret-hash:19000:0:99999:7:::\n' > "$dir/shadow_like"
printf '[model]\ntype = "matrices"\nM = "shadow_like"\nK = "M2.mtx"\n' > "$dir/shadow.toml"
expect "missing banner" eig "$dir/shadow.toml" --speed 1
if grep -q "secret-hash" "$dir/err"; then echo "FAIL: an error quoted the content of a foreign file"; fail=1; fi
python3 -c "print('[model]'); print('type = \"matrices\"'); print('k' * 1000000 + ' = 1')" > "$dir/hugekey.toml"
expect "unknown key 'kkkk" eig "$dir/hugekey.toml" --speed 1
[ "$(wc -c < "$dir/err")" -lt 2000 ] || { echo "FAIL: the error echoed a 1 MB key"; fail=1; }

# A parameter whose matrices overflow the solvers' arithmetic: a range error, not LAPACK's info = -5.
sed 's/^m = .*/m = 1e308/' "$data/centrifuge.toml" > "$dir/m308.toml"
expect "allowed: magnitudes up to 1e+150" eig "$dir/m308.toml" --speed 10

# A DOF no matrix touches (a pencil singular at every lambda): one line for either solver, never a hang.
printf '%%%%MatrixMarket matrix coordinate real general\n201 201 1\n1 1 1.0\n' > "$dir/one.mtx"
printf '[model]\ntype = "matrices"\nM = "one.mtx"\nK = "one.mtx"\n' > "$dir/one.toml"
timeout 60 "$cli" eig "$dir/one.toml" --speed 1 --solver sparse > "$dir/out" 2> "$dir/err"
rc=$?
if [ "$rc" -ne 2 ] || ! grep -q "has no mass, stiffness, damping or coupling" "$dir/err"; then
    echo "FAIL: a DOF no matrix touches, sparse solver -> exit $rc (124: a hang)"; fail=1
fi
expect "has no mass, stiffness, damping or coupling" eig "$dir/one.toml" --speed 1 --solver dense

# Numbers, lists and names that once gave a wrong or unreadable answer: one line naming the value and range.
td=$data/three_disk_rotor.toml
expect "frequency 5e+299 rad/s: the dynamic stiffness K - w^2 M leaves double precision's range" \
    frf "$td" --units rad/s --speed 100 --input y3 --frequencies 0:1e300:3
expect "--dofs 'y3,y3': 'y3' is listed twice" frf "$td" --speed 100 --input y3 --frequencies 1:1000:3 --dofs y3,y3
expect "--dofs 'y3,y3': 'y3' is listed twice" transient "$td" --speed 100 --dofs y3,y3
expect "--stiffness '1e-320:1:3': allowed:" critical-map "$td" --stiffness 1e-320:1:3
expect "takes 6.28e+300 steps; allowed: at most --max-steps" transient "$td" --units rad/s --speed 100 --node 3 --dt 1e-300
expect "0 <= K < N <= 1000000" screen "$data/screen_centrifuge.toml" --shard 0/10000000
expect "--gravity '0x10': allowed: a number from 0 to 1e+06" static "$td" --gravity 0x10
expect "--gravity '1e-310': a subnormal number" static "$td" --gravity 1e-310
expect "has the component 1e+200; allowed: finite magnitudes up to 1e+15" static "$td" --load 3:0:1e200
expect "--speeds '0x10:20:3': expected FROM:TO:N" campbell "$td" --speeds 0x10:20:3
cp "$data/centrifuge.toml" "$dir/"
sed 's/^\[model\]/[model]\nshaft = "rigid"/' "$data/centrifuge.toml" > "$dir/rigid.toml"
sweep() {   # sweep FILE NAME PATHS SCENE: a one-parameter sweep of two values
    printf 'scene = "%s"\n[[parameter]]\nname = "%s"\n%s\nvalues = [1000.0, 3000.0]\n[operating]\nfrom = 24.0\nto = 50.0\n[criteria.separation]\nmargin_percent = 15.0\n' \
        "$4" "$2" "$3" > "$1"
}
sweep "$dir/ignored.toml" model.c_T "" rigid.toml
expect "parameter 'model.c_T' does not change the model of scene" screen "$dir/ignored.toml"
sweep "$dir/verdict.toml" verdict 'paths = ["model.c_G"]' centrifuge.toml
expect "parameter name 'verdict' is also the name of a result column" screen "$dir/verdict.toml"
sweep "$dir/newline.toml" 'a\nb' 'paths = ["model.c_G"]' centrifuge.toml
expect "parameter name 'a?b' holds a line break" screen "$dir/newline.toml"
sweep "$dir/tie.toml" 'model.c_R' 'paths = ["model.c_G"]' centrifuge.toml
expect "parameter name 'model.c_R' reads as a scene path but the parameter sets model.c_G" screen "$dir/tie.toml"

exit $fail
