/**
 * @file
 * Flanagan-Belytschko hourglass control of a one-point hexahedron (seed
 * section 3.7, Eqs. (42)-(44); Flanagan and Belytschko 1981) as two named
 * functions: the hourglass rates of the element's nodal velocities, and the
 * nodal forces of the hourglass resistances. The element loop's scalar path
 * calls them (source/element/element_group.cc, which adds the viscous or
 * stiffness resistance between the two); tests/unit/hourglass.cc calls them
 * directly. The batched path computes the same quantities in the Walsh
 * basis of the eight lanes (the same gamma vectors, another order of the
 * sums).
 */
#pragma once

namespace anvil::Element
{
  /**
   * The hourglass rates h_aj of the velocities @p v (8 nodes x 3) of an
   * element at positions @p x, with the base vectors Gamma_j (seed
   * Eq. (42), 4 x 8, entries +-1) and the centroid's inverse Jacobian
   * @p Jinv (dxi_c/dx_a as Jinv[c][a]) and velocity Jacobian @p Jd
   * (dv_a/dxi_c as Jd[a][c]).
   *
   * With g_ja = Gamma_jK x_Ka and t_jc = g_ja dxi_c/dx_a, the
   * Flanagan-Belytschko vectors are gamma_jI = Gamma_jI - t_jc dN_I/dxi_c:
   * orthogonal to every linear velocity field, so that an affine motion has
   * no hourglass rate on any mesh. Then
   *   h_aj = v_Ia gamma_jI = v_Ia Gamma_jI - t_jc (dv_a/dxi_c),
   * which never forms gamma. Returns t (4 x 3) for the forces.
   */
  inline void hourglass_rates(const double (&Gamma)[4][8],
                              const double (&x)[8][3],
                              const double (&v)[8][3],
                              const double (&Jinv)[3][3],
                              const double (&Jd)[3][3],
                              double (&t)[4][3],
                              double (&h)[3][4])
  {
    for (unsigned int j = 0; j < 4; ++j)
      {
        double g[3] = {}, vg[3] = {};
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            {
              g[a] += Gamma[j][n] * x[n][a];
              vg[a] += Gamma[j][n] * v[n][a];
            }
        for (unsigned int c = 0; c < 3; ++c)
          t[j][c] = g[0] * Jinv[c][0] + g[1] * Jinv[c][1] + g[2] * Jinv[c][2];
        for (unsigned int a = 0; a < 3; ++a)
          h[a][j] = vg[a] - (t[j][0] * Jd[a][0] + t[j][1] * Jd[a][1] + t[j][2] * Jd[a][2]);
      }
  }


  /**
   * Add the nodal forces of the hourglass resistances @p r (r_aj, seed
   * Eq. (44): the viscous k h_aj or the stiffness k q_aj) to @p f:
   * f_Ia -= r_aj gamma_jI = -r_aj Gamma_jI + (r_aj t_jc) dN_I/dxi_c, with
   * @p dN the shape-function derivatives at the centroid and @p t from
   * hourglass_rates(). Their power, -r_aj h_aj, is never positive for
   * r = k h, and they sum to zero (sum_I gamma_jI = 0).
   */
  inline void add_hourglass_forces(const double (&Gamma)[4][8],
                                   const double (&dN)[8][3],
                                   const double (&t)[4][3],
                                   const double (&r)[3][4],
                                   double (&f)[8][3])
  {
    double u[3][3];
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int c = 0; c < 3; ++c)
        u[a][c] = r[a][0] * t[0][c] + r[a][1] * t[1][c] + r[a][2] * t[2][c] + r[a][3] * t[3][c];
    for (unsigned int n = 0; n < 8; ++n)
      for (unsigned int a = 0; a < 3; ++a)
        f[n][a] += u[a][0] * dN[n][0] + u[a][1] * dN[n][1] + u[a][2] * dN[n][2] -
                   (r[a][0] * Gamma[0][n] + r[a][1] * Gamma[1][n] + r[a][2] * Gamma[2][n] +
                    r[a][3] * Gamma[3][n]);
  }
} // namespace anvil::Element
