#!/usr/bin/env bash
# The fuzz targets of a sanitized clang build (tests/sanitize.sh builds them in
# its own tree, -DGYROKIT_FUZZ=ON): each run on 20,000 inputs from the seeded
# corpus with a fixed seed. Usage: smoke.sh BUILD_DIR (the tree built with -DGYROKIT_FUZZ=ON)
set -u
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bash "$(dirname "$0")/run.sh" "$build" 20000 "$work"
