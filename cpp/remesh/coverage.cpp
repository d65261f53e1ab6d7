// The reference side of the fidelity check (issue 17's Hausdorff target). fidelity.cpp keeps every
// edge of the remeshed surface near the reference; nothing there sees a part of the reference the
// surface has left. A horn's tip is worn away that way, an iteration at a time: relaxation pulls
// the vertex on the tip towards its ring and the projection puts it back on the horn's side, a
// little lower, and every edge stays on the horn (cgal/triceratops at epsilon 1 %: the tips 1.1,
// 1.8, 2.6 and 3.1 % of the diagonal from the output after 1, 2, 3 and 5 iterations).
//
// After each whole-mesh adaptive iteration, every reference point farther than kCoverageLimit x
// the tolerance from the surface gets a vertex back on it: a corner of the nearest face moved
// there or, failing that, the nearest edge of that face split there, when the fan crosses nothing,
// turns no triangle over and keeps fair angles. The vertex is anchored to the point: never
// removed, and moved (relaxation, sliver placement) only within the limit of it. After a split
// the edges from it to the cut are long for the sizing there, so the next iteration's splits
// rebuild the part; in the last two iterations of a batch a pin only moves a vertex (with one
// iteration left, the dragon's split pins left 19-degree triangles), but for a point farther than
// the Hausdorff target of 2 tolerances, which may still get a split whose new edges stay on the
// reference. Moves alone left such points 1.0-1.4 x the target from the output (the move's
// 25-degree triangles refused): of 186 sweep runs over the Hausdorff target, late splits brought
// 17 within it and none beyond, with the same minimum angles (cgal/hand at epsilon 0.2 %: 1.21 ->
// 0.90 x the target).
// The farthest points go first, and a point within the limit of a pin made in the same call waits
// for the next: one pin per worn tip, not one per point of it.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// The gather budget of one query (cells and entries looked at) in the crossing guard's grid, whose
// cells are a few edges wide.
constexpr size_t kQueryBudget = 4096;
// How far out the nearest face of an uncovered point is looked for, in limits (the box doubles
// from 2); a point farther than that from every face is left alone.
constexpr double kFarthestSearch = 64;
// A pin's triangles may turn by up to this from the one they replace (cosine): a worn tip stands
// steeply over the cut, but a pin must not turn a triangle over.
constexpr double kMinTurnCos = 0.05;
// Pins trade angles for fidelity, and on a noisy scan a worn place is often a crumpled one
// (dragon.off at the defaults: saddles of -84 degrees among 5-degree input triangles). A vertex
// moved onto the point keeps triangles of at least 25 degrees, and a split's four at least 15,
// else the point is left as it is: with 15 and 0.6 degrees, the dragon's remesh at the defaults
// ended at 16 degrees (25.1 before pins and with these), its Hausdorff distance at 0.18 % of the
// diagonal instead of 0.23 % (0.31 % before pins).
constexpr double kMovedMinSin2 = 0.1786;  // sin^2 25 degrees
constexpr double kSplitMinSin2 = 0.0670;  // sin^2 15 degrees
// But a point on a tip (an angle deficit over 45 degrees: a horn's end, not a crumpled saddle of a
// scan) may take a split down to 3 degrees: the tent over a worn horn is steep, and the
// iterations after it rebuild the horn (cgal/triceratops at epsilon 1 %: the tips 3.1 % of the
// diagonal from the surface with the 15-degree limit, 1.5 % with this, min angle 29.6 -> 28.7).
constexpr double kTipSplitMinSin2 = 0.0027;  // sin^2 3 degrees
constexpr double kPinnedTipDeficit = M_PI / 4;
// Late splits (see above): for points farther than this many tolerances from the surface.
constexpr double kLateSplitTolerances = 2.0;
// Crease samples (sample_reference_creases): at most this many per reference edge, and in all
// this many per reference point or the floor, whichever is more; past that the spacing grows.
constexpr size_t kMaxSamplesPerEdge = 256;
// Two reference triangles this close to parallel (cosine of 1 degree) are one flat face for the
// width of a crease beside them (sample_reference_creases).
constexpr double kFlatCos = 0.99985;
constexpr size_t kSamplesPerPoint = 4;
constexpr size_t kMinSamples = 100000;
// A crease sample is pinned only where no anchored vertex lies within this many sizings of it:
// anchored vertices are never collapsed, and pins along a crease closer than the sizing left
// slivers between them.
constexpr double kCreasePinSpacing = 0.5;
// Crease samples lie this many coverage limits apart, or this many sizings where that is more.
constexpr double kSampleSpacingLimits = 1.0;
constexpr double kSampleSpacingSizings = 0.25;
}  // namespace

// Whether a vertex anchored to a point lies within `radius` of p (a box query in the guard's grid).
bool Remesher::Impl::anchored_near(const Point& p, double radius) {
  const Vec3 r(radius);
  coverage_faces.clear();
  size_t budget = kQueryBudget;
  crossing_guard.gather_faces(p - r, p + r, coverage_faces, budget);
  for (Face f : coverage_faces) {
    if (mesh.is_deleted(f)) continue;
    Vertex c[3];
    mesh.face_vertices(f, c);
    for (Vertex v : c)
      if (anchor[v] != UINT32_MAX && glm::dot(mesh.position(v) - p, mesh.position(v) - p) <= radius * radius)
        return true;
  }
  return false;
}

const Point& Remesher::Impl::cover_point(std::uint32_t id) const {
  const size_t n = tree.points().size();
  return id < n ? tree.points()[id] : crease_samples[id - n].p;
}

std::uint32_t Remesher::Impl::cover_triangle(std::uint32_t id) const {
  const size_t n = tree.points().size();
  return id < n ? ref_fan[ref_fan_offset[id]] : crease_samples[id - n].triangle;
}

double Remesher::Impl::cover_sizing(std::uint32_t id) const {
  const size_t n = tree.points().size();
  return id < n ? ref_sizing[id] : crease_samples[id - n].sizing;
}

bool Remesher::Impl::is_reference_segment(std::uint32_t a, std::uint32_t b) const {
  for (std::uint32_t k = ref_segment_offset[a]; k < ref_segment_offset[a + 1]; ++k) {
    const auto& s = ref_segments[ref_segment_of_point[k]];
    if ((s[0] == a && s[1] == b) || (s[0] == b && s[1] == a)) return true;
  }
  return false;
}

// A crease of the reference whose faces turn by theta can be cut off by a chord across it by up
// to (its reach) x sin(theta / 2), where the reach is as far as a chord's ends may lie from it:
// the width of its faces, or the length of an edge there. The sizing field does not see such a
// crease where the input is coarse: the curvature measured at a vertex spreads the crease's turn
// over the vertex's fan (cgal/hand at epsilon 0.05 %, features off: a 98-degree crease 0.16 % of
// the diagonal from the output, midway between its ends). The creases whose cut may pass the
// coverage limit are sampled every quarter of the smaller sizing at their ends (one limit at
// least). Feature lines are left out: their vertices are projected onto them.
void Remesher::Impl::sample_reference_creases() {
  crease_samples.clear();
  sampled_creases.clear();
  creases_of_triangle.clear();
  creases_of_triangle_offset.assign(tree.triangles().size() + 1, 0u);
  crease_samples_due = false;
  const double limit = coverage_limit();
  if (!(limit > 0)) return;
  const auto& pts = tree.points();
  const auto& tris = tree.triangles();
  struct Crease {
    std::uint32_t triangle, other, a, b;
    size_t count;
  };
  std::vector<Crease> creases;
  size_t total = 0;
  // Which of t's edges leads to its neighbour u.
  auto edge_to = [&](std::uint32_t t, std::uint32_t u) {
    for (int k = 0; k < 3; ++k)
      if (ref_adjacent[t][k] == u) return k;
    return 0;
  };
  // How far the flat surface at t's edge k reaches across it: t's height over the edge, or the
  // farther corner of a neighbour across t's other edges that lies in t's plane. A CAD exporter's
  // cap along a sharp edge is a few thousandths of the face it belongs to, and its height alone
  // said the edge could not be cut deeper than that: a box's edges under 0.1-degree caps went
  // unsampled, and the remeshed box was 0.79 % of the diagonal off at epsilon 0.05 %.
  auto flat_width = [&](std::uint32_t t, int k, double height) {
    const Point& a = pts[tris[t][k]];
    const Vec3 along = pts[tris[t][(k + 1) % 3]] - a;
    const double along2 = glm::dot(along, along);
    const Vec3& n = ref_normal[t];  // (build_reference_normals)
    double width = height;
    for (int side = 1; side <= 2; ++side) {
      const std::uint32_t u = ref_adjacent[t][(k + side) % 3];
      if (u == UINT32_MAX || !(glm::dot(ref_normal[u], n) > kFlatCos)) continue;
      for (std::uint32_t c : tris[u]) {
        const Vec3 d = pts[c] - a;
        const Vec3 off = d - along * (glm::dot(d, along) / along2);
        width = std::max(width, glm::length(off));
      }
    }
    return width;
  };
  for (std::uint32_t ti = 0; ti < tris.size(); ++ti) {
    const auto& t = tris[ti];
    const Vec3 n0 = glm::cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]);
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t other = ref_adjacent[ti][i];
      if (other == UINT32_MAX || other < ti) continue;  // a border, or seen from the other side
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      if (is_reference_segment(a, b)) continue;
      const auto& u = tris[other];
      const Vec3 n1 = glm::cross(pts[u[1]] - pts[u[0]], pts[u[2]] - pts[u[0]]);
      const double length = glm::length(pts[b] - pts[a]), l0 = glm::length(n0), l1 = glm::length(n1);
      if (!(length > 0 && l0 > 0 && l1 > 0)) continue;
      const double sin_half = std::sqrt(std::max(0.0, 0.5 * (1 - glm::dot(n0, n1) / (l0 * l1))));
      const double cap = kSplitFactor * std::max(ref_sizing[a], ref_sizing[b]);
      if (!(cap * sin_half > limit)) continue;  // (most edges of a smooth part: no width matters)
      // |n| is twice the face's area: over the edge's length, its height; for a cap along the
      // crease, the flat face beyond it (flat_width, only where the heights alone say no).
      double width = std::min(l0, l1) / length;
      if (!(width * sin_half > limit))
        width = std::min(flat_width(ti, i, l0 / length), flat_width(other, edge_to(other, ti), l1 / length));
      const double reach = std::min(width, cap);
      if (!(reach * sin_half > limit)) continue;
      const double spacing =
          std::max(kSampleSpacingLimits * limit, kSampleSpacingSizings * std::min(ref_sizing[a], ref_sizing[b]));
      const size_t count = std::min(kMaxSamplesPerEdge, static_cast<size_t>(length / spacing));
      if (count == 0) continue;
      creases.push_back({ti, other, a, b, count});
      total += count;
    }
  }
  const size_t budget = std::max(kMinSamples, kSamplesPerPoint * pts.size());
  const double thin = total > budget ? static_cast<double>(budget) / static_cast<double>(total) : 1.0;
  for (const Crease& c : creases) {
    const size_t n = std::max<size_t>(1, static_cast<size_t>(thin * static_cast<double>(c.count)));
    sampled_creases.push_back(
        {c.a, c.b, static_cast<std::uint32_t>(crease_samples.size()), static_cast<std::uint32_t>(n)});
    ++creases_of_triangle_offset[c.triangle + 1];
    ++creases_of_triangle_offset[c.other + 1];
    for (size_t j = 1; j <= n; ++j) {
      const double s = static_cast<double>(j) / static_cast<double>(n + 1);
      crease_samples.push_back({pts[c.a] + s * (pts[c.b] - pts[c.a]), c.triangle,
                                (1 - s) * ref_sizing[c.a] + s * ref_sizing[c.b]});
    }
  }
  // Each crease under both of its triangles (a counting sort by triangle).
  for (size_t t = 0; t < tris.size(); ++t) creases_of_triangle_offset[t + 1] += creases_of_triangle_offset[t];
  creases_of_triangle.resize(creases_of_triangle_offset.back());
  std::vector<std::uint32_t> at(creases_of_triangle_offset.begin(), creases_of_triangle_offset.end() - 1);
  for (size_t k = 0; k < creases.size(); ++k) {
    creases_of_triangle[at[creases[k].triangle]++] = static_cast<std::uint32_t>(k);
    creases_of_triangle[at[creases[k].other]++] = static_cast<std::uint32_t>(k);
  }
}

Face Remesher::Impl::a_face_at(Vertex v) const {
  for (const Halfedge out : mesh.halfedges(v))
    if (!mesh.is_boundary(out)) return mesh.face(out);
  return Face();
}

double Remesher::Impl::face_distance2(Face f, const Point& p) const {
  Vertex c[3];
  mesh.face_vertices(f, c);
  double bary[3];
  const Point q =
      geometry::closest_point_on_triangle(p, mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]), bary);
  return glm::dot(q - p, q - p);
}

// Whether f, or a face next to it across an edge, lies within sqrt(limit2) of p; that face, if so.
Face Remesher::Impl::face_near_covering(const Point& p, Face f, double limit2) const {
  if (!f.is_valid() || mesh.is_deleted(f)) return Face();
  if (face_distance2(f, p) <= limit2) return f;
  for (const Halfedge h : mesh.halfedges(f)) {
    const Halfedge o = mesh.opposite(h);
    if (!mesh.is_boundary(o) && face_distance2(mesh.face(o), p) <= limit2) return mesh.face(o);
  }
  return Face();
}

// The quick passes of the coverage check see only the reference points in the triangles under the
// surface's vertices. Under a coarse surface (epsilon 2 % on the 50k-point dragon: 22k vertices)
// most points lie under the middle of a face, and each then took a search of the guard's grid in
// a box as wide as the limit, holding hundreds of faces: 58 % of that remesh's time. A point's
// neighbour on the reference is usually covered by the face that covers the point, or one next to
// it: tried first, spreading from the covered points over the reference's edges (and along each
// sampled crease from its ends). Each is an exact distance test, so the points left for the grid
// are the same as before, only found sooner: the dragon's remesh above 5.5 -> 2.1 s. Seeded from
// every covered point, the spread cost the bunny's remesh at the defaults 1.2 % more instructions;
// seeded from the uncovered ones, nothing measurable.
void Remesher::Impl::spread_cover_over_reference(double limit2) {
  const auto& pts = tree.points();
  const auto& tris = tree.triangles();
  // Point j covered by `from` or a face next to it: marked, and queued to spread further.
  auto try_cover = [&](std::uint32_t j, Face from) {
    const Face f = face_near_covering(pts[j], from, limit2);
    if (!f.is_valid()) return false;
    point_covered[j] = 1;
    covered_by[j] = f;
    coverage_queue.push_back(j);
    return true;
  };
  // Seeded from the points still uncovered (few at a fine tolerance): each tries the faces of its
  // covered neighbours; then out from each point covered that way.
  coverage_queue.clear();
  for (std::uint32_t j = 0; j < pts.size(); ++j)
    for (std::uint32_t k = ref_fan_offset[j]; k < ref_fan_offset[j + 1] && !point_covered[j]; ++k)
      for (const std::uint32_t i : tris[ref_fan[k]])
        if (point_covered[i] && covered_by[i].is_valid() && try_cover(j, covered_by[i])) break;
  for (size_t next = 0; next < coverage_queue.size(); ++next) {
    const std::uint32_t i = coverage_queue[next];
    for (std::uint32_t k = ref_fan_offset[i]; k < ref_fan_offset[i + 1]; ++k)
      for (const std::uint32_t j : tris[ref_fan[k]])
        if (!point_covered[j]) try_cover(j, covered_by[i]);
  }
  // Along each crease, forwards from a's face and backwards from b's, each sample trying the face
  // of the last one.
  auto walk_samples = [&](Face from, const SampledCrease& crease, bool forwards) {
    for (std::uint32_t i = 0; i < crease.count && from.is_valid(); ++i) {
      const std::uint32_t s = forwards ? crease.first + i : crease.first + crease.count - 1 - i;
      if (sample_covered[s]) continue;
      from = face_near_covering(crease_samples[s].p, from, limit2);
      sample_covered[s] = from.is_valid();
    }
  };
  for (const SampledCrease& crease : sampled_creases) {
    if (point_covered[crease.a]) walk_samples(covered_by[crease.a], crease, true);
    if (point_covered[crease.b]) walk_samples(covered_by[crease.b], crease, false);
  }
}

size_t Remesher::Impl::cover_reference_points(bool may_split, size_t* splits) {
  *splits = 0;
  const double tolerance = fidelity_tolerance();
  if (!(tolerance > 0) || !crossing_guard.active()) return 0;
  const double limit = coverage_limit();
  const double limit2 = limit * limit;
  const auto& pts = tree.points();
  // The nearest live face within `radius` of p and its squared distance (none found: radius^2,
  // nearest invalid); the search stops at the first face within sqrt(stop2).
  auto nearest_face = [&](const Point& p, double radius, double stop2, Face* nearest) {
    const Vec3 r(radius);
    coverage_faces.clear();
    size_t budget = kQueryBudget;
    crossing_guard.gather_faces(p - r, p + r, coverage_faces, budget);
    double best2 = radius * radius;
    *nearest = Face();
    for (Face f : coverage_faces) {
      if (mesh.is_deleted(f)) continue;
      const double d2 = face_distance2(f, p);
      if (d2 < best2) {
        best2 = d2;
        *nearest = f;
        if (d2 <= stop2) break;
      }
    }
    return best2;
  };

  // Most points are seen covered without a search: every vertex lies on the reference, in the
  // triangle its hint names, and the corners of that triangle near the vertex, or near a face at
  // the vertex, are covered. Only the rest are looked up in the grid. (Remeshes at the defaults:
  // the whole check 72M of 1.74G instructions on fandisk.off, 167M of 4.19G on bunny.off; the
  // grid alone, with no pass over the faces, 40M and 215M.)
  const auto& tris = tree.triangles();
  if (crease_samples_due) sample_reference_creases();
  mesh::resize_scratch(point_covered, pts.size(), std::uint8_t(0));
  std::fill(point_covered.begin(), point_covered.end(), std::uint8_t(0));
  mesh::resize_scratch(covered_by, pts.size(), Face());
  sample_covered.assign(crease_samples.size(), 0);
  for (Vertex v : mesh.vertices()) {
    const std::uint32_t t = ref_hint[v];
    if (t >= tris.size()) continue;
    for (std::uint32_t i : tris[t]) {
      const Vec3 to_v = pts[i] - mesh.position(v);
      if (glm::dot(to_v, to_v) <= limit2) {
        point_covered[i] = 1;
        covered_by[i] = a_face_at(v);
      }
    }
  }
  for (Face f : mesh.faces()) {
    Vertex c[3];
    mesh.face_vertices(f, c);
    const Point& a = mesh.position(c[0]);
    const Point& b = mesh.position(c[1]);
    const Point& d = mesh.position(c[2]);
    const Vec3 n = glm::cross(b - a, d - a);
    const double n2 = glm::dot(n, n);
    // The ball around the face's centre through its farthest corner, grown by the limit.
    const Point centre = (a + b + d) / 3.0;
    const double reach = std::sqrt(std::max({glm::dot(a - centre, a - centre), glm::dot(b - centre, b - centre),
                                             glm::dot(d - centre, d - centre)})) +
                         limit;
    auto covers = [&](const Point& p) {
      const double height = glm::dot(p - a, n);
      if (height * height > limit2 * n2) return false;  // off the face's plane by more
      if (glm::dot(p - centre, p - centre) > reach * reach) return false;  // or beside it
      double bary[3];
      const Point q = geometry::closest_point_on_triangle(p, a, b, d, bary);
      return glm::dot(q - p, q - p) <= limit2;
    };
    for (int corner = 0; corner < 3; ++corner) {
      const std::uint32_t t = ref_hint[c[corner]];
      // Each hint triangle once (the corners of most faces share one).
      if (t >= tris.size() || (corner > 0 && t == ref_hint[c[0]]) || (corner == 2 && t == ref_hint[c[1]])) continue;
      for (std::uint32_t i : tris[t])
        if (!point_covered[i] && covers(pts[i])) {
          point_covered[i] = 1;
          covered_by[i] = f;
        }
      // The samples of the triangle's creases within the face's ball: a run of each crease's
      // evenly spaced samples (searching the grid for each sample, every iteration, was 9 % of
      // cgal/ChineseDragon-10kv's remesh at epsilon 0.05 %).
      for (std::uint32_t k = creases_of_triangle_offset[t]; k < creases_of_triangle_offset[t + 1]; ++k) {
        const SampledCrease& crease = sampled_creases[creases_of_triangle[k]];
        const Point& from = pts[crease.a];
        const Vec3 along = pts[crease.b] - from;
        const double length2 = glm::dot(along, along);
        if (!(length2 > 0)) continue;
        const double mid = glm::dot(centre - from, along) / length2, half = reach / std::sqrt(length2);
        // Sample j (1 .. count) lies at j / (count + 1) along the crease.
        const double steps = static_cast<double>(crease.count) + 1;
        const double lo = std::max(1.0, std::ceil((mid - half) * steps));
        const double hi = std::min(static_cast<double>(crease.count), std::floor((mid + half) * steps));
        if (!(lo <= hi)) continue;
        const std::uint32_t end = crease.first + static_cast<std::uint32_t>(hi);
        for (std::uint32_t sample = crease.first + static_cast<std::uint32_t>(lo) - 1; sample < end; ++sample)
          if (!sample_covered[sample] && covers(crease_samples[sample].p)) sample_covered[sample] = 1;
      }
    }
  }
  spread_cover_over_reference(limit2);
  uncovered.clear();
  auto check = [&](const Point& p, std::uint32_t id) {
    Face nearest;
    if (nearest_face(p, limit, limit2, &nearest) <= limit2 && nearest.is_valid()) return;
    // Uncovered: find the nearest face farther out.
    double d2 = 0;
    for (double radius = 2 * limit; radius <= kFarthestSearch * limit; radius *= 2) {
      d2 = nearest_face(p, radius, 0.0, &nearest);
      if (nearest.is_valid()) break;
    }
    if (nearest.is_valid()) uncovered.push_back({d2, id, nearest});
  };
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    if (point_covered[i]) continue;
    if (ref_fan_offset[i] == ref_fan_offset[i + 1]) continue;  // in no kept triangle
    check(pts[i], i);
  }
  for (size_t i = 0; i < crease_samples.size(); ++i)
    if (!sample_covered[i]) check(crease_samples[i].p, static_cast<std::uint32_t>(pts.size() + i));
  if (uncovered.empty()) return 0;
  // The reference's own points first (corners, tips), then the crease samples: a crease pin made
  // first next to a corner anchors the vertex the corner's pin would move (cgal/corner_tris_with_hole
  // at epsilon 0.2 %: a triangle spanning the inner corner, 2.5 tolerances off it).
  const std::uint32_t n_points = static_cast<std::uint32_t>(pts.size());
  std::sort(uncovered.begin(), uncovered.end(), [n_points](const Uncovered& a, const Uncovered& b) {
    const bool a_sample = a.point >= n_points, b_sample = b.point >= n_points;
    return a_sample != b_sample ? b_sample : a.distance2 > b.distance2;
  });
  pinned_now.clear();
  size_t pins = 0;
  const double late2 = (kLateSplitTolerances * tolerance) * (kLateSplitTolerances * tolerance);
  for (const Uncovered& u : uncovered) {
    if (splits_allowed() == 0) break;
    const Point& p = cover_point(u.point);
    const bool near_a_pin = std::any_of(pinned_now.begin(), pinned_now.end(), [&](const Point& q) {
      return glm::dot(q - p, q - p) <= limit2;
    });
    // The face may have gone in an earlier pin's split (its slot reused by a half): ask again.
    if (near_a_pin || mesh.is_deleted(u.nearest)) continue;
    if (u.point >= pts.size() && anchored_near(p, kCreasePinSpacing * cover_sizing(u.point))) continue;
    const PinSplit split = may_split ? PinSplit::kAny : u.distance2 > late2 ? PinSplit::kLate : PinSplit::kNever;
    if (const int how = pin_reference_point(u.point, u.nearest, split)) {
      *splits += how == 2;
      pinned_now.push_back(p);
      ++pins;
    }
  }
  return pins;
}

// Moves w onto the reference point when its fan keeps its orientation and fair angles, crosses
// nothing and strays from the reference nowhere; w is then anchored there.
bool Remesher::Impl::move_onto_reference_point(Vertex w, std::uint32_t point) {
  if (!movable(w) || vclass[w] != kFree || anchor[w] != UINT32_MAX || mesh.is_boundary(w)) return false;
  const Point& p = cover_point(point);
  const Point start = mesh.position(w);
  for (Halfedge out : mesh.halfedges(w)) {
    if (mesh.is_boundary(out)) return false;
    const Point& a = mesh.position(mesh.to_vertex(out));
    const Point& b = mesh.position(mesh.to_vertex(mesh.next(out)));
    const Vec3 before = glm::cross(a - start, b - start);
    const Vec3 after = glm::cross(a - p, b - p);
    const double lengths = glm::length(before) * glm::length(after);
    if (!(lengths > 0) || glm::dot(before, after) < kMinTurnCos * lengths || min_angle_sin2(p, a, b) < kMovedMinSin2)
      return false;
  }
  const std::uint32_t start_hint = ref_hint[w];
  note_cover_duty(w);  // (a pin must not uncover a point the vertex covers: a corner next to a crease)
  mesh.position(w) = p;
  ref_hint[w] = cover_triangle(point);
  // A crease sample's pin also keeps its faces near the reference: with every edge on it, a fan can
  // still tent across an inner corner beside the crease (cgal/corner_tris_with_hole at epsilon
  // 0.2 %: 1.7 x 2 epsilon).
  if (crossing_guard.fan_crosses(mesh, w) || fan_strays(w) || !move_keeps_cover(w, start) ||
      (point >= tree.points().size() && fan_faces_stray(w))) {
    mesh.position(w) = start;
    ref_hint[w] = start_hint;
    return false;
  }
  sizing[w] = cover_sizing(point);
  anchor[w] = point;
  note_fan_changed(w);
  return true;
}

double Remesher::Impl::reference_angle_deficit(std::uint32_t point) const {
  const auto& pts = tree.points();
  const auto& tris = tree.triangles();
  double angles = 0;
  for (std::uint32_t k = ref_fan_offset[point]; k < ref_fan_offset[point + 1]; ++k) {
    const auto& t = tris[ref_fan[k]];
    double corner[3];
    geometry::triangle_angles(pts[t[0]], pts[t[1]], pts[t[2]], corner);
    angles += corner[t[0] == point ? 0 : t[1] == point ? 1 : 2];
  }
  return 2 * M_PI - angles;
}

// The squared distance from p to the nearest face at v, v at `at`.
double Remesher::Impl::fan_distance2(Vertex v, const Point& at, const Point& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (Halfedge out : mesh.halfedges(v)) {
    if (mesh.is_boundary(out)) continue;
    double bary[3];
    const Point q = geometry::closest_point_on_triangle(p, at, mesh.position(mesh.to_vertex(out)),
                                                       mesh.position(mesh.to_vertex(mesh.next(out))), bary);
    best = std::min(best, glm::dot(q - p, q - p));
  }
  return best;
}

void Remesher::Impl::note_cover_duty(Vertex v) {
  cover_duty.clear();
  const double limit = coverage_limit();
  if (!(limit > 0)) return;
  const auto& pts = tree.points();
  const auto& tris = tree.triangles();
  const Point& at = mesh.position(v);
  auto add = [&](std::uint32_t id) {
    if (std::any_of(cover_duty.begin(), cover_duty.end(), [&](const CoverDuty& d) { return d.point == id; })) return;
    const double d2 = fan_distance2(v, at, cover_point(id));
    if (d2 <= limit * limit) cover_duty.push_back({id, std::sqrt(d2)});
  };
  // The fan's reach: a sample farther from v than its longest edge plus the limit is not
  // covered by it.
  double reach2 = 0;
  for (Halfedge out : mesh.halfedges(v)) {
    const Vec3 d = mesh.position(mesh.to_vertex(out)) - at;
    reach2 = std::max(reach2, glm::dot(d, d));
  }
  const double reach = std::sqrt(reach2) + limit;
  auto note = [&](std::uint32_t t) {
    if (t >= tris.size()) return;
    for (std::uint32_t i : tris[t]) add(i);
    // And the samples of the triangle's creases: on a coarse CAD part most of a crease lies
    // between reference points an edge or more apart (cgal/part at epsilon 0.05 %: the polish
    // moved a vertex off the middle of a crease of a 175-degree input sliver, 0.73 % of the
    // diagonal from the output).
    if (crease_samples_due || t + 1 >= creases_of_triangle_offset.size()) return;
    for (std::uint32_t k = creases_of_triangle_offset[t]; k < creases_of_triangle_offset[t + 1]; ++k) {
      const SampledCrease& crease = sampled_creases[creases_of_triangle[k]];
      for (std::uint32_t j = 0; j < crease.count; ++j) {
        const Vec3 d = crease_samples[crease.first + j].p - at;
        if (glm::dot(d, d) <= reach * reach) add(static_cast<std::uint32_t>(pts.size()) + crease.first + j);
      }
    }
  };
  note(ref_hint[v]);
  for (Halfedge out : mesh.halfedges(v)) note(ref_hint[mesh.to_vertex(out)]);
}

bool Remesher::Impl::move_keeps_cover(Vertex v, const Point& start) const {
  const double limit = coverage_limit();
  if (!(limit > 0)) return true;
  const double limit2 = limit * limit;
  const Point& now = mesh.position(v);
  // Every point of the fan moved by at most |now - start| (v's share of it is at most 1), so a
  // point that far within the limit at the start is within it still.
  const double moved = glm::length(now - start);
  for (const CoverDuty& duty : cover_duty) {
    if (duty.distance + moved <= limit) continue;
    const Point& p = cover_point(duty.point);
    if (fan_distance2(v, now, p) <= limit2) continue;
    // Covered by a face next to the fan, which the move left where it was?
    bool covered = false;
    for (Halfedge out : mesh.halfedges(v)) {
      const Vertex w = mesh.to_vertex(out);
      if (fan_distance2(w, mesh.position(w), p) <= limit2) {
        covered = true;
        break;
      }
    }
    if (!covered) return false;
  }
  return true;
}

bool Remesher::Impl::anchor_holds(Vertex v, const Point& p) const {
  const Vec3 d = p - cover_point(anchor[v]);
  const double limit = coverage_limit();
  return glm::dot(d, d) <= limit * limit;
}

bool Remesher::Impl::fan_faces_stray(Vertex w) const {
  const double limit = kFidelityMidpoint * fidelity_tolerance();
  for (Halfedge out : mesh.halfedges(w)) {
    if (mesh.is_boundary(out)) continue;
    const Vertex a = mesh.to_vertex(out), b = mesh.to_vertex(mesh.next(out));
    const Point centre = (mesh.position(w) + mesh.position(a) + mesh.position(b)) / 3.0;
    if (closest_on_reference(centre, ref_hint[w]).distance2 > limit * limit) return true;
  }
  return false;
}

bool Remesher::Impl::split_strays(Edge e, const Point& p, std::uint32_t hint) const {
  const double tolerance = fidelity_tolerance();
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh.halfedge(e, i);
    const Vertex ends[2] = {mesh.to_vertex(h), mesh.to_vertex(mesh.next(h))};
    for (unsigned k = 0; k < (mesh.is_boundary(h) ? 1u : 2u); ++k)
      if (segment_strays(p, hint, mesh.position(ends[k]), ref_hint[ends[k]], tolerance)) return true;
  }
  return false;
}

// Puts a vertex on the reference point: a corner of `nearest` moved there, else the edge of
// `nearest` closest to it split there, whichever is safe first; the vertex is anchored to it.
int Remesher::Impl::pin_reference_point(std::uint32_t point, Face nearest, PinSplit split) {
  const Point& p = cover_point(point);
  // First a corner of the face moved onto the point, nearest first: no vertex added, and no
  // valence-4 vertex where an iteration may not be left to even the valences out.
  Vertex corners[3];
  mesh.face_vertices(nearest, corners);
  std::sort(corners, corners + 3, [&](Vertex a, Vertex b) {
    return glm::dot(mesh.position(a) - p, mesh.position(a) - p) < glm::dot(mesh.position(b) - p, mesh.position(b) - p);
  });
  for (Vertex w : corners)
    if (move_onto_reference_point(w, point)) return 1;
  if (split == PinSplit::kNever) return 0;
  // The face's edges, nearest to p first.
  Halfedge sides[3];
  double side_d2[3];
  Halfedge h = mesh.halfedge(nearest);
  for (int k = 0; k < 3; ++k, h = mesh.next(h)) {
    sides[k] = h;
    const Point q =
        geometry::closest_point_on_segment(p, mesh.position(mesh.from_vertex(h)), mesh.position(mesh.to_vertex(h)));
    side_d2[k] = glm::dot(q - p, q - p);
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return side_d2[a] < side_d2[b]; });
  const bool tip = point < tree.points().size() && reference_angle_deficit(point) >= kPinnedTipDeficit;
  const double min_sin2 = tip ? kTipSplitMinSin2 : kSplitMinSin2;
  for (int k : order) {
    const Edge e = mesh.edge(sides[k]);
    // Feature and boundary edges keep their line; every corner of the two triangles must be free
    // to change (not masked, not the border of a held region).
    if (is_feature(e) || mesh.is_boundary(e)) continue;
    bool ok = true;
    for (unsigned i = 0; i < 2 && ok; ++i) {
      const Halfedge side = mesh.halfedge(e, i);
      ok = scope[mesh.from_vertex(side)] == kActive && scope[mesh.to_vertex(side)] == kActive &&
           scope[mesh.to_vertex(mesh.next(side))] == kActive;
    }
    ok = ok && split_halves_fair(e, p, kMinTurnCos, min_sin2);
    // A crease sample lies off the edge split for it, and the edges from it to the corners must
    // not leave the reference: they tented across a corner beside it (cgal/anchor, tripod at
    // epsilon 0.2 %: 1.2-1.5 x 2 epsilon next to the pin). (A point's pin may: a worn tip is
    // rebuilt by the iterations after it. Not a late one: none follows.)
    const bool sample = point >= tree.points().size();
    if (ok && (sample || split == PinSplit::kLate)) ok = !split_strays(e, p, cover_triangle(point));
    if (!ok || crossing_guard.split_crosses(mesh, e, p)) continue;
    const Vertex v = split_edge(e, p);
    anchor[v] = point;
    sizing[v] = cover_sizing(point);
    ref_hint[v] = cover_triangle(point);
    return 2;
  }
  return 0;
}

}  // namespace adasculpt::remesh
