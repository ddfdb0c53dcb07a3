/**
 * Objectivity: a pre-stressed element rotated rigidly by 90 degrees about
 * an oblique axis over many steps.
 *
 * Exact answer: the Cauchy stress rotates with the body, sigma = R sigma_0
 * R^T, and no strain energy appears. Updated Lagrangian: the Jaumann rate
 * (seed Eq. (15)) integrated with the Hughes-Winget rotation on the
 * mid-step configuration is exact for rigid rotations, so the tolerance is
 * round-off (1e-10 relative after 2000 steps). Total Lagrangian: E and S do
 * not change under rotation (seed Eqs. (7), (14)). Both integration rules.
 */
#include "unit_test.h"

using namespace anvil;
using test::check_below;

namespace
{
  /** Rotation by angle a about the unit axis n (Rodrigues). */
  void rotation(const double a, const double *n, double (&R)[3][3])
  {
    const double c = std::cos(a), s = std::sin(a);
    const double K[3][3] = {{0, -n[2], n[1]}, {n[2], 0, -n[0]}, {-n[1], n[0], 0}};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          double KK = 0;
          for (unsigned int k = 0; k < 3; ++k)
            KK += K[i][k] * K[k][j];
          R[i][j] = (i == j) + s * K[i][j] + (1 - c) * KK;
        }
  }

  void rotate_sym(const double (&R)[3][3], const double *s, double *out)
  {
    const double S[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
    double       T[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        {
          T[i][j] = 0;
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              T[i][j] += R[i][k] * S[k][l] * R[j][l];
        }
    out[0] = T[0][0];
    out[1] = T[1][1];
    out[2] = T[2][2];
    out[3] = T[0][1];
    out[4] = T[1][2];
    out[5] = T[0][2];
  }
} // namespace

int main()
{
  MaterialModel::Elastic material;
  material.set(7850., 2e11, 0.3);
  const double       axis[3] = {1. / std::sqrt(3.), 1. / std::sqrt(3.), 1. / std::sqrt(3.)};
  const unsigned int n_steps = 2000;
  const double       angle   = M_PI / 2;
  const double       dt      = 1e-6;
  const double       moves[8][3] = {{0.05, 0.02, -0.03}, {-0.04, 0.03, 0.02}, {0.02, -0.05, 0.04}, {0.03, 0.04, -0.02},
                                    {-0.02, 0.01, 0.05}, {0.04, -0.03, 0.01}, {-0.03, 0.02, -0.04}, {0.01, 0.05, 0.03}};

  for (const auto formulation : {Formulation::updated_lagrangian, Formulation::total_lagrangian})
    for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
      {
        std::printf("== %s, %s integration\n", to_string(formulation).c_str(),
                    Element::to_string(integration).c_str());
        test::Block block(1, 1, 1);
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int d = 0; d < 3; ++d)
            block.X[3 * n + d] += moves[n][d];
        Element::ElementGroup group(material, formulation, integration, Element::HourglassType::viscous, 0.1);
        block.make_elements(group);

        // Pre-stress: UL sets the Cauchy stress; TL pre-stretches the
        // element by F0 and lets the material give S.
        std::vector<double> X0(block.X);
        const double        F0[3][3] = {{1.002, 0.001, 0}, {0.001, 0.998, 0.0005}, {0, 0.0005, 1.001}};
        if (formulation == Formulation::total_lagrangian)
          for (unsigned int n = 0; n < 8; ++n)
            for (unsigned int i = 0; i < 3; ++i)
              X0[3 * n + i] = F0[i][0] * block.X[3 * n] + F0[i][1] * block.X[3 * n + 1] + F0[i][2] * block.X[3 * n + 2];
        else
          for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
            {
              const double s0[6] = {3e8, -1e8, 2e8, 5e7, -4e7, 6e7};
              std::copy(s0, s0 + 6, group.stress(0, q));
            }

        std::vector<double> x(X0), x_old(X0), v(24, 0.), f(24);
        double              energy = 0;
        double              sigma0[6];
        {
          f.assign(24, 0.);
          group.compute_internal_forces(x.data(), v.data(), 0., f.data());
          group.cauchy_stress(0, x.data(), sigma0);
        }
        double R[3][3];
        for (unsigned int step = 1; step <= n_steps; ++step)
          {
            rotation(angle * step / n_steps, axis, R);
            x_old = x;
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int i = 0; i < 3; ++i)
                x[3 * n + i] = R[i][0] * X0[3 * n] + R[i][1] * X0[3 * n + 1] + R[i][2] * X0[3 * n + 2];
            for (unsigned int k = 0; k < 24; ++k)
              v[k] = (x[k] - x_old[k]) / dt;
            f.assign(24, 0.);
            energy += group.compute_internal_forces(x.data(), v.data(), dt, f.data()).internal_energy_increment;
          }
        double sigma[6], expected[6];
        group.cauchy_stress(0, x.data(), sigma);
        rotate_sym(R, sigma0, expected);
        double err = 0, scale = 0;
        for (unsigned int k = 0; k < 6; ++k)
          {
            err   = std::max(err, std::abs(sigma[k] - expected[k]));
            scale = std::max(scale, std::abs(expected[k]));
          }
        check_below("|sigma - R sigma_0 R^T| / |sigma_0| after 90 degrees in 2000 steps", err / scale, 1e-10);
        // Strain energy scale: |sigma_0| x volume x (sigma_0 / E).
        const double e_scale = scale * scale / 2e11;
        check_below("strain energy created by the rotation / (sigma_0^2 V / E)", std::abs(energy) / e_scale, 1e-8);
      }
  return test::finish();
}
