/**
 * Large stretch of one element against closed forms.
 *
 * Uniaxial strain x = lambda X (lambda = 1.5), face forces against the
 * first Piola-Kirchhoff stress P = F S on the unit reference faces:
 * - St. Venant-Kirchhoff (total Lagrangian): E11 = (lambda^2 - 1)/2,
 *   S11 = (lam + 2 mu) E11, S22 = lam E11;
 * - neo-Hookean (total Lagrangian): S = mu (I - C^-1) + lam ln J C^-1,
 *   J = lambda, C^-1_11 = 1/lambda^2;
 * - Jaumann hypoelastic (updated Lagrangian) stretched at constant rate in
 *   N steps: D11 = lambda_dot / lambda integrates to the logarithmic strain,
 *   sigma11 = (lam + 2 mu) ln(lambda), sigma22 = lam ln(lambda); the
 *   mid-point rule makes the error O(1/N^2) (tolerance 1e-6 at N = 2000).
 */
#include "unit_test.h"

using namespace anvil;
using test::check;

int main()
{
  const double E = 2e11, nu = 0.3, stretch = 1.5;
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));

  MaterialModel::Elastic    svk;
  MaterialModel::NeoHookean neo;
  svk.set(7850., E, nu);
  neo.set(7850., E, nu);

  for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
    for (unsigned int model = 0; model < 2; ++model)
      {
        const MaterialModel::Elastic &m = model == 0 ? svk : neo;
        std::printf("== %s, total Lagrangian, %s integration, stretch %.2f\n",
                    model == 0 ? "St. Venant-Kirchhoff" : "neo-Hookean",
                    Element::to_string(integration).c_str(), stretch);
        test::Block           block(1, 1, 1);
        Element::ElementGroup group(m, Formulation::total_lagrangian, integration, Element::HourglassType::viscous, 0.1);
        block.make_elements(group);
        std::vector<double> x(block.X), v(24, 0.), f(24, 0.);
        for (unsigned int n = 0; n < 8; ++n)
          x[3 * n] *= stretch;
        group.compute_internal_forces(x.data(), v.data(), 0., f.data());
        // Internal force on the x = 1 face: -(P11 A0) in x, -(P21 A0)=0;
        // on the y = 1 face: -(P22 A0) in y.
        double fx = 0, fy = 0;
        for (unsigned int n = 0; n < 8; ++n)
          {
            if (n & 1)
              fx += f[3 * n];
            if (n & 2)
              fy += f[3 * n + 1];
          }
        double S11, S22;
        if (model == 0)
          {
            const double E11 = 0.5 * (stretch * stretch - 1);
            S11              = (lam + 2 * mu) * E11;
            S22              = lam * E11;
          }
        else
          {
            const double lnJ = std::log(stretch);
            S11              = mu * (1 - 1 / (stretch * stretch)) + lam * lnJ / (stretch * stretch);
            S22              = lam * lnJ;
          }
        const double P11 = stretch * S11, P22 = S22;
        check("P11 from the x-face force [Pa]", -fx, P11, 1e-12 * std::abs(P11));
        check("P22 from the y-face force [Pa]", -fy, P22, 1e-12 * std::abs(P11));
      }

  for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
    {
      std::printf("== Jaumann hypoelastic, updated Lagrangian, %s integration, stretch %.2f\n",
                  Element::to_string(integration).c_str(), stretch);
      test::Block           block(1, 1, 1);
      Element::ElementGroup group(svk, Formulation::updated_lagrangian, integration, Element::HourglassType::viscous, 0.1);
      block.make_elements(group);
      const unsigned int  n_steps = 2000;
      const double        dt      = 1e-6;
      std::vector<double> x(block.X), v(24, 0.), f(24);
      for (unsigned int step = 1; step <= n_steps; ++step)
        {
          const double l_old = 1 + (stretch - 1) * (step - 1) / n_steps;
          const double l_new = 1 + (stretch - 1) * double(step) / n_steps;
          for (unsigned int n = 0; n < 8; ++n)
            {
              x[3 * n] = block.X[3 * n] * l_new;
              v[3 * n] = block.X[3 * n] * (l_new - l_old) / dt;
            }
          f.assign(24, 0.);
          group.compute_internal_forces(x.data(), v.data(), dt, f.data());
        }
      const double eps = std::log(stretch);
      check("sigma11 [Pa]", group.stress(0, 0)[0], (lam + 2 * mu) * eps, 1e-6 * (lam + 2 * mu) * eps);
      check("sigma22 [Pa]", group.stress(0, 0)[1], lam * eps, 1e-6 * (lam + 2 * mu) * eps);
      // Current face area is 1 x 1 (uniaxial strain): f = sigma11.
      double fx = 0;
      for (unsigned int n = 0; n < 8; ++n)
        if (n & 1)
          fx += f[3 * n];
      check("x-face force / current area [Pa]", -fx, group.stress(0, 0)[0], 1e-12 * std::abs(group.stress(0, 0)[0]));
    }
  return test::finish();
}
