#!/usr/bin/env bash
# Robustness sweep of the remesher (issue 17): remeshes every closed or bordered manifold mesh of
# Debian's libcgal-demo (downloaded by scripts/fetch-cgal-meshes.sh into $ADASCULPT_DATA, default
# ~/.cache/adasculpt; never committed), of ../shared/meshes and three generated hard cases (a coarse fan-
# triangulated bar, a plate thinner than any target length, a cylinder of 0.2° slivers) at every setting:
#   adaptive  --epsilon {0.01 0.05 0.2 0.5 1 2 5}% x --min-length {0.02 0.2}% x --features {off 45}  (28)
#   uniform   --length {0.5 2 8}% x --features {off 45}                                               (6)
# Each run is capped (10 s CPU, 1 GB address space; a cap hit is reported as TIME / MEM) and measured by
# `adasculpt stats OUT --reference IN --self-intersections`. Prints ONE table (mesh, setting, ms, CPU s,
# peak MB, vertices, min / mean min angle, Hausdorff % of the diagonal, input SI pairs, new SI pairs =
# output pairs not at the input's own crossings (cpp/geometry/inherited_crossings.h), status) and a summary of the misses of the issue's targets, worst first, each with the
# command that reproduces it: cap hits and crashes, new crossing pairs, Hausdorff > 2 max(eps, min length / 2)
# (adaptive: the min length the user set wins where eps asks for shorter edges) or > length (uniform), a
# coarser setting (larger eps / min length / length) giving more than 1 % (+5) more vertices (see
# MIN_LENGTH_REACH and MONOTONE_SLACK in scripts/sweep_remesh.py).
#
#   scripts/sweep-remesh.sh [options]
#     -j N               parallel runs (default 2)
#     --meshes REGEX     mesh names: cgal/<file>, shared/<file> (e.g. --meshes 'shared/(bunny|horse)')
#     --settings REGEX   setting names: eps<E>-min<M>-f<F>, len<L>-f<F> (e.g. --settings 'eps(1|2)-min0.2')
#     -o FILE            also write the table + summary to FILE;  --doc FILE: a markdown page (docs/robustness.md)
#     --list             meshes (with skip reasons) and the run count, nothing run
#     --sample --check   the fast sample run by ctest (RemeshSweepSample): exit 1 on any hard-target miss
#     --fresh            ignore cached results;  --results DIR: cache directory;  --no-table: summary only
#     --cached-only      run nothing, report the cached runs;  --label TEXT: what the binary is, for --doc
#     --cpu-cap S --mem-cap MB --samples N --no-fetch --worst N   (see --help)
# Binaries: ADASCULPT_BIN (the remesher swept; default build/native/adasculpt) and ADASCULPT_STATS_BIN
# (the measuring one, needs `stats --self-intersections`; default build/native/adasculpt of this tree).
#
# Resumable: each run's result is cached under $ADASCULPT_DATA/sweep/<hash of ADASCULPT_BIN>/, so an
# interrupted sweep continues where it stopped and a rebuilt binary starts afresh. The full sweep is
# 151 usable meshes (140 CGAL, 8 shared, 3 generated; 3 CGAL files skipped: non-manifold, no faces) x 34
# settings = 5,134 runs (--list prints the exact count; the five *-shuffled.off files load since the loader
# orients their faces). Most meshes are small: ~0.5 s CPU per
# run and its measurement, so roughly 20-40 min with -j2 on an idle 2-core machine, plus 10 s for every
# capped run. --sample (55 runs) takes ~20 s CPU when nothing runs away. Filter with --meshes / --settings;
# --cached-only re-prints (or --doc's) what a sweep still running has finished.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v python3 >/dev/null || { echo "sweep-remesh: python3 is required" >&2; exit 1; }
command -v prlimit >/dev/null || { echo "sweep-remesh: prlimit (util-linux) is required" >&2; exit 1; }
exec python3 scripts/sweep_remesh.py "$@"
