/**
 * Concrete damaged plasticity at the apex: a point (f'c = 45.4 MPa, MC2010
 * curves, h = 50 mm) in hydrostatic expansion D = e_dot I until the cracks
 * are fully open, updated Lagrangian form called as the element loop does.
 *
 * All three principal directions reach the tension cut-off together, with
 * equal plastic rates S / 3; kappa_t grows by S / 3, and each direction
 * follows the tension curve in kappa_t. Closed forms:
 * - the mean stress peaks at f_t (the cut-off; Lubliner's surface alone
 *   would allow more there);
 * - the stress stays hydrostatic;
 * - it falls to zero at full opening;
 * - the dissipated energy density is 3 k G_F / h with k = b_t + (1 - b_t)
 *   E / (3 K) = b_t + (1 - b_t)(1 - 2 nu): per direction, the damaged part
 *   of the cracking strain sees the bulk stiffness 3 K instead of E.
 */
#include "concrete_point.h"
#include "unit_test.h"

#include <algorithm>

using namespace anvil::MaterialModel;
using anvil::test::check;
using anvil::test::check_below;

int main()
{
  const auto                p = anvil::test::column_concrete();
  ConcreteDamagedPlasticity model;
  model.set(p);
  const double h = 0.05, f_t = p.curves.tensile_strength, G_F = p.curves.fracture_energy;
  const double nu = p.poissons_ratio, b = p.tensile_plastic_fraction;
  std::vector<double> history = anvil::test::fresh_history(model, h);

  // Strain at full opening: kappa = b w_c / h plus the elastic-damaged part
  // (1 - b) E e_in / (3 K); run to 1.2 times it.
  const double w_c = 5. * G_F / f_t, e_in = w_c / h;
  const double eps_end = 1.2 * (b * e_in + (1. - b) * (1. - 2. * nu) * e_in);
  const unsigned int n = 20000;
  const double dt = 1e-3, rate = eps_end / n / dt;
  const double D[6] = {rate, rate, rate, 0., 0., 0.};
  double       stress[6] = {0, 0, 0, 0, 0, 0};
  double       peak = 0, worst_deviator = 0, work = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      const double old_mean = (stress[0] + stress[1] + stress[2]) / 3.;
      model.update_cauchy_stress(D, dt, stress, history.data());
      const double mean = (stress[0] + stress[1] + stress[2]) / 3.;
      work += 3. * 0.5 * (old_mean + mean) * rate * dt;
      peak = std::max(peak, mean);
      double dev = 0;
      for (unsigned int k = 0; k < 6; ++k)
        dev = std::max(dev, std::abs(k < 3 ? stress[k] - mean : stress[k]));
      worst_deviator = std::max(worst_deviator, dev);
    }
  const double k_hyd = b + (1. - b) * (1. - 2. * nu);
  std::printf("== hydrostatic tension (h = %.0f mm, f_t = %.4g MPa, G_F = %.2f J/m^2)\n", h * 1e3,
              f_t / 1e6, G_F);
  check("peak mean stress / f_t", peak / f_t, 1., 1e-3);
  check_below("largest deviatoric stress / f_t", worst_deviator / f_t, 1e-9);
  check_below("mean stress left at 1.2 times the full opening / f_t",
              std::abs(stress[0] + stress[1] + stress[2]) / 3. / f_t, 1e-6);
  const double expected = 3. * k_hyd * G_F / h;
  check("dissipated energy density / (3 k G_F / h), k = " + std::to_string(k_hyd),
        history[ConcreteDamagedPlasticity::i_dissipation] / expected, 1., 0.01);
  check("the same against the stress work 3 int p d eps", history[ConcreteDamagedPlasticity::i_dissipation] / work,
        1., 1e-3);
  return anvil::test::finish();
}
