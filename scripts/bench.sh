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
  # glibc hands freed blocks of a megabyte or more back to the kernel, so every repetition pays
  # fresh page faults again (about 1,400 per fandisk remesh, some 20 ms on the 2-core VM this is
  # developed on). The benchmark process keeps its freed memory instead, as a long-running app and
  # the browser's wasm heap do; ADASCULPT_BENCH_MALLOC_DEFAULTS=1 measures with glibc's defaults.
  if [ "${ADASCULPT_BENCH_MALLOC_DEFAULTS:-0}" != 1 ]; then
    export GLIBC_TUNABLES=glibc.malloc.mmap_threshold=1073741824:glibc.malloc.trim_threshold=1073741824
    echo "=== freed memory kept in the process (ADASCULPT_BENCH_MALLOC_DEFAULTS=1: glibc's defaults)"
  fi
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
# Stroke scaling and undo memory (tests/bench/stroke_scaling_bench.cpp) run above; docs/undo-and-scaling.md: bash scripts/undo-scaling-doc.sh
