/**
 * Flanagan-Belytschko hourglass control (seed section 3.7, Eq. (44)).
 *
 * On a distorted one-point element:
 * - a velocity field in a pure hourglass mode v_I = Gamma_jI e_a has zero
 *   velocity gradient at the centroid (seed Eq. (43): the base vectors
 *   Gamma are orthogonal to Lambda), so no stress arises; the hourglass
 *   force opposes the motion (negative power), with the magnitude of seed
 *   Eq. (44): |h| = 8 for the unit mode;
 * - any affine velocity field v = B x + c produces exactly zero hourglass
 *   force (the FB vectors gamma are orthogonal to linear fields), viscous
 *   and stiffness form.
 *
 * And the two named functions of include/anvil/element/hourglass.h on their
 * own: on a cube, the unit mode's rate is h = 8 exactly (Gamma_j . Gamma_j)
 * and the other modes' 0; on the distorted element, an affine velocity
 * field's rates vanish to round-off, and the forces of any resistance sum
 * to zero and do no work on an affine velocity field (sum_I gamma_jI = 0,
 * gamma orthogonal to x).
 */
#include "unit_test.h"

#include <anvil/element/hourglass.h>

using namespace anvil;
using test::check;
using test::check_below;

int main()
{
  MaterialModel::Elastic material;
  material.set(7850., 2e11, 0.3);
  const double moves[8][3] = {{0.05, 0.02, -0.03}, {-0.04, 0.03, 0.02}, {0.02, -0.05, 0.04}, {0.03, 0.04, -0.02},
                              {-0.02, 0.01, 0.05}, {0.04, -0.03, 0.01}, {-0.03, 0.02, -0.04}, {0.01, 0.05, 0.03}};
  const double sgn[8][3]   = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1},
                              {-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1, 1, 1}};
  for (const auto type : {Element::HourglassType::viscous, Element::HourglassType::stiffness})
    {
      std::printf("== %s hourglass control, distorted one-point element\n", Element::to_string(type).c_str());
      for (unsigned int mode = 0; mode < 4; ++mode)
        {
          test::Block block(1, 1, 1);
          for (unsigned int n = 0; n < 8; ++n)
            for (unsigned int d = 0; d < 3; ++d)
              block.X[3 * n + d] += moves[n][d];
          Element::ElementGroup group(material, Formulation::updated_lagrangian,
                                      Element::Integration::one_point, type, 0.1);
          block.make_elements(group);
          std::vector<double> x(block.X), v(24, 0.), f(24, 0.);
          for (unsigned int n = 0; n < 8; ++n)
            {
              const double G[4] = {sgn[n][0] * sgn[n][1], sgn[n][1] * sgn[n][2], sgn[n][0] * sgn[n][2],
                                   sgn[n][0] * sgn[n][1] * sgn[n][2]};
              v[3 * n + (mode % 3)] = G[mode];
            }
          const double dt = 1e-7;
          const auto   r  = group.compute_internal_forces(x.data(), v.data(), dt, f.data());
          double       s  = 0;
          for (unsigned int k = 0; k < 6; ++k)
            s = std::max(s, std::abs(group.stress(0, 0)[k]));
          check_below("mode Gamma_" + std::to_string(mode + 1) + ": stress from the centroid strain rate [Pa]", s, 1e-6);
          double power = 0;
          for (unsigned int i = 0; i < 24; ++i)
            power += f[i] * v[i];
          check("mode Gamma_" + std::to_string(mode + 1) + ": hourglass force opposes the motion (sign of power)",
                power < 0 ? -1. : 1., -1., 0.);
          if (type == Element::HourglassType::viscous)
            {
              // The energy the viscous force takes out, by the trapezoidal
              // rule over a step that starts from rest, is - power dt / 2.
              check_below("mode Gamma_" + std::to_string(mode + 1) +
                            ": hourglass energy increment equals minus the power times dt, relative",
                          std::abs(r.hourglass_energy_increment + 0.5 * power * dt) /
                            std::abs(0.5 * power * dt),
                          1e-12);
            }
        }

      // Affine velocity fields: zero hourglass force, to round-off.
      test::Block block(1, 1, 1);
      for (unsigned int n = 0; n < 8; ++n)
        for (unsigned int d = 0; d < 3; ++d)
          block.X[3 * n + d] += moves[n][d];
      Element::ElementGroup group(material, Formulation::updated_lagrangian,
                                  Element::Integration::one_point, type, 0.1);
      block.make_elements(group);
      std::vector<double> x(block.X), v(24), f(24, 0.);
      const double        B[3][3] = {{1.3, -0.7, 0.4}, {0.2, 0.9, -1.1}, {-0.5, 0.6, 0.8}};
      const double        c[3]    = {2., -1., 0.5};
      for (unsigned int n = 0; n < 8; ++n)
        for (unsigned int i = 0; i < 3; ++i)
          v[3 * n + i] = c[i] + B[i][0] * x[3 * n] + B[i][1] * x[3 * n + 1] + B[i][2] * x[3 * n + 2];
      // dt = 0: no stress update, so every force is hourglass force.
      const auto r = group.compute_internal_forces(x.data(), v.data(), 0., f.data());
      // Compare with the force of a hourglass mode of the same velocity size.
      std::vector<double> vh(24, 0.), fh(24, 0.);
      for (unsigned int n = 0; n < 8; ++n)
        vh[3 * n] = 3. * sgn[n][0] * sgn[n][1] * sgn[n][2];
      Element::ElementGroup ref(material, Formulation::updated_lagrangian,
                                Element::Integration::one_point, Element::HourglassType::viscous, 0.1);
      block.make_elements(ref);
      ref.compute_internal_forces(x.data(), vh.data(), 0., fh.data());
      double fa = 0, fr = 0;
      for (unsigned int i = 0; i < 24; ++i)
        {
          fa = std::max(fa, std::abs(f[i]));
          fr = std::max(fr, std::abs(fh[i]));
        }
      check_below("affine velocity field: hourglass force / that of a hourglass mode of equal speed", fa / fr, 1e-13);
      check_below("affine velocity field: hourglass energy increment [J]", std::abs(r.hourglass_energy_increment), 1e-300);
    }
  // The named functions on their own. The centroid's derivatives of the
  // shape functions are sgn_I / 8; J_ac = x_Ia dN_I/dxi_c, Jd_ac = v_Ia
  // dN_I/dxi_c.
  {
    double Gamma[4][8], dN[8][3];
    for (unsigned int I = 0; I < 8; ++I)
      {
        Gamma[0][I] = sgn[I][0] * sgn[I][1];
        Gamma[1][I] = sgn[I][1] * sgn[I][2];
        Gamma[2][I] = sgn[I][0] * sgn[I][2];
        Gamma[3][I] = sgn[I][0] * sgn[I][1] * sgn[I][2];
        for (unsigned int c = 0; c < 3; ++c)
          dN[I][c] = 0.125 * sgn[I][c];
      }
    const auto centroid_jacobians = [&](const double (&x)[8][3], const double (&v)[8][3], double (&Jinv)[3][3],
                                        double (&Jd)[3][3]) {
      double J[3][3] = {};
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = 0; c < 3; ++c)
          {
            Jd[a][c] = 0;
            for (unsigned int I = 0; I < 8; ++I)
              {
                J[a][c] += x[I][a] * dN[I][c];
                Jd[a][c] += v[I][a] * dN[I][c];
              }
          }
      // Jinv[c][a] = dxi_c/dx_a, the inverse of J[a][c].
      const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      for (unsigned int c = 0; c < 3; ++c)
        for (unsigned int a = 0; a < 3; ++a)
          {
            const unsigned int c1 = (c + 1) % 3, c2 = (c + 2) % 3, a1 = (a + 1) % 3, a2 = (a + 2) % 3;
            Jinv[c][a] = (J[a1][c1] * J[a2][c2] - J[a1][c2] * J[a2][c1]) / det;
          }
    };
    std::printf("== hourglass_rates and add_hourglass_forces (include/anvil/element/hourglass.h)\n");
    // A cube of side 2 (x = xi): t = 0, h_aj = Gamma_j . v_a.
    double cube[8][3], distorted[8][3];
    for (unsigned int I = 0; I < 8; ++I)
      for (unsigned int a = 0; a < 3; ++a)
        {
          cube[I][a]      = sgn[I][a];
          distorted[I][a] = sgn[I][a] + 2. * moves[I][a];
        }
    double worst_mode = 0;
    for (unsigned int j = 0; j < 4; ++j)
      for (unsigned int a = 0; a < 3; ++a)
        {
          double v[8][3] = {}, Jinv[3][3], Jd[3][3], t[4][3], h[3][4];
          for (unsigned int I = 0; I < 8; ++I)
            v[I][a] = Gamma[j][I];
          centroid_jacobians(cube, v, Jinv, Jd);
          Element::hourglass_rates(Gamma, cube, v, Jinv, Jd, t, h);
          for (unsigned int b = 0; b < 3; ++b)
            for (unsigned int k = 0; k < 4; ++k)
              worst_mode = std::max(worst_mode, std::abs(h[b][k] - (b == a && k == j ? 8. : 0.)));
        }
    check_below("cube, the 12 unit modes: largest |h_bk - 8 delta_ab delta_jk|", worst_mode, 1e-14);

    const double B[3][3] = {{1.3, -0.7, 0.4}, {0.2, 0.9, -1.1}, {-0.5, 0.6, 0.8}};
    const double c0[3]   = {2., -1., 0.5};
    double       v[8][3], Jinv[3][3], Jd[3][3], t[4][3], h[3][4];
    for (unsigned int I = 0; I < 8; ++I)
      for (unsigned int a = 0; a < 3; ++a)
        v[I][a] = c0[a] + B[a][0] * distorted[I][0] + B[a][1] * distorted[I][1] + B[a][2] * distorted[I][2];
    centroid_jacobians(distorted, v, Jinv, Jd);
    Element::hourglass_rates(Gamma, distorted, v, Jinv, Jd, t, h);
    double worst_affine = 0;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int j = 0; j < 4; ++j)
        worst_affine = std::max(worst_affine, std::abs(h[a][j]));
    // (The scale: a unit mode's rate, 8.)
    check_below("distorted element, affine velocity field: largest |h_aj| over a unit mode's 8", worst_affine / 8.,
                1e-14);

    const double r[3][4] = {{0.7, -1.2, 0.3, 2.1}, {-0.4, 0.9, 1.6, -0.8}, {1.1, 0.2, -0.6, 0.5}};
    double       f[8][3] = {};
    Element::add_hourglass_forces(Gamma, dN, t, r, f);
    double sum[3] = {}, work = 0, size = 0;
    for (unsigned int I = 0; I < 8; ++I)
      for (unsigned int a = 0; a < 3; ++a)
        {
          sum[a] += f[I][a];
          work += f[I][a] * v[I][a];
          size = std::max(size, std::abs(f[I][a]));
        }
    check_below("distorted element, forces of an arbitrary resistance: largest |sum_I f_Ia| over max |f|",
                std::max({std::abs(sum[0]), std::abs(sum[1]), std::abs(sum[2])}) / size, 1e-14);
    double vmax = 0;
    for (unsigned int I = 0; I < 8; ++I)
      for (unsigned int a = 0; a < 3; ++a)
        vmax = std::max(vmax, std::abs(v[I][a]));
    check_below("... their work on the affine velocity field over max |f| max |v|", std::abs(work) / (size * vmax),
                1e-14);
  }
  return test::finish();
}
