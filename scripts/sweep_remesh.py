#!/usr/bin/env python3
"""Robustness sweep of `adasculpt remesh` (issue 17): every mesh x every setting, each run under a
CPU-time and a memory cap, measured by `adasculpt stats --reference --self-intersections`.

Run through scripts/sweep-remesh.sh (see its header for the options). Results are cached per run
(one JSON file per mesh x setting, keyed by the remesh binary's content hash), so an interrupted
sweep resumes where it stopped and the table can be re-printed without re-running anything.
"""
import argparse
import atexit
import concurrent.futures
import hashlib
import json
import math
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DATA = Path(os.environ.get("ADASCULPT_DATA", Path.home() / ".cache" / "adasculpt"))
MESH_EXTENSIONS = (".off", ".obj", ".ply", ".stl")

# The grid of issue 17: adaptive epsilon x min length x features, uniform length x features (% of diagonal).
EPSILONS = [0.01, 0.05, 0.2, 0.5, 1, 2, 5]
MIN_LENGTHS = [0.02, 0.2]
FEATURES = [0, 45]
LENGTHS = [0.5, 2, 8]

# Targets of issue 17.
CPU_CAP_S = 10.0
MEM_CAP_MB = 1024
HAUSDORFF_FACTOR = 2.0  # adaptive: Hausdorff <= 2 epsilon; uniform: <= the target length
# Where epsilon asks for edges shorter than the min length, the min length wins (the user set both):
# the sizing field is clamped there, and a mesh of edges L follows a sharp edge or tip it does not
# sample (features off) only to within about L / 2, the reach the remesher's own guards allow
# (kToleranceMinLengths in cpp/remesh/remesher_impl.h). So the adaptive bound is
# HAUSDORFF_FACTOR x max(epsilon, MIN_LENGTH_REACH x min length): 2 epsilon whenever epsilon >= half
# the min length (every setting but epsilon 0.01 and 0.05 % at min length 0.2 %), else the min length.
MIN_LENGTH_REACH = 0.5
# Coarser settings must not give more vertices. The remesher is a discrete process: two settings whose
# sizing fields agree almost everywhere (min length 0.02 or 0.2 % where the field never asks for
# less than 0.2 %) end a few vertices apart either way (dragon: 5,245 against 5,224, 0.4 %). A
# count within MONOTONE_SLACK (+ MONOTONE_SLACK_VERTICES) of the finer setting's is that noise; the
# failures this guards against are several times the finer count.
MONOTONE_SLACK = 0.01
MONOTONE_SLACK_VERTICES = 5
# Min angle >= 20 degrees wherever the input allows it. Where two feature (or boundary) edges of the input
# meet at a vertex at a smaller angle, the triangles filling that sector cannot do better; the remesh keeps
# the feature lines but may re-sample them (a curved line's first chord leaves the corner at another
# angle than its first input edge), hence the share. The bound of a run is
# min(MIN_ANGLE_GOAL, MIN_ANGLE_SECTOR_SHARE x the input's smallest feature sector at the run's feature angle)
# (adasculpt stats --features, cpp/remesh/feature_sectors.h).
MIN_ANGLE_GOAL = 20.0
MIN_ANGLE_SECTOR_SHARE = 0.9


def min_angle_bound(feature_sector_deg):
    return min(MIN_ANGLE_GOAL, MIN_ANGLE_SECTOR_SHARE * feature_sector_deg)


class Setting:
    def __init__(self, kind, features, epsilon=None, min_length=None, length=None):
        self.kind, self.features = kind, features
        self.epsilon, self.min_length, self.length = epsilon, min_length, length
        if kind == "adaptive":
            self.name = f"eps{epsilon:g}-min{min_length:g}-f{features:g}"
            self.args = ["--epsilon", f"{epsilon:g}%", "--min-length", f"{min_length:g}%"]
            self.bound_pct = HAUSDORFF_FACTOR * max(epsilon, MIN_LENGTH_REACH * min_length)
        else:
            self.name = f"len{length:g}-f{features:g}"
            self.args = ["--uniform", "--length", f"{length:g}%"]
            self.bound_pct = length
        if features:
            self.args += ["--features", f"{features:g}"]

    def __repr__(self):
        return self.name


def all_settings():
    out = [Setting("adaptive", f, epsilon=e, min_length=m) for m in MIN_LENGTHS for f in FEATURES for e in EPSILONS]
    out += [Setting("uniform", f, length=l) for f in FEATURES for l in LENGTHS]
    return out


# ---- meshes ------------------------------------------------------------------------------------

class Mesh:
    def __init__(self, name, path):
        self.name, self.path = name, Path(path)


def meshes_in(directory, prefix):
    if not directory or not Path(directory).is_dir():
        return []
    files = sorted(p for p in Path(directory).iterdir() if p.suffix.lower() in MESH_EXTENSIONS and p.is_file())
    return [Mesh(f"{prefix}/{p.name}", p) for p in files]


def cgal_dir(fetch):
    """The CGAL demo meshes: the cache when present, else downloaded by fetch-cgal-meshes.sh."""
    cached = DATA / "cgal" / "data" / "meshes"
    if cached.is_dir():
        return cached
    if not fetch:
        return None
    r = subprocess.run(["bash", str(REPO / "scripts" / "fetch-cgal-meshes.sh")], stdout=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print("sweep: CGAL meshes unavailable (see the message above); continuing without them", file=sys.stderr)
        return None
    return Path(r.stdout.strip().splitlines()[-1])


def write_off(path, points, triangles):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(points)} {len(triangles)} 0\n")
        for p in points:
            f.write(" ".join(f"{c:.17g}" for c in p) + "\n")
        for t in triangles:
            f.write(f"3 {t[0]} {t[1]} {t[2]}\n")


def orient_outwards(points, triangles, centre):
    """Orients every triangle of a convex closed surface away from an interior point."""
    out = []
    for t in triangles:
        a, b, c = (points[i] for i in t)
        n = [(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
             (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
             (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])]
        g = [(a[k] + b[k] + c[k]) / 3 - centre[k] for k in range(3)]
        out.append(t if sum(n[k] * g[k] for k in range(3)) > 0 else (t[0], t[2], t[1]))
    return out


def fan_bar(n=16, size=(4.0, 1.0, 1.0)):
    """A coarse CAD-like bar: long edges cut into n pieces, each long face triangulated as two
    fans (skinny triangles, valence up to n + 3), sharp 90 degree edges everywhere."""
    sx, sy, sz = size
    points, index = [], {}

    def vertex(i, y, z):
        key = (i, y, z)
        if key not in index:
            index[key] = len(points)
            points.append((sx * i / n, sy * y, sz * z))
        return index[key]

    triangles = []
    # Long faces: between two long edges (y0,z0) and (y1,z1).
    for (y0, z0), (y1, z1) in [((0, 0), (1, 0)), ((1, 0), (1, 1)), ((1, 1), (0, 1)), ((0, 1), (0, 0))]:
        bottom = [vertex(i, y0, z0) for i in range(n + 1)]
        top = [vertex(i, y1, z1) for i in range(n + 1)]
        for i in range(n):
            triangles.append((bottom[i], bottom[i + 1], top[n]))
            triangles.append((bottom[0], top[i + 1], top[i]))
    for i in (0, n):  # square ends
        a, b, c, d = vertex(i, 0, 0), vertex(i, 1, 0), vertex(i, 1, 1), vertex(i, 0, 1)
        triangles += [(a, b, c), (a, c, d)]
    return points, orient_outwards(points, triangles, (sx / 2, sy / 2, sz / 2))


def thin_plate(thickness=0.002):
    """A 1 x 1 plate far thinner than any target length: 8 vertices, 12 triangles."""
    points = [(x, y, z) for x in (0.0, 1.0) for y in (0.0, 1.0) for z in (0.0, thickness)]
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    triangles = [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]
    return points, orient_outwards(points, triangles, (0.5, 0.5, thickness / 2))


def sliver_cylinder(around=48, radius=0.1, height=4.0):
    """A closed cylinder whose side is one row of quads as tall as the cylinder: every side
    triangle is a sliver (about 0.2 degrees), the caps are fans around a centre vertex."""
    points = []
    for z in (0.0, height):
        for i in range(around):
            a = 2 * math.pi * i / around
            points.append((radius * math.cos(a), radius * math.sin(a), z))
    points += [(0.0, 0.0, 0.0), (0.0, 0.0, height)]
    triangles = []
    for i in range(around):
        j = (i + 1) % around
        triangles += [(i, j, around + j), (i, around + j, around + i)]
        triangles += [(2 * around, j, i), (2 * around + 1, around + i, around + j)]
    return points, orient_outwards(points, triangles, (0.0, 0.0, height / 2))


GENERATED = {"fan_bar.off": fan_bar, "thin_plate.off": thin_plate, "sliver_cylinder.off": sliver_cylinder}


def generated_meshes(directory):
    directory.mkdir(parents=True, exist_ok=True)
    out = []
    for name, make in GENERATED.items():
        path = directory / name
        if not path.exists():
            write_off(path, *make())
        out.append(Mesh(f"gen/{name}", path))
    return out


# ---- running -----------------------------------------------------------------------------------

def file_hash(path):
    h = hashlib.sha1()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()[:12]


def run_capped(cmd, cpu_s, mem_mb, wall_s, stdout_path, stderr_path):
    """Runs cmd under an address-space and CPU-time limit (prlimit) and a wall-clock limit.
    Returns (status, wait_status, cpu seconds, peak RSS MB, wall seconds)."""
    limited = ["prlimit", f"--as={int(mem_mb) * 1024 * 1024}", f"--cpu={int(math.ceil(cpu_s))}:{int(math.ceil(cpu_s)) + 2}",
               "--"] + [str(c) for c in cmd]
    with open(stdout_path, "wb") as out, open(stderr_path, "wb") as err:
        start = time.monotonic()
        proc = subprocess.Popen(limited, stdout=out, stderr=err, stdin=subprocess.DEVNULL)
        fired = threading.Event()

        def kill():
            fired.set()
            proc.kill()

        timer = threading.Timer(wall_s, kill)
        timer.start()
        _, status, usage = os.wait4(proc.pid, 0)
        timer.cancel()
        proc.returncode = 0  # reaped by wait4; keep Popen from waiting again
        wall = time.monotonic() - start
    cpu = usage.ru_utime + usage.ru_stime
    rss = usage.ru_maxrss / 1024.0
    err_text = Path(stderr_path).read_text(errors="replace")
    if fired.is_set():
        return "TIME(wall)", status, cpu, rss, wall
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        # SIGXCPU comes only from the CPU limit (rusage may lag it by a tick); SIGKILL from its hard limit.
        if sig == signal.SIGXCPU or (sig == signal.SIGKILL and cpu >= cpu_s - 0.5):
            return "TIME", status, cpu, rss, wall
        if "bad_alloc" in err_text or rss > 0.9 * mem_mb:
            return "MEM", status, cpu, rss, wall
        return f"CRASH({signal.Signals(sig).name})", status, cpu, rss, wall
    code = os.WEXITSTATUS(status)
    if code != 0:
        if "bad_alloc" in err_text or "memory" in err_text.lower():
            return "MEM", status, cpu, rss, wall
        return f"EXIT{code}", status, cpu, rss, wall
    return "ok", status, cpu, rss, wall


def first_line(path):
    lines = [l for l in Path(path).read_text(errors="replace").splitlines() if l.strip()]
    return lines[0][:160] if lines else ""


class Sweep:
    def __init__(self, args):
        self.bin = Path(args.bin).resolve()
        self.stats_bin = Path(args.stats_bin).resolve()
        self.cpu_cap, self.mem_cap = args.cpu_cap, args.mem_cap
        self.samples = args.samples
        self.fresh = args.fresh
        self.tmp = Path(tempfile.mkdtemp(prefix="adasculpt-sweep-"))
        atexit.register(shutil.rmtree, self.tmp, True)
        # Run private copies, hashed after copying: a binary rebuilt while the sweep runs must neither fail a
        # run half-written nor mix two remeshers under one result key.
        self.run_bin = self.tmp / "remesh-bin" / "adasculpt"
        self.run_stats_bin = self.tmp / "stats-bin" / "adasculpt"
        for source, copy in ((self.bin, self.run_bin), (self.stats_bin, self.run_stats_bin)):
            copy.parent.mkdir()
            shutil.copy2(source, copy)
        self.results = Path(args.results) if args.results else DATA / "sweep" / file_hash(self.run_bin)
        self.results.mkdir(parents=True, exist_ok=True)
        self.probes = DATA / "sweep" / "inputs" / file_hash(self.run_stats_bin)
        self.probes.mkdir(parents=True, exist_ok=True)
        self.lock = threading.Lock()

    def repro(self, mesh, setting):
        return (f"prlimit --as={self.mem_cap * 1024 * 1024} --cpu={int(self.cpu_cap)} {self.bin} remesh "
                f"{mesh.path} /tmp/out.off " + " ".join(setting.args))

    def probe(self, mesh):
        """The input's figures (or why it is skipped), cached per file content."""
        key = self.probes / f"{file_hash(mesh.path)}.json"
        if key.exists() and not self.fresh:
            return json.loads(key.read_text())
        out, err = self.tmp / f"probe-{os.getpid()}-{threading.get_ident()}.out", self.tmp / f"probe-{threading.get_ident()}.err"
        status, *_ = run_capped([self.run_stats_bin, "stats", mesh.path, "--json", "--self-intersections"],
                                120, 8192, 300, out, err)
        info = {"mesh": str(mesh.path)}
        warnings = [l for l in Path(err).read_text(errors="replace").splitlines() if l.strip()]
        if status != "ok":
            info["skip"] = f"loader: {first_line(err) or status}"
        elif any("non-manifold" in w for w in warnings):
            info["skip"] = "non-manifold (repaired by the loader): " + next(w for w in warnings if "non-manifold" in w)[:160]
        else:
            s = json.loads(Path(out).read_text())
            if s.get("faces", 0) < 1:
                info["skip"] = "no faces"
            else:
                info.update(vertices=s["vertices"], faces=s["faces"], boundary_loops=s["boundary_loops"],
                            components=s["components"], si=s["self_intersecting_pairs"],
                            si_capped=s["self_intersections_capped"], min_angle=s["min_angle_deg"],
                            warnings=warnings[:3])
                # The smallest angle the input's feature lines force, per feature angle of the grid.
                info["feature_sector"] = {}
                for features in FEATURES:
                    st, *_ = run_capped([self.run_stats_bin, "stats", mesh.path, "--reference", mesh.path, "--json",
                                         "--samples", "1", "--features", f"{features:g}"], 120, 8192, 300, out, err)
                    if st != "ok":
                        info["skip"] = f"feature sectors: {first_line(err) or st}"
                        break
                    info["feature_sector"][f"{features:g}"] = json.loads(Path(out).read_text())["reference_feature_sector_deg"]
        key.write_text(json.dumps(info))
        return info

    def result_file(self, mesh, setting):
        return self.results / f"{mesh.name.replace('/', '__')}__{setting.name}.json"

    def cached(self, mesh, setting):
        return self.result_file(mesh, setting).exists()

    def run(self, mesh, setting, input_info):
        key = self.result_file(mesh, setting)
        sector = input_info["feature_sector"][f"{setting.features:g}"]
        if key.exists() and not self.fresh:
            return {**json.loads(key.read_text()), "feature_sector": sector}  # the input's, measured by the stats binary
        tag = f"{threading.get_ident()}"
        out_mesh = self.tmp / f"out-{tag}.off"
        so, se = self.tmp / f"remesh-{tag}.out", self.tmp / f"remesh-{tag}.err"
        if out_mesh.exists():
            out_mesh.unlink()
        # The cap is on CPU time, which a loaded machine does not inflate; the wall-clock limit
        # only guards against a process that sleeps or waits forever.
        status, _, cpu, rss, wall = run_capped([self.run_bin, "remesh", mesh.path, out_mesh] + setting.args,
                                               self.cpu_cap, self.mem_cap, 30 * self.cpu_cap + 60, so, se)
        r = {"mesh": mesh.name, "path": str(mesh.path), "setting": setting.name, "status": status,
             "cpu_s": round(cpu, 3), "rss_mb": round(rss, 1), "wall_s": round(wall, 3),
             "note": first_line(se), "input_vertices": input_info["vertices"], "input_si": input_info["si"],
             "feature_sector": sector}
        m = re.search(r"in ([0-9.]+) ms", Path(so).read_text(errors="replace"))
        r["remesh_ms"] = float(m.group(1)) if m else round(wall * 1000, 1)
        if status == "ok" and "warning" in Path(se).read_text(errors="replace"):
            status = r["status"] = "ok+warning"  # e.g. the runaway guard stopped early: still judged by the targets
        if status.startswith("ok"):
            mo, me = self.tmp / f"stats-{tag}.out", self.tmp / f"stats-{tag}.err"
            st, *_ = run_capped([self.run_stats_bin, "stats", out_mesh, "--reference", mesh.path, "--json",
                                 "--self-intersections", "--samples", str(self.samples)], 300, 16384, 900, mo, me)
            if st != "ok":
                r["status"] = f"MEASURE-{st}"
                r["note"] = first_line(me)
            else:
                s = json.loads(Path(mo).read_text())
                r.update(vertices=s["vertices"], faces=s["faces"], min_angle=s["min_angle_deg"],
                         mean_min_angle=s["mean_min_angle_deg"], hausdorff_pct=100 * s["hausdorff_rel"],
                         output_si=s["self_intersecting_pairs"], si_capped=s["self_intersections_capped"],
                         genus=s["genus"], boundary_loops=s["boundary_loops"])
                # Pairs where the input crosses itself already are re-sampled, not made: the stats
                # command counts the rest (geometry/inherited_crossings.h); older binaries: the difference.
                r["new_si"] = s.get("self_intersecting_pairs_not_inherited", r["output_si"] - input_info["si"])
        if not r["status"].startswith("MEASURE"):  # a failed measurement is retried next time
            key.write_text(json.dumps(r))
        return r


# ---- judging -----------------------------------------------------------------------------------

def failures(results, settings_by_name, sweep):
    """Every miss of the issue's hard targets: (kind, severity for sorting, mesh, setting, text)."""
    out = []
    for r in results:
        s = settings_by_name[r["setting"]]
        if not r["status"].startswith("ok"):
            sev = 1e9 if r["status"].startswith(("TIME", "MEM", "CRASH")) else 1e8
            out.append(("cap/crash", sev, r, f"{r['status']} after {r['cpu_s']:.1f} s CPU, {r['rss_mb']:.0f} MB"
                        + (f" — {r['note']}" if r["note"] else "")))
            continue
        if r["new_si"] > 0:
            out.append(("new crossings", r["new_si"], r, f"{r['new_si']} new self-intersecting pairs"
                        + (" (capped)" if r["si_capped"] else "")))
        if r["hausdorff_pct"] > s.bound_pct:
            out.append(("hausdorff", r["hausdorff_pct"] / s.bound_pct, r,
                        f"Hausdorff {r['hausdorff_pct']:.3g} % > {s.bound_pct:g} %"))
        angle_bound = min_angle_bound(r["feature_sector"])
        if r["min_angle"] < angle_bound:
            out.append(("min angle", angle_bound / max(r["min_angle"], 1e-3), r,
                        f"min angle {r['min_angle']:.2f}° < {angle_bound:.3g}° (the input's smallest feature sector: "
                        f"{r['feature_sector']:.3g}°)"))
    # Coarser settings must never give more vertices: epsilon and min length (adaptive), length (uniform).
    done = {(r["mesh"], r["setting"]): r for r in results if r["status"].startswith("ok")}
    worst_monotone = {}  # (mesh, coarser setting) -> (ratio, result, text)
    for (mesh, name), r in done.items():
        s = settings_by_name[name]
        for other_name, o in settings_by_name.items():
            q = done.get((mesh, other_name))
            if q is None or o.kind != s.kind or o.features != s.features or o is s:
                continue
            if s.kind == "adaptive":
                coarser = (o.epsilon >= s.epsilon and o.min_length >= s.min_length)
            else:
                coarser = o.length >= s.length
            if coarser and q["vertices"] > (1 + MONOTONE_SLACK) * r["vertices"] + MONOTONE_SLACK_VERTICES:
                ratio = q["vertices"] / max(1, r["vertices"])
                key = (mesh, other_name)
                if ratio > worst_monotone.get(key, (0,))[0]:
                    worst_monotone[key] = (ratio, q, f"{q['vertices']} vertices > {r['vertices']} at the finer {name}")
    out += [("monotone", ratio, q, text) for ratio, q, text in worst_monotone.values()]
    out.sort(key=lambda f: -f[1])
    return out


KINDS = ("cap/crash", "new crossings", "hausdorff", "monotone", "min angle")


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def table(results):
    lines = ["| mesh | setting | ms | CPU s | MB | V in | V out | min ∠ | sector ∠ | mean min ∠ | Hausdorff % diag | "
             "SI in | new SI | status |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in results:
        lines.append(
            f"| {r['mesh']} | {r['setting']} | {r['remesh_ms']:.0f} | {r['cpu_s']:.2f} | {r['rss_mb']:.0f} | "
            f"{r['input_vertices']} | {fmt(r.get('vertices'), 'd')} | {fmt(r.get('min_angle'), '.2f')} | "
            f"{fmt(r.get('feature_sector'), '.1f')} | "
            f"{fmt(r.get('mean_min_angle'), '.2f')} | {fmt(r.get('hausdorff_pct'), '.3f')} | {r['input_si']} | "
            f"{fmt(r.get('new_si'), 'd')} | {r['status']} |")
    return "\n".join(lines)


def summary(results, fails, skipped, sweep, settings_by_name, limit):
    lines = []
    n = len(results)
    by_kind = {}
    for kind, _, r, text in fails:
        by_kind.setdefault(kind, []).append((r, text))
    ok = sum(r["status"].startswith("ok") for r in results)
    warned = sum(r["status"] == "ok+warning" for r in results)
    low_angle = [r for r in results if r["status"].startswith("ok") and r["min_angle"] < MIN_ANGLE_GOAL]
    forced = [r for r in low_angle if min_angle_bound(r["feature_sector"]) < MIN_ANGLE_GOAL]
    lines.append(f"runs: {n} ({ok} finished under the caps of {sweep.cpu_cap:g} s CPU / {sweep.mem_cap} MB, "
                 f"{warned} of them with a warning)")
    for kind in KINDS:
        runs = {(r["mesh"], r["setting"]) for r, _ in by_kind.get(kind, [])}
        lines.append(f"  {kind:14s} {len(runs)} runs fail")
    lines.append(f"  (min angle < {MIN_ANGLE_GOAL:g}° in {len(low_angle)} runs, {len(forced)} of them where the input's "
                 f"feature lines meet at less than {MIN_ANGLE_GOAL / MIN_ANGLE_SECTOR_SHARE:.3g}°)")
    if skipped:
        lines.append(f"skipped meshes: {len(skipped)}")
        for name, why in skipped:
            lines.append(f"  {name}: {why}")
    if fails:
        lines.append(f"worst failures (up to {limit} per kind; reproduce with the command):")
        for kind in KINDS:
            for r, text in by_kind.get(kind, [])[:limit]:
                lines.append(f"  [{kind}] {r['mesh']} {r['setting']}: {text}")
                lines.append(f"      {sweep.repro(Mesh(r['mesh'], r['path']), settings_by_name[r['setting']])}")
    return "\n".join(lines)


# ---- main --------------------------------------------------------------------------------------

# The fast sample (ctest RemeshSweepSample): small meshes and the settings that exposed each failure mode of
# issue 17 on main f486e7c: an epsilon series (coarser must not mean more vertices), a tiny min length (the
# runaway), features 45 on thin parts and sharp edges, uniform lengths. Clean meshes keep it honest both ways.
SAMPLE_SETTINGS = ["eps0.5-min0.2-f0", "eps2-min0.2-f0", "eps5-min0.2-f0", "eps1-min0.02-f0", "eps0.5-min0.2-f45",
                   "len2-f0", "len8-f45"]
SAMPLE_MESHES = ["repo/eight.off", "repo/fandisk.off", "gen/fan_bar.off", "gen/thin_plate.off",
                 "gen/sliver_cylinder.off", "cgal/elephant-with-holes.off", "cgal/pinion_small.off"]
# Single runs the sample adds, each a miss a fix removed (kept from coming back): the needle cylinder's strips
# collapsed into chords (Hausdorff 13 x the bound) and 3torus's sliver-repair flips across its shallow creases
# (14 x), both cpp/remesh/flip_relax.cpp fix_bad_faces; the thin plate's flips across its rim (3.6 x: notches
# 1.4 % of the diagonal deep), cpp/remesh/fidelity.cpp flip_keeps_fidelity; part.off's long-edge split left at its
# midpoint 3 tolerances off a crease (1.5 x), cpp/remesh/split_collapse.cpp split_with_mirror. Min angle: the
# cut cone of mask_cone kept a flat triangle at its apex (0.00°; a collapse made it, and its long side is the
# border: split_collapse.cpp collapse_geometry_ok, flip_relax.cpp fix_bad_faces), blobby_3cc a 16° triangle
# on a short border edge (angle_collapse.cpp), pig three triangles of 0.00° where an input flap folded back onto
# its neighbour made two feature lines on one line (degenerate.cpp collapse_flat_across_features).
SAMPLE_RUNS = [("gen/sliver_cylinder.off", "eps0.05-min0.02-f0"), ("cgal/3torus.off", "eps0.01-min0.02-f45"),
               ("gen/thin_plate.off", "eps0.2-min0.02-f0"), ("cgal/part.off", "eps0.05-min0.2-f0"),
               ("cgal/mask_cone.off", "eps0.5-min0.2-f0"), ("cgal/blobby_3cc.off", "eps2-min0.2-f0"),
               ("cgal/pig.off", "eps1-min0.2-f45")]


# Misses of the generated and sample meshes the remesher is known not to meet yet (issue 17 item 2, geometric
# safety), as measured by the full sweep of main 624e574 (docs/robustness.md): with features off, the rim of the
# thin plate (0.002 thick, thinner than any target length) is still cut by more than 2 epsilon at epsilon 0.01 and
# 0.05 % (relaxation and projection wear its 90-degree edges down in the iterations after the first). The plate at
# every coarser epsilon, fan_bar, elephant-with-holes and pinion_small now pass the sample's settings, and are no
# longer excused. `--check` reports these under "known open" instead of failing; caps, crashes and monotone vertex counts
# are never excused. Keep the entries narrow: a fixed miss must fail the check when it comes back. (kind, mesh
# regex, setting regex matched at the start of the setting name).
#
# The min angle target (judged since the sweep measures the input's feature sectors): the sample's runs under
# min(20°, 0.9 x sector) on the commit that started judging it. The holes of elephant-with-holes (boundary corners
# of 30°, slivers of 10-17° beside them; at epsilon 2 % it passes since angle_collapse.cpp, at 5 % since
# strips.cpp's short border edges), pinion_small's and the plate's sharp edges at coarse lengths (9-14°, 1-2°),
# 3torus's creases at epsilon 0.01 % (0.2°) and part.off's crease at 0.05 % (13.9°).
KNOWN_OPEN = [
    ("hausdorff", r"gen/thin_plate\.off", r"eps(0\.01|0\.05)-min[0-9.]+-f0"),
    ("min angle", r"cgal/elephant-with-holes\.off", r"(eps(0\.5|1)-min[0-9.]+|len(2|8))-f"),
    ("min angle", r"cgal/pinion_small\.off", r"(eps0\.5-min0\.2|len8)-f45"),
    ("min angle", r"gen/thin_plate\.off", r"(eps0\.5-min0\.2|len8)-f45"),
    ("min angle", r"cgal/3torus\.off", r"eps0\.01-min0\.02-f45"),
    ("min angle", r"cgal/part\.off", r"eps0\.05-min0\.2-f0"),
]


def known_open(kind, r):
    return any(kind == k and re.fullmatch(m, r["mesh"]) and re.match(st, r["setting"]) for k, m, st in KNOWN_OPEN)


def main():
    ap = argparse.ArgumentParser(prog="sweep-remesh.sh", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.environ.get("ADASCULPT_BIN", str(REPO / "build/native/adasculpt")),
                    help="the adasculpt binary whose remesher is swept (env ADASCULPT_BIN)")
    ap.add_argument("--stats-bin", default=os.environ.get("ADASCULPT_STATS_BIN", str(REPO / "build/native/adasculpt")),
                    help="the adasculpt binary that measures (needs stats --self-intersections)")
    ap.add_argument("--meshes", default="", help="regex on mesh names (cgal/..., shared/..., repo/..., gen/...)")
    ap.add_argument("--settings", default="", help="regex on setting names (e.g. 'eps(1|2)-min0.2-f0|len')")
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("-o", "--output", help="also write the table and summary to this file")
    ap.add_argument("--doc", help="write a markdown page (table + summary + command) to this file")
    ap.add_argument("--sample", action="store_true", help="the fast sample of npm test: few meshes and settings")
    ap.add_argument("--check", action="store_true", help="exit 1 when any hard target fails")
    ap.add_argument("--cpu-cap", type=float, default=CPU_CAP_S, help="CPU seconds per remesh run")
    ap.add_argument("--mem-cap", type=int, default=MEM_CAP_MB, help="address space MB per remesh run")
    ap.add_argument("--samples", type=int, default=100000, help="area samples per direction for the Hausdorff distance")
    ap.add_argument("--results", help="result cache directory (default: $ADASCULPT_DATA/sweep/<binary hash>)")
    ap.add_argument("--fresh", action="store_true", help="ignore cached results")
    ap.add_argument("--no-fetch", action="store_true", help="do not download the CGAL meshes when missing")
    ap.add_argument("--no-table", action="store_true", help="print only the summary")
    ap.add_argument("--cached-only", action="store_true",
                    help="run nothing: report the runs already in the result cache (e.g. of a sweep still running)")
    ap.add_argument("--label", help="what the remesh binary is (commit), for --doc; default: git log of its tree")
    ap.add_argument("--list", action="store_true", help="list meshes (with skip reasons) and the run count, run nothing")
    ap.add_argument("--worst", type=int, default=15, help="failures listed per kind in the summary")
    args = ap.parse_args()

    for b in (args.bin, args.stats_bin):
        if not os.access(b, os.X_OK):
            sys.exit(f"sweep: {b} not found or not executable (bash scripts/build.sh native)")
    settings = all_settings()
    shared = Path(os.environ.get("ADASCULPT_SHARED_MESHES", REPO.parent / "shared" / "meshes"))
    sweep = Sweep(args)
    if args.sample:
        meshes = meshes_in(REPO / "tests" / "data" / "meshes", "repo") + generated_meshes(DATA / "sweep" / "generated")
        cgal = cgal_dir(fetch=not args.no_fetch)
        if cgal is None:
            print("sweep: sample runs without the CGAL meshes (not cached and not downloadable)")
        meshes += meshes_in(cgal, "cgal")
        sample_run_names = {mesh for mesh, _ in SAMPLE_RUNS}
        meshes = [m for m in meshes if m.name in SAMPLE_MESHES or m.name in sample_run_names]
    else:
        meshes = (meshes_in(cgal_dir(fetch=not args.no_fetch), "cgal") + meshes_in(shared, "shared") +
                  generated_meshes(DATA / "sweep" / "generated"))
        if not shared.is_dir():
            print(f"sweep: {shared} not found: shared meshes skipped", file=sys.stderr)
    if args.meshes:
        meshes = [m for m in meshes if re.search(args.meshes, m.name)]
    if args.settings:
        settings = [s for s in settings if re.search(args.settings, s.name)]
    settings_by_name = {s.name: s for s in settings}

    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        infos = dict(zip((m.name for m in meshes), pool.map(sweep.probe, meshes)))
    skipped = [(m.name, infos[m.name]["skip"]) for m in meshes if "skip" in infos[m.name]]
    usable = [m for m in meshes if "skip" not in infos[m.name]]
    if args.sample:
        wanted = {(mesh, name) for mesh in SAMPLE_MESHES for name in SAMPLE_SETTINGS} | set(SAMPLE_RUNS)
        runs = [(m, s) for m in usable for s in settings if (m.name, s.name) in wanted]
    else:
        runs = [(m, s) for m in usable for s in settings]
    planned = len(runs)
    if args.cached_only:
        runs = [(m, s) for m, s in runs if sweep.cached(m, s)]
    print(f"sweep: {len(usable)} meshes, {len(runs)} runs "
          f"({len(skipped)} meshes skipped); remesh binary {sweep.bin}, results in {sweep.results}", file=sys.stderr)
    if args.list:
        for m in usable:
            i = infos[m.name]
            print(f"{m.name}: V {i['vertices']} F {i['faces']} loops {i['boundary_loops']} SI {i['si']}")
        for name, why in skipped:
            print(f"{name}: SKIP {why}")
        return 0

    order = {(m.name, s.name): k for k, (m, s) in enumerate(runs)}
    results, done, t0 = [], 0, time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        futures = {pool.submit(sweep.run, m, s, infos[m.name]): (m, s) for m, s in runs}
        for f in concurrent.futures.as_completed(futures):
            results.append(f.result())
            done += 1
            if done % 25 == 0 or done == len(runs):
                print(f"sweep: {done}/{len(runs)} runs ({time.monotonic() - t0:.0f} s)", file=sys.stderr)
    results.sort(key=lambda r: order[(r["mesh"], r["setting"])])
    fails = failures(results, settings_by_name, sweep)
    text = ("" if args.no_table else table(results) + "\n\n") + summary(results, fails, skipped, sweep,
                                                                         settings_by_name, args.worst)
    print(text)
    if args.output:
        Path(args.output).write_text(text + "\n")
    if args.doc:
        write_doc(Path(args.doc), sys.argv[1:], sweep, results, fails, skipped, settings_by_name, args.label, planned)
    excused = [f for f in fails if known_open(f[0], f[2])]
    hard = [f for f in fails if not known_open(f[0], f[2])]
    if args.check and excused:
        print(f"sweep: {len(excused)} known open misses (issue 17 item 2, see KNOWN_OPEN in scripts/sweep_remesh.py) "
              f"do not fail --check; {len(hard)} other misses")
    for kind, _, r, text in hard:
        print(f"  [{kind}] {r['mesh']} {r['setting']}: {text}")
    return 1 if args.check and hard else 0


def write_doc(path, argv, sweep, results, fails, skipped, settings_by_name, label, planned):
    git = label or subprocess.run(["git", "-C", str(sweep.bin.parent), "log", "-1", "--format=%h %s"],
                                  stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
    drop = {"--cached-only", "--label", label}  # options that only shape this page
    argv = [a for a in argv if a not in drop]
    body = [
        "# Remeshing robustness sweep",
        "",
        "Generated by `scripts/sweep-remesh.sh` (do not edit by hand). Every closed or bordered manifold mesh of",
        "Debian's `libcgal-demo` (fetched by `scripts/fetch-cgal-meshes.sh`, never committed) and of `../shared/meshes`,",
        "remeshed at every setting of issue 17, each run capped at "
        f"{sweep.cpu_cap:g} s CPU and {sweep.mem_cap} MB address space, measured by",
        "`adasculpt stats --reference INPUT --self-intersections` (exact self-intersection test, CGAL's definition;",
        "\"new SI\" = output pairs that do not re-sample a crossing of the input: not inside the box of an input",
        "crossing pair grown by twice the Hausdorff distance, `cpp/geometry/inherited_crossings.h`; Hausdorff relative",
        "to the input's bounding-box diagonal).",
        "Judged: no cap hit or crash, no new crossing pairs, Hausdorff <= 2 max(eps, min length / 2) (adaptive; the",
        "min length wins where eps asks for shorter edges) or <= the length (uniform), and no coarser setting with",
        f"more than {100 * MONOTONE_SLACK:g} % (+{MONOTONE_SLACK_VERTICES}) more vertices "
        "(scripts/sweep_remesh.py: MIN_LENGTH_REACH, MONOTONE_SLACK), and a min angle of at least",
        f"min({MIN_ANGLE_GOAL:g}°, {MIN_ANGLE_SECTOR_SHARE:g} x the input's smallest feature sector): \"sector\" is the "
        "smallest angle between two feature or boundary edges meeting at a vertex of the input, marked as the run's",
        "`--features` marks them (`adasculpt stats --features`; 360: none), which no remesh that keeps them can beat.",
        "",
        "Regenerate:",
        "",
        "```",
        ("" if sweep.bin == (REPO / "build/native/adasculpt").resolve() else "ADASCULPT_BIN=<that binary> ") +
        "bash scripts/sweep-remesh.sh " + " ".join(shlex.quote(a) for a in argv),
        "```",
        "",
        f"Remesh binary: `{sweep.bin}` ({git or 'unknown commit'}), generated {time.strftime('%Y-%m-%d %H:%M %Z')}.",
        "" if len(results) == planned else
        f"This page covers {len(results)} of the {planned} runs of that command (the others were not run yet; the "
        "sweep is resumable: the same command continues it).",
        "",
        "## Summary",
        "",
        "```",
        summary(results, fails, skipped, sweep, settings_by_name, 10),
        "```",
        "",
        "## All runs",
        "",
        table(results),
        "",
    ]
    # Machine-independent paths on the page.
    text = "\n".join(body)
    for local, portable in ((str(DATA), "~/.cache/adasculpt"), (str(REPO.parent / "shared"), "../shared"),
                            (str(sweep.bin), "$ADASCULPT_BIN"), (str(REPO) + "/", "")):
        text = text.replace(local, portable)
    path.write_text(text)


if __name__ == "__main__":
    sys.exit(main())
