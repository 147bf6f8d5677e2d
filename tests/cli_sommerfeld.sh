#!/usr/bin/env bash
# Bad input to `gyrokit sommerfeld`: exit status 2, exactly one line on stderr that
# names the offending key or value, nothing on stdout. Also good runs of both modes.
set -u
cli=$1
data=$2
source "$(dirname "$0")/cli_lib.sh"

good='type = "autobalancer"
m = 1.0
J = 0.0054
m0 = 0.05
eps0 = 0.065
k = 15830.0
c = 15.0
L0 = 2.5
beta0 = 0.005'
runup='[runup]
max_speed = 300.0
rise = 2.0
hold = 1.0
fall = 0.5'

scene() {   # scene NAME MODEL-LINES [EXTRA]
    printf '[model]\n%s\n%s\n' "$2" "${3:-}" > "$dir/$1.toml"
}
change() { printf '%s\n' "$good" | sed "$1"; }

scene ok "$good" "$runup"
scene speed "$(change 's/^L0 = 2.5/speed = 100.0/; /^beta0/d')"
scene aniso "$(change 's/^k = 15830.0/k_x = 15830.0\nk_y = 20000.0/')"
scene nodamp "$(change 's/^c = 15.0/c = 0.0/')"
scene negc "$(change 's/^c = 15.0/c = -1.0/')"
scene bothk "$good
k_x = 100.0"
scene noexc "$(change 's/^m0 = 0.05/m0 = 0.0/')"
scene norunup "$good"
scene badmax "$good" "$(printf '%s\n' "$runup" | sed 's/^max_speed = 300.0/max_speed = -3.0/')"
scene badrise "$good" "$(printf '%s\n' "$runup" | sed 's/^rise = 2.0/rise = 0.0/')"
scene runupkey "$good" "$runup
duration = 3.0"
scene runupalpha "$good" "$runup
alpha1 = 10.0"
scene badmethod "$good" "$runup
method = \"euler\""
scene rollers "$good
m1 = 0.0025
eps1 = 0.065
R1 = 0.07
mu1 = 0.4
beta1 = 2.5e-5
m2 = 0.003
eps2 = 0.065
R2 = 0.07
mu2 = 0.4
beta2 = 2.5e-5"
printf '[model\n' > "$dir/syntax.toml"

expect "L0 and beta0" sommerfeld "$dir/speed.toml"
expect "isotropic" sommerfeld "$dir/aniso.toml"
expect "c = 0" sommerfeld "$dir/nodamp.toml"
expect "c = -1" sommerfeld "$dir/negc.toml"
expect "k_x" sommerfeld "$dir/bothk.toml"
expect "m0 * eps0 = 0" sommerfeld "$dir/noexc.toml"
expect "[runup]" sommerfeld "$dir/norunup.toml" --runup
expect "max_speed = -3" sommerfeld "$dir/badmax.toml"
expect "rise = 0" sommerfeld "$dir/badrise.toml"
expect "unknown key 'duration'" sommerfeld "$dir/runupkey.toml"
expect "alpha1" sommerfeld "$dir/runupalpha.toml"
expect "euler" sommerfeld "$dir/badmethod.toml"
expect "identical" sommerfeld "$dir/rollers.toml"
expect "line 1" sommerfeld "$dir/syntax.toml"
expect "not found" sommerfeld "$dir/missing.toml"
expect "xml" sommerfeld "$dir/ok.toml" --format xml
expect "--speeds" sommerfeld "$dir/ok.toml" --speeds 10:5:3
expect "--speeds" sommerfeld "$dir/ok.toml" --speeds abc
expect "--speeds" sommerfeld "$dir/ok.toml" --runup --speeds 0:10:3
expect "need --runup" sommerfeld "$dir/ok.toml" --integrator rkf45
expect "rk8pd" sommerfeld "$dir/ok.toml" --runup --integrator euler
expect "--abs-tol" sommerfeld "$dir/ok.toml" --runup --abs-tol 0
expect "--max-speed" sommerfeld "$dir/ok.toml" --runup --max-speed -1
expect "plot" sommerfeld "$dir/ok.toml" --plot out.pdf
expect "--rows" sommerfeld "$dir/ok.toml" --runup --rows

# A run that cannot end within max_steps stops within seconds, saying so (before:
# a run-up to 1e9 rad/s failed at the step limit after 397 s).
start=$(date +%s)
"$cli" sommerfeld "$data/sommerfeld_rotor.toml" --runup --max-speed 1e9 > "$dir/out" 2> "$dir/err"
rc=$?
took=$(( $(date +%s) - start ))
if [ "$rc" -ne 3 ] || [ "$took" -gt 30 ] || ! grep -q "project about .* more than max_steps" "$dir/err"; then
    echo "FAIL: run-up to 1e9 rad/s: exit $rc after $took s"; cat "$dir/err"; fail=1
fi

# The first screen: summary and folds, no stationary rows; --rows adds them.
first=$("$cli" sommerfeld "$data/sommerfeld_rotor.toml" --speeds 0:400:5)
rows=$("$cli" sommerfeld "$data/sommerfeld_rotor.toml" --speeds 0:400:5 --rows)
if ! grep -q "^quasi_static_runup  *passes the resonance" <<< "$first" || grep -q "resonance  *[0-9]" <<< "$first" ||
   [ "$(grep -cE '^ +[0-9.]+ +(resonance|unstable|upper) ' <<< "$rows")" -ne 9 ]; then
    echo "FAIL: sommerfeld first screen / --rows"; echo "$first"; echo "$rows"; fail=1
fi

# Good runs: the summary rows exist and the output holds finite numbers only.
if ! "$cli" sommerfeld "$data/sommerfeld_rotor.toml" --format csv --table summary > "$dir/s.csv" 2> "$dir/err" ||
   grep -qiE '(^|,)-?(nan|inf)(,|$)' "$dir/s.csv"; then
    echo "FAIL: sommerfeld stationary"; cat "$dir/err"; fail=1
fi
for q in omega_krit limit_speed_estimate jump_up jump_down; do
    grep -q "^$q,[0-9]" "$dir/s.csv" || { echo "FAIL: sommerfeld csv lacks $q"; fail=1; }
done
if ! "$cli" sommerfeld "$dir/ok.toml" --runup --format csv --table summary > "$dir/r.csv" 2> "$dir/err" ||
   grep -qiE '(^|,)-?(nan|inf)(,|$)' "$dir/r.csv" || ! tail -1 "$dir/r.csv" | grep -qE '^captured,(true|false),$' ||
   ! grep -q '^held_rotor_speed,[0-9]' "$dir/r.csv"; then
    echo "FAIL: sommerfeld --runup"; cat "$dir/err"; tail -5 "$dir/r.csv"; fail=1
fi
# Without --table, CSV holds the first table and a note names the others.
"$cli" sommerfeld "$data/sommerfeld_rotor.toml" --format csv > "$dir/first.csv" 2> "$dir/err"
head -1 "$dir/first.csv" | grep -q '^nominal' && grep -q "note: CSV holds one table (stationary_states); the others with --table folds, summary" "$dir/err" ||
    { echo "FAIL: sommerfeld CSV without --table"; head -2 "$dir/first.csv"; cat "$dir/err"; fail=1; }
expect "--table 'all': allowed: stationary_states, folds, summary" sommerfeld "$data/sommerfeld_rotor.toml" --table all
exit $fail
