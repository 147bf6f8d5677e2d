#!/usr/bin/env bash
# gyrokit transient: bad input gives exit status 2 and one line naming the option, the
# value and the allowed range; a run prints its envelope, writes the full history and
# draws the orbit, the run-up envelope and the waterfall.
set -u
cli=$1
data=$(cd "${2:-$(dirname "$0")/../data}" && pwd)
source "$(dirname "$0")/cli_lib.sh"
# The three-disk rotor with its [speeds] in rad/s: the speeds below are written in rad/s,
# the unit a run takes and prints by default (the scene's [speeds] units).
rotor="$dir/three_disk_rotor.toml"
sed 's/^units = "rpm"/units = "rad\/s"/' "$data/three_disk_rotor.toml" > "$rotor"

expect "--dt -1 s: allowed: (0, 0.001309] s" transient "$rotor" --speed 600 --dt -1
expect "--dt 0 s: allowed: a finite time step > 0" transient "$rotor" --speed 600 --dt 0
expect "--dt 'abc': allowed: a number" transient "$rotor" --speed 600 --dt abc
expect "--dt 0.5 s: allowed: (0, 0.001309] s" transient "$rotor" --speed 600 --dt 0.5
expect "--duration -3 s: allowed: a finite time > 0" transient "$rotor" --speed 600 --duration -3
expect "takes 500000000 steps; allowed: at most --max-steps 2000000 (up to 50000000)" \
    transient "$rotor" --speed 600 --duration 100000 --dt 0.0002
expect "--max-steps 0: allowed: 1 to 50000000" transient "$rotor" --speed 600 --max-steps 0
expect "--acceleration -5 rpm/s with a run-up from 0 to 15000 rpm: allowed: a finite number > 0" \
    transient "$rotor" --run-up 0:15000 --acceleration -5 --units rpm
expect "--acceleration 5 rpm/s with a run-down from 15000 to 0 rpm: allowed: a finite number < 0" \
    transient "$rotor" --run-up 15000:0 --acceleration 5 --units rpm
expect "--run-up needs --acceleration (rad/s^2" transient "$rotor" --run-up 0:1500
expect "--run-up 0:0 rad/s: allowed: two different finite speeds >= 0" transient "$rotor" --run-up 0:0 --acceleration 3
expect "--speed and --run-up: allowed: one of them" transient "$rotor" --speed 600 --run-up 0:5 --acceleration 1
expect "no speed: allowed: --speed (a constant speed), or --run-up (from, to) with --acceleration" transient "$rotor"
expect "--speed 0 rad/s: allowed: a finite speed > 0" transient "$rotor" --speed 0
expect "--acceleration: only together with --run-up" transient "$rotor" --speed 600 --acceleration 5
expect "--node 99: node 99 does not exist; allowed: 0 to 24" transient "$rotor" --speed 600 --node 99
expect "--dofs 'x99': 'x99' is not a DOF of the model" transient "$rotor" --speed 600 --dofs x99
expect "--start 'hot': allowed: rest, steady" transient "$rotor" --speed 600 --start hot
expect "--plot at a constant speed draws an orbit: allowed: two DOFs" \
    transient "$rotor" --speed 600 --dofs x12 --plot "$dir/o.png"
expect "--waterfall '$dir/w.pdf': unsupported extension '.pdf'; allowed: .svg, .png" \
    transient "$rotor" --speed 600 --waterfall "$dir/w.pdf"
# Picture paths are checked before the run, not after it.
expect "--waterfall $dir/none/w.png: the folder '$dir/none' does not exist" \
    transient "$rotor" --speed 600 --waterfall "$dir/none/w.png"
expect "--plot $dir/none/o.png: the folder '$dir/none' does not exist" \
    transient "$rotor" --speed 600 --node 12 --plot "$dir/none/o.png"
expect "--out $dir/none/h.csv: the folder '$dir/none' does not exist" transient "$rotor" --speed 600 --out "$dir/none/h.csv"
printf '[model]\ntype = "matrices"\nM = "M.mtx"\nK = "K.mtx"\n' > "$dir/nounb.toml"
printf '%%%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1.0\n2 2 1.0\n' > "$dir/M.mtx"
cp "$dir/M.mtx" "$dir/K.mtx"
expect "no unbalance load" transient "$dir/nounb.toml" --speed 1

# A run: the envelope, the history (steps + 1 rows and a header), the orbit, the waterfall.
if ! "$cli" transient "$rotor" --speed 600 --duration 0.1 --node 12 --start steady --out "$dir/h.csv" \
        --plot "$dir/orbit.png" --waterfall "$dir/w.svg" > "$dir/out" 2> "$dir/err"; then
    echo "FAIL: a constant-speed run failed"; cat "$dir/err"; fail=1
fi
# The default step at a constant speed: the band's, shortened for the amplitude to settle within 0.05 %.
grep -q "^note: Newmark average acceleration, 1417 steps of 7.057e-05 s over 0.1 s.*within 0.045 % of the steady response" "$dir/err" ||
    { echo "FAIL: no time-step note"; cat "$dir/err"; fail=1; }
[ "$(wc -l < "$dir/h.csv")" -eq 1419 ] || { echo "FAIL: history rows $(wc -l < "$dir/h.csv")"; fail=1; }
[ "$(head -1 "$dir/h.csv")" = "time_s,speed_rad_s,x12,y12" ] || { echo "FAIL: history header"; fail=1; }
grep -q "nan" "$dir/out" "$dir/h.csv" && { echo "FAIL: nan printed"; fail=1; }
[ -s "$dir/orbit.png" ] && [ -s "$dir/w.svg" ] || { echo "FAIL: no orbit or waterfall"; fail=1; }
# A run-down in rpm as CSV: one table, speeds falling, and the run-up picture.
"$cli" transient "$rotor" --run-up 6000:3000 --acceleration -6000 --units rpm --format csv \
    --plot "$dir/down.svg" > "$dir/down.csv" 2> "$dir/err" || { echo "FAIL: run-down"; cat "$dir/err"; fail=1; }
head -1 "$dir/down.csv" | grep -q "^time_s,speed_rpm,revolution,dof,unit,peak,steady$" ||
    { echo "FAIL: run-down header"; head -2 "$dir/down.csv"; fail=1; }
[ -s "$dir/down.svg" ] || { echo "FAIL: no run-down plot"; fail=1; }
exit $fail
