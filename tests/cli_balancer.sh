#!/usr/bin/env bash
# Bad input to `gyrokit balancer`: exit status 2, exactly one line on stderr that
# names the offending key or value, nothing on stdout. Also one good run of each mode.
set -u
cli=$1
data=$2
source "$(dirname "$0")/cli_lib.sh"

good='type = "autobalancer"
m = 1.0
J = 0.01
m0 = 0.002
eps0 = 0.05
omega_x = 62.5
omega_y = 125.1
c_x = 2.0
c_y = 2.0
m1 = 0.0024
eps1 = 0.05
R1 = 0.055
mu1 = 0.4
beta1 = 3e-5
m2 = 0.0016
eps2 = 0.05
R2 = 0.055
mu2 = 0.4
beta2 = 3e-5
speed = 300.0'
sim='[simulation]
duration = 1.0
alpha1 = 2.0
alpha2 = -2.0'

scene() {   # scene NAME MODEL-LINES [EXTRA]
    printf '[model]\n%s\n%s\n' "$2" "${3:-}" > "$dir/$1.toml"
}
change() { printf '%s\n' "$good" | sed "$1"; }


scene ok "$good" "$sim"
scene negmass "$(change 's/^m1 = 0.0024/m1 = -0.0024/')"
scene negbase "$(change 's/^m = 1.0/m = -1.0/')"
scene Rsmall "$(change 's/^R1 = 0.055/R1 = 0.05/')"
scene nobeta "$(change 's/^beta2 = 3e-5/beta2 = 0.0/')"
scene mubig "$(change 's/^mu1 = 0.4/mu1 = 1.5/')"
scene unknown "$good
k_z = 1.0"
scene bothk "$good
k_x = 4000.0"
scene nodrive "$(change '/^speed/d')"
scene motorbeta "$(change 's/^speed = 300.0/L0 = 1.0\nbeta0 = 5e-5/')"
scene roller2only "$(change '/^m1 =/d; /^eps1/d; /^R1/d; /^mu1/d; /^beta1/d')"
scene badr "$(change 's/^R1 = 0.055/R1 = 0.055\nr1 = 0.01/')"
scene nodamp "$(change 's/^c_x = 2.0/c_x = 0.0/')" "$sim"
scene nosim "$good"
scene badmethod "$good" "$sim
method = \"euler\""
scene badalpha "$good" '[simulation]
duration = 1.0
alpha1 = "north"
alpha2 = 0.0'
scene shortrun "$good" '[simulation]
duration = 0.001
alpha1 = 0.0
alpha2 = 0.0'
scene noimb "$(change 's/^m0 = 0.002/m0 = 0.0/')"
printf '[model\n' > "$dir/syntax.toml"

expect "m1 = -0.0024" balancer "$dir/negmass.toml"
expect "m = -1" balancer "$dir/negbase.toml"
expect "R1 = 0.05" balancer "$dir/Rsmall.toml"
expect "beta2 = 0" balancer "$dir/nobeta.toml"
expect "mu1 = 1.5" balancer "$dir/mubig.toml"
expect "unknown key 'k_z'" balancer "$dir/unknown.toml"
expect "k_x" balancer "$dir/bothk.toml"
expect "speed" balancer "$dir/nodrive.toml"
expect "beta0 = 5e-05" balancer "$dir/motorbeta.toml"
expect "roller 2" balancer "$dir/roller2only.toml"
expect "r1 = 0.01" balancer "$dir/badr.toml"
expect "c_x = 0" balancer "$dir/nodamp.toml" --simulate
expect "[simulation]" balancer "$dir/nosim.toml" --simulate
expect "euler" balancer "$dir/badmethod.toml" --simulate
expect "alpha1" balancer "$dir/badalpha.toml" --simulate
expect "duration" balancer "$dir/shortrun.toml" --simulate
expect "m0 * eps0" balancer "$dir/noimb.toml"
expect "line 1" balancer "$dir/syntax.toml"
expect "not found" balancer "$dir/missing.toml"
expect "xml" balancer "$dir/ok.toml" --format xml
expect "--simulate" balancer "$dir/ok.toml" --speed 100
expect "--rows" balancer "$dir/ok.toml" --simulate --rows
expect "balancing_ranges" balancer "$dir/ok.toml" --table nosuch
expect "--speed" balancer "$dir/ok.toml" --simulate --speed -5
expect "--abs-tol" balancer "$dir/ok.toml" --simulate --abs-tol 0
expect "plot" balancer "$dir/ok.toml" --simulate --plot out.pdf
expect "rk8pd" balancer "$dir/ok.toml" --simulate --integrator euler

# Good runs: the state table and a short simulation end with finite numbers only.
if ! "$cli" balancer "$data/balancer_table3.toml" --format csv > "$dir/t.csv" 2> "$dir/err" ||
   ! head -1 "$dir/t.csv" | grep -q '^state,alpha1_deg,alpha2_deg,range,from_rad_s,to_rad_s,stable' ||
   grep -qiE 'nan' "$dir/t.csv"; then
    echo "FAIL: balancer state table"; cat "$dir/err"; fail=1
fi
if ! "$cli" balancer "$dir/ok.toml" --simulate --format csv > "$dir/s.csv" 2> "$dir/err" ||
   grep -qiE 'nan|inf' "$dir/s.csv" || ! head -1 "$dir/s.csv" | grep -q 'alpha1_deg,alpha2_deg$'; then
    echo "FAIL: balancer --simulate"; cat "$dir/err" "$dir/s.csv"; fail=1
fi

# A simulation that cannot end within max_steps (1e6 s: about 2e8 steps) stops
# within seconds, saying so, instead of at the step limit minutes later.
start=$(date +%s)
"$cli" balancer "$data/balancer_bild7.toml" --simulate --duration 1e6 > "$dir/out" 2> "$dir/err"
rc=$?
took=$(( $(date +%s) - start ))
if [ "$rc" -ne 3 ] || [ "$took" -gt 30 ] || ! grep -q "project about .* more than max_steps" "$dir/err"; then
    echo "FAIL: simulation of 1e6 s: exit $rc after $took s"; cat "$dir/err"; fail=1
fi
exit $fail
