/**
 * @file
 * Small 3x3 helpers on plain arrays (row-major matrices, Voigt symmetric
 * tensors [xx,yy,zz,xy,yz,xz]) for material models and drivers, where
 * deal.II's Tensor would be fine but the kernels' plain-array interface
 * keeps conversions out of the way.
 */
#pragma once

#include <algorithm>
#include <cmath>

namespace anvil::Kinematics
{
  /**
   * Eigenvalues of the symmetric tensor @p A (Voigt), in descending order,
   * by the closed form of Smith (1961): A = m I + p B with
   * det(B) / 2 = cos(3 phi).
   */
  inline void principal_values(const double *A, double (&value)[3])
  {
    const double off = A[3] * A[3] + A[4] * A[4] + A[5] * A[5];
    const double m   = (A[0] + A[1] + A[2]) / 3.;
    const double a = A[0] - m, b = A[1] - m, c = A[2] - m;
    const double p2  = a * a + b * b + c * c + 2. * off;
    if (!(p2 > 1e-30 * (m * m + 1e-300)))
      {
        value[0] = value[1] = value[2] = m;
        return;
      }
    const double p = std::sqrt(p2 / 6.);
    const double r = (a * (b * c - A[4] * A[4]) - A[3] * (A[3] * c - A[4] * A[5]) +
                      A[5] * (A[3] * A[4] - b * A[5])) /
                     (2. * p * p * p);
    const double phi = std::acos(std::clamp(r, -1., 1.)) / 3.;
    value[0]         = m + 2. * p * std::cos(phi);
    value[2]         = m + 2. * p * std::cos(phi + 2.0943951023931957);
    value[1]         = 3. * m - value[0] - value[2];
  }

  /**
   * Largest and smallest eigenvalue of the symmetric tensor with Voigt
   * components @p a0 ... @p a5, without trigonometric functions, so that a
   * loop over a batch of points vectorises.
   *
   * With the deviator's invariants J2 = 3 p^2 and J3, the deviatoric
   * eigenvalues are s = p t with t^3 - 3 t = 2 r, r = J3 / (2 p^3) in
   * [-1, 1]. For r >= 0 the largest root t_1 in [sqrt 3, 2] is a simple
   * root (a double root needs r = -1), an analytic function of r (the
   * inverse of (t^3 - 3 t) / 2, whose slope is 3 to 4.5 there), whose
   * nearest singularity is r = -1. Its Chebyshev interpolant of degree 9
   * in x = 2 r - 1 is within 5.3e-10 of it on [0, 1] (monomial
   * coefficients in x below 1.9, evaluated by Estrin's scheme: four levels
   * of independent multiply-adds instead of nine in a row), and one Newton
   * step, whose error is about 0.8 e^2, takes that to round-off: the next
   * step moves it by at most one unit in the last place (checked on 4e5
   * points of [0, 1]), so the value is the iteration's fixed point as
   * three steps from a cubic start were before. For r < 0 the same solve
   * for -r gives the smallest root. The other extreme follows from the
   * quadratic left after deflation, s = -(t +- sqrt(3 (4 - t^2))) p / 2.
   *
   * The function is a chain of dependent operations whose latency, not
   * its operation count, is its cost in the element loop (the core must
   * retire it before the batch's later work): so p = sqrt(p^2) and 1 / p^2
   * run side by side, r = (J3 / (2 p^2)) (p / p^2), and the start needs
   * one division where the cubic start's three Newton steps needed three.
   */
  // (Always inlined: a loop over a batch that calls it vectorises.)
  [[gnu::always_inline]] inline void extreme_principal_values(const double a0,
                                                              const double a1,
                                                              const double a2,
                                                              const double a3,
                                                              const double a4,
                                                              const double a5,
                                                              double      &largest,
                                                              double      &smallest)
  {
    const double m = (a0 + a1 + a2) / 3.;
    const double a = a0 - m, b = a1 - m, c = a2 - m;
    const double J2 = 0.5 * (a * a + b * b + c * c) + a3 * a3 + a4 * a4 + a5 * a5;
    const double J3 = a * (b * c - a4 * a4) - a3 * (a3 * c - a4 * a5) + a5 * (a3 * a4 - b * a5);
    const double p2 = J2 / 3.;
    const double p  = std::sqrt(p2);
    const double ip2 = 1. / p2;
    // Zero deviator (to round-off of the mean): all three equal m.
    const bool   spherical = !(J2 > 1e-30 * (m * m + 1e-300));
    const double r  = spherical ? 0. : std::clamp((0.5 * J3 * ip2) * (p * ip2), -1., 1.);
    const double ra = std::abs(r);
    const double x = 2. * ra - 1., x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    double       t = ((1.8793852411943512 + 0.13164361465425195 * x) +
                (-0.012862809134103825 + 0.0022133044535502526 * x) * x2) +
               ((-0.00046743994464176655 + 0.00010987210414801902 * x) +
                (-2.7172480083067206e-05 + 7.127861673771623e-06 * x) * x2) *
                 x4 +
               (-2.415438424643636e-06 + 6.770221431883365e-07 * x) * x8;
    t -= (t * t * t - 3. * t - 2. * ra) / (3. * t * t - 3.);
    const double simple = p * t;
    const double other  = 0.5 * p * (t + std::sqrt(std::max(3. * (4. - t * t), 0.)));
    largest  = spherical ? m : m + (r >= 0 ? simple : other);
    smallest = spherical ? m : m - (r >= 0 ? other : simple);
  }

  inline double determinant(const double *A)
  {
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
           A[2] * (A[3] * A[7] - A[4] * A[6]);
  }

  /** B = A^-1. */
  inline void invert(const double *A, double *B)
  {
    const double r = 1. / determinant(A);
    B[0]           = r * (A[4] * A[8] - A[5] * A[7]);
    B[1]           = r * (A[2] * A[7] - A[1] * A[8]);
    B[2]           = r * (A[1] * A[5] - A[2] * A[4]);
    B[3]           = r * (A[5] * A[6] - A[3] * A[8]);
    B[4]           = r * (A[0] * A[8] - A[2] * A[6]);
    B[5]           = r * (A[2] * A[3] - A[0] * A[5]);
    B[6]           = r * (A[3] * A[7] - A[4] * A[6]);
    B[7]           = r * (A[1] * A[6] - A[0] * A[7]);
    B[8]           = r * (A[0] * A[4] - A[1] * A[3]);
  }

  /** C = A B. */
  inline void multiply(const double *A, const double *B, double *C)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  }

  /** out = A B A^T / c for the symmetric @p B (Voigt): push-forward
      (A = F, c = J) or pull-back (A = F^-1, c = 1/J) of a stress, or a
      rotation (A = Q, c = 1). @p out may alias @p B. */
  inline void congruence(const double *A, const double *B, const double c, double *out)
  {
    const double Bm[9] = {B[0], B[3], B[5], B[3], B[1], B[4], B[5], B[4], B[2]};
    double       T[9];
    multiply(A, Bm, T);
    auto r = [&](unsigned int i, unsigned int j) {
      return (T[3 * i] * A[3 * j] + T[3 * i + 1] * A[3 * j + 1] + T[3 * i + 2] * A[3 * j + 2]) / c;
    };
    out[0] = r(0, 0);
    out[1] = r(1, 1);
    out[2] = r(2, 2);
    out[3] = r(0, 1);
    out[4] = r(1, 2);
    out[5] = r(0, 2);
  }
} // namespace anvil::Kinematics
