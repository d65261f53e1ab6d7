// Moving single vertices where no collapse or flip may help: in necks after every whole-mesh
// iteration, and anywhere once after the last one (Remesher::polish).
//
// dragon.off has fins about 0.02 % of the diagonal thick whose necks are narrower than
// min_length (neck.cpp sizes them by their girth). Meshed with edges of a third of that girth,
// the rows of vertices along the two sides of a flat neck are a fraction of an edge apart: the
// link condition forbids the collapses there, every flip folds the surface, and slivers (down
// to 7 degrees) and crossings of the two sides stayed whatever the sizing. Such a vertex nearly
// always has a place in its own fan where every triangle is well shaped: a pattern search for
// it, each candidate projected onto the reference, finds it. Nothing else is changed: no
// connectivity (so never the topology), and no vertex whose fan would get worse.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// Rounds over the slivers that remain (a move can leave a neighbour's fan the worst one).
constexpr int kSliverRounds = 10;
// Candidate positions tried per vertex: eight directions per step size.
constexpr int kMaxEvaluations = 96;
// First step of the search, as a fraction of the vertex's shortest edge; it halves down to
// 1/64 of that whenever no direction improves.
constexpr double kFirstStep = 0.25;
constexpr double kSmallestStep = kFirstStep / 64;
// A moved triangle may turn by up to 60 degrees (cos 0.5), as in a collapse: no fold-over.
constexpr double kMinNormalCos = 0.5;
// The other side of a thin fin lies within this many rings of a vertex (edges of a third of
// the girth: about two rings around the neck's rim).
constexpr int kNearRings = 3;
// ... and at most this many vertices (a stray vertex far away may gather thousands of needles).
constexpr size_t kMaxRing = 64;
// The pass is for the few slivers that the other passes leave. A mesh full of them (the needles
// around such a stray vertex, which no move can fix) gets at most this many placements per
// call, plus one per kPlacementsPerVertex vertices of the mesh: the dragon's necks need about
// 1200 in the first iteration.
constexpr size_t kMinPlacements = 500;
constexpr size_t kPlacementsPerVertex = 256;
// ... and at most this many tests of a triangle pair in the fans of the vertices placed, plus so
// many per vertex of the mesh (the dragon's necks need about 200k per iteration).
constexpr size_t kMinCrossingTests = 1000000;
constexpr size_t kCrossingTestsPerVertex = 16;
// Pairs of neck triangles tested for crossings, per neck triangle.
constexpr size_t kPairTestsPerFace = 16;
// A vertex of higher valence is a hub (the needles around a stray vertex) that no move fixes.
constexpr size_t kMaxPlacedValence = 16;
// How far from the reference a vertex may move to separate two crossing sides, in epsilons.
constexpr double kOffSurface = 0.5;
constexpr double kKeepCoverMinSin2 = 0.0670;  // sin^2 15 degrees

double orient(const Point& a, const Point& b, const Point& c, const Point& d) {
  return glm::dot(glm::cross(b - a, c - a), d - a);
}

// Whether the segment pq crosses the plane of abc inside the triangle (not coplanar).
bool segment_crosses(const Point& p, const Point& q, const Point& a, const Point& b, const Point& c) {
  const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || (sp == 0 && sq == 0)) return false;
  const double s1 = orient(p, q, a, b), s2 = orient(p, q, b, c), s3 = orient(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// A triangle by its corners, with its bounding box.
struct Tri {
  Vertex v[3];
  Point p[3];
  Point lo, hi;
  void set(const SurfaceMesh& m, Vertex a, Vertex b, Vertex c) {
    v[0] = a, v[1] = b, v[2] = c;
    for (int i = 0; i < 3; ++i) p[i] = m.position(v[i]);
    lo = glm::min(p[0], glm::min(p[1], p[2]));
    hi = glm::max(p[0], glm::max(p[1], p[2]));
  }
  bool has(Vertex w) const { return v[0] == w || v[1] == w || v[2] == w; }
};

// Whether two triangles cross other than in shared corners: an edge of one passes through the
// other. Triangles sharing an edge never count (the mesh's own dihedral), and an edge from a
// shared corner can meet the other triangle only there unless the two are coplanar.
bool triangles_cross(const Tri& s, const Tri& t) {
  for (int i = 0; i < 3; ++i)
    if (s.lo[i] > t.hi[i] || t.lo[i] > s.hi[i]) return false;
  int shared = 0;
  for (Vertex w : s.v) shared += t.has(w);
  if (shared >= 2) return false;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (!t.has(s.v[i]) && !t.has(s.v[j]) && segment_crosses(s.p[i], s.p[j], t.p[0], t.p[1], t.p[2])) return true;
    if (!s.has(t.v[i]) && !s.has(t.v[j]) && segment_crosses(t.p[i], t.p[j], s.p[0], s.p[1], s.p[2])) return true;
  }
  return false;
}
}  // namespace

size_t Remesher::Impl::place_sliver_vertices(double angle_deg, bool necks_only) {
  if (!has_reference || reference_stale || mirror_axis >= 0 || (necks_only && necks.empty())) return 0;
  const double sin_limit = portable::sin(angle_deg * M_PI / 180.0);
  const double sin2_limit = sin_limit * sin_limit;

  // Only necks have a sizing below min_length (neck.cpp): there the two sides of a fin come
  // within an edge of each other, and a vertex may push one side through the other.
  auto in_neck = [&](Vertex v) { return !necks.empty() && sizing[v] < opt.min_length; };

  // ---- one vertex: its fan (the triangles a move reshapes) and the faces near it
  std::vector<Tri> star, near;
  std::vector<Vec3> old_normals;
  std::vector<Vertex> ring;
  std::vector<std::uint32_t> ring_stamp, ring_index;
  std::uint32_t ring_run = 0;
  auto gather = [&](Vertex v, bool with_near) {
    star.clear();
    old_normals.clear();
    for (Halfedge out : mesh.halfedges(v)) {
      if (mesh.is_boundary(out)) continue;
      star.emplace_back().set(mesh, v, mesh.to_vertex(out), mesh.to_vertex(mesh.next(out)));
      const Tri& t = star.back();
      old_normals.push_back(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
    }
    near.clear();
    if (!with_near) return;
    // Rings by breadth-first search; ring_index marks the members (stamped per search) with
    // their position, so that each face is taken once, from its first corner in the ring.
    if (++ring_run == 0) {
      std::fill(ring_stamp.begin(), ring_stamp.end(), 0);
      ring_run = 1;
    }
    ring_stamp.resize(mesh.vertices_size(), 0);
    ring_index.resize(mesh.vertices_size());
    auto join = [&](Vertex w) {
      if (ring_stamp[w.idx] == ring_run) return;
      ring_stamp[w.idx] = ring_run;
      ring_index[w.idx] = static_cast<std::uint32_t>(ring.size());
      ring.push_back(w);
    };
    ring.clear();
    join(v);
    for (size_t begin = 0, r = 0; r < kNearRings && ring.size() < kMaxRing; ++r) {
      const size_t end = ring.size();
      for (size_t i = begin; i < end && ring.size() < kMaxRing; ++i)
        for (Vertex w : mesh.vertices(ring[i])) join(w);
      begin = end;
    }
    auto earlier = [&](Vertex w, size_t i) { return ring_stamp[w.idx] == ring_run && ring_index[w.idx] < i; };
    for (size_t i = 1; i < ring.size(); ++i)
      for (Halfedge out : mesh.halfedges(ring[i])) {
        if (mesh.is_boundary(out)) continue;
        const Vertex a = mesh.to_vertex(out), b = mesh.to_vertex(mesh.next(out));
        if (a == v || b == v || earlier(a, i) || earlier(b, i)) continue;  // the fan of v is `star`
        near.emplace_back().set(mesh, ring[i], a, b);
      }
  };
  // The fan with v at p: its smallest angle as a squared sine, -1 when a triangle turned too far
  // or lost its area.
  auto fan_quality = [&](const Point& p) {
    double worst = 1.0;
    for (size_t k = 0; k < star.size(); ++k) {
      const Tri& t = star[k];
      const Vec3 n = glm::cross(t.p[1] - p, t.p[2] - p), o = old_normals[k];
      const double ln = glm::length(n), lo = glm::length(o);
      if (!(ln > 0) || (lo > 0 && glm::dot(n, o) < kMinNormalCos * ln * lo)) return -1.0;
      worst = std::min(worst, min_angle_sin2(p, t.p[1], t.p[2]));
    }
    return worst;
  };
  // How many times the fan crosses itself and the faces near v, with v where the mesh has it.
  size_t crossing_tests = 0;
  const size_t max_crossing_tests = kMinCrossingTests + kCrossingTestsPerVertex * mesh.n_vertices();
  auto fan_crossings = [&]() {
    for (Tri& t : star) t.set(mesh, t.v[0], t.v[1], t.v[2]);
    int n = 0;
    crossing_tests += star.size() * (near.size() + star.size());
    for (size_t i = 0; i < star.size(); ++i) {
      for (const Tri& t : near) n += triangles_cross(star[i], t);
      for (size_t j = i + 1; j < star.size(); ++j) n += triangles_cross(star[i], star[j]);
    }
    return n;
  };

  // ---- the pattern search: steps in eight directions of the tangent plane, each candidate
  // projected onto the reference, the step halved when none is better. A position is better when
  // its fan crosses fewer faces, or as many and its smallest angle is larger; the smallest angle
  // never drops below the limit or its value at the start. Crossings are counted in necks only:
  // elsewhere the normal test is enough, as for a collapse or a flip.
  auto place = [&](Vertex v) {
    const bool neck = in_neck(v);
    gather(v, neck);
    const Point start = mesh.position(v);
    const std::uint32_t start_hint = ref_hint[v];
    const double start_sizing = sizing[v];
    double quality = fan_quality(start);
    // The fan keeps the reference points it covers covered (coverage.cpp), unless it mends a
    // triangle under 15 degrees: the polish after the last iteration wore a CAD part's edge
    // (cgal/rotor_small at epsilon 0.5 %: 1.4 % of the diagonal off, against the target's 1 %),
    // but always keeping them left a 14.9-degree triangle on cgal/camel at 0.5 % (25.7 without).
    const bool keep_cover = quality >= kKeepCoverMinSin2;
    if (keep_cover) note_cover_duty(v);
    int crossings = neck ? fan_crossings() : 0;
    const double floor = std::min(quality, sin2_limit);
    Vec3 normal(0.0);
    for (const Vec3& n : old_normals) normal += n;
    double shortest = std::numeric_limits<double>::infinity();
    for (const Tri& t : star) shortest = std::min(shortest, glm::length(t.p[1] - start));
    const double nl = glm::length(normal);
    if (!(nl > 0) || !(shortest > 0) || quality < 0) return false;
    normal /= nl;
    Vec3 t1 = glm::cross(normal, std::abs(normal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
    t1 /= glm::length(t1);
    const Vec3 t2 = glm::cross(normal, t1);
    const double r = std::sqrt(0.5);
    const Vec3 dirs[8] = {t1, -t1, t2, -t2, r * (t1 + t2), -r * (t1 + t2), r * (t1 - t2), -r * (t1 - t2)};
    struct Candidate {
      double quality;
      Point p;
      std::uint32_t hint;
      double sizing;
    };
    std::array<Candidate, 10> tried;  // the eight tangent steps and the two along the normal
    Point best_p = start;
    std::uint32_t best_hint = start_hint;
    double best_sizing = start_sizing;
    int evaluations = 0;
    for (double h = kFirstStep * shortest; h >= kSmallestStep * shortest && evaluations < kMaxEvaluations;) {
      int n_tried = 0;
      for (const Vec3& d : dirs) {
        mesh.position(v) = best_p + h * d;
        ref_hint[v] = best_hint;
        project(v, normal);  // the fan's normal at the start: which sheet v is on
        ++evaluations;
        const double q = fan_quality(mesh.position(v));
        if (q >= floor && (!keep_cover || move_keeps_cover(v, start)))
          tried[n_tried++] = {q, mesh.position(v), ref_hint[v], sizing[v]};
      }
      // Two sides of a fin that cross are a fraction of an edge apart, both on the reference:
      // no position on it separates them. Off it, along the normal, within half the tolerance.
      for (double sign : {1.0, -1.0}) {
        if (crossings == 0) break;
        const Point p = best_p + sign * h * normal;
        const geometry::TriangleTree::ClosestHit hit = closest_on_reference(p, best_hint);
        if (hit.distance2 > kOffSurface * kOffSurface * opt.epsilon * opt.epsilon) continue;
        const double q = fan_quality(p);
        if (q >= floor) tried[n_tried++] = {q, p, hit.triangle, best_sizing};
      }
      // Best angle first; the crossings (the costly test) only until one is accepted.
      std::stable_sort(tried.begin(), tried.begin() + n_tried,
                       [](const Candidate& a, const Candidate& b) { return a.quality > b.quality; });
      bool moved = false;
      for (int i = 0; i < n_tried && !moved; ++i) {
        if (crossings == 0 && tried[i].quality <= quality) break;
        mesh.position(v) = tried[i].p;
        const int c = neck ? fan_crossings() : 0;
        if (c < crossings || (c == crossings && tried[i].quality > quality)) {
          quality = tried[i].quality;
          crossings = c;
          best_p = tried[i].p;
          best_hint = tried[i].hint;
          best_sizing = tried[i].sizing;
          moved = true;
        }
      }
      if (!moved) h *= 0.5;
    }
    mesh.position(v) = best_p;
    ref_hint[v] = best_hint;
    sizing[v] = best_p == start ? start_sizing : best_sizing;
    if (best_p == start) return false;
    // Better angles, but not at the price of a crossing with the surface around the fan, nor of
    // an edge off the reference (fidelity.cpp: a tip's fan turned around it cuts the tip off). A
    // fan off the reference already may move, but not farther off: polish()'s placement took an
    // edge across a right-angled crease from 2 to 4.5 tolerances off (a D-shaped prism at epsilon
    // 0.2 %, Hausdorff 2.5 x the target).
    const bool strays = fan_strays(v);
    if (crossing_guard.fan_crosses(mesh, v) ||
        (strays && (!fan_strayed_at(v, start, start_hint) ||
                    fan_stray_peak2(v, mesh.position(v), ref_hint[v]) > fan_stray_peak2(v, start, start_hint))) ||
        (anchored(v) && !anchor_holds(v, mesh.position(v))) || (keep_cover && !move_keeps_cover(v, start))) {
      mesh.position(v) = start;
      ref_hint[v] = start_hint;
      sizing[v] = start_sizing;
      return false;
    }
    note_fan_changed(v);
    return true;
  };

  // ---- which vertices: the corners of slivers, and in necks the corners of crossing triangles
  std::vector<Vertex> corners, moved_vertices;
  std::vector<mesh::Face> neck_faces;  // a corner in a neck; the pass changes no connectivity
  std::vector<Tri> thin;
  std::vector<std::pair<Tri, Tri>> crossing;
  auto add_corners = [&](const Vertex* c) {
    for (int i = 0; i < 3; ++i)
      if (movable(c[i]) && vclass[c[i]] == kFree && (!necks_only || in_neck(c[i]))) corners.push_back(c[i]);
  };
  // A face in a neck has edges shorter than the split threshold of min_length; a longer one is
  // no neck (a needle to a stray vertex far away, which no split can shorten) and is left out
  // of the pairwise test, whose sweep it would make quadratic.
  auto small = [&](const Vertex* c) {
    const double limit = 2 * opt.min_length;
    for (int i = 0; i < 3; ++i) {
      const Vec3 d = mesh.position(c[i]) - mesh.position(c[(i + 1) % 3]);
      if (glm::dot(d, d) > limit * limit) return false;
    }
    return true;
  };
  auto add_if_sliver = [&](const Vertex* c) {
    if (min_angle_sin2(mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])) < sin2_limit) add_corners(c);
  };
  size_t moved = 0, placements = 0;
  const size_t max_placements = kMinPlacements + mesh.n_vertices() / kPlacementsPerVertex;
  for (int round = 0; round < kSliverRounds && placements < max_placements && crossing_tests < max_crossing_tests;
       ++round) {
    corners.clear();
    if (round == 0) {
      // Flat arrays: this scan runs on every mesh and mostly finds nothing.
      const auto* hc = mesh.halfedge_connectivity_data();
      const Halfedge* fh = mesh.face_halfedge_data();
      const std::uint8_t* fdel = mesh.face_deleted_data();
      const mesh::Index n_faces = static_cast<mesh::Index>(mesh.faces_size());
      for (mesh::Index f = 0; f < n_faces; ++f) {
        if (fdel[f]) continue;
        const Halfedge h0 = fh[f], h1 = hc[h0.idx].next, h2 = hc[h1.idx].next;
        const Vertex c[3] = {hc[h0.idx].to, hc[h1.idx].to, hc[h2.idx].to};
        add_if_sliver(c);
        if (in_neck(c[0]) && in_neck(c[1]) && in_neck(c[2]) && small(c)) neck_faces.push_back(mesh::Face(f));
      }
    } else {
      // Only the fans of the vertices moved in the last round changed.
      for (Vertex v : moved_vertices)
        for (mesh::Face f : mesh.faces(v)) {
          Vertex c[3];
          mesh.face_vertices(f, c);
          add_if_sliver(c);
        }
    }
    // The passes before may have pushed one side of a fin through the other: the triangles at
    // necks are tested pairwise once (sorted along x, the pairs whose boxes overlap), then the
    // pairs found again after each round (a move never adds a crossing in its rings).
    if (round == 0) {
      thin.reserve(neck_faces.size());
      for (mesh::Face f : neck_faces) {
        Vertex c[3];
        mesh.face_vertices(f, c);
        thin.emplace_back().set(mesh, c[0], c[1], c[2]);
      }
      std::sort(thin.begin(), thin.end(), [](const Tri& a, const Tri& b) {
        if (a.lo.x != b.lo.x) return a.lo.x < b.lo.x;
        return std::lexicographical_compare(a.v, a.v + 3, b.v, b.v + 3);
      });
      // Bounded like the placements: a degenerate input can make most pairs overlap.
      size_t tests = kPairTestsPerFace * thin.size();
      for (size_t i = 0; i < thin.size() && tests > 0 && crossing.size() < max_placements; ++i)
        for (size_t j = i + 1; j < thin.size() && thin[j].lo.x <= thin[i].hi.x && tests > 0; ++j, --tests)
          if (triangles_cross(thin[i], thin[j])) crossing.push_back({thin[i], thin[j]});
    }
    size_t still = 0;
    for (auto& [s, t] : crossing) {
      s.set(mesh, s.v[0], s.v[1], s.v[2]);
      t.set(mesh, t.v[0], t.v[1], t.v[2]);
      if (!triangles_cross(s, t)) continue;
      add_corners(s.v);
      add_corners(t.v);
      crossing[still++] = {s, t};
    }
    crossing.resize(still);
    if (corners.empty()) break;
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    corners.erase(std::remove_if(corners.begin(), corners.end(),
                                 [&](Vertex v) { return mesh.valence(v) > kMaxPlacedValence; }),
                  corners.end());
    moved_vertices.clear();
    for (Vertex v : corners) {
      if (placements == max_placements || crossing_tests >= max_crossing_tests) break;
      ++placements;
      if (place(v)) moved_vertices.push_back(v);
    }
    moved += moved_vertices.size();
    if (moved_vertices.empty()) break;
  }
  return moved;
}

}  // namespace adasculpt::remesh
