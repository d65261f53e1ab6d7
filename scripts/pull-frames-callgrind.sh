#!/usr/bin/env bash
# Instructions per frame of the pull benchmarks (issue 18) under callgrind: the load-independent
# figure of the frame-time tail (wall and CPU time on a shared 2-core machine move by 2x with the
# load; instruction counts do not). Each frame of each run is dumped by the benchmark
# (ADASCULPT_PULL_FRAMES) and counted from Session::grab_drag down (the drag alone: not the press,
# not the scene's set-up). Prints median / p95 / max per benchmark, and with -v every frame's
# count and its phases (field solve, refinement, region iteration, sizing measurement).
#   bash scripts/pull-frames-callgrind.sh [-v] [benchmark regex]   (default: BM_PullFrame/)
# ADASCULPT_BENCH: another build of adasculpt_bench (e.g. a copy of the one before a change).
# About 1-2 minutes per scene on this machine (the set-up's whole-mesh remesh dominates).
set -euo pipefail
cd "$(dirname "$0")/.."
verbose=0
if [ "${1:-}" = -v ]; then verbose=1; shift; fi
filter=${1:-BM_PullFrame/}
command -v valgrind >/dev/null || { echo "pull-frames-callgrind: valgrind not installed" >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
GLIBC_TUNABLES=glibc.malloc.mmap_threshold=1073741824:glibc.malloc.trim_threshold=1073741824 ADASCULPT_PULL_FRAMES=1 \
  valgrind --tool=callgrind --callgrind-out-file="$dir/cg.out" "${ADASCULPT_BENCH:-build/native/adasculpt_bench}" --benchmark_filter="$filter" \
  >"$dir/log" 2>&1 || { tail -20 "$dir/log"; exit 1; }
grep '^pull' "$dir/log" || true
# One line per dump: inclusive instructions of the drag and of its phases.
for f in $(ls "$dir"/cg.out.* | awk -F. '{ print $NF, $0 }' | sort -n | cut -d" " -f2); do
  callgrind_annotate --inclusive=yes --threshold=100 "$f" 2>/dev/null | awk -v file="$f" '
    function count(s) { gsub(",", "", s); return s + 0 }
    /Trigger: Client Request:/ { sub(/.*Client Request: /, ""); frame = $0 }
    /Session::grab_drag\(/ && !drag { drag = count($1) }
    /BiharmonicSolver::advance_amortized\(/ && !field { field = count($1) }
    /HandleDeformer::refine\(/ && !refine { refine = count($1) }
    /Remesher::iterate_region\(/ && !region { region = count($1) }
    /compute_sizing_from_current_surface\(/ && !sizing { sizing = count($1) }
    END { if (drag) printf "%s %d %d %d %d %d\n", frame, drag, field, refine, region, sizing }'
done >"$dir/frames"
if [ "$verbose" = 1 ]; then
  awk '{ printf "  %-9s %3d  drag %6.1fM  field %5.1fM  refine %5.1fM  region %5.1fM (sizing %5.1fM)\n", $1, $2, $3 / 1e6, $4 / 1e6, $5 / 1e6, $6 / 1e6, $7 / 1e6 }' "$dir/frames"
fi
# Percentiles as the benchmark computes them (linear between the sorted frames).
awk '{ print $3 }' "$dir/frames" | sort -n | awk -v filter="$filter" '
  { v[++n] = $1 }
  function pct(p,   idx, lo, hi) { idx = p * (n - 1); lo = int(idx); hi = lo + 2 > n ? n : lo + 2; return v[lo + 1] + (idx - lo) * (v[hi] - v[lo + 1]) }
  END {
    if (!n) { print "pull-frames-callgrind: no frames (is the benchmark skipped?)"; exit 1 }
    printf "instructions per frame (%d frames, %s): median %.1fM, p95 %.1fM, max %.1fM\n", n, filter, pct(0.5) / 1e6, pct(0.95) / 1e6, v[n] / 1e6
  }'
