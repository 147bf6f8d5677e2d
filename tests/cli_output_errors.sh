#!/usr/bin/env bash
# Output is never lost silently: a full disk (/dev/full) on stdout or on a result
# file gives exit status 1 and one line on stderr, for every kind of writer.
set -u
cli=$1
data=$2
source "$(dirname "$0")/cli_lib.sh"

full() {   # full ARGS...: stdout on a full disk must fail with one error line
    "$cli" "$@" > /dev/full 2> "$dir/err"
    local rc=$?
    if [ "$rc" -ne 1 ] || ! grep -q "^error: .*write" "$dir/err"; then
        echo "FAIL: gyrokit $* > /dev/full -> exit $rc"; sed 's/^/    /' "$dir/err"; fail=1
    fi
}

full eig "$data/centrifuge.toml" --speed 20
full critical "$data/centrifuge.toml"
full critical "$data/centrifuge.toml" --format json
full fluid "$data/fluid_N2.toml"
full balancer "$data/balancer_table1.toml"
full screen "$data/screen_centrifuge.toml" --format csv
full screen "$data/screen_centrifuge.toml" --format json
# A result file on a full disk: while running, and when merging.
"$cli" screen "$data/screen_centrifuge.toml" --out "$dir/rows.csv" > /dev/null 2>&1 || { echo "FAIL: screen --out"; fail=1; }
for args in "screen $data/screen_centrifuge.toml --out /dev/full" \
            "screen $data/screen_centrifuge.toml --merge $dir/rows.csv --out /dev/full"; do
    # shellcheck disable=SC2086
    "$cli" $args > /dev/null 2> "$dir/err"
    rc=$?
    if [ "$rc" -eq 0 ] || ! grep -q "write failed" "$dir/err"; then
        echo "FAIL: gyrokit $args -> exit $rc"; sed 's/^/    /' "$dir/err"; fail=1
    fi
done
exit $fail
