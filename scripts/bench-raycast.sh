#!/usr/bin/env bash
# The brush's picking ray in JS (web/surface-raycast.js through web/slot-ray-tree.js) on the wasm module's
# render buffers, 1 and 16 bunny copies, against the brute force (tests/bench/raycast-wasm.mjs).
set -euo pipefail
cd "$(dirname "$0")/.."
node tests/bench/raycast-wasm.mjs "$@"
