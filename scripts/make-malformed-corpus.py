#!/usr/bin/env python3
"""Writes the malformed-mesh corpus in tests/data/malformed/ (one file per case).

Every file must make adasculpt::io::read_soup throw IoError; the expected
message for each file lives in tests/cpp/io_malformed_test.cpp. The files are
committed; rerun this script after changing a case here and update the table.
"""
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "malformed")

TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def off_text(verts, faces, header="OFF"):
    lines = [header, f"{len(verts)} {len(faces)} 0"]
    lines += [" ".join(str(c) for c in v) for v in verts]
    lines += [f"{len(f)} " + " ".join(str(i) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def obj_text(verts, faces):
    lines = [f"v {v[0]} {v[1]} {v[2]}" for v in verts]
    lines += ["f " + " ".join(str(i) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def stl_binary(tris, declared=None, header=b"binary test file"):
    data = header.ljust(80, b" ")
    data += struct.pack("<I", len(tris) if declared is None else declared)
    for tri in tris:
        data += struct.pack("<3f", 0, 0, 0)
        for corner in tri:
            data += struct.pack("<3f", *corner)
        data += b"\0\0"
    return data


def tet_tris():
    return [[TET_V[i] for i in f] for f in TET_F]


def ply_header(fmt, nv, nf, vtype="float", count="uchar", index="int"):
    return (f"ply\nformat {fmt} 1.0\nelement vertex {nv}\n"
            f"property {vtype} x\nproperty {vtype} y\nproperty {vtype} z\n"
            f"element face {nf}\nproperty list {count} {index} vertex_indices\nend_header\n").encode()


def ply_binary(verts, faces, endian="<", fmt="binary_little_endian", nv=None, nf=None):
    data = ply_header(fmt, len(verts) if nv is None else nv, len(faces) if nf is None else nf)
    for v in verts:
        data += struct.pack(endian + "3f", *v)
    for f in faces:
        data += struct.pack(endian + "B", len(f)) + struct.pack(endian + f"{len(f)}i", *f)
    return data


def cases():
    c = {}
    # ---- OFF (ascii) ----
    c["off_empty.off"] = b""
    c["off_bad_header.off"] = b"OFX\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    c["off_4d_header.off"] = b"4OFF\n3 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 0\n3 0 1 2\n"
    c["off_absurd_counts.off"] = b"OFF\n999999999999 1 0\n"
    long_v = [(0.125, 0.25, 0.375), (1.125, 0.25, 0.375), (0.125, 1.25, 0.375), (0.125, 0.25, 1.375)]
    c["off_truncated_vertices.off"] = off_text(long_v, TET_F).encode()[:60]
    c["off_truncated_faces.off"] = off_text(long_v, TET_F).encode()[:-16]
    c["off_index_out_of_range.off"] = off_text(TET_V, TET_F[:3] + [(1, 2, 7)]).encode()
    c["off_negative_index.off"] = off_text(TET_V, [(0, 2, 1), (0, -1, 3)]).encode()
    c["off_nan_coordinate.off"] = off_text(TET_V[:2] + [("nan", 1, 0)] + TET_V[3:], TET_F).encode()
    c["off_msvc_infinity.off"] = off_text(TET_V[:1] + [("1.#INF", 0, 0)] + TET_V[2:], TET_F).encode()
    c["off_two_vertex_face.off"] = off_text(TET_V, TET_F[:2] + [(0, 3)]).encode()
    c["off_repeated_index.off"] = off_text(TET_V, [(0, 2, 1), (0, 1, 1)]).encode()
    c["off_no_faces.off"] = off_text(TET_V, []).encode()
    c["off_huge_polygon.off"] = b"OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n999999999 0 1 2\n"
    c["off_junk.off"] = bytes(range(256)) * 4
    # ---- OBJ (ascii) ----
    c["obj_index_out_of_range.obj"] = obj_text(TET_V, [(1, 3, 2), (1, 2, 9)]).encode()
    c["obj_zero_index.obj"] = obj_text(TET_V, [(1, 3, 2), (0, 1, 2)]).encode()
    c["obj_relative_before_start.obj"] = obj_text(TET_V, [(1, 3, 2), (-1, -2, -5)]).encode()
    c["obj_two_vertex_face.obj"] = obj_text(TET_V, [(1, 3, 2), (1, 2)]).encode()
    c["obj_missing_coordinate.obj"] = b"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"
    c["obj_inf_coordinate.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n"
    c["obj_malformed_face.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x3\n"
    c["obj_repeated_index.obj"] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/5/1 1//4\n"
    c["obj_no_faces.obj"] = b"# only vertices\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
    c["obj_junk.obj"] = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR" + bytes(range(256))
    # ---- STL (binary) ----
    tris = tet_tris()
    c["stl_binary_truncated.stl"] = stl_binary(tris)[:150]
    c["stl_binary_absurd_count.stl"] = stl_binary(tris, declared=0xFFFFFFFF)
    c["stl_binary_short.stl"] = stl_binary([])[:50]
    c["stl_binary_no_triangles.stl"] = stl_binary([])
    nan_tris = [list(t) for t in tris]
    nan_tris[2] = [nan_tris[2][0], (0.0, float("nan"), 0.0), nan_tris[2][2]]
    c["stl_binary_nan.stl"] = stl_binary(nan_tris)
    c["stl_binary_all_degenerate.stl"] = stl_binary([[(1, 2, 3), (1, 2, 3), (4, 5, 6)]])
    # ---- STL (ascii) ----
    facet = ("  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n"
             "      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n")
    c["stl_ascii_truncated.stl"] = ("solid t\n" + facet + facet[:60]).encode()
    c["stl_ascii_bad_number.stl"] = ("solid t\n" + facet + facet.replace("vertex 1 0 0", "vertex 1 0,5 0")
                                     + "endsolid t\n").encode()
    c["stl_ascii_two_vertex_loop.stl"] = ("solid t\n" + facet.replace("      vertex 0 1 0\n", "")
                                          + "endsolid t\n").encode()
    c["stl_ascii_missing_endloop.stl"] = ("solid t\n" + facet.replace("    endloop\n", "")
                                          + "endsolid t\n").encode()
    c["stl_ascii_junk_keyword.stl"] = ("solid t\n" + facet + "  facet_normal 0 0 1\nendsolid t\n").encode()
    # ---- PLY ----
    ply_ascii_ok = (b"ply\nformat ascii 1.0\ncomment extra property\nelement vertex 4\n"
                    b"property float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                    b"element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                    b"0 0 0 255\n1 0 0 255\n0 1 0 255\n0 0 1 255\n")
    c["ply_ascii_index_out_of_range.ply"] = ply_ascii_ok + b"3 0 2 1\n3 0 1 4\n"
    c["ply_ascii_truncated.ply"] = ply_ascii_ok + b"3 0 2 1\n3 0 1"
    c["ply_ascii_nan.ply"] = ply_ascii_ok.replace(b"1 0 0 255", b"1 NaN 0 255") + b"3 0 2 1\n3 0 1 3\n"
    c["ply_missing_end_header.ply"] = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
    c["ply_bad_format.ply"] = ply_header("binary_middle_endian", 3, 1) + b"\0" * 60
    c["ply_unknown_type.ply"] = ply_header("ascii", 3, 1, vtype="float128") + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    c["ply_absurd_count.ply"] = ply_header("binary_little_endian", 4000000000, 1) + b"\0" * 40
    c["ply_no_vertex_indices.ply"] = (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                      b"property float y\nproperty float z\nelement face 1\n"
                                      b"property list uchar int vertex_ids\nend_header\n"
                                      b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    c["ply_binary_le_truncated.ply"] = ply_binary(TET_V, TET_F)[:-7]
    c["ply_binary_be_index_out_of_range.ply"] = ply_binary(
        TET_V, TET_F[:3] + [(1, 2, 4)], endian=">", fmt="binary_big_endian")
    c["ply_binary_huge_list.ply"] = (ply_header("binary_little_endian", 3, 1, count="int")
                                     + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
                                     + struct.pack("<i", 2000000000) + struct.pack("<3i", 0, 1, 2))
    nan_v = list(TET_V)
    nan_v[1] = (1, 0, float("inf"))
    c["ply_binary_inf.ply"] = ply_binary(nan_v, TET_F)
    c["ply_binary_two_vertex_face.ply"] = ply_binary(TET_V, TET_F[:1] + [(0, 1)])
    c["ply_binary_no_faces.ply"] = ply_binary(TET_V, [])
    # ---- content sniffing: unknown extension and no recognisable content ----
    c["unknown_format.bin"] = b"\x7fELF" + bytes(96)
    return c


def main():
    os.makedirs(OUT, exist_ok=True)
    for name, data in sorted(cases().items()):
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
    print(f"wrote {len(cases())} files to {os.path.normpath(OUT)}")


if __name__ == "__main__":
    main()
