#!/usr/bin/env bash
# Runs every fuzz target on a corpus seeded from data/ (and tests/fuzz/seeds),
# for LIMIT each: "60s" (a time), or "20000" (that many inputs with -seed=1:
# the same inputs on every run of the same binary, as the test suite wants).
# Exit 1 when a target finds a crash, a sanitizer report, an escaped exception,
# a hang (60 s on one input) or runaway memory (2 GB).
# Usage: run.sh BUILD_FUZZ_DIR LIMIT [WORK_DIR]
# SKIP_SEEDS="a.toml b.toml" leaves those data files out of the corpus (a long
# campaign leaves out fe_rotor_100k.toml: each of its mutations builds 100,000 DOFs).
set -u
build=$1 limit=$2
case $limit in
    *s) budget=(-max_total_time="${limit%s}") ;;
    *) budget=(-runs="$limit" -seed=1) ;;
esac
here=$(cd "$(dirname "$0")" && pwd)
data=$(cd "$here/../../data" && pwd)
work=${3:-$(mktemp -d)}
mkdir -p "$work"
seed() {   # seed TARGET FILES...
    local t=$1; shift
    mkdir -p "$work/$t"
    for f in "$@"; do
        case " ${SKIP_SEEDS:-} " in *" $(basename "$f") "*) continue ;; esac
        [ -f "$f" ] && cp "$f" "$work/$t/$(basename "$(dirname "$f")")_$(basename "$f")"; done
}
seed scene "$data"/*.toml
# The exported rotor's scene with its files named from data/.
sed 's|= "\([A-Za-z_]*\.mtx\)"|= "ross_rotor_example/\1"|' "$data/ross_rotor_example/scene.toml" > "$work/scene/ross_scene.toml"
seed matrix_market "$data"/ross_rotor_example/*.mtx
seed bearing_csv "$data"/bearings/*.csv
mkdir -p "$work/sweep"
sed "s|^scene = \"\\(.*\\)\"|scene = \"$data/\\1\"|" "$data/screen_centrifuge.toml" > "$work/sweep/screen_centrifuge.toml"
seed results "$here/seeds/results.csv"
status=0
for t in scene matrix_market bearing_csv sweep results; do
    "$build/tests/fuzz/fuzz_$t" "$work/$t" "${budget[@]}" -timeout=60 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$work/crash_${t}_" > "$work/$t.log" 2>&1
    rc=$?
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/$t.log" | grep -o '[0-9]*$')
    secs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$work/$t.log" | grep -o 'in [0-9]*' | grep -o '[0-9]*$')
    echo "fuzz_$t: ${runs:-?} inputs in ${secs:-?} s, corpus $(ls "$work/$t" | wc -l) files, exit $rc"
    if [ "$rc" -ne 0 ]; then
        status=1
        grep -m 20 -E "ERROR|SUMMARY|terminate|what\(\)|deadly|timeout" "$work/$t.log" | sed 's/^/    /'
        ls "$work"/crash_"${t}"_* 2>/dev/null | sed 's/^/    input: /'
    fi
done
exit $status
