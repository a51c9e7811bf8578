#!/usr/bin/env bash
# The embedding example against an installed neomesh, as a user builds it: install the library
# from this build tree into a fresh prefix, build examples/library with find_package(neomesh)
# and run it serially and on 2 processes. Fails if any step fails or if the example reports an
# inverted cell. Usage: build_example.sh BUILD_DIR SOURCE_DIR [MPIEXEC]
set -euo pipefail
build=$1 source=$2 mpiexec=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -f "$work/prefix/include/neomesh/neomesh.hpp"
cmake -S "$source/examples/library" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/example" > "$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
if grep -q "warning" "$work/build.log"; then cat "$work/build.log"; exit 1; fi

check_run() {
  local output=$1
  echo "$output"
  grep -q "^smoothed in" <<< "$output"
  test "$(grep -c "^step " <<< "$output")" = 5
  test "$(grep -c "adapted:.*, 0 inverted" <<< "$output")" = 5
  grep -q "is now at" <<< "$output"
  # The mesh is fitted to the bubble at every step, to round-off.
  test "$(grep -c "fitted: .* within [0-9.]*e-1[0-9]" <<< "$output")" = 5
  test -s moving_bubble.vtu
  grep -q '"interface"' moving_bubble.msh
  rm moving_bubble.vtu moving_bubble.msh
}
cd "$work"
check_run "$("$work/example/moving_bubble")"
if [ -n "$mpiexec" ]; then
  # Its own Open MPI session directory: another mpiexec that ctest -j starts at the same moment
  # could race it to create the default one.
  check_run "$($mpiexec --allow-run-as-root --oversubscribe --mca orte_tmpdir_base "$work/mpi" \
    -n 2 "$work/example/moving_bubble")"
fi
