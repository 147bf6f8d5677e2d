# Shared by the CLI checks: a scratch directory, a failure flag and `expect`.
# Source it after setting `cli` (the gyrokit binary).
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0

# expect "needle" args... : bad input gives exit status 2, exactly one line on
# stderr containing the needle, and nothing on stdout.
expect() {
    local needle=$1; shift
    "$cli" "$@" > "$dir/out" 2> "$dir/err"
    local rc=$?
    local lines
    lines=$(wc -l < "$dir/err")
    if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || [ -s "$dir/out" ] || ! grep -qF -- "$needle" "$dir/err"; then
        echo "FAIL: gyrokit $* -> exit $rc, $lines stderr lines, expected exit 2 and '$needle'"
        sed 's/^/    /' "$dir/err"
        fail=1
    fi
}
