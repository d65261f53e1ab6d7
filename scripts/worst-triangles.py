#!/usr/bin/env python3
"""Where a remeshed OFF file's worst triangles are: the N with the smallest angle, with their
angles, corner valences, edge lengths and centroid, to look at next to the reference's creases.

`adasculpt stats` gives the minimum angle only; this says which triangles and where (issue 17:
the slivers the fidelity check's undone relaxation moves leave along an icosahedron's edges).

usage: scripts/worst-triangles.py MESH.off [N]
"""
import math
import sys


def read_off(path):
    """Vertices and triangles of an ASCII OFF file (polygons are fanned)."""
    words = []
    with open(path) as f:
        for line in f:
            words.extend(line.split("#", 1)[0].split())
    if not words or not words[0].startswith("OFF"):
        raise SystemExit(f"{path}: not an ASCII OFF file")
    i = 1 if words[0] == "OFF" else 0
    if words[0] != "OFF":
        words[0] = words[0][3:]
    n_vertices, n_faces = int(words[i]), int(words[i + 1])
    i += 3
    vertices = []
    for _ in range(n_vertices):
        vertices.append(tuple(float(w) for w in words[i:i + 3]))
        i += 3
    triangles = []
    for _ in range(n_faces):
        k = int(words[i])
        corners = [int(w) for w in words[i + 1:i + 1 + k]]
        i += 1 + k
        triangles.extend((corners[0], corners[j], corners[j + 1]) for j in range(1, k - 1))
    return vertices, triangles


def angle_at(a, b, c):
    """The angle at a of the triangle abc, in degrees."""
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return math.degrees(math.atan2(math.sqrt(sum(x * x for x in cross)), sum(u[i] * v[i] for i in range(3))))


def main():
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__.strip().splitlines()[-1])
    vertices, triangles = read_off(sys.argv[1])
    count = int(sys.argv[2]) if len(sys.argv) == 3 else 10
    valence = [0] * len(vertices)
    for t in triangles:
        for v in t:
            valence[v] += 1  # triangles at a vertex: its valence on a closed mesh
    rows = []
    for f, (a, b, c) in enumerate(triangles):
        p = [vertices[a], vertices[b], vertices[c]]
        angles = [angle_at(p[0], p[1], p[2]), angle_at(p[1], p[2], p[0]), angle_at(p[2], p[0], p[1])]
        rows.append((min(angles), f, angles))
    rows.sort()
    below = lambda limit: sum(1 for r in rows if r[0] < limit)
    print(f"{len(triangles)} triangles, {below(20)} below 20 deg, {below(25)} below 25 deg")
    for smallest, f, angles in rows[:count]:
        corners = triangles[f]
        p = [vertices[v] for v in corners]
        lengths = [math.dist(p[i], p[(i + 1) % 3]) for i in range(3)]
        centroid = [sum(q[i] for q in p) / 3 for i in range(3)]
        print(f"face {f}: min {smallest:.2f} deg, angles {' '.join(f'{x:.1f}' for x in angles)}, "
              f"corners {corners} valence {[valence[v] for v in corners]}, "
              f"edges {' '.join(f'{x:.5g}' for x in lengths)}, at {' '.join(f'{x:.4f}' for x in centroid)}")


if __name__ == "__main__":
    main()
