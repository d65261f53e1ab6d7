#include "io/polygon_triangulation.h"

#include <algorithm>
#include <cmath>

namespace adasculpt::io::detail {

namespace {

using P2 = std::array<double, 2>;
using P3 = std::array<double, 3>;

double cross(const P2& o, const P2& a, const P2& b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

// Whether p lies in the closed triangle (a, b, c), counter-clockwise.
bool in_triangle(const P2& p, const P2& a, const P2& b, const P2& c) {
  return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

// The sine squared of the triangle's smallest angle, up to a common factor: the quality an ear
// is chosen by (area^2 over the product of the squared sides at the smallest angle's corner).
double min_angle_quality(const P2& a, const P2& b, const P2& c) {
  auto d2 = [](const P2& p, const P2& q) { return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]); };
  const double ab = d2(a, b), bc = d2(b, c), ca = d2(c, a);
  const double area2 = cross(a, b, c) * cross(a, b, c);
  // The smallest angle faces the shortest side: its sine is 2 area / (product of the other two).
  const double longest_pair = std::max({ab * bc, bc * ca, ca * ab});
  return longest_pair > 0 ? area2 / longest_pair : 0;
}

// Clipping ears with the best shape costs O(n^2) corner tests per ear; past this many corners the
// first ear found is taken, the search going on from the last one clipped (where the next ear
// usually is).
constexpr size_t kBestEarCorners = 64;
// The corner tests one polygon may spend past kBestEarCorners, per squared corner count (up to it,
// n^3: every ear tried for every clip): a file is untrusted input, and a pathological outline must
// not stall the reader (it keeps its fan instead).
constexpr size_t kTestsPerSquaredCorner = 8;

}  // namespace

bool ear_clip(const std::vector<P2>& corners, std::vector<std::array<uint32_t, 3>>& out) {
  const size_t n = corners.size();
  if (n < 3) return false;
  std::vector<uint32_t> ring(n);
  for (size_t i = 0; i < n; ++i) ring[i] = uint32_t(i);
  const size_t out_size = out.size();
  size_t tests_left = (n <= kBestEarCorners ? n * n * n : kTestsPerSquaredCorner * n * n) + 1024;
  bool spent = false;
  auto is_ear = [&](size_t i) {
    const size_t m = ring.size();
    const uint32_t a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
    const P2 &pa = corners[a], &pb = corners[b], &pc = corners[c];
    if (!(cross(pa, pb, pc) > 0)) return false;  // reflex or collinear: its triangle is outside or flat
    for (uint32_t k : ring) {
      if (k == a || k == b || k == c) continue;
      const P2& pk = corners[k];
      // A corner at the same place as one of the ear's (a polygon touching itself) does not block it.
      if (pk == pa || pk == pb || pk == pc) continue;
      if (tests_left == 0) {
        spent = true;
        return false;
      }
      --tests_left;
      if (in_triangle(pk, pa, pb, pc)) return false;
    }
    return true;
  };
  size_t from = 0;  // first-ear mode: where the search starts
  while (ring.size() > 3) {
    const size_t m = ring.size();
    size_t best = m;
    double best_quality = -1;
    for (size_t step = 0; step < m && !spent; ++step) {
      const size_t i = (from + step) % m;
      if (!is_ear(i)) continue;
      const double q = min_angle_quality(corners[ring[(i + m - 1) % m]], corners[ring[i]], corners[ring[(i + 1) % m]]);
      if (q > best_quality) {
        best_quality = q;
        best = i;
      }
      if (n > kBestEarCorners) break;
    }
    if (best == m) {
      out.resize(out_size);
      return false;
    }
    out.push_back({ring[(best + m - 1) % m], ring[best], ring[(best + 1) % m]});
    ring.erase(ring.begin() + std::ptrdiff_t(best));
    from = best > 0 ? best - 1 : 0;
  }
  if (!(cross(corners[ring[0]], corners[ring[1]], corners[ring[2]]) > 0)) {
    out.resize(out_size);
    return false;
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return true;
}

void append_polygon(PolygonSoup& soup, const uint32_t* idx, size_t n) {
  if (n >= 4) {
    soup.polygons.push_back({uint32_t(soup.triangles.size()), uint32_t(soup.polygon_corners.size())});
    soup.polygon_corners.insert(soup.polygon_corners.end(), idx, idx + n);
  }
  for (size_t i = 1; i + 1 < n; ++i) soup.triangles.push_back({idx[0], idx[i], idx[i + 1]});
}

size_t triangulate_concave_polygons(PolygonSoup& soup) {
  size_t cut = 0;
  std::vector<P2> flat;
  std::vector<std::array<uint32_t, 3>> ears;
  for (size_t k = 0; k < soup.polygons.size(); ++k) {
    const PolygonSoup::Polygon& poly = soup.polygons[k];
    const size_t end = k + 1 < soup.polygons.size() ? soup.polygons[k + 1].first_corner : soup.polygon_corners.size();
    const uint32_t* idx = soup.polygon_corners.data() + poly.first_corner;
    const size_t n = end - poly.first_corner;
    // Newell's normal: the polygon's area vector, right for a warped outline too.
    double normal[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
      const P3& p = soup.points[idx[i]];
      const P3& q = soup.points[idx[(i + 1) % n]];
      normal[0] += (p[1] - q[1]) * (p[2] + q[2]);
      normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
      normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    // Into the plane by dropping the normal's largest axis; the two kept axes in the order that
    // keeps the outline counter-clockwise.
    int drop = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(normal[a]) > std::abs(normal[drop])) drop = a;
    if (!(std::abs(normal[drop]) > 0)) continue;  // no area: nothing to cut
    int u = (drop + 1) % 3, v = (drop + 2) % 3;
    if (normal[drop] < 0) std::swap(u, v);
    flat.resize(n);
    for (size_t i = 0; i < n; ++i) flat[i] = {soup.points[idx[i]][u], soup.points[idx[i]][v]};
    bool convex = true;
    for (size_t i = 0; i < n && convex; ++i) convex = cross(flat[i], flat[(i + 1) % n], flat[(i + 2) % n]) >= 0;
    if (convex) continue;  // the fan is exact
    ears.clear();
    if (!ear_clip(flat, ears)) continue;
    for (size_t t = 0; t < ears.size(); ++t)
      soup.triangles[poly.first_triangle + t] = {idx[ears[t][0]], idx[ears[t][1]], idx[ears[t][2]]};
    ++cut;
  }
  soup.polygons.clear();
  soup.polygon_corners.clear();
  return cut;
}

}  // namespace adasculpt::io::detail
