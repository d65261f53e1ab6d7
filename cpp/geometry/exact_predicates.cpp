#include "geometry/exact_predicates.h"

#include <cmath>

namespace adasculpt::geometry {

namespace {

// Unit roundoff of IEEE double (round to nearest): every basic operation is exact up to a
// relative error of kEps.
constexpr double kEps = 0x1.0p-53;
// Forward error bounds of the plain floating-point determinants below, relative to their
// "permanent" (the same sum of products with absolute values): if |det| exceeds it, the
// rounded sign is the true sign (Shewchuk 1997, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates", first stage of orient2d/orient3d).
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;

// An exact real number as a sum of doubles ordered by increasing magnitude that do not
// overlap bitwise; its sign is the sign of the last (largest) component. Zero components
// are dropped as they appear, so exactly representable inputs stay short. The capacity
// covers the longest expansion orient3d builds (3 terms of 2 x 8 x 2 x 2 components).
struct Expansion {
  static constexpr int kCapacity = 192;
  double c[kCapacity];
  int n = 0;
  void push(double x) {
    if (x != 0) c[n++] = x;
  }
  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
};

// x + y == a + b exactly, x the rounded sum (Knuth's two-sum; valid for any a, b).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// x + y == a * b exactly (the fma computes the rounding error of the product exactly).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

// a - b as an exact two-component expansion.
Expansion difference(double a, double b) {
  double x, y;
  two_sum(a, -b, x, y);
  Expansion e;
  e.push(y);
  e.push(x);
  return e;
}

// h = e + f: merge both by magnitude, then a chain of exact two-sums carrying the
// running sum upwards and emitting the rounding errors (Shewchuk's fast expansion sum).
void add(const Expansion& e, const Expansion& f, Expansion& h) {
  double merged[Expansion::kCapacity];
  int i = 0, j = 0, m = 0;
  while (i < e.n && j < f.n) merged[m++] = std::fabs(e.c[i]) < std::fabs(f.c[j]) ? e.c[i++] : f.c[j++];
  while (i < e.n) merged[m++] = e.c[i++];
  while (j < f.n) merged[m++] = f.c[j++];
  h.n = 0;
  if (m == 0) return;
  double q = merged[0];
  for (int k = 1; k < m; ++k) {
    double sum, err;
    two_sum(q, merged[k], sum, err);
    h.push(err);
    q = sum;
  }
  h.push(q);
}

void negate(Expansion& e) {
  for (int i = 0; i < e.n; ++i) e.c[i] = -e.c[i];
}

// h = e * b for a single double b (Shewchuk's scale-expansion).
void scale(const Expansion& e, double b, Expansion& h) {
  h.n = 0;
  if (e.n == 0 || b == 0) return;
  double q, err;
  two_product(e.c[0], b, q, err);
  h.push(err);
  for (int i = 1; i < e.n; ++i) {
    double hi, lo, sum;
    two_product(e.c[i], b, hi, lo);
    two_sum(q, lo, sum, err);
    h.push(err);
    two_sum(hi, sum, q, err);
    h.push(err);
  }
  h.push(q);
}

// h = e * f, as the sum over the components of f of e scaled by each.
void multiply(const Expansion& e, const Expansion& f, Expansion& h) {
  h.n = 0;
  Expansion term, sum;
  for (int j = 0; j < f.n; ++j) {
    scale(e, f.c[j], term);
    add(h, term, sum);
    h = sum;
  }
}

// a * d - b * c exactly.
Expansion cross_term(const Expansion& a, const Expansion& d, const Expansion& b, const Expansion& c) {
  Expansion ad, bc, out;
  multiply(a, d, ad);
  multiply(b, c, bc);
  negate(bc);
  add(ad, bc, out);
  return out;
}

int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  const Expansion ux = difference(bx, ax), uy = difference(by, ay);
  const Expansion vx = difference(cx, ax), vy = difference(cy, ay);
  return cross_term(ux, vy, uy, vx).sign();
}

int orient3d_exact(const Point& a, const Point& b, const Point& c, const Point& d) {
  const Expansion ux = difference(b.x, a.x), uy = difference(b.y, a.y), uz = difference(b.z, a.z);
  const Expansion vx = difference(c.x, a.x), vy = difference(c.y, a.y), vz = difference(c.z, a.z);
  const Expansion wx = difference(d.x, a.x), wy = difference(d.y, a.y), wz = difference(d.z, a.z);
  // u . (v x w)
  const Expansion cx = cross_term(vy, wz, vz, wy), cy = cross_term(vz, wx, vx, wz), cz = cross_term(vx, wy, vy, wx);
  Expansion tx, ty, tz, sum, det;
  multiply(ux, cx, tx);
  multiply(uy, cy, ty);
  multiply(uz, cz, tz);
  add(tx, ty, sum);
  add(sum, tz, det);
  return det.sign();
}

inline int sign_of(double x) { return (x > 0) - (x < 0); }

}  // namespace

int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  const double left = (bx - ax) * (cy - ay), right = (by - ay) * (cx - ax);
  const double det = left - right;
  const double bound = kOrient2dBound * (std::fabs(left) + std::fabs(right));
  if (det > bound || -det > bound) return sign_of(det);
  return orient2d_exact(ax, ay, bx, by, cx, cy);
}

int orient3d(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
  const double vywz = vy * wz, vzwy = vz * wy, vzwx = vz * wx, vxwz = vx * wz, vxwy = vx * wy, vywx = vy * wx;
  const double det = ux * (vywz - vzwy) + uy * (vzwx - vxwz) + uz * (vxwy - vywx);
  const double permanent = (std::fabs(vywz) + std::fabs(vzwy)) * std::fabs(ux) +
                           (std::fabs(vzwx) + std::fabs(vxwz)) * std::fabs(uy) +
                           (std::fabs(vxwy) + std::fabs(vywx)) * std::fabs(uz);
  const double bound = kOrient3dBound * permanent;
  if (det > bound || -det > bound) return sign_of(det);
  return orient3d_exact(a, b, c, d);
}

}  // namespace adasculpt::geometry
