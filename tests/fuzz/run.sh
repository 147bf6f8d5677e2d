#!/usr/bin/env bash
# Runs every fuzz target on a corpus seeded from data/ (and tests/fuzz/seeds),
# for LIMIT each: "60s" (a time), or "20000" (that many inputs with -seed=1:
# the same inputs on every run of the same binary, as the test suite wants).
# Exit 1 when a target finds a crash, a sanitizer report, an escaped exception,
# a hang (60 s on one input) or runaway memory (2 GB).
# Usage: run.sh BUILD_FUZZ_DIR LIMIT [WORK_DIR]
# SKIP_SEEDS="a.toml b.toml" leaves those data files out of the corpus (a long
# campaign leaves out fe_rotor_100k.toml: each of its mutations builds 100,000 DOFs).
# Inputs up to 2 MiB; LONG_SEEDS=1 adds a seed of 1 to 2 MiB per reader (a
# scene, a matrix, a bearing table, a sweep and a result file of that size).
# TARGETS="solvers scene" runs only those targets, in that order.
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
# Small models for the solvers: DOF count, shape bits, then two bytes per entry
# (docs/reliability.md, "Fuzzing the readers").
mkdir -p "$work/solvers"
printf '\x01\x1b\x05\x1e\x00\x00\x00\x00\x05\x22\x00\x00\x09\x1e' > "$work/solvers/one_dof"
printf '\x02\xff%s' "$(head -c 200 /dev/zero | tr '\0' '\005')" > "$work/solvers/two_dof_all"
printf '\x04\x5a%s' "$(head -c 300 /dev/zero | tr '\0' '\035')" > "$work/solvers/four_dof"
if [ "${LONG_SEEDS:-0}" = 1 ]; then
    big=1100000
    { cat "$data/fe_rotor.toml"; yes '# a long comment line of a scene file, repeated to pass one mebibyte' | head -c $big; } \
        > "$work/scene/long_scene.toml"
    { echo '%%MatrixMarket matrix coordinate real general'; echo '20000 20000 60000'
      awk 'BEGIN { for (i = 1; i <= 60000; i++) printf "%d %d %.17g\n", (i % 20000) + 1, ((7 * i + int(i / 20000)) % 20000) + 1, i / 3.0 }'; } \
        > "$work/matrix_market/long.mtx"
    { echo 'speed,dof_x,dof_y,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy'
      awk 'BEGIN { for (i = 0; i < 30000; i++) printf "%d,0,1,%.9g,0,0,%.9g,2000,0,0,2400\n", i, 2e7 + i, 1.5e7 + i }'; } \
        > "$work/bearing_csv/long.csv"
    sed '/^values = /d' "$work/sweep/screen_centrifuge.toml" |
        awk '{ print } /^name = "model.d_G"/ { printf "values = ["
               for (i = 0; i < 120000; i++) printf "%s%.6f", (i ? ", " : ""), i / 1000.0; print "]" }' \
        > "$work/sweep/long_sweep.toml"
    { head -1 "$here/seeds/results.csv"
      awk 'BEGIN { for (i = 0; i < 13000; i++) printf "%d,150,0,18.6676024482,22.2183231327,,,0.00243578587443,24,pass,,all criteria met\n", i }'; } \
        > "$work/results/long.csv"
fi
status=0
for t in ${TARGETS:-scene matrix_market bearing_csv sweep results solvers}; do
    "$build/tests/fuzz/fuzz_$t" "$work/$t" "${budget[@]}" -max_len=2097152 -timeout=60 -rss_limit_mb=2048 \
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
