/**
 * The strain rate that enters the concrete DIFs: the largest principal
 * |D|, low-pass filtered with time constant tau (concrete_damaged_plasticity.h).
 *
 * A point in uniaxial compression (D = diag(-r, nu r, nu r)) at r_1 = 1 1/s
 * jumps to r_2 = 100 1/s. Closed forms, with tau = 5 us and dt = tau / 100:
 * - before the jump the filtered rate equals r_1 (started at the first
 *   step's value, no ramp from 0);
 * - after it, rate(t) = r_2 + (r_1 - r_2) exp(-t / tau) (within 1 % of
 *   r_2 - r_1: the recurrence is backward Euler of that ODE);
 * - the CDIF and TDIF shown are the DIFs of the stored rate;
 * - with tau = 0 the rate follows the jump at once.
 */
#include <anvil/material_model/concrete_damaged_plasticity.h>
#include <anvil/material_model/concrete_dif.h>

#include "unit_test.h"

#include <cmath>

using namespace anvil::MaterialModel;
using anvil::test::check;
using anvil::test::check_below;

namespace
{
  double run(const double tau, double &worst_error, double &worst_dif)
  {
    ConcreteDamagedPlasticity             model;
    ConcreteDamagedPlasticity::Parameters p;
    p.curves           = ConcreteCurves::model_code_2010(45.4e6);
    p.rate_effects     = true;
    p.cube_strength    = 45.4e6 / 0.8;
    p.rate_filter_time = tau;
    model.set(p);
    std::vector<double> h(model.n_history(anvil::Formulation::updated_lagrangian), 0.);
    PointData           data;
    data.characteristic_length = 0.05;
    model.initialize_history(h.data(), data);

    using C                 = ConcreteDamagedPlasticity;
    const double r1 = 1., r2 = 100., dt = 5e-8, tau_ref = 5e-6;
    double       stress[6] = {0, 0, 0, 0, 0, 0};
    worst_error = worst_dif = 0;
    for (unsigned int i = 0; i < 2000; ++i)
      {
        const double r    = i < 1000 ? r1 : r2;
        const double D[6] = {-r, 0.2 * r, 0.2 * r, 0, 0, 0};
        model.update_cauchy_stress(D, dt, stress, h.data());
        // After the step that reads r2 (i = 1000), t = (i - 999) dt.
        const double expected =
          i < 1000 ? r1 : r2 + (r1 - r2) * std::exp(-(double(i) - 999.) * dt / tau_ref);
        if (tau > 0)
          worst_error = std::max(worst_error, std::abs(h[C::i_rate] - expected) / (r2 - r1));
        worst_dif = std::max(
          {worst_dif,
           std::abs(model.history_value(h.data(), model.compressive_dif_index()) - ConcreteDIF::compressive(h[C::i_rate], p.cube_strength)),
           std::abs(model.history_value(h.data(), model.tensile_dif_index()) - ConcreteDIF::tensile(h[C::i_rate], 45.4e6))});
      }
    return h[C::i_rate];
  }
} // namespace

int main()
{
  std::printf("== filtered strain rate, jump from 1 to 100 1/s, tau = 5 us\n");
  double err, dif;
  const double end = run(5e-6, err, dif);
  check_below("largest |rate - (r2 + (r1 - r2) exp(-t / tau))| / (r2 - r1)", err, 0.01);
  check("rate after 10 tau", end, 100., 100. * 1e-3);
  check_below("largest |DIF shown - DIF(stored rate)|", dif, 1e-14);
  std::printf("== unfiltered (tau = 0)\n");
  double dummy;
  const double end0 = run(0., dummy, dif);
  check("rate at the end", end0, 100., 1e-12);
  return anvil::test::finish();
}
