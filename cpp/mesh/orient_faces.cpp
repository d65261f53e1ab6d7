#include "mesh/orient_faces.h"

#include <algorithm>
#include <string>
#include <utility>

#include "mesh/build_from_triangles.h"

namespace adasculpt::mesh {

namespace {

constexpr std::uint32_t kNoFace = ~0u;

struct EdgeUse {
  std::uint32_t lo, hi;  // sorted endpoints
  std::uint32_t face;
  bool forward;  // the face runs from lo to hi
};

// Each face's neighbour across each of its edges (kNoFace on a border or a non-manifold edge)
// and whether the two faces run the edge the same way (then one of them must be reversed).
struct Neighbours {
  std::vector<std::array<std::uint32_t, 3>> face;
  std::vector<std::array<std::uint8_t, 3>> same_direction;
  std::vector<std::array<std::array<std::uint32_t, 2>, 3>> edge;  // its endpoints, for messages
};

Neighbours find_neighbours(const std::vector<std::array<std::uint32_t, 3>>& faces) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (unsigned i = 0; i < 3; ++i) {
      const std::uint32_t a = faces[f][i], b = faces[f][(i + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  Neighbours n;
  n.face.assign(faces.size(), {kNoFace, kNoFace, kNoFace});
  n.same_direction.assign(faces.size(), {0, 0, 0});
  n.edge.resize(faces.size());
  std::vector<std::uint8_t> slots_used(faces.size(), 0);
  for (size_t k = 0; k < uses.size();) {
    size_t end = k + 1;
    while (end < uses.size() && uses[end].lo == uses[k].lo && uses[end].hi == uses[k].hi) ++end;
    if (end - k == 2) {
      const EdgeUse &x = uses[k], &y = uses[k + 1];
      const std::uint8_t same = x.forward == y.forward;
      for (const auto& [self, other] : {std::pair{x, y}, std::pair{y, x}}) {
        const std::uint8_t slot = slots_used[self.face]++;  // at most 3: a face has 3 edges
        n.face[self.face][slot] = other.face;
        n.same_direction[self.face][slot] = same;
        n.edge[self.face][slot] = {x.lo, x.hi};
      }
    }
    k = end;
  }
  return n;
}

// Six times the signed volume the piece encloses, with the given faces reversed.
double signed_volume6(const std::vector<std::array<double, 3>>& points,
                      const std::vector<std::array<std::uint32_t, 3>>& faces, const std::vector<std::uint32_t>& piece,
                      const std::vector<std::uint8_t>& reverse) {
  double sum = 0;
  for (const std::uint32_t f : piece) {
    const auto& a = points[faces[f][0]];
    const auto& b = points[faces[f][reverse[f] ? 2 : 1]];
    const auto& c = points[faces[f][reverse[f] ? 1 : 2]];
    sum += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return sum;
}

}  // namespace

size_t orient_faces_consistently(const std::vector<std::array<double, 3>>& points,
                                 std::vector<std::array<std::uint32_t, 3>>& faces) {
  const Neighbours n = find_neighbours(faces);
  constexpr std::uint8_t kUnset = 2;
  std::vector<std::uint8_t> reverse(faces.size(), kUnset);
  std::vector<std::uint32_t> piece, queue;
  size_t reversed = 0;
  for (std::uint32_t seed = 0; seed < faces.size(); ++seed) {
    if (reverse[seed] != kUnset) continue;
    // One connected piece, breadth first: each neighbour's reversal follows from its face's.
    piece.clear();
    queue.assign(1, seed);
    reverse[seed] = 0;
    bool closed = true;
    size_t n_reversed = 0;
    while (!queue.empty()) {
      const std::uint32_t f = queue.back();
      queue.pop_back();
      piece.push_back(f);
      n_reversed += reverse[f];
      for (unsigned i = 0; i < 3; ++i) {
        const std::uint32_t g = n.face[f][i];
        if (g == kNoFace) {
          closed = false;
          continue;
        }
        const std::uint8_t want = reverse[f] ^ n.same_direction[f][i];
        if (reverse[g] == kUnset) {
          reverse[g] = want;
          queue.push_back(g);
        } else if (reverse[g] != want) {
          throw TopologyError("inconsistent face orientation at the edge between vertices " +
                              std::to_string(n.edge[f][i][0]) + " and " + std::to_string(n.edge[f][i][1]) +
                              ": the surface is one-sided (a Moebius strip or a Klein bottle) and cannot be oriented");
        }
      }
    }
    if (n_reversed == 0) continue;  // consistent as written: the file's choice of side stands
    const bool flip_all = closed ? signed_volume6(points, faces, piece, reverse) < 0 : 2 * n_reversed > piece.size();
    for (const std::uint32_t f : piece) {
      if (flip_all) reverse[f] ^= 1;
      if (reverse[f]) {
        std::swap(faces[f][1], faces[f][2]);
        ++reversed;
      }
    }
  }
  return reversed;
}

}  // namespace adasculpt::mesh
