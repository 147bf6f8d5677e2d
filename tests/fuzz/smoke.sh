#!/usr/bin/env bash
# The fuzz targets in the test suite: builds them with clang, ASan and UBSan in
# BUILD/fuzz (library and targets only) and runs each on 20,000 inputs from the
# seeded corpus with a fixed seed. Usage: smoke.sh SOURCE_DIR BUILD_DIR
set -u
src=$1 build=$2/fuzz
command -v clang++ > /dev/null || { echo "FAIL: clang++ is missing (.ci/install-deps.sh installs it)"; exit 1; }
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DGYROKIT_FUZZ=ON -DGYROKIT_BUILD_TESTS=OFF -DGYROKIT_BUILD_PYTHON=OFF > "$build.configure.log" 2>&1 ||
    { cat "$build.configure.log"; exit 1; }
cmake --build "$build" -j2 --target fuzz_scene fuzz_matrix_market fuzz_bearing_csv fuzz_sweep fuzz_results fuzz_solvers \
    > "$build.build.log" 2>&1 || { tail -30 "$build.build.log"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bash "$src/tests/fuzz/run.sh" "$build" 20000 "$work"
