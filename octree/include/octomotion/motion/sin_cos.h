// sin and cos of one angle together, inline: forward kinematics needs both for every revolute
// joint of every checked state, and an inline kernel avoids the cost of a libm call per angle.
// Cody-Waite reduction by pi/2 to |r| <= pi/4, then the classic odd/even minimax polynomials of
// fdlibm's kernels (Sun Microsystems, 1993; coefficients are public constants). Absolute error
// at most 2^-52 for |x| <= kSinCosFastRange (tests/motion/sin_cos_test.cpp, against long double);
// larger or non-finite angles go to std::sin/std::cos.
#pragma once

#include <cmath>

namespace octomotion {

// Joint angles are a few radians; up to here the two-constant reduction keeps its accuracy.
inline constexpr double kSinCosFastRange = 1.0e5;

inline void sinCos(double x, double& s, double& c) {
  if (!(std::fabs(x) <= kSinCosFastRange)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  // pi/2 split into a 33-bit head (k * head is exact for |k| < 2^20) and a tail.
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPiOver2Head = 1.57079632673412561417e+00;
  constexpr double kPiOver2Tail = 6.07710050650619224932e-11;
  // Round to the nearest integer by adding and subtracting 1.5 * 2^52 (exact in the default
  // rounding mode for |x * 2/pi| < 2^51); std::nearbyint is a libm call without SSE4.1.
  constexpr double kRound = 6755399441055744.0;
  const double k = (x * kTwoOverPi + kRound) - kRound;
  const double r = (x - k * kPiOver2Head) - k * kPiOver2Tail;
  const double z = r * r;
  const double sr =
      r + r * z *
              (-1.66666666666666324348e-01 +
               z * (8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 +
                         z * (2.75573137070700676789e-06 + z * (-2.50507602534068634195e-08 +
                                                                z * 1.58969099521155010221e-10)))));
  const double cr =
      1.0 - 0.5 * z +
      z * z *
          (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 +
                          z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  switch (static_cast<long>(k) & 3) {
    case 0:
      s = sr;
      c = cr;
      break;
    case 1:
      s = cr;
      c = -sr;
      break;
    case 2:
      s = -sr;
      c = -cr;
      break;
    default:
      s = -cr;
      c = sr;
      break;
  }
}

}  // namespace octomotion
