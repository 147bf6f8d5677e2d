#!/usr/bin/env bash
# The fluid command: documented CSV columns on the Tabelle 2 scenes, a fill
# sweep, the core commands on a fluid scene; bad input gives exit status 2 and
# exactly one line on stderr naming the key or value, nothing on stdout.
set -u
cli=$1
data=$2
source "$(dirname "$0")/cli_lib.sh"


good='[model]
type = "fluid_rotor"
R = 0.6
a = 1.0
l = 2.5
nu = 1.0e-6
c1 = 6.0e8
c2 = 2.0e8
c11 = 3.0e6
m0 = 600.0
I0 = 200.0
J0 = 160.0'
scene() {   # scene NAME EXTRA-LINES
    printf '%s\n%s\n' "$good" "$2" > "$dir/$1.toml"
}
scene full 'R0 = 0.6
rho = 1000.0'
scene over 'R0 = 0.7
rho = 1000.0'
scene negrho 'R0 = 0.4
rho = -1000.0'
scene zeromodes 'R0 = 0.4
rho = 1000.0
modes = 0'
scene unknown 'R0 = 0.4
rho = 1000.0
colour = "red"'
scene missing 'rho = 1000.0'
scene badtol 'R0 = 0.4
rho = 1000.0
tolerance = 2.0'
scene ok 'R0 = 0.4
rho = 1000.0
modes = 5'

expect "R0 = 0.6 is not below R = 0.6" fluid "$dir/full.toml"
expect "R0 = 0.7 is not below R = 0.6" fluid "$dir/over.toml"
expect "rho = -1000" fluid "$dir/negrho.toml"
expect "modes = 0" fluid "$dir/zeromodes.toml"
expect "unknown key 'colour'" fluid "$dir/unknown.toml"
expect "'R0' is missing" fluid "$dir/missing.toml"
expect "tolerance = 2" fluid "$dir/badtol.toml"
expect "--fill" fluid "$dir/ok.toml" --fill 0.1:0.7:5
expect "--fill" fluid "$dir/ok.toml" --fill 0:0.5:5
expect "--fill" fluid "$dir/ok.toml" --fill 0.1:0.5
expect "--table 'x'" fluid "$dir/ok.toml" --table x
expect "--plot" fluid "$dir/ok.toml" --plot "$dir/a.svg"
expect "needs type = \"fluid_rotor\"" fluid "$data/centrifuge.toml"

# CSV columns and rows of the Tabelle 2 scenes.
for n in 1 2 3 4; do
    got=$("$cli" fluid "$data/fluid_N$n.toml" --format csv 2> "$dir/err" | head -n 1)
    [ "$got" = "model,index,speed_rad_s" ] || { echo "FAIL: fluid N$n header '$got'"; cat "$dir/err"; fail=1; }
done
"$cli" fluid "$data/fluid_N2.toml" --format csv | grep -q "^moving_undamped,2," ||
    { echo "FAIL: N2 second critical speed missing"; fail=1; }
"$cli" fluid "$data/fluid_N3.toml" --format csv | grep -q "^rigid,2," ||
    { echo "FAIL: N3 second rigid critical speed missing"; fail=1; }
got=$("$cli" fluid "$data/fluid_N2.toml" --fill 0.05:0.55:11 --format csv | head -n 1)
[ "$got" = "fill_m,model,index,speed_rad_s" ] || { echo "FAIL: fill header '$got'"; fail=1; }
if "$cli" fluid "$data/fluid_N2.toml" --fill 0.05:0.55:51 --format csv | grep -qiE "nan|inf"; then
    echo "FAIL: NaN/Inf in the fill sweep"; fail=1
fi
"$cli" fluid "$data/fluid_N4.toml" --table sloshing_modes --format csv | head -n 1 | grep -q "^n,sigma_over_omega,lambda_kg_m,mu_kg,tau_1_s" ||
    { echo "FAIL: modes table"; fail=1; }
"$cli" fluid "$data/fluid_N1.toml" > /dev/null || { echo "FAIL: text output"; fail=1; }
# The core commands on a fluid scene.
"$cli" eig "$data/fluid_N2.toml" --speed 49.3 --format csv > /dev/null || { echo "FAIL: eig on a fluid scene"; fail=1; }
"$cli" campbell "$data/fluid_N2.toml" --speeds 0:100:11 --format csv > /dev/null ||
    { echo "FAIL: campbell on a fluid scene"; fail=1; }
"$cli" response "$data/fluid_N2.toml" --speeds 40:60:21 --format csv > /dev/null ||
    { echo "FAIL: response on a fluid scene"; fail=1; }
if command -v gnuplot > /dev/null; then
    "$cli" fluid "$data/fluid_N2.toml" --fill 0.05:0.55:21 --plot "$dir/fill.svg" > /dev/null 2>&1 && [ -s "$dir/fill.svg" ] ||
        { echo "FAIL: fill plot"; fail=1; }
fi
exit $fail
