#!/usr/bin/env bash
# Installs gyrokit into a temporary prefix, builds examples/ against it with
# find_package(gyrokit) only (and one example through pkg-config), and runs them.
# Usage: install_examples.sh BUILD_DIR SOURCE_DIR
set -u
build=$1 src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$dir/prefix" > "$dir/install.log" || { cat "$dir/install.log"; fail "cmake --install"; }
[ -f "$dir/prefix/include/gyrokit/gyrokit.hpp" ] || fail "umbrella header not installed"
for f in gyrokitConfig.cmake gyrokitConfigVersion.cmake gyrokit-targets.cmake gyrokit.pc; do
    [ -n "$(find "$dir/prefix" -name "$f")" ] || fail "not installed: $f"
done
[ -n "$(find "$dir/prefix" -name 'libgyrokit.a')" ] || fail "no static library installed"
[ -n "$(find "$dir/prefix" -name 'libgyrokit.so*')" ] || fail "no shared library installed"
# No private glue in the public headers: they must compile without toml++, fmt, LAPACKE or ARPACK.
if grep -rlE '#include <(toml\+\+|fmt/|lapacke|arpack|nlohmann|gsl/)' "$dir/prefix/include/gyrokit"; then
    fail "a public header includes a private dependency"
fi

cmake -S "$src/examples" -B "$dir/examples" -DCMAKE_PREFIX_PATH="$dir/prefix" -DCMAKE_BUILD_TYPE=Release \
    > "$dir/configure.log" 2>&1 || { cat "$dir/configure.log"; fail "configure examples"; }
cmake --build "$dir/examples" -j2 > "$dir/build.log" 2>&1 || { cat "$dir/build.log"; fail "build examples"; }

run() {
    "$@" > "$dir/out" 2>&1 || { cat "$dir/out"; fail "$*"; }
    cat "$dir/out"
}
libdir=$(dirname "$(find "$dir/prefix" -name 'libgyrokit.so' | head -1)")
export LD_LIBRARY_PATH="$libdir"
run "$dir/examples/gyrostat_campbell"
run "$dir/examples/own_matrices"
run "$dir/examples/own_matrices_static"
run "$dir/examples/critical_speeds" "$src/data/centrifuge.toml"
grep -q "rad/s" "$dir/out" || fail "critical_speeds printed no critical speed"
run "$dir/examples/rotor_in_code" "$src/data/three_disk_rotor.toml"
grep -q "critical speed" "$dir/out" || fail "rotor_in_code printed no critical speed"
# Its scene, written by the library, is the scene file's rotor for the CLI too.
"$dir/examples/rotor_in_code" "$src/data/three_disk_rotor.toml" --write > "$dir/written.toml" || fail "rotor_in_code --write"
run "$dir/examples/rotor_in_code" "$dir/written.toml"

# pkg-config: the same example from the .pc file alone (--define-prefix: the prefix is where the .pc file was installed).
export PKG_CONFIG_PATH="$libdir/pkgconfig"
# shellcheck disable=SC2046
c++ -O1 -o "$dir/own_matrices_pc" "$src/examples/own_matrices.cpp" $(pkg-config --define-prefix --cflags --libs gyrokit) \
    || fail "pkg-config build"
run "$dir/own_matrices_pc"
# Every C++ snippet of docs/ compiles against the installed package and runs (from the source folder: data/).
/usr/bin/python3 "$src/tests/doc_snippets.py" "$src" "$dir/doc_snippets.cpp" || fail "docs snippets: extraction"
# shellcheck disable=SC2046
c++ -std=c++17 -O0 -o "$dir/doc_snippets" "$dir/doc_snippets.cpp" $(pkg-config --define-prefix --cflags --libs gyrokit) \
    > "$dir/out" 2>&1 || { cat "$dir/out"; cat -n "$dir/doc_snippets.cpp"; fail "the C++ of docs/ does not compile"; }
(cd "$src" && "$dir/doc_snippets") || fail "the C++ of docs/ failed"
# The Python package from the installed prefix alone (when the build has it).
if [ -f "$build/python/gyrokit/__init__.py" ]; then
    site=$(dirname "$(find "$dir/prefix" -path '*/gyrokit/__init__.py' | head -1)")
    [ -n "$site" ] && [ "$site" != "." ] || fail "the Python package is not installed"
    PYTHONPATH=$(dirname "$site") /usr/bin/python3 -c "import gyrokit; print('python', gyrokit.__version__, gyrokit.eig(gyrokit.load_scene('$src/data/centrifuge.toml'), 20.0).eigenvalues.size, 'modes')" \
        > "$dir/out" 2>&1 || { cat "$dir/out"; fail "import gyrokit from the prefix"; }
    cat "$dir/out"
fi
echo "install and examples: ok"
