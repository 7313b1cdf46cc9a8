// sinCos (motion/sin_cos.h) against long-double sin/cos: absolute error at most 2^-52 over the
// fast range (joint angles and far beyond), exact quadrant signs at multiples of pi/2, and the
// libm fallback for huge and non-finite angles.
#include "octomotion/motion/sin_cos.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace octomotion {
namespace {

constexpr double kTolerance = 0x1p-52;  // one ulp of 1

void expectClose(double x) {
  double s = 0, c = 0;
  sinCos(x, s, c);
  const long double lx = x;
  EXPECT_NEAR(s, static_cast<double>(std::sin(lx)), kTolerance) << "sin(" << x << ")";
  EXPECT_NEAR(c, static_cast<double>(std::cos(lx)), kTolerance) << "cos(" << x << ")";
}

TEST(SinCos, MatchesLongDoubleOverJointRanges) {
  std::mt19937_64 rng(0x51c05);
  std::uniform_real_distribution<double> joint(-2 * M_PI, 2 * M_PI);
  for (int i = 0; i < 200000; ++i) expectClose(joint(rng));
  std::uniform_real_distribution<double> wide(-kSinCosFastRange, kSinCosFastRange);
  for (int i = 0; i < 50000; ++i) expectClose(wide(rng));
}

TEST(SinCos, QuadrantBoundariesAndTinyAngles) {
  for (int k = -40; k <= 40; ++k) {
    const double x = k * (M_PI / 2);
    for (const double dx : {0.0, 1e-12, -1e-12, 0.3, -0.3, M_PI / 4, -M_PI / 4})
      expectClose(x + dx);
  }
  for (const double x : {0.0, -0.0, 1e-300, -1e-300, 5e-324, 1e-8}) expectClose(x);
  double s = 1, c = 0;
  sinCos(-0.0, s, c);
  EXPECT_EQ(c, 1.0);
  EXPECT_EQ(s, 0.0);
}

TEST(SinCos, FallsBackBeyondTheFastRange) {
  for (const double x : {kSinCosFastRange * 1.0000001, 1e9, -3e15, 1e300}) {
    double s = 0, c = 0;
    sinCos(x, s, c);
    EXPECT_EQ(s, std::sin(x)) << x;
    EXPECT_EQ(c, std::cos(x)) << x;
  }
  for (const double x :
       {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    double s = 0, c = 0;
    sinCos(x, s, c);
    EXPECT_TRUE(std::isnan(s) && std::isnan(c)) << x;
  }
}

}  // namespace
}  // namespace octomotion
