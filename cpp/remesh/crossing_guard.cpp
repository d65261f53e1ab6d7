// No operation of a whole-mesh iteration may make the surface cross itself (issue 17 item 2).
// The per-face orientation tests of the passes only look at the one-ring: a collapse on one side
// of a thin part (a dragon's fin, a CAD part's coarse wall) can push its new triangles through
// the other side a few rings away while every triangle keeps its orientation (dragon, uniform
// 8 % with features at 45 degrees: 566 crossing pairs). Here the triangles an operation would
// create are tested exactly (geometry/self_intersections) against every face whose box their
// box touches, found in a hash grid of the current faces (geometry/face_grid) kept up to date by
// the operations; a crossing refuses the collapse or flip, and sends a relaxed vertex back.
//
// Whole-mesh iterations only: a sculpting frame's region would need the faces around it, and its
// budget has no room for them (the frame path pays a test of grid.built() per operation).
#include <algorithm>
#include <array>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/self_intersections.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// Cells as long as this many mean edges: a face's box then covers about one to eight cells.
constexpr double kCellEdges = 3.0;
}  // namespace

void Remesher::Impl::start_crossing_guard() {
  if (!whole_mesh) return;
  const auto* hc = mesh.halfedge_connectivity_data();
  const Point* pos = mesh.positions().data();
  double sum = 0;
  size_t n = 0;
  // The mean edge: where the collapses that follow make faces larger, the grid's cells grow too
  // (FaceGrid::insert). Cells of the target length would hold hundreds of a fine input's faces.
  for (Edge e : mesh.edges()) {
    sum += glm::length(pos[hc[e.idx << 1].to.idx] - pos[hc[(e.idx << 1) | 1u].to.idx]);
    ++n;
  }
  if (n == 0) return;
  face_grid.build(mesh, kCellEdges * sum / static_cast<double>(n));
}

void Remesher::Impl::stop_crossing_guard() {
  face_grid.clear();
}

// The faces near the triangles are gathered once for all of them (an operation's new triangles
// are neighbours: their boxes overlap), then each candidate is read once from the mesh.
Remesher::Impl::Crossing Remesher::Impl::triangles_cross_nearby(const GuardTriangle* ts, size_t n, Vertex replaced0,
                                                                Vertex replaced1, Face skip0, Face skip1) const {
  Crossing crossing;
  if (n == 0) return crossing;
  Point lo = ts[0].p[0], hi = ts[0].p[0];
  for (size_t i = 0; i < n; ++i) {
    if (geometry::collinear(ts[i].p[0], ts[i].p[1], ts[i].p[2])) {  // no orientation: never created
      crossing.found = true;
      crossing.triangle = i;
      return crossing;
    }
    for (const Point& p : ts[i].p) lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  guard_candidates.clear();
  face_grid.gather(lo, hi, guard_candidates);
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* fh = mesh.face_halfedge_data();
  const std::uint8_t* fdel = mesh.face_deleted_data();
  const Point* pos = mesh.positions().data();
  auto disjoint = [](const Point& alo, const Point& ahi, const Point& blo, const Point& bhi) {
    return ahi.x < blo.x || alo.x > bhi.x || ahi.y < blo.y || alo.y > bhi.y || ahi.z < blo.z || alo.z > bhi.z;
  };
  for (const Face g : guard_candidates) {
    if (g.idx >= mesh.faces_size() || fdel[g.idx] || g == skip0 || g == skip1) continue;
    const Halfedge h0 = fh[g.idx], h1 = hc[h0.idx].next, h2 = hc[h1.idx].next;
    const std::array<std::uint32_t, 3> ids = {hc[h0.idx].to.idx, hc[h1.idx].to.idx, hc[h2.idx].to.idx};
    if (ids[0] == replaced0.idx || ids[1] == replaced0.idx || ids[2] == replaced0.idx || ids[0] == replaced1.idx ||
        ids[1] == replaced1.idx || ids[2] == replaced1.idx)
      continue;  // a face the operation rewrites
    const Point q[3] = {pos[ids[0]], pos[ids[1]], pos[ids[2]]};
    const Point qlo = glm::min(q[0], glm::min(q[1], q[2])), qhi = glm::max(q[0], glm::max(q[1], q[2]));
    if (disjoint(qlo, qhi, lo, hi)) continue;  // (the grid's boxes are rounded outwards)
    bool tested_degeneracy = false;
    for (size_t i = 0; i < n; ++i) {
      const GuardTriangle& t = ts[i];
      if (g == t.face) continue;
      const Point tlo = glm::min(t.p[0], glm::min(t.p[1], t.p[2])), thi = glm::max(t.p[0], glm::max(t.p[1], t.p[2]));
      if (disjoint(qlo, qhi, tlo, thi)) continue;
      if (!tested_degeneracy) {
        tested_degeneracy = true;
        if (geometry::collinear(q[0], q[1], q[2])) break;  // left out, as the self-intersection count does
      }
      if (geometry::faces_intersect(t.p, t.ids, q, ids)) {
        // A crossing the faces being replaced have already (the input's own, which the split
        // pass multiplies) is not the operation's: refusing every operation next to one would
        // leave the slivers around it (bunny: a 6.7-degree triangle at an input crossing).
        if (crossed_already(g, q, ids, replaced0, replaced1, skip0, skip1)) break;
        crossing.found = true;
        crossing.triangle = i;
        crossing.face = g;
        return crossing;
      }
    }
  }
  return crossing;
}

bool Remesher::Impl::crossed_already(Face g, const Point q[3], const std::array<std::uint32_t, 3>& ids,
                                      Vertex replaced0, Vertex replaced1, Face skip0, Face skip1) const {
  auto crosses_g = [&](Face f) {
    if (!f.is_valid() || f == g) return false;
    mesh::Vertex c[3];
    mesh.face_vertices(f, c);
    const Point p[3] = {mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])};
    if (geometry::collinear(p[0], p[1], p[2])) return false;
    return geometry::faces_intersect(p, {c[0].idx, c[1].idx, c[2].idx}, q, ids);
  };
  for (const Vertex r : {replaced0, replaced1})
    if (r.is_valid())
      for (Face f : mesh.faces(r))
        if (crosses_g(f)) return true;
  return crosses_g(skip0) || crosses_g(skip1);
}

bool Remesher::Impl::collapse_crosses(Halfedge h, const Point& target, bool both_ends_move) const {
  if (!face_grid.built()) return false;
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  guard_triangles.clear();
  auto add_fan = [&](Vertex centre, Vertex other) {
    for (Halfedge out : mesh.halfedges(centre)) {
      if (mesh.is_boundary(out)) continue;
      const Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
      if (w == other || w2 == other) continue;  // one of the two triangles that vanish
      guard_triangles.push_back({{target, mesh.position(w), mesh.position(w2)}, {v1.idx, w.idx, w2.idx}, Face()});
    }
  };
  add_fan(v0, v1);
  if (both_ends_move) add_fan(v1, v0);
  if (triangles_cross_nearby(guard_triangles.data(), guard_triangles.size(), v0, both_ends_move ? v1 : Vertex(),
                             Face(), Face())
          .found)
    return true;
  // The new fan against itself: triangles meeting only at the survivor may still cross.
  for (size_t i = 0; i < guard_triangles.size(); ++i)
    for (size_t j = i + 1; j < guard_triangles.size(); ++j)
      if (geometry::faces_intersect(guard_triangles[i].p, guard_triangles[i].ids, guard_triangles[j].p,
                                    guard_triangles[j].ids))
        return true;
  return false;
}

bool Remesher::Impl::flip_crosses(Edge e) const {
  if (!face_grid.built()) return false;
  const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Vertex a = mesh.to_vertex(o), b = mesh.to_vertex(h);
  const Vertex c = mesh.to_vertex(mesh.next(h)), d = mesh.to_vertex(mesh.next(o));
  const Point &pa = mesh.position(a), &pb = mesh.position(b), &pc = mesh.position(c), &pd = mesh.position(d);
  // The two new triangles share the edge cd; flip_geometry_ok keeps them from folding.
  const GuardTriangle t[2] = {{{pa, pd, pc}, {a.idx, d.idx, c.idx}, Face()}, {{pd, pb, pc}, {d.idx, b.idx, c.idx}, Face()}};
  return triangles_cross_nearby(t, 2, Vertex(), Vertex(), mesh.face(h), mesh.face(o)).found;
}

Remesher::Impl::Crossing Remesher::Impl::fan_crossing(Vertex v) const {
  if (!face_grid.built()) return {};
  guard_triangles.clear();
  for (Face f : mesh.faces(v)) {
    mesh::Vertex c[3];
    mesh.face_vertices(f, c);
    guard_triangles.push_back(
        {{mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])}, {c[0].idx, c[1].idx, c[2].idx}, f});
  }
  return triangles_cross_nearby(guard_triangles.data(), guard_triangles.size(), Vertex(), Vertex(), Face(), Face());
}

void Remesher::Impl::note_flip(Edge e) {
  if (!face_grid.built()) return;
  face_grid.insert(mesh, mesh.face(mesh.halfedge(e, 0)));
  face_grid.insert(mesh, mesh.face(mesh.halfedge(e, 1)));
}

void Remesher::Impl::note_fan_changed(Vertex v) { face_grid.insert_fan(mesh, v); }

// The relaxation moves every vertex at once and the projection after it moves them again, so
// its moves are checked together afterwards: a face with a moved corner that crosses a face
// nearby sends its moved corners back to where they were before the relaxation,
// with those of the face it crosses, and the fans of the vertices sent back are checked again.
// Every vertex goes back at most once, and the mesh before the relaxation had no new crossing,
// so this ends crossing-free (but for crossings between faces that did not move: the relaxation
// did not make them). The first round checks every pair of touching boxes in one sweep over
// the grid: a search around each of the tens of thousands of moved vertices cost four times as
// much (memory-bound), the later rounds search around the few vertices sent back.
// A face that turns over without crossing anything stays: the relaxation untangles the folds of
// an input that crosses itself that way (bunny.off's two crossing pairs), and sending such faces
// back restored them.
size_t Remesher::Impl::undo_crossing_moves() {
  if (!whole_mesh || relaxed_from.size() != scope_vertices.size()) return 0;
  mesh::resize_scratch(before_move, mesh.vertices_size());
  const Point* pos = mesh.positions().data();
  std::copy(pos, pos + mesh.vertices_size(), before_move.begin());  // (masked vertices stay)
  bool any_moved = false;
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Vertex v = scope_vertices[i];
    before_move[v.idx] = relaxed_from[i];
    any_moved = any_moved || (!mesh.is_deleted(v) && relaxed_from[i] != pos[v.idx]);
  }
  if (!any_moved) return 0;
  start_crossing_guard();
  auto moved = [&](std::uint32_t w) { return pos[w] != before_move[w]; };
  auto corners = [&](Face f) {
    const auto* hc = mesh.halfedge_connectivity_data();
    const Halfedge h0 = mesh.face_halfedge_data()[f.idx], h1 = hc[h0.idx].next, h2 = hc[h1.idx].next;
    return std::array<std::uint32_t, 3>{hc[h0.idx].to.idx, hc[h1.idx].to.idx, hc[h2.idx].to.idx};
  };
  auto undo_corners = [&](const std::array<std::uint32_t, 3>& c) {
    for (std::uint32_t w : c)
      if (moved(w)) to_undo.push_back(Vertex(w));
  };
  // ---- first round: the moved faces (face_seen: the relaxation's scratch, free now)
  mesh::resize_scratch(face_seen, mesh.faces_size(), 0u);
  if (++face_run == 0) {
    std::fill(face_seen.begin(), face_seen.end(), 0);
    face_run = 1;
  }
  to_undo.clear();
  for (Face f : mesh.faces()) {
    const std::array<std::uint32_t, 3> c = corners(f);
    if (moved(c[0]) || moved(c[1]) || moved(c[2])) face_seen[f.idx] = face_run;
  }
  face_grid.for_each_overlapping_pair([&](Face f, Face g) {
    if (face_seen[f.idx] != face_run && face_seen[g.idx] != face_run) return;
    const std::array<std::uint32_t, 3> cf = corners(f), cg = corners(g);
    const Point pf[3] = {pos[cf[0]], pos[cf[1]], pos[cf[2]]}, pg[3] = {pos[cg[0]], pos[cg[1]], pos[cg[2]]};
    if (geometry::collinear(pf[0], pf[1], pf[2]) || geometry::collinear(pg[0], pg[1], pg[2])) return;
    if (!geometry::faces_intersect(pf, cf, pg, cg)) return;
    undo_corners(cf);
    undo_corners(cg);
  });
  // ---- later rounds: the fans of the vertices sent back
  size_t undone = 0;
  for (;;) {
    to_check.clear();
    for (const Vertex w : to_undo) {
      if (!moved(w.idx)) continue;  // listed twice, or back already
      mesh.position(w) = before_move[w.idx];
      face_grid.insert_fan(mesh, w);
      to_check.push_back(w);
      ++undone;
    }
    if (to_check.empty()) break;
    to_undo.clear();
    for (const Vertex v : to_check) {
      const Crossing crossing = fan_crossing(v);  // (guard_triangles: v's fan)
      if (!crossing.found) continue;
      undo_corners(guard_triangles[crossing.triangle].ids);
      if (crossing.face.is_valid()) undo_corners(corners(crossing.face));
    }
  }
  return undone;
}

}  // namespace adasculpt::remesh
