#!/usr/bin/env bash
# Every file a command writes goes through the library's one output guard. The
# writing options are taken from the help of every command (the "Output files"
# group), not from a list kept here: each is pointed at an input of the run, at a
# symbolic link and a hard link to it, and at another output of the same run. Each
# must be refused (exit 2, one line naming the option) with the input unchanged.
# Then a failed write leaves the old file byte-identical, and a scene in a bare
# file name resolves the files it names from the working folder.
set -u
cli=$(readlink -f "$1")
data=$2
source "$(dirname "$0")/cli_lib.sh"

w=$dir/w
mkdir -p "$w/ross"
cp "$data/three_disk_rotor.toml" "$data/centrifuge.toml" "$data/screen_centrifuge.toml" "$data/fluid_N2.toml" \
   "$data/balancer_bild7.toml" "$data/sommerfeld_rotor.toml" "$w/"
cp "$data"/ross_rotor_example/*.mtx "$data/ross_rotor_example/scene.toml" "$w/ross/"
# Speeds below are written in rad/s, the unit of a scene whose [speeds] name none.
sed -i 's/^units = "rpm"/units = "rad\/s"/' "$w/three_disk_rotor.toml"

# How to run each command that writes files, quickly: its input first.
declare -A recipe=(
    [campbell]="$w/three_disk_rotor.toml --speeds 0:1000:11"
    [modes]="$w/three_disk_rotor.toml --speed 100"
    [model]="$w/three_disk_rotor.toml"
    [response]="$w/three_disk_rotor.toml --speeds 0:1000:11"
    [frf]="$w/three_disk_rotor.toml --speed 100 --input y3 --frequencies 10:1000:5"
    [static]="$w/three_disk_rotor.toml"
    [critical-map]="$w/three_disk_rotor.toml --stiffness 1e6:1e8:3"
    [level1]="$w/three_disk_rotor.toml --mcs 1000 --qa 1e6 --intervals 4"
    [api-unbalance]="$w/three_disk_rotor.toml --mcs 1000 --min-speed 700 --trip-speed 1050 --speeds 41"
    [transient]="$w/three_disk_rotor.toml --speed 100 --node 3 --duration 0.02"
    [export]="$w/ross/scene.toml --speed 10"
    [fluid]="$w/fluid_N2.toml --fill 0.1:0.5:3"
    [balancer]="$w/balancer_bild7.toml --simulate --duration 0.05"
    [sommerfeld]="$w/sommerfeld_rotor.toml"
    [screen]="$w/screen_centrifuge.toml --limit 2"
    [report]="$w/centrifuge.toml --mode-shapes 1"
)

# refused NEEDLE INPUT ARGS...: exit 2, the needle on stderr, INPUT byte-identical.
refused() {
    local needle=$1 input=$2; shift 2
    cp "$input" "$dir/before"
    "$cli" "$@" > "$dir/out" 2> "$dir/err"
    local rc=$?
    if [ "$rc" -ne 2 ] || ! grep -qF -- "$needle" "$dir/err" || ! cmp -s "$input" "$dir/before"; then
        echo "FAIL: gyrokit $* -> exit $rc, expected exit 2, '$needle' and $input unchanged"
        sed 's/^/    /' "$dir/err"
        fail=1
    fi
}

commands=$("$cli" --help | awk '/^Subcommands:/ {on = 1; next} on && !NF {on = 0} on && NF {print $1}')
[ -n "$commands" ] || { echo "FAIL: no commands in gyrokit --help"; exit 1; }
checked=0
for cmd in $commands; do
    opts=$("$cli" "$cmd" --help | awk '/^Output files:/ {on = 1; next} on && !NF {on = 0} on && $1 ~ /^--/ {print $1 ":" $2}')
    [ -n "$opts" ] || continue
    if [ -z "${recipe[$cmd]:-}" ]; then
        echo "FAIL: gyrokit $cmd writes files ($opts) but this test has no recipe to run it"
        fail=1
        continue
    fi
    # shellcheck disable=SC2206
    args=(${recipe[$cmd]})
    input=${args[0]}
    # The command writes its first file option to a new path: a recipe that fails is this test's fault.
    o=${opts%%$'\n'*}
    "$cli" "$cmd" "${args[@]}" "${o%%:*}" "$w/fresh_$cmd.svg" > /dev/null 2> "$dir/err" || {
        echo "FAIL: recipe of $cmd does not run: ${args[*]} ${o%%:*} $w/fresh_$cmd.svg"; sed 's/^/    /' "$dir/err"
        fail=1; continue; }
    [ -e "$w/fresh_$cmd.svg" ] || { echo "FAIL: $cmd ${o%%:*} wrote nothing"; fail=1; }
    first=""
    for o in $opts; do
        opt=${o%%:*} kind=${o#*:}
        checked=$((checked + 1))
        rm -f "$w/link.svg" "$w/hard.svg" "$w/linkdir"
        if [ "$kind" = DIR ]; then
            # A folder of outputs: the folder the scene's matrices are in, directly and through a link.
            folder=$(dirname "$input")
            ln -s "$folder" "$w/linkdir"
            refused "input of this run" "$folder/M.mtx" "$cmd" "${args[@]}" "$opt" "$folder"
            refused "input of this run" "$folder/M.mtx" "$cmd" "${args[@]}" "$opt" "$w/linkdir"
            continue
        fi
        ln -s "$input" "$w/link.svg"
        ln "$input" "$w/hard.svg"
        refused "input of this run" "$input" "$cmd" "${args[@]}" "$opt" "$w/link.svg"
        refused "input of this run" "$input" "$cmd" "${args[@]}" "$opt" "$w/hard.svg"
        [ -L "$w/link.svg" ] || { echo "FAIL: $cmd $opt replaced the link"; fail=1; }
        case "$opt" in --plot|--waterfall) ;; *)
            refused "input of this run" "$input" "$cmd" "${args[@]}" "$opt" "$input" ;;
        esac
        # Another output of the same run: the first file option and this one on one file.
        if [ -n "$first" ]; then
            echo "keep" > "$w/other.svg"
            refused "another output of this run" "$w/other.svg" "$cmd" "${args[@]}" "$first" "$w/other.svg" "$opt" "$w/other.svg"
        fi
        [ -z "$first" ] && [ "$opt" != --resume ] && first=$opt
    done
done
[ "$checked" -ge 14 ] || { echo "FAIL: only $checked file options found in the help"; fail=1; }

# A symbolic link to a file that is no input: written through, the link kept.
echo old > "$w/target.svg"
ln -sf "$w/target.svg" "$w/through.svg"
"$cli" campbell "$w/three_disk_rotor.toml" --speeds 0:1000:11 --plot "$w/through.svg" > /dev/null 2>&1 || {
    echo "FAIL: --plot through a link to a new file"; fail=1; }
if [ ! -L "$w/through.svg" ] || ! grep -q "<svg" "$w/target.svg"; then
    echo "FAIL: --plot through a link: the link was replaced or its target not written"; fail=1
fi

# A failed write leaves the old file byte-identical and no temporary file behind:
# a file size limit (EFBIG with SIGXFSZ ignored) stands in for a full disk.
printf 'old rows\n' > "$w/history.csv"
cp "$w/history.csv" "$dir/before"
(trap '' XFSZ; ulimit -f 4; exec "$cli" transient "$w/three_disk_rotor.toml" --speed 100 --node 3 --duration 0.2 \
    --out "$w/history.csv") > /dev/null 2> "$dir/err"
rc=$?
if [ "$rc" -ne 1 ] || ! cmp -s "$w/history.csv" "$dir/before" || ! grep -qF -- "--out $w/history.csv" "$dir/err"; then
    echo "FAIL: a failed write of --out: exit $rc (expected 1), the old file changed or the message names no file"
    sed 's/^/    /' "$dir/err"; fail=1
fi
if ls -a "$w" | grep -q '^\.history\.csv\..*\.tmp$'; then echo "FAIL: a temporary file was left behind"; fail=1; fi

# A read-only folder: refused before the run, the old file byte-identical. Root writes
# anywhere, so the command runs as nobody where the test runs as root.
ro=$(mktemp -d)
cp "$data/three_disk_rotor.toml" "$ro/"
printf 'old rows\n' > "$ro/history.csv"
chmod 644 "$ro"/*
chmod 555 "$ro"
as_user=()
[ "$(id -u)" -eq 0 ] && command -v setpriv > /dev/null && as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
if [ "$(id -u)" -ne 0 ] || [ ${#as_user[@]} -gt 0 ]; then
    "${as_user[@]}" "$cli" transient "$ro/three_disk_rotor.toml" --speed 100 --node 3 --duration 0.02 \
        --out "$ro/history.csv" > /dev/null 2> "$dir/err"
    rc=$?
    if [ "$rc" -ne 2 ] || [ "$(cat "$ro/history.csv")" != "old rows" ] || ! grep -q "is not writable" "$dir/err"; then
        echo "FAIL: --out into a read-only folder: exit $rc (expected 2), or the old file changed"
        sed 's/^/    /' "$dir/err"; fail=1
    fi
fi
chmod 755 "$ro"
rm -rf "$ro"

# A scene named by a bare file name resolves its matrices from the working folder.
(cd "$w/ross" && "$cli" eig scene.toml --speed 1 > /dev/null 2> "$dir/err") || {
    echo "FAIL: eig scene.toml from the scene's own folder"; sed 's/^/    /' "$dir/err"; fail=1; }

# The base scene edited while a study runs: the run exits 2, its result file ends in a
# trailer that says so, and --resume and --merge refuse the file.
mkdir -p "$w/edit"
cp "$data/centrifuge.toml" "$w/edit/"
sed 's/^count = 6$/count = 400/' "$data/screen_centrifuge.toml" > "$w/edit/sweep.toml"
"$cli" screen "$w/edit/sweep.toml" --jobs 1 --limit 300 --out "$w/edit/rows.csv" > /dev/null 2> "$w/edit/err" &
pid=$!
for _ in $(seq 1 500); do
    [ "$(wc -l < "$w/edit/rows.csv" 2> /dev/null || echo 0)" -ge 6 ] && break
    sleep 0.02
done
if kill -0 "$pid" 2> /dev/null; then
    echo "# edited while the study runs" >> "$w/edit/centrifuge.toml"
    wait "$pid"
    rc=$?
    if [ "$rc" -ne 2 ] || ! grep -q "centrifuge.toml: the scene file changed during the run" "$w/edit/err" ||
       ! tail -n 1 "$w/edit/rows.csv" | grep -q "^# inputs changed during the run:"; then
        echo "FAIL: a scene edited during screen: exit $rc (expected 2), message or trailer missing"
        sed 's/^/    /' "$w/edit/err"; tail -n 1 "$w/edit/rows.csv"; fail=1
    fi
    # The scene back as it was: the study's identity matches again, the trailer still refuses.
    cp "$data/centrifuge.toml" "$w/edit/centrifuge.toml"
    refused "saw an input change while it ran" "$w/edit/rows.csv" screen "$w/edit/sweep.toml" --resume "$w/edit/rows.csv"
    refused "saw an input change while it ran" "$w/edit/rows.csv" screen "$w/edit/sweep.toml" --merge "$w/edit/rows.csv"
else
    echo "FAIL: the study ended before the edit (300 designs in under the poll time)"; fail=1
fi

[ "$fail" -eq 0 ] && echo "cli_outputs: $checked file options refused onto inputs, links and each other"
exit "$fail"
