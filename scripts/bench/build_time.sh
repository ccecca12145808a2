#!/usr/bin/env bash
# A clean build's time, each file its own translation unit and then in unity batches
# (-DVAEGAIL_UNITY=OFF, then ON): for each, a fresh configure and `cmake --build -j JOBS` of every
# stage into a scratch folder, with ccache off, and the wall-clock and CPU (user + system) seconds
# it took. docs/benchmarks.md, "Build time". Nothing else should run meanwhile: anything that does
# shares the cores with the builds.
# Usage: scripts/bench/build_time.sh [JOBS]   (default: the number of cores; about 31 minutes on 2)
set -euo pipefail
cd "$(dirname "$0")/../.."
jobs=${1:-$(nproc)}
scratch=$(mktemp -d /tmp/vaegail_build_time.XXXXXX)
trap 'rm -rf "$scratch"' EXIT
stages="util;env;data;rl;experts;vae;gail;eval;render;bench;cli;controller"

TIMEFORMAT='%R %U %S'  # bash's `time`: wall, user and system seconds of the command and its children
for unity in OFF ON; do
  dir=$scratch/build_unity_$unity
  { time CCACHE_DISABLE=1 cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DVAEGAIL_UNITY=$unity \
      -DVAEGAIL_STAGES="$stages" > "$scratch/configure.log" 2>&1; } 2> "$scratch/configure_time"
  { time CCACHE_DISABLE=1 cmake --build "$dir" -j "$jobs" > "$scratch/build.log" 2>&1; } 2> "$scratch/build_time" ||
    { tail -20 "$scratch/build.log" >&2; exit 1; }
  read -r configure _ < "$scratch/configure_time"
  read -r wall user sys < "$scratch/build_time"
  awk -v unity="$unity" -v c="$configure" -v w="$wall" -v u="$user" -v s="$sys" -v j="$jobs" -v load="$(cut -d' ' -f1 /proc/loadavg)" \
    'BEGIN { printf "VAEGAIL_UNITY=%-3s  configure %5.1f s  build %5.0f s wall (%4.1f min), %5.0f s CPU  (-j %s, load %s at the end)\n", unity, c, w, w / 60, u + s, j, load }'
  rm -rf "$dir"
done
