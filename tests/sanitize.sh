#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer, in a
# second build folder (default build-sanitize), built with clang so that the fuzz
# targets (libFuzzer needs clang) are built from the same tree and run as the test
# fuzz_smoke. Python is off (the interpreter is not instrumented); install_examples
# is left to the main build, and so are the tests labelled `slow`. A sanitizer report
# makes the test that hit it fail.
# Usage: sanitize.sh [BUILD_DIR]
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$src/build-sanitize}
# RelWithDebInfo's -O2 (Eigen's kernels want the inlining) with line tables only (CMakeLists.txt).
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" \
    -DGYROKIT_SANITIZE=ON -DGYROKIT_FUZZ=ON -DGYROKIT_BUILD_PYTHON=OFF
cmake --build "$build" -j2
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The `slow` tests (numerical repeats of the fast ones' code paths over every data/ scene)
# run in the Release stages only; the fuzz smoke run (label `fuzz`) runs here.
ctest --test-dir "$build" --output-on-failure -j2 -LE slow
