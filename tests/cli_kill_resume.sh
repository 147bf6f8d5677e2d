#!/usr/bin/env bash
# A screening run killed with SIGKILL at 20 random moments and resumed each time
# ends with the same bytes as an uninterrupted run.
set -u
cli=$1
data=$(cd "$2" && pwd)
source "$(dirname "$0")/cli_lib.sh"

# The example sweep with 120 designs (about 3 s), so that each kill interrupts it.
sweep=$dir/sweep.toml
sed -e "s|^scene = \"centrifuge.toml\"|scene = \"$data/centrifuge.toml\"|" \
    -e 's|^values = \[0.0, 1.0, 4.0, 10.0\]|values = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5, 7.0, 7.5, 8.0, 8.5, 9.0, 10.0]|' \
    "$data/screen_centrifuge.toml" > "$sweep"
grep -q "values = \[0.0, 0.5" "$sweep" || { echo "FAIL: could not widen the sweep"; exit 1; }
"$cli" screen "$sweep" --out "$dir/whole.csv" --jobs 1 > /dev/null 2>&1 || { echo "FAIL: uninterrupted run"; exit 1; }
RANDOM=7   # reproducible moments
kills=0
for attempt in $(seq 1 20); do
    "$cli" screen "$sweep" --resume "$dir/killed.csv" --jobs 1 > /dev/null 2>&1 &
    pid=$!
    sleep "0.$(printf '%03d' $((RANDOM % 150)))"
    if kill -9 "$pid" 2> /dev/null; then kills=$((kills + 1)); fi
    wait "$pid" 2> /dev/null
done
"$cli" screen "$sweep" --resume "$dir/killed.csv" --jobs 1 > /dev/null 2> "$dir/err" \
    || { echo "FAIL: the final --resume"; cat "$dir/err"; fail=1; }
if ! cmp -s "$dir/whole.csv" "$dir/killed.csv"; then
    echo "FAIL: killed and resumed $kills times, the result differs from the uninterrupted run"
    diff "$dir/whole.csv" "$dir/killed.csv" | head -5
    fail=1
fi
[ "$kills" -ge 15 ] || { echo "FAIL: only $kills of 20 runs were still running when killed"; fail=1; }
exit $fail
