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
 */
#include "unit_test.h"

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
  return test::finish();
}
