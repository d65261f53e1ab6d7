#!/usr/bin/env bash
# Remeshing figures on every shared mesh with the CLI defaults (adaptive, epsilon 0.05%, min 0.2%, max 5%,
# 5 iterations, projection), plus fandisk and rocker_arm with --features 45: vertices, faces, genus and boundary
# loops kept, min / mean min angle, share under 30 degrees, RMS and Hausdorff to the input, and the remeshing time
# (median of RUNS runs, the remeshing alone). Skips with a message when ../shared/meshes is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
CLI=${ADASCULPT_CLI:-build/native/adasculpt}
MESHES=${ADASCULPT_SHARED_MESHES:-../shared/meshes}
RUNS=${RUNS:-3}
if [ ! -d "$MESHES" ]; then echo "bench-remesh-quality: $MESHES not found; skipped"; exit 0; fi
[ -x "$CLI" ] || { echo "bench-remesh-quality: $CLI not built (scripts/build.sh native)"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf '| mesh | options | V in | V out | F out | genus | bnd | min angle | mean min angle | %% < 30 | RMS / diag | Hausdorff / diag | ms (median of %s) |\n' "$RUNS"
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
run() {  # mesh, extra options...
  local mesh=$1; shift
  local times=() json=""
  for ((i = 0; i < RUNS; i++)); do
    json=$("$CLI" remesh "$MESHES/$mesh.off" "$tmp/out.off" --json "$@")
    times+=("$(python3 -c 'import json,sys; print(json.loads(sys.argv[1])["remesh_ms"])' "$json")")
  done
  python3 - "$mesh" "$json" "${*:-defaults}" "${times[@]}" <<'PY'
import json, sys, statistics
mesh, d, opts, times = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3], [float(t) for t in sys.argv[4:]]
print(f"| {mesh} | {opts} | {d['input_vertices']} | {d['vertices']} | {d['faces']} | {d['genus']} | {d['boundary_loops']} | "
      f"{d['min_angle_deg']:.2f} | {d['mean_min_angle_deg']:.2f} | {d['pct_min_angle_lt_30']:.3f} | {d['rms_rel']:.2e} | "
      f"{d['hausdorff_rel']:.2e} | {statistics.median(times):.0f} |")
PY
}
for m in fandisk hemisphere eight rocker_arm face bunny horse dragon; do
  [ -f "$MESHES/$m.off" ] && run "$m"
done
for m in fandisk rocker_arm; do
  [ -f "$MESHES/$m.off" ] && run "$m" --features 45
done
