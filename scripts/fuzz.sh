#!/usr/bin/env bash
# Runs the libFuzzer targets (built in the sanitized clang build, build/asan: scripts/build.sh asan; the
# core's objects there carry the fuzzer's coverage hooks) for a bounded time each on its seed corpus
# (tests/fuzz/corpus/<target>/) plus every saved regression input (tests/fuzz/regressions/<target>/),
# ADASCULPT_JOBS targets at a time (libFuzzer itself uses one core).
#
#   scripts/fuzz.sh [target...]        targets: off obj stl ply load_mesh session_file (default: all)
#
# Every input that crashes, leaks, trips UBSan, runs out of memory or hangs is copied to
# tests/fuzz/regressions/<target>/ (commit it: tests/cpp/reliability_fuzz_regressions_test.cpp replays
# every file there under ctest) and the script exits 1. Slow machines do not fail it: the run time is
# bounded, and an input that timed out is re-run alone with a generous limit; only if it still does not
# finish is it reported as a hang. Executions per target are printed in a closing table.
# Environment:
#   ADASCULPT_FUZZ_SECONDS=N    seconds per target (default 10)
#   ADASCULPT_FUZZ_ARGS="..."   extra libFuzzer flags (e.g. "-max_len=65536")
#   ADASCULPT_BUILD_ROOT=DIR    build root (default build): binaries in DIR/asan, working corpora and logs
#                               in DIR/fuzz/work (never written into tests/)
#   ADASCULPT_JOBS=N            targets run at once (default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${ADASCULPT_FUZZ_SECONDS:-10}
ROOT=${ADASCULPT_BUILD_ROOT:-build}
JOBS=${ADASCULPT_JOBS:-2}
BUILD=$ROOT/asan
WORK=$ROOT/fuzz/work
ALL=(off obj stl ply load_mesh session_file)
TARGETS=("$@")
((${#TARGETS[@]})) || TARGETS=("${ALL[@]}")
read -r -a EXTRA <<<"${ADASCULPT_FUZZ_ARGS:-}"

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (apt: clang libclang-rt-14-dev)" >&2; exit 1; }
bash scripts/build.sh asan >/dev/null  # nothing to do when the asan stage built it
[ -x "$BUILD/fuzz_off" ] || { echo "fuzz: $BUILD has no fuzz targets (is it a clang build?)" >&2; exit 1; }

# libFuzzer's own options. -timeout: one input; -rss_limit_mb: also the per-allocation limit, so a reader
# that believes an absurd header count and allocates gigabytes is a finding.
FUZZ_FLAGS=(-max_total_time="$SECONDS_PER_TARGET" -rss_limit_mb=2048 -timeout=5 -print_final_stats=1
            -close_fd_mask=1)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# Copies an artifact into the regression folder unless a file with the same bytes is already there
# (a saved input that still crashes is reported again under a new name); prints the saved path.
keep() {  # artifact, target
  local f
  for f in "tests/fuzz/regressions/$2/"*; do
    [ -f "$f" ] && cmp -s "$f" "$1" && { echo "$f (already saved)"; return; }
  done
  cp "$1" "tests/fuzz/regressions/$2/$(basename "$1")"
  echo "tests/fuzz/regressions/$2/$(basename "$1")"
}

run_target() {  # target: runs it, leaves the exit code in $WORK/<t>/rc
  local t=$1 bin=$BUILD/fuzz_$1 dict=()
  [ -f "tests/fuzz/dict/$t.dict" ] && dict=(-dict="tests/fuzz/dict/$t.dict")
  local rc=0
  # The first corpus dir is the writable working corpus; seeds and regressions are read only.
  "$bin" "${FUZZ_FLAGS[@]}" "${dict[@]}" "${EXTRA[@]}" -artifact_prefix="$WORK/$t/artifacts/" \
    "$WORK/$t/corpus" "tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t" >"$WORK/$t/log.txt" 2>&1 || rc=$?
  echo "$rc" >"$WORK/$t/rc"
}

for t in "${TARGETS[@]}"; do
  [ -x "$BUILD/fuzz_$t" ] || { echo "fuzz: unknown target '$t' (known: ${ALL[*]})" >&2; exit 2; }
  mkdir -p "$WORK/$t/corpus" "$WORK/$t/artifacts" "tests/fuzz/regressions/$t"
  rm -f "$WORK/$t/artifacts/"* "$WORK/$t/rc"
done
echo "=== fuzz ${TARGETS[*]} (${SECONDS_PER_TARGET} s each, $JOBS at a time)"
running=0
for t in "${TARGETS[@]}"; do
  if ((running >= JOBS)); then wait -n; running=$((running - 1)); fi
  run_target "$t" &
  running=$((running + 1))
done
wait

failed=()
rows=()
for t in "${TARGETS[@]}"; do
  bin=$BUILD/fuzz_$t
  log=$WORK/$t/log.txt
  rc=$(cat "$WORK/$t/rc" 2>/dev/null || echo 99)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1 || true)
  cov=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 | cut -d' ' -f2 || true)
  verdict=ok
  for a in "$WORK/$t/artifacts/"*; do
    [ -e "$a" ] || continue
    name=$(basename "$a")
    case $name in
      slow-unit-*) continue ;;  # informational only
      timeout-*)
        # A loaded machine can make a legitimate input slow: re-run it alone with a generous limit.
        if "$bin" -timeout=60 -rss_limit_mb=2048 "$a" >"$a.rerun.txt" 2>&1; then
          echo "fuzz $t: $name took over 5 s but finished alone (slow machine?): kept as a regression input"
          keep "$a" "$t"
          continue
        fi ;;
    esac
    echo "fuzz $t: FINDING $name -> $(keep "$a" "$t")" >&2
    verdict=FINDING
  done
  if [ "$verdict" = ok ] && [ "$rc" -ne 0 ]; then
    verdict="FAILED (exit $rc)"  # libFuzzer failed without an artifact (e.g. the binary could not start)
  fi
  if [ "$verdict" != ok ]; then
    grep -E '^==[0-9]+==ERROR|SUMMARY|runtime error|fuzz\[|out-of-memory|timeout after' "$log" | head -5 >&2 || true
    echo "fuzz $t: full log in $log" >&2
    failed+=("$t")
  fi
  rows+=("$(printf '%-13s %10s %6s  %s' "$t" "${execs:-?}" "${cov:-?}" "$verdict")")
done

echo "=== fuzz summary (${SECONDS_PER_TARGET} s per target)"
printf '%-13s %10s %6s  %s\n' target executions cov result
printf '%s\n' "${rows[@]}"
if ((${#failed[@]})); then
  echo "fuzz: findings in: ${failed[*]} (inputs saved under tests/fuzz/regressions/; replay: build/.../adasculpt_tests --gtest_filter='*ReliabilityFuzz*')" >&2
  exit 1
fi
