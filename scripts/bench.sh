#!/usr/bin/env bash
# Benchmarks (what `npm run bench` runs): numbers to read and report, never pass/fail.
#   npm run bench -- --benchmark_filter=Remesh   extra arguments go to adasculpt_bench
# Runs build/native/adasculpt_bench (Google Benchmark, from tests/bench/*.cpp) when it exists, then every
# scripts/bench-*.sh (e.g. wasm or browser timings). Keep the machine otherwise idle while measuring.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh native
ran=0
if [ -x build/native/adasculpt_bench ]; then
  echo "=== build/native/adasculpt_bench $*"
  build/native/adasculpt_bench "$@"
  ran=1
fi
for b in scripts/bench-*.sh; do
  [ -e "$b" ] || continue
  echo "=== $b"
  bash "$b"
  ran=1
done
((ran)) || echo "no benchmarks yet (tests/bench/*.cpp or scripts/bench-*.sh)"
