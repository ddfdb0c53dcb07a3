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
                            double      *s)
  {
    // With K = dt W / 2 and its axial vector k (K x = k x x),
    // (I - K)^{-1} = I + (K + K^2) / (1 + k.k) since K^3 = -(k.k) K, so
    // Q = (I - K)^{-1} (I + K) = I + 2 (K + K^2) / (1 + k.k): exactly
    // orthogonal, with no matrix inverse.
    const double h  = 0.5 * dt;
    const double k0 = -h * w12, k1 = h * w02, k2 = -h * w01; // axial vector
    const double K[3][3] = {{0., -k2, k1}, {k2, 0., -k0}, {-k1, k0, 0.}};
    const double kk      = k0 * k0 + k1 * k1 + k2 * k2;
    const double c       = 2. / (1. + kk);
    const double kv[3]   = {k0, k1, k2};
    double       Q[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        Q[i][j] = (i == j) + c * (K[i][j] + kv[i] * kv[j] - (i == j) * kk);
    const double Qr[9] = {Q[0][0], Q[0][1], Q[0][2], Q[1][0], Q[1][1], Q[1][2], Q[2][0], Q[2][1], Q[2][2]};
    congruence(Qr, s, 1., s);
  }
} // namespace anvil::Kinematics
