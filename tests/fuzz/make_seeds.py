#!/usr/bin/env python3
"""Writes the seed corpora tests/fuzz/corpus/<target>/ (run from anywhere; idempotent).

Seeds: the sample files (tests/data/samples), the malformed corpus (tests/data/malformed), small valid
meshes written here in every format variant the readers know (OFF/COFF/NOFF, OBJ with v/vt/vn forms
and negative indices, ASCII and binary STL, ASCII and both binary PLY byte orders, quads and a
pentagon to exercise fan triangulation), and session files. Kept small: libFuzzer's default maximum
input length follows the largest seed.
"""
import json
import pathlib
import shutil
import struct

ROOT = pathlib.Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "fuzz" / "corpus"

# An octahedron (closed), a quad strip with a pentagon (open, polygons), and a tetrahedron.
OCTA_V = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
OCTA_F = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
POLY_V = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1, 0), (2.5, 0.5, 0), (1e-3, 2.5e6, -7.25e-9)]
POLY_F = [(0, 1, 4, 3), (1, 2, 6, 5, 4), (3, 4, 7)]
TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
MESHES = {"octa": (OCTA_V, OCTA_F), "poly": (POLY_V, POLY_F), "tet": (TET_V, TET_F)}


def tris(faces):
    for f in faces:
        for i in range(1, len(f) - 1):
            yield (f[0], f[i], f[i + 1])


def off(v, f, header="OFF", extra=""):
    s = f"{header}\n# comment\n{len(v)} {len(f)} 0\n"
    s += "".join(f"{x} {y} {z}{extra}\n" for x, y, z in v)
    s += "".join(f"{len(p)} " + " ".join(map(str, p)) + "\n" for p in f)
    return s.encode()


def obj(v, f, style):
    s = "# obj seed\no thing\n" + "".join(f"v {x} {y} {z}\n" for x, y, z in v)
    s += "vt 0 0\nvn 0 0 1\n"
    n = len(v)
    for p in f:
        if style == "plain":
            s += "f " + " ".join(str(i + 1) for i in p) + "\n"
        elif style == "slashes":
            s += "f " + " ".join(f"{i + 1}/1/1" for i in p) + "\n"
        elif style == "normals":
            s += "f " + " ".join(f"{i + 1}//1" for i in p) + "\n"
        else:  # negative (relative) indices
            s += "f " + " ".join(str(i - n) for i in p) + "\n"
    return s.encode()


def stl_ascii(v, f):
    s = "solid seed\n"
    for a, b, c in tris(f):
        s += "  facet normal 0 0 0\n    outer loop\n"
        for i in (a, b, c):
            s += "      vertex {} {} {}\n".format(*v[i])
        s += "    endloop\n  endfacet\n"
    return (s + "endsolid seed\n").encode()


def stl_binary(v, f):
    t = list(tris(f))
    out = b"binary seed".ljust(80, b" ") + struct.pack("<I", len(t))
    for a, b, c in t:
        out += struct.pack("<3f", 0, 0, 0)
        for i in (a, b, c):
            out += struct.pack("<3f", *v[i])
        out += struct.pack("<H", 0)
    return out


def ply(v, f, fmt):
    head = (f"ply\nformat {fmt} 1.0\ncomment seed\nelement vertex {len(v)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    if fmt == "ascii":
        body = "".join(f"{x} {y} {z}\n" for x, y, z in v)
        body += "".join(f"{len(p)} " + " ".join(map(str, p)) + "\n" for p in f)
        return head + body.encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(e + "3f", *p) for p in v)
    body += b"".join(struct.pack(e + "B" + "i" * len(p), len(p), *p) for p in f)
    return head + body


def ply_double(v, f):
    head = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\n"
            "property double x\nproperty double y\nproperty double z\nproperty uchar red\n"
            f"element face {len(f)}\nproperty list ushort uint vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<3dB", *p, 7) for p in v)
    body += b"".join(struct.pack("<H" + "I" * len(p), len(p), *p) for p in f)
    return head + body


SESSIONS = {
    "minimal": {"version": 1, "steps": []},
    # Every mask operation, strokes across the masked part, a remesh, undo/redo.
    "mask": {
        "version": 1,
        "steps": [
            {"mask": {"op": "fill"}},
            {"mask": {"op": "erase", "path": [[0, 0, -1], [0, 0.3, -0.95]], "radius": 0.8, "strength": 1}},
            {"mask": {"op": "paint", "path": [[1, 0, 0]], "radius": 0.3, "strength": 0.5}},
            {"mask": {"op": "blur"}},
            {"mask": {"op": "sharpen"}},
            {"brush": {"tool": "draw", "path": [[0, -1, 0], [0, -0.9, 0.44]], "radius": 0.3, "strength": 1}},
            {"grab": {"center": [0, -1, 0], "handle_radius": 0.1, "roi_radius": 0.8, "translate": [0, -0.4, 0.3],
                      "substeps": 3}},
            {"mask": {"op": "invert"}},
            {"remesh": {"iterations": 1}},
            {"mask": {"op": "clear"}},
            {"undo": 3},
            {"redo": 2},
        ],
    },
    "full": {
        "version": 1,
        "settings": {"epsilon": "0.05%", "min_length": 0.002, "max_length": "5%", "features": 45},
        "steps": [
            {"grab": {"center": [0, 0, 1], "handle_radius": 0.1, "roi_radius": 0.5, "translate": [0, 0, 0.3],
                      "rotate": {"axis": [0, 0, 1], "degrees": 30}, "scale": 1.2, "substeps": 4}},
            {"grab": {"center": [1, 0, 0], "handle_radius": 0, "roi_radius": 0.25}},
            {"remesh": {"iterations": 2}},
            {"undo": 2},
            {"redo": 1},
        ],
    },
    # Every brush tool, each symmetry axis, invert, spacing, pressure, a one-point path; then a remesh and undo/redo.
    "brush": {
        "version": 1,
        "settings": {"min_length": "0.5%", "max_length": "4%"},
        "steps": [
            {"brush": {"tool": "draw", "path": [[0, 0, 1], [0.1, 0, 0.99], [0.2, 0.05, 0.97]], "radius": 0.2,
                       "strength": 0.6, "symmetry": "x", "spacing": 0.25, "invert": False,
                       "pressure": [0.2, 0.7, 1]}},
            {"brush": {"tool": "inflate", "path": [[1, 0, 0], [0.98, 0.2, 0]], "radius": 0.15, "invert": True}},
            {"brush": {"tool": "smooth", "path": [[0, 1, 0]], "radius": 0.3, "strength": 1}},
            {"brush": {"tool": "flatten", "path": [[0, 0, -1], [0, 0.1, -0.99]], "radius": 0.25, "symmetry": "y",
                       "strength": 0}},
            {"brush": {"tool": "pinch", "path": [[-1, 0, 0], [-0.99, 0, 0.1]], "radius": 0.1, "spacing": 0.05,
                       "pressure": [0, 0.5]}},
            {"brush": {"tool": "crease", "path": [[0, -1, 0], [0.1, -0.99, 0]], "radius": 0.1, "symmetry": "z",
                       "invert": True, "spacing": 4}},
            {"brush": {"tool": "grab", "path": [[0.7, 0.7, 0], [0.9, 0.9, 0.1], [1.2, 1.1, 0.2]], "radius": 0.2,
                       "symmetry": "none"}},
            {"remesh": {"iterations": 1}},
            {"undo": 3},
            {"redo": 1},
        ],
    },
    "bad_brush": {"version": 1, "steps": [{"brush": {"tool": "chisel", "path": [[0, 0]], "radius": 0,
                                                     "strength": 2, "spacing": 0.01, "symmetry": "w",
                                                     "pressure": [1.5, -1]}}]},
    "settings_only": {"version": 1, "settings": {"epsilon": 0.001}, "steps": [{"remesh": {"iterations": 1}}]},
    "bad_step": {"version": 1, "steps": [{"grab": {"center": [0, 0], "handle_radius": -1, "roi_radius": "x"}}]},
}


def main():
    if OUT.exists():
        shutil.rmtree(OUT)
    seeds = {t: {} for t in ["off", "obj", "stl", "ply", "load_mesh", "session_file"]}
    for name, (v, f) in MESHES.items():
        seeds["off"][f"{name}.off"] = off(v, f)
        seeds["off"][f"{name}_noff.off"] = off(v, f, "NOFF", " 0 0 1")
        seeds["off"][f"{name}_coff.off"] = off(v, f, "COFF", " 255 0 0 255")
        for style in ["plain", "slashes", "normals", "negative"]:
            seeds["obj"][f"{name}_{style}.obj"] = obj(v, f, style)
        seeds["stl"][f"{name}_ascii.stl"] = stl_ascii(v, f)
        seeds["stl"][f"{name}_binary.stl"] = stl_binary(v, f)
        for fmt in ["ascii", "binary_little_endian", "binary_big_endian"]:
            seeds["ply"][f"{name}_{fmt}.ply"] = ply(v, f, fmt)
        seeds["ply"][f"{name}_double_ushort.ply"] = ply_double(v, f)
    for d in ["samples", "malformed"]:
        for p in sorted((ROOT / "tests" / "data" / d).iterdir()):
            ext = p.suffix.lstrip(".").lower()
            if ext in ("off", "obj", "stl", "ply"):
                seeds[ext][f"{d}_{p.name}"] = p.read_bytes()
    # load_mesh sniffs the format: every reader seed is a load_mesh seed too.
    for t in ["off", "obj", "stl", "ply"]:
        seeds["load_mesh"].update(seeds[t])
    for name, s in SESSIONS.items():
        seeds["session_file"][f"{name}.json"] = json.dumps(s, indent=1).encode()
    seeds["session_file"]["not_json.json"] = b'{"version": 1, "steps": [ {"undo": 1}, '
    for t, files in seeds.items():
        (OUT / t).mkdir(parents=True)
        for n, data in files.items():
            (OUT / t / n).write_bytes(data)
        print(f"{t}: {len(files)} seeds")


if __name__ == "__main__":
    main()
