#!/usr/bin/env bash
# Brushes side by side with three.js's Sculptor addon (issue #7): the same strokes on the same meshes
# through both in one node process, quality of the brushed region and ms per stamp, as a markdown table.
# Uses the wasm module in public/wasm (skips with a message when it is absent) and, for the native
# column, build/native/adasculpt when it exists. Arguments go to tests/bench/sculptor-compare.mjs
# (--repeats N, --detail D, --quick); `npm run bench` runs it with ADASCULPT_SCULPTOR_ARGS (default none).
set -euo pipefail
cd "$(dirname "$0")/.."
# shellcheck disable=SC2086
exec node tests/bench/sculptor-compare.mjs ${ADASCULPT_SCULPTOR_ARGS:-} "$@"
