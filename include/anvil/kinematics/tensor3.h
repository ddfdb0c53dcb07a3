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
