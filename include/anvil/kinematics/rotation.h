/**
 * @file
 * Objective stress rotation shared by the element kernels and the material
 * models that integrate a rate form on the reference mesh.
 */
#pragma once

#include <anvil/kinematics/tensor3.h>

namespace anvil::Kinematics
{
  /**
   * Objective rotation of the stress @p s (Voigt [xx,yy,zz,xy,yz,xz]) by the
   * spin W over dt with the Hughes-Winget midpoint rule,
   * Q = (I - dt W/2)^-1 (I + dt W/2), sigma <- Q sigma Q^T: the integrated
   * form of the Jaumann rate of seed Eq. (15) that stays exactly orthogonal
   * (Hughes & Winget 1980). @p w01, @p w12, @p w02 are the components
   * W_01 = (L_01 - L_10)/2, W_12, W_02 of the spin.
   */
  inline void rotate_stress(const double w01,
                            const double w12,
                            const double w02,
                            const double dt,
                            double &s0, double &s1, double &s2,
                            double &s3, double &s4, double &s5)
  {
    // With K = dt W / 2 and its axial vector k (K x = k x x),
    // (I - K)^{-1} = I + (K + K^2) / (1 + k.k) since K^3 = -(k.k) K, so
    // Q = (I - K)^{-1} (I + K) = I + 2 (K + K^2) / (1 + k.k): exactly
    // orthogonal, with no matrix inverse. Written out component by
    // component (no inner loops), so that a loop over a batch of points
    // calling it vectorises across them.
    const double h   = 0.5 * dt;
    const double k0  = -h * w12, k1 = h * w02, k2 = -h * w01; // axial vector
    const double kk  = k0 * k0 + k1 * k1 + k2 * k2;
    const double c   = 2. / (1. + kk);
    const double Q00 = 1. + c * (k0 * k0 - kk), Q11 = 1. + c * (k1 * k1 - kk),
                 Q22 = 1. + c * (k2 * k2 - kk);
    const double Q01 = c * (-k2 + k0 * k1), Q10 = c * (k2 + k0 * k1);
    const double Q02 = c * (k1 + k0 * k2), Q20 = c * (-k1 + k0 * k2);
    const double Q12 = c * (-k0 + k1 * k2), Q21 = c * (k0 + k1 * k2);
    // T = Q S, then sigma = T Q^T.
    const double T00 = Q00 * s0 + Q01 * s3 + Q02 * s5;
    const double T01 = Q00 * s3 + Q01 * s1 + Q02 * s4;
    const double T02 = Q00 * s5 + Q01 * s4 + Q02 * s2;
    const double T10 = Q10 * s0 + Q11 * s3 + Q12 * s5;
    const double T11 = Q10 * s3 + Q11 * s1 + Q12 * s4;
    const double T12 = Q10 * s5 + Q11 * s4 + Q12 * s2;
    const double T20 = Q20 * s0 + Q21 * s3 + Q22 * s5;
    const double T21 = Q20 * s3 + Q21 * s1 + Q22 * s4;
    const double T22 = Q20 * s5 + Q21 * s4 + Q22 * s2;
    s0 = T00 * Q00 + T01 * Q01 + T02 * Q02;
    s1 = T10 * Q10 + T11 * Q11 + T12 * Q12;
    s2 = T20 * Q20 + T21 * Q21 + T22 * Q22;
    s3 = T00 * Q10 + T01 * Q11 + T02 * Q12;
    s4 = T10 * Q20 + T11 * Q21 + T12 * Q22;
    s5 = T00 * Q20 + T01 * Q21 + T02 * Q22;
  }

  /** The same rotation of a stress stored as 6 contiguous values. */
  inline void rotate_stress(const double w01,
                            const double w12,
                            const double w02,
                            const double dt,
                            double      *s)
  {
    rotate_stress(w01, w12, w02, dt, s[0], s[1], s[2], s[3], s[4], s[5]);
  }
} // namespace anvil::Kinematics
