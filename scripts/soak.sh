#!/usr/bin/env bash
# The long soak run: 20,000 random sculpting steps (grabs, brush strokes with every tool, whole-mesh
# remeshes, undo/redo runs) through
# sculpt::Session on several meshes under AddressSanitizer + UndefinedBehaviorSanitizer, with validate(),
# topology and undo/redo-exactness checks (tests/cpp/reliability_soak_test.cpp; ctest runs the same test
# with a short default). Prints per-mesh lines and a closing total: steps, meshes, frames, time, peak RSS
# (VmHWM) and the number of invariant checks passed.
#
#   scripts/soak.sh                    20,000 steps on the default meshes below
# Environment:
#   ADASCULPT_SOAK_STEPS=N       total steps (default 20000), split evenly across the meshes
#   ADASCULPT_SOAK_MESHES=a,b    "icosphere", repo-relative paths or names in ../shared/meshes
#                                (default icosphere,eight.off,hemisphere.off,fandisk.off,rocker_arm.off)
#   ADASCULPT_SOAK_CHECK_EVERY=N validate + topology period (default 100)
#   ADASCULPT_SOAK_RESTART_FACES=N  load a mesh afresh after a check once it has grown past N faces
#                                (default 60000: sculpting keeps refining, and a sanitizer step on 180k
#                                faces costs about ten times one on 20k)
#   ADASCULPT_SOAK_SEED=N        random seed (default 1)
#   ADASCULPT_SOAK_PROGRESS_EVERY=N  a progress line every N steps per mesh (default 500)
#   ADASCULPT_SOAK_BUILD=DIR     a configured sanitizer build to use (default: $ADASCULPT_BUILD_ROOT/asan,
#                                built here with scripts/build.sh asan)
#   ADASCULPT_SOAK_BINARY=FILE   run this adasculpt_tests binary as it is, no build (e.g. a copy taken
#                                before a long run, so that rebuilds in the checkout do not touch it)
# The long run wants the cores to itself or `nice -n 19 scripts/soak.sh` on a shared machine.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=${ADASCULPT_BUILD_ROOT:-build}
BUILD=${ADASCULPT_SOAK_BUILD:-$ROOT/asan}
if [ -n "${ADASCULPT_SOAK_BINARY:-}" ]; then
  BIN=$ADASCULPT_SOAK_BINARY
elif [ -z "${ADASCULPT_SOAK_BUILD:-}" ]; then
  bash scripts/build.sh asan
  BIN=$BUILD/adasculpt_tests
else
  cmake --build "$BUILD" -j "${ADASCULPT_JOBS:-2}"
  BIN=$BUILD/adasculpt_tests
fi
export ADASCULPT_SOAK_STEPS=${ADASCULPT_SOAK_STEPS:-20000}
export ADASCULPT_SOAK_MESHES=${ADASCULPT_SOAK_MESHES:-icosphere,eight.off,hemisphere.off,fandisk.off,rocker_arm.off}
export ADASCULPT_SOAK_CHECK_EVERY=${ADASCULPT_SOAK_CHECK_EVERY:-100}
export ADASCULPT_SOAK_RESTART_FACES=${ADASCULPT_SOAK_RESTART_FACES:-60000}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
echo "soak: $ADASCULPT_SOAK_STEPS steps on $ADASCULPT_SOAK_MESHES (validate every $ADASCULPT_SOAK_CHECK_EVERY, fresh load past $ADASCULPT_SOAK_RESTART_FACES faces), $BIN"
echo "soak: machine $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(uname -sr)"
start=$EPOCHREALTIME
"$BIN" --gtest_filter='ReliabilitySoak.*' --gtest_color=no
awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "soak: wall time %.0f s\n", b - a }'
