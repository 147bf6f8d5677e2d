#!/usr/bin/env bash
# Installs the Debian packages gyrokit builds, tests and plots with.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends \
    g++ make cmake pkgconf \
    libeigen3-dev liblapack-dev liblapacke-dev libblas-dev libarpack2-dev libgsl-dev \
    libtomlplusplus-dev nlohmann-json3-dev libcli11-dev libfmt-dev \
    catch2 gnuplot-nox \
    python3-dev python3-pybind11 python3-numpy python3-scipy python3-pytest python3-pandas python3-matplotlib \
    python3-distributed python3-mypy \
    clang libclang-rt-14-dev \
    procps util-linux \
    > /dev/null
# The report's browser check (tests/report_browser.py, its own stage of .ci/run):
# Debian's chromium, headless, and PIL to read its screenshot.
$sudo apt-get install -y -qq --no-install-recommends chromium python3-pil > /dev/null
# BLIS (serial build) as the libblas.so.3 alternative: vectorized kernels for the
# matrix-vector products of ARPACK's Arnoldi iteration, and safe to call from
# several threads at once (gyrokit solves speeds in parallel). Reference LAPACK
# runs on top of it. A serial OpenBLAS build is not safe for concurrent calls.
$sudo apt-get install -y -qq --no-install-recommends libblis4-serial > /dev/null
