#!/usr/bin/env bash
# The whole test pipeline (what `npm test` and CI run):
#   setup → native build → ctest → ASan build → ctest under ASan/UBSan → fuzzers (scripts/fuzz.sh) → wasm build
#   → node --test tests/js/ → tsc on the declarations (tests/types) → vite build → playwright (headless Debian
#   Chromium; e2e/addon-host.spec.mjs also packs the npm package and builds a host project with it)
# Prints one "[stage] name: N s" line per stage and a summary; any failure stops the run with a non-zero exit.
# Environment:
#   ADASCULPT_SKIP="asan e2e"   stages to skip (names: native asan fuzz wasm js types web e2e); for quick local runs only
#   ADASCULPT_ASAN_FILTER=REGEX  only the ctest tests matching REGEX under ASan (default: all)
#   ADASCULPT_CTEST_ARGS="..."   extra ctest arguments for both ctest runs (e.g. "-R Remesh")
#   ADASCULPT_BUILD_ROOT=DIR     private build dirs (default build), ADASCULPT_PUBLISH_WASM=OFF, ADASCULPT_E2E_PORT:
#                                see scripts/build.sh and playwright.config.mjs
set -euo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
JOBS=${ADASCULPT_JOBS:-2}
ROOT=${ADASCULPT_BUILD_ROOT:-build}   # shared with scripts/build.sh
SKIP=" ${ADASCULPT_SKIP:-} "
read -r -a CTEST_EXTRA <<<"${ADASCULPT_CTEST_ARGS:-}"

summary=()
since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
t_all=$EPOCHREALTIME
stage() {  # name, command...
  local name=$1; shift
  local t0=$EPOCHREALTIME
  echo "=== [stage] $name"
  if "$@"; then
    local dt; dt=$(since "$t0")
    echo "[stage] $name: ${dt} s"
    summary+=("$(printf '%-14s %7s s' "$name" "$dt")")
  else
    local rc=$?
    echo "[stage] $name: FAILED (exit $rc)" >&2
    exit "$rc"
  fi
}
skipped() { [[ "$SKIP" == *" $1 "* ]]; }
note() { echo "[stage] $1: skipped ($2)"; summary+=("$(printf '%-14s %9s' "$1" skipped)"); }

has_files() {  # dir, find -name patterns...: true when any file matches
  local dir=$1; shift
  [ -d "$dir" ] && [ -n "$(find "$dir" -type f \( "$@" \) -print -quit)" ]
}

run_ctest() {  # build dir, extra args...
  local dir=$1; shift
  if [ ! -x "$dir/adasculpt_tests" ]; then
    echo "no tests/cpp/*.cpp yet: nothing for ctest"; return 0
  fi
  ctest --test-dir "$dir" --output-on-failure --no-tests=error -j "$JOBS" "${CTEST_EXTRA[@]}" "$@"
}

asan_ctest() {
  local args=()
  [ -n "${ADASCULPT_ASAN_FILTER:-}" ] && args=(-R "$ADASCULPT_ASAN_FILTER")
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:check_initialization_order=1} \
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    run_ctest "$ROOT/asan" "${args[@]}"
}

stage setup bash scripts/setup.sh

if skipped native; then note native "ADASCULPT_SKIP"; else
  stage native-build bash scripts/build.sh native
  stage native-ctest run_ctest "$ROOT/native"
fi

if skipped asan; then note asan "ADASCULPT_SKIP"; else
  stage asan-build bash scripts/build.sh asan
  stage asan-ctest asan_ctest
fi

# libFuzzer on every reader and the session-file parser, bounded (ADASCULPT_FUZZ_SECONDS per target,
# default 10); fails only on a finding (crash, leak, UB, OOM, hang), never on a slow machine.
if skipped fuzz; then note fuzz "ADASCULPT_SKIP"; else
  stage fuzz bash scripts/fuzz.sh
fi

if skipped wasm; then note wasm "ADASCULPT_SKIP"; else
  stage wasm-build bash scripts/build.sh wasm
fi

if skipped js; then note node-test "ADASCULPT_SKIP"
elif ! has_files tests/js -name '*.test.js' -o -name '*.test.cjs' -o -name '*.test.mjs'; then note node-test "no tests/js/*.test.*"
else stage node-test node --test tests/js/
fi

# The hand-written TypeScript declarations (web/*.d.ts, the JS API's reference) against an example host.
if skipped types; then note types "ADASCULPT_SKIP"
else stage types npx tsc -p tests/types
fi

if skipped web; then note vite-build "ADASCULPT_SKIP"
elif [ ! -f web/index.html ]; then note vite-build "no web/index.html"
else stage vite-build npx vite build --logLevel warn
fi

if skipped e2e; then note playwright "ADASCULPT_SKIP"
elif [ ! -f web/index.html ] || ! has_files e2e -name '*.spec.*' -o -name '*.test.*'; then note playwright "no e2e tests or no web/index.html"
else stage playwright npx playwright test
fi

total=$(since "$t_all")
echo "=== stage timings"
printf '%s\n' "${summary[@]}"
echo "total: ${total} s"
