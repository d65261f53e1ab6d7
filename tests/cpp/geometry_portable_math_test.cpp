// The portable trigonometry must match the platform's to a few ulp: it replaces it in the
// core so that native and WebAssembly builds agree bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/portable_math.h"

using namespace adasculpt;

TEST(PortableMath, MatchesTheStandardLibrary) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 200000; ++i) {
    double y = u(rng), x = u(rng);
    ASSERT_NEAR(portable::atan2(y, x), std::atan2(y, x), 1e-15 * std::max(1.0, std::fabs(std::atan2(y, x)))) << y << " " << x;
    ASSERT_NEAR(portable::sin(x), std::sin(x), 1e-15) << x;
    ASSERT_NEAR(portable::cos(x), std::cos(x), 1e-15) << x;
    double c = x / 10.0;
    ASSERT_NEAR(portable::acos(c), std::acos(c), 1e-14) << c;
  }
}

TEST(PortableMath, SpecialValues) {
  EXPECT_EQ(portable::atan2(0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(portable::atan2(1.0, 0.0), M_PI / 2);
  EXPECT_DOUBLE_EQ(portable::atan2(0.0, -1.0), M_PI);
  EXPECT_DOUBLE_EQ(portable::atan2(-1.0, -1.0), -3 * M_PI / 4);
  EXPECT_DOUBLE_EQ(portable::atan2(1e-300, 1.0), 1e-300);
  EXPECT_EQ(portable::sin(0.0), 0.0);
  EXPECT_EQ(portable::cos(0.0), 1.0);
  EXPECT_DOUBLE_EQ(portable::acos(-1.0), M_PI);
  EXPECT_TRUE(std::isnan(portable::acos(1.5)));
}
