#!/usr/bin/env bash
# The controller package as a user meets it (ctest runs this as `controller_install_test`):
# `cmake --install` into a temporary prefix; the installed header includes the standard library
# only and the library carries no HDF5 or training code; examples/controller configures with
# find_package(vaegail), builds, and walks the walker for one episode: the committed diverse-GAIL
# policy imitating the committed 1 m/s demonstration, from its initial state.
# Usage: src/controller/install_test.sh BUILD_DIR REPO_ROOT
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 BUILD_DIR REPO_ROOT" >&2; exit 2; }
build=$1 root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
header=$tmp/prefix/include/vaegail/controller.h
lib=$(ls "$tmp"/prefix/lib*/libvaegail_controller.so)
ls "$tmp"/prefix/lib*/cmake/vaegail/vaegail-config.cmake >/dev/null

included=$(grep -E '^#include' "$header" | grep -vE '^#include <(memory|string|vector)>$' || true)
[ -z "$included" ] || fail "controller.h includes more than the standard library: $included"
needed=$(objdump -p "$lib" | awk '/NEEDED/ { print $2 }')
! grep -qiE 'hdf5|CLI11' <<< "$needed" || fail "libvaegail_controller needs $(grep -iE 'hdf5|CLI11' <<< "$needed")"
training=$(nm -C "$lib" | grep -E 'Trpo|GailTrainer|VaeTrainer|BehaviorCloning|Discriminator|DemoWriter|H5' || true)
[ -z "$training" ] || fail "libvaegail_controller holds training or HDF5 code: $(head -3 <<< "$training")"
exported=$(nm -DC --defined-only "$lib" | grep ' vaegail::' | grep -v 'vaegail::Controller' || true)
[ -z "$exported" ] || fail "libvaegail_controller exports more than the Controller: $(head -3 <<< "$exported")"

# The library of a sanitizer build (docs/sanitizers.md) needs the sanitizers' runtime loaded before
# any other library: the example links it too.
sanitizers=()
! grep -q '^libasan' <<< "$needed" || sanitizers=(-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined)
cmake -S "$root/examples/controller" -B "$tmp/example" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_BUILD_TYPE=Release \
  "${sanitizers[@]}" >/dev/null
cmake --build "$tmp/example" >/dev/null
out=$("$tmp/example/walker_controller" "$root/models/walker.xml" "$root/examples/controller/walker_demo.txt" \
  "$root/checkpoints/walker/vae/checkpoints/latest.pt" "$root/checkpoints/walker/diverse_gail")
echo "$out"
grep -q '^demonstration: 401 states, mean forward speed 1.0. m/s; z has 20 values$' <<< "$out" || fail "demonstration line"
grep -qE '^policy: 400 steps \(10.0 s\), did not fall' <<< "$out" || fail "the diverse-GAIL policy did not walk the whole episode"
echo "controller_install_test: ok"
