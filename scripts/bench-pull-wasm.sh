#!/usr/bin/env bash
# The pull scene (issue 18) in the WebAssembly module under node; run by scripts/bench.sh after
# the native benchmarks. Needs public/wasm (scripts/build.sh wasm) and the scene file the native
# benchmark writes (build/bench/pull-scene.json; made here when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/bench/pull-scene.json ] && [ -x build/native/adasculpt_bench ]; then
  build/native/adasculpt_bench --benchmark_filter=BM_PullScene >/dev/null
fi
NODE_PATH=${NODE_PATH:-/usr/share/nodejs} node tests/bench/pull-frame-wasm.mjs "$@"
