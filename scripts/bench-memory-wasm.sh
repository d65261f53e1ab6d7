#!/usr/bin/env bash
# Wasm heap per triangle after a load, a grab and a stroke (the figure behind BYTES_PER_FACE in
# web/memory-estimate.js), on generated tori of 0.2M, 1M and 2M triangles (tests/bench/memory-per-face-wasm.mjs).
set -euo pipefail
cd "$(dirname "$0")/.."
node tests/bench/memory-per-face-wasm.mjs "$@"
