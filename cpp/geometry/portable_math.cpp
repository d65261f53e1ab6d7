#include "geometry/portable_math.h"

#include <cmath>

namespace adasculpt::portable {

namespace {

constexpr double kPi = 3.141592653589793238462643383279502884;
constexpr double kHalfPi = kPi / 2;
constexpr double kQuarterPi = kPi / 4;

// atan on [0, 1] by two argument halvings (atan t = 2 atan(t / (1 + sqrt(1 + t^2)))) and the
// Taylor series, which converges fast once |t| < 0.1.
double atan_unit(double x) {
  double t = x / (1.0 + std::sqrt(1.0 + x * x));
  t = t / (1.0 + std::sqrt(1.0 + t * t));
  const double t2 = t * t;
  // sum_{k=0}^{11} (-1)^k t^(2k+1) / (2k+1), evaluated from the small end (Horner).
  double sum = 0.0;
  for (int k = 11; k >= 0; --k) sum = (k % 2 ? -1.0 : 1.0) / (2 * k + 1) + t2 * sum;
  return 4.0 * t * sum;
}

// sin and cos of r in [-pi/4, pi/4] by their Taylor series.
double sin_small(double r) {
  const double r2 = r * r;
  double term = r, sum = r;
  for (int k = 1; k <= 11; ++k) {
    term *= -r2 / ((2 * k) * (2 * k + 1));
    sum += term;
  }
  return sum;
}
double cos_small(double r) {
  const double r2 = r * r;
  double term = 1.0, sum = 1.0;
  for (int k = 1; k <= 11; ++k) {
    term *= -r2 / ((2 * k - 1) * (2 * k));
    sum += term;
  }
  return sum;
}

// x = n * (pi/2) + r with |r| <= pi/4; pi/2 in two parts keeps r accurate for moderate x.
double reduce(double x, long long* quadrant) {
  constexpr double kHalfPiHi = 1.5707963267948966;       // nearest double to pi/2
  constexpr double kHalfPiLo = 6.123233995736766e-17;    // pi/2 - kHalfPiHi
  double n = std::nearbyint(x / kHalfPi);
  *quadrant = static_cast<long long>(n);
  return (x - n * kHalfPiHi) - n * kHalfPiLo;
}

}  // namespace

double atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return std::nan("");
  const double ay = std::fabs(y), ax = std::fabs(x);
  if (ay == 0.0 && ax == 0.0) return std::signbit(x) ? (std::signbit(y) ? -kPi : kPi) : (std::signbit(y) ? -0.0 : 0.0);
  double a;
  if (std::isinf(ay) || std::isinf(ax)) {
    a = std::isinf(ay) ? (std::isinf(ax) ? kQuarterPi : kHalfPi) : 0.0;
  } else if (ay <= ax) {
    a = atan_unit(ay / ax);
  } else {
    a = kHalfPi - atan_unit(ax / ay);
  }
  if (std::signbit(x)) a = kPi - a;
  return std::signbit(y) ? -a : a;
}

double sin(double x) {
  if (!std::isfinite(x)) return std::nan("");
  long long q;
  double r = reduce(x, &q);
  switch (q & 3) {
    case 0: return sin_small(r);
    case 1: return cos_small(r);
    case 2: return -sin_small(r);
    default: return -cos_small(r);
  }
}

double cos(double x) {
  if (!std::isfinite(x)) return std::nan("");
  long long q;
  double r = reduce(x, &q);
  switch (q & 3) {
    case 0: return cos_small(r);
    case 1: return -sin_small(r);
    case 2: return -cos_small(r);
    default: return sin_small(r);
  }
}

double acos(double x) {
  if (!(x >= -1.0 && x <= 1.0)) return std::nan("");
  return atan2(std::sqrt((1.0 - x) * (1.0 + x)), x);
}

}  // namespace adasculpt::portable
