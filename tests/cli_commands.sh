#!/usr/bin/env bash
# Every gyrokit command on the centrifuge scene: exit 0, the documented CSV
# columns, valid JSON, plots written, matrices exported.
set -u
cli=$1
data=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
scene="$data/centrifuge.toml"

header() {   # header "expected,columns" command args...
    local want=$1; shift
    local got
    if ! got=$("$cli" "$@" --format csv 2> "$dir/err" | head -n 1); then
        echo "FAIL: gyrokit $* exited non-zero"; cat "$dir/err"; fail=1; return
    fi
    case "$got" in
        "$want"*) ;;
        *) echo "FAIL: gyrokit $*: header '$got' does not start with '$want'"; fail=1 ;;
    esac
}

header "speed_rad_s,index,re_1_s,im_rad_s" eig "$scene" --speed 30
header "speed_rad_s,mode,re_1_s,im_rad_s" campbell "$scene"
header "speed_rad_s,bound_rad_s,mode,whirl,harmonic" critical "$scene"
header "damping,speed_rad_s,mode" pervasive "$scene"
header "speed_rad_s,dof,unit,amplitude,phase_deg" response "$scene"
header "speed_rad_s,bound_rad_s,mode,change" stability "$scene"

# The eig table carries the whirl and backward-error columns the docs promise.
"$cli" eig "$scene" --speed 30 --format csv | head -n 1 | grep -q "whirl,damping_ratio,log_dec,backward_error" ||
    { echo "FAIL: eig columns"; fail=1; }

# Units: 60 rad/s is 572.958 rpm.
"$cli" campbell "$scene" --units rpm --speeds 0:572.957795:3 --format csv | tail -n 1 | grep -q "^572.957795" ||
    { echo "FAIL: rpm output"; fail=1; }
# The unit is in the column names, in CSV and JSON alike (case-insensitive --units).
header "speed_rpm,mode,re_1_s,im_rad_s,frequency_rpm" campbell "$scene" --units RPM --speeds 0:60:3
header "speed_hz,bound_hz,mode,whirl,harmonic,frequency_hz" critical "$scene" --units hz
"$cli" eig "$scene" --speed 3 --units Hz --format json | grep -q '"frequency_hz":' || { echo "FAIL: Hz JSON keys"; fail=1; }

# The summary's stability verdict covers every mode up to f_cut, also those --modes does not show,
# each onset the one `gyrokit stability` refines (251.609 and 1083.43 rad/s), not a grid speed.
"$cli" campbell "$data/fe_rotor.toml" --modes 1 2> /dev/null | grep -q "^stability  *mode 2 unstable from 251.609 to 4000 rad/s (beyond the 1 shown)" ||
    { echo "FAIL: campbell verdict of untracked modes"; fail=1; }
# The sparse window is widened to hold the modes up to f_cut: the same verdict as the dense path.
"$cli" campbell "$data/fe_rotor.toml" --modes 2 --solver sparse 2> /dev/null | grep -q "^stability  *mode 2 unstable from 251.609 to 4000 rad/s; mode 4 unstable from 1083.43 to 4000 rad/s (beyond the 2 shown) *$" ||
    { echo "FAIL: campbell verdict of a widened sparse window"; fail=1; }
# Where the model's size caps the window short of f_cut, the verdict covers the window and a note says so.
"$cli" campbell "$data/fe_rotor.toml" --modes 2 --solver sparse --f-cut 1e7 > "$dir/short" 2> "$dir/short.err"
grep -q "modes beyond the 32 of the window are not checked" "$dir/short" ||
    { echo "FAIL: campbell verdict of a sparse window short of f_cut"; fail=1; }
grep -q "the sparse window of 32 modes (as wide as its cost budget for this model.s size allows) reaches .* short of 1.5 times f_cut" "$dir/short.err" ||
    { echo "FAIL: note of a sparse window short of f_cut"; fail=1; }

# The 336-DOF compressor: with the modes in range (the default) auto keeps the dense
# continuation, which judges every mode in range (no window note); its seal makes mode 2
# unstable at 803.71 rad/s, as the sparse window of 6 modes finds within the bounds.
"$cli" stability "$data/compressor336.toml" --units rad/s > "$dir/c336" 2> "$dir/c336.err" ||
    { echo "FAIL: compressor336 stability"; fail=1; }
grep -q "sparse" "$dir/c336.err" && { echo "FAIL: compressor336 default is not the dense continuation"; fail=1; }
grep -q "^ *803\.7[01][0-9]* .* 2  unstable" "$dir/c336" || { echo "FAIL: compressor336 threshold"; cat "$dir/c336"; fail=1; }
"$cli" stability "$data/compressor336.toml" --units rad/s --solver sparse 2> /dev/null | grep -q "^ *803\.7[01][0-9]* .* 2  unstable" ||
    { echo "FAIL: compressor336 sparse threshold"; fail=1; }

# A dense diagram of fewer modes than DOFs still judges a divergent (real, positive)
# eigenvalue, whatever its size: it ranks after the modes that vibrate but is not left out.
mkdir -p "$dir/div"
printf '%%%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 1\n3 3 1\n' > "$dir/div/M.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 100\n2 2 -40000\n3 3 1\n' > "$dir/div/K.mtx"
printf '%%%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 0.1\n2 2 0\n3 3 100\n' > "$dir/div/D.mtx"
printf '[model]\ntype = "matrices"\nM = "M.mtx"\nK = "K.mtx"\nD = "D.mtx"\n[speeds]\nfrom = 0\nto = 10\ncount = 5\n' > "$dir/div/div.toml"
for m in 1 3; do
    "$cli" campbell "$dir/div/div.toml" --modes $m 2> /dev/null | grep -Eq "^stability  *mode [0-9]+ unstable from 0 to 10 rad/s" ||
        { echo "FAIL: campbell --modes $m misses the divergent mode"; fail=1; }
done
# The stability command's verdict covers the modes beyond the K shown as well.
"$cli" stability "$dir/div/div.toml" --modes 1 2>&1 | grep -q "no mode changes stability in the range; some are unstable throughout" ||
    { echo "FAIL: stability --modes 1 calls a divergent rotor stable"; fail=1; }

# JSON parses.
# JSON: an array of objects with the documented keys.
"$cli" critical "$scene" --format json > "$dir/c.json" && head -c 1 "$dir/c.json" | grep -q '\[' &&
    grep -q '"speed_rad_s":' "$dir/c.json" && grep -q '"whirl": "forward"' "$dir/c.json" ||
    { echo "FAIL: critical JSON"; fail=1; }

# Plots.
"$cli" campbell "$scene" --plot "$dir/campbell.svg" > /dev/null 2>&1 && grep -q "<svg" "$dir/campbell.svg" ||
    { echo "FAIL: campbell plot"; fail=1; }
"$cli" response "$scene" --plot "$dir/response.png" > /dev/null 2>&1 && [ -s "$dir/response.png" ] ||
    { echo "FAIL: response plot"; fail=1; }

# Export.
"$cli" export "$scene" --speed 20 --dir "$dir/mtx" 2> /dev/null &&
    for f in M K G D D_d_G C Kw pencil_A pencil_B state; do
        [ -s "$dir/mtx/$f.mtx" ] || { echo "FAIL: export misses $f.mtx"; fail=1; }
    done

# The direct critical speeds of the undamped centrifuge agree with the branch method.
sed -e '/^d_[GTR] /d' "$scene" > "$dir/undamped.toml"
# (both are refined to about 1e-12 relative: equal to 1e-9, whatever the rounding)
a=$("$cli" critical "$dir/undamped.toml" --format csv | cut -d, -f1 | tail -n +2)
b=$("$cli" critical "$dir/undamped.toml" --critical-method direct --format csv | cut -d, -f1 | tail -n +2)
[ -n "$a" ] && [ "$(echo "$a" | wc -l)" = "$(echo "$b" | wc -l)" ] &&
    paste -d' ' <(echo "$a") <(echo "$b") | awk '{d = $1 - $2; if (d < 0) d = -d; if (d > 1e-9 * $1) exit 1}' ||
    { echo "FAIL: direct vs branch: '$a' vs '$b'"; fail=1; }

# The first screen of campbell (table format): the summary and the critical speeds. Its
# numbers are compared with docs/cli.md to their printed digits by the docs test
# (docs_examples.py); here, that each line of the summary is there.
(cd "$(dirname "$0")/.." && "$cli" campbell data/centrifuge.toml) > "$dir/summary"
for line in "modes tracked" "speed range" "critical speeds" "least damping" "stability" "largest backward error" "plot"; do
    grep -q "^$line  " "$dir/summary" || { echo "FAIL: campbell's first screen has no '$line' line"; fail=1; }
done
"$cli" campbell "$scene" --rows | grep -q "^Campbell diagram$" || { echo "FAIL: campbell --rows"; fail=1; }

[ "$fail" -eq 0 ] && echo "all CLI commands OK"
exit $fail
