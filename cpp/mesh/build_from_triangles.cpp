#include "mesh/build_from_triangles.h"

#include <algorithm>
#include <numeric>

#include "mesh/orient_faces.h"

namespace adasculpt::mesh {

namespace {

struct DirectedEdge {
  std::uint32_t lo, hi;  // sorted endpoints: the undirected key
  std::uint32_t corner;  // 3 * face + i: the halfedge from corner i to corner i+1
  bool forward;          // from lo to hi
};

// Two faces (and only two) on one edge, both running it from lo to hi or both from hi to lo.
bool has_neighbours_running_alike(const std::vector<DirectedEdge>& sorted) {
  for (size_t k = 0; k + 1 < sorted.size(); ++k) {
    const DirectedEdge &x = sorted[k], &y = sorted[k + 1];
    const bool two = x.lo == y.lo && x.hi == y.hi &&
                     (k + 2 >= sorted.size() || sorted[k + 2].lo != x.lo || sorted[k + 2].hi != x.hi) &&
                     (k == 0 || sorted[k - 1].lo != x.lo || sorted[k - 1].hi != x.hi);
    if (two && x.forward == y.forward) return true;
  }
  return false;
}

// Sorts by (lo, hi, corner): a counting sort by lo, then each vertex's few edges by hi. The
// edges come in corner order and both steps are stable, so equal keys stay in corner order: the
// same sequence as a comparison sort, in linear time (std::sort was 4 % of the instructions of a
// command-line remesh of bunny.off at the defaults, loading included).
constexpr std::uint32_t kInsertionSortMax = 32;

void sort_by_key(std::vector<DirectedEdge>& des, std::uint32_t n_points) {
  std::vector<std::uint32_t> start(size_t(n_points) + 1, 0);
  for (const DirectedEdge& d : des) ++start[d.lo + 1];
  for (std::uint32_t v = 0; v < n_points; ++v) start[v + 1] += start[v];
  std::vector<DirectedEdge> sorted(des.size());
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (const DirectedEdge& d : des) sorted[next[d.lo]++] = d;
  }
  for (std::uint32_t v = 0; v < n_points; ++v) {
    // A fan's centre (a CAD disc's, a cone's apex) may have thousands: sorted as before.
    if (start[v + 1] - start[v] > kInsertionSortMax) {
      std::sort(sorted.begin() + start[v], sorted.begin() + start[v + 1], [](const DirectedEdge& x, const DirectedEdge& y) {
        return x.hi != y.hi ? x.hi < y.hi : x.corner < y.corner;
      });
      continue;
    }
    // Insertion sort by hi: a vertex has a handful of edges from it as the lower end.
    for (std::uint32_t i = start[v] + 1; i < start[v + 1]; ++i) {
      const DirectedEdge d = sorted[i];
      std::uint32_t j = i;
      for (; j > start[v] && sorted[j - 1].hi > d.hi; --j) sorted[j] = sorted[j - 1];
      sorted[j] = d;
    }
  }
  des.swap(sorted);
}

std::string vertex_pair(std::uint32_t a, std::uint32_t b) {
  return "vertices " + std::to_string(a) + " and " + std::to_string(b);
}

}  // namespace

SurfaceMesh build_from_triangles(const std::vector<std::array<double, 3>>& points,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                 BuildReport* report_out) {
  BuildReport report;
  const std::uint32_t n_points = static_cast<std::uint32_t>(points.size());

  // Faces that survive: valid indices, three distinct corners.
  std::vector<std::array<std::uint32_t, 3>> faces;
  faces.reserve(triangles.size());
  for (size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    for (auto i : t)
      if (i >= n_points)
        throw TopologyError("face " + std::to_string(f) + " refers to vertex " + std::to_string(i) + ", there are " +
                            std::to_string(n_points) + " vertices");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++report.dropped_faces;
      continue;
    }
    faces.push_back(t);
  }
  if (report.dropped_faces)
    report.warnings.push_back("dropped " + std::to_string(report.dropped_faces) + " face(s) with a repeated vertex");
  if (faces.empty()) throw TopologyError("the mesh has no faces");

  // Pair up the directed edges of all corners by their undirected key.
  const size_t n_corners = 3 * faces.size();
  std::vector<DirectedEdge> des(n_corners);
  auto pair_up_edges = [&] {
    for (size_t f = 0; f < faces.size(); ++f)
      for (unsigned i = 0; i < 3; ++i) {
        std::uint32_t a = faces[f][i], b = faces[f][(i + 1) % 3];
        des[3 * f + i] = {std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(3 * f + i), a < b};
      }
    sort_by_key(des, n_points);
  };
  pair_up_edges();
  // Neighbours that run their common edge the same way: the soup's faces disagree about which
  // side is out. Reversing faces repairs that unless the surface is one-sided.
  if (has_neighbours_running_alike(des)) {
    report.reoriented_faces = orient_faces_consistently(points, faces);
    if (report.reoriented_faces)
      report.warnings.push_back("reversed " + std::to_string(report.reoriented_faces) +
                                " face(s) to orient the surface consistently");
    pair_up_edges();
  }

  // Compact vertex numbering: only referenced vertices are kept.
  std::vector<Index> vmap(n_points, kInvalidIndex);
  SurfaceMesh mesh;
  {
    std::vector<std::uint8_t> used(n_points, 0);
    for (const auto& t : faces)
      for (auto i : t) used[i] = 1;
    size_t n_used = std::count(used.begin(), used.end(), 1);
    report.unreferenced_vertices = n_points - n_used;
    // An eighth more of every element: the first sculpting strokes add some without copying
    // the arrays (as SurfaceMesh::reserve_room_for_edits).
    const size_t edges = faces.size() * 3 / 2 + 16;
    mesh.reserve(n_used + n_used / 8, edges + edges / 8, faces.size() + faces.size() / 8);
    for (std::uint32_t i = 0; i < n_points; ++i)
      if (used[i]) vmap[i] = mesh.add_vertex(Point(points[i][0], points[i][1], points[i][2])).idx;
  }
  if (report.unreferenced_vertices)
    report.warnings.push_back("ignored " + std::to_string(report.unreferenced_vertices) + " unreferenced vertices");
  std::vector<std::uint32_t> original_index(mesh.vertices_size());
  for (std::uint32_t i = 0; i < n_points; ++i)
    if (vmap[i] != kInvalidIndex) original_index[vmap[i]] = i;

  std::vector<Halfedge> corner_halfedge(n_corners);
  for (size_t k = 0; k < des.size();) {
    size_t end = k + 1;
    while (end < des.size() && des[end].lo == des[k].lo && des[end].hi == des[k].hi) ++end;
    const size_t count = end - k;
    if (count > 2)
      throw TopologyError("non-manifold edge between " + vertex_pair(des[k].lo, des[k].hi) + " (" +
                          std::to_string(count) + " faces)");
    if (count == 2 && des[k].forward == des[k + 1].forward)
      throw TopologyError("inconsistent face orientation at the edge between " + vertex_pair(des[k].lo, des[k].hi));
    Vertex lo(vmap[des[k].lo]), hi(vmap[des[k].hi]);
    Halfedge forward = mesh.new_edge(lo, hi);  // lo -> hi
    for (size_t j = k; j < end; ++j)
      corner_halfedge[des[j].corner] = des[j].forward ? forward : SurfaceMesh::opposite(forward);
    k = end;
  }

  // Faces.
  for (size_t f = 0; f < faces.size(); ++f) {
    Face face = mesh.new_face();
    Halfedge h[3] = {corner_halfedge[3 * f], corner_halfedge[3 * f + 1], corner_halfedge[3 * f + 2]};
    for (unsigned i = 0; i < 3; ++i) {
      mesh.set_next(h[i], h[(i + 1) % 3]);
      mesh.set_face(h[i], face);
      mesh.set_halfedge(mesh.from_vertex(h[i]), h[i]);
    }
    mesh.set_halfedge(face, h[0]);
  }

  // Fans: walk around each vertex over interior halfedges. Every fan after the first gets a
  // vertex of its own (boundary halfedges have no links yet, so the walk stops at them).
  const Index n_he = static_cast<Index>(mesh.halfedges_size());
  std::vector<std::uint8_t> visited(n_he, 0);
  std::vector<std::vector<Halfedge>> outgoing(mesh.vertices_size());
  for (Index i = 0; i < n_he; ++i) {
    Halfedge h(i);
    if (!mesh.is_boundary(h)) outgoing[mesh.from_vertex(h).idx].push_back(h);
  }
  const size_t n_original_vertices = mesh.vertices_size();
  std::vector<Halfedge> fan;
  for (Index vi = 0; vi < n_original_vertices; ++vi) {
    bool first_fan = true;
    for (Halfedge seed : outgoing[vi]) {
      if (visited[seed.idx]) continue;
      fan.clear();
      // Walk one way (ccw), then the other (cw) when the walk hit the boundary.
      Halfedge h = seed;
      bool closed = false;
      do {
        fan.push_back(h);
        visited[h.idx] = 1;
        Halfedge next = mesh.ccw_rotated(h);
        if (mesh.is_boundary(next)) break;
        h = next;
        if (h == seed) closed = true;
      } while (!closed);
      if (!closed) {
        Halfedge o = SurfaceMesh::opposite(seed);
        while (!mesh.is_boundary(o)) {
          h = mesh.next(o);
          fan.push_back(h);
          visited[h.idx] = 1;
          o = SurfaceMesh::opposite(h);
        }
      }
      if (first_fan) {
        first_fan = false;
        continue;
      }
      Vertex v = mesh.add_vertex(mesh.position(Vertex(vi)));
      original_index.push_back(original_index[vi]);
      for (Halfedge out : fan) mesh.set_vertex(SurfaceMesh::opposite(out), v);
      for (Halfedge out : fan) mesh.set_vertex(mesh.prev(out), v);
      mesh.set_halfedge(v, fan.front());
      mesh.set_halfedge(Vertex(vi), Halfedge());
      ++report.split_vertices;
    }
    // The first fan keeps the original vertex; make sure its halfedge belongs to that fan.
    if (!mesh.halfedge(Vertex(vi)).is_valid() || mesh.from_vertex(mesh.halfedge(Vertex(vi))) != Vertex(vi)) {
      for (Halfedge out : outgoing[vi])
        if (mesh.from_vertex(out) == Vertex(vi)) {
          mesh.set_halfedge(Vertex(vi), out);
          break;
        }
    }
  }
  if (report.split_vertices)
    report.warnings.push_back("split " + std::to_string(report.split_vertices) +
                              " non-manifold vertex fan(s) into separate vertices");

  // Boundary loops: each boundary halfedge continues with the boundary halfedge leaving its end.
  std::vector<Halfedge> boundary_out(mesh.vertices_size());
  for (Index i = 0; i < n_he; ++i) {
    Halfedge h(i);
    if (mesh.is_boundary(h)) {
      Vertex from = mesh.from_vertex(h);
      if (boundary_out[from.idx].is_valid())
        // Cannot happen after fan splitting; kept as a guard against a broken invariant.
        throw TopologyError("vertex " + std::to_string(original_index[from.idx]) + " lies on the boundary twice");
      boundary_out[from.idx] = h;
    }
  }
  for (Index i = 0; i < n_he; ++i) {
    Halfedge h(i);
    if (mesh.is_boundary(h)) {
      mesh.set_next(h, boundary_out[mesh.to_vertex(h).idx]);
      mesh.set_halfedge(mesh.from_vertex(h), h);
    }
  }
  mesh.validate();
  if (report_out) *report_out = std::move(report);
  return mesh;
}

}  // namespace adasculpt::mesh
