#!/usr/bin/env bash
# Incremental autosave figures in the wasm module (tests/bench/autosave-wasm.mjs): the time and size
# of one stroke's record on the dragon, and the restore of a whole state plus records.
set -euo pipefail
cd "$(dirname "$0")/.."
node tests/bench/autosave-wasm.mjs "$@"
