/**
 * Dynamic increase factors of concrete (seed Eqs. (64)-(67)), in the form
 * that is continuous at the branch rates (see concrete_dif.h):
 *
 * - continuity at 30 1/s (compression) and 1 1/s (tension) to 1e-12,
 *   approached from both sides;
 * - the branches against their closed forms at sample rates, for the seed's
 *   column concrete (f'c = 45.4 MPa, f_cu = f'c / 0.8);
 * - 1 at and below the static rates; increasing with the rate;
 * - the seed's printed constants (1.206 alpha, 0.49) would not be
 *   continuous: the jump they leave is printed.
 */
#include <anvil/material_model/concrete_dif.h>

#include <algorithm>
#include <vector>

#include "unit_test.h"

using namespace anvil::MaterialModel;
using anvil::test::check;
using anvil::test::check_below;

int main()
{
  const double fc = 45.4e6, fcu = fc / 0.8;
  const double alpha = 1. / (5. + 0.75 * fcu / 1e6), delta = 1. / (1. + 8. * fc / 1e6 / 10.);

  std::printf("== continuity\n");
  const double eps = 1e-9;
  const double c_lo = ConcreteDIF::compressive(30., fcu), c_hi = ConcreteDIF::compressive(30. * (1 + eps), fcu);
  // The slope is finite: remove the O(eps) change of the upper branch.
  const double c_hi0 = std::pow(10., 6.156 * alpha - std::log10(30.) / 3.) * std::cbrt(30.);
  check("CDIF: the two branches at 30 1/s", c_lo, c_hi0, 1e-12 * c_lo);
  check_below("CDIF: |f(30 (1 + 1e-9)) - f(30)| / f", std::abs(c_hi - c_lo) / c_lo, 1e-9);
  const double t_lo = ConcreteDIF::tensile(1., fc), t_hi = ConcreteDIF::tensile(1. + eps, fc);
  const double t_hi0 = std::pow(10., 6. * delta - 2.) * std::cbrt(1. / 1e-6);
  check("TDIF: the two branches at 1 1/s", t_lo, t_hi0, 1e-12 * t_lo);
  check_below("TDIF: |f(1 + 1e-9) - f(1)| / f", std::abs(t_hi - t_lo) / t_lo, 1e-9);

  std::printf("== values (f'c = 45.4 MPa)\n");
  check("CDIF(1 1/s) = (1 / 30e-6)^(1.026 alpha)", ConcreteDIF::compressive(1., fcu),
        std::pow(1. / 30e-6, 1.026 * alpha), 1e-12);
  check("CDIF(100 1/s) = gamma 100^(1/3)", ConcreteDIF::compressive(100., fcu),
        std::pow(10., 6.156 * alpha - std::log10(30.) / 3.) * std::cbrt(100.), 1e-12);
  check("TDIF(1e-2 1/s) = (1e-2 / 1e-6)^delta", ConcreteDIF::tensile(1e-2, fc), std::pow(1e4, delta), 1e-12);
  check("TDIF(10 1/s) = beta (1e7)^(1/3)", ConcreteDIF::tensile(10., fc),
        std::pow(10., 6. * delta - 2.) * std::cbrt(1e7), 1e-11);
  check("CDIF at the static rate", ConcreteDIF::compressive(30e-6, fcu), 1., 0.);
  check("TDIF below the static rate", ConcreteDIF::tensile(1e-8, fc), 1., 0.);
  double previous = 0;
  bool   increasing = true;
  for (double r = 1e-6; r < 1e4; r *= 1.1)
    {
      const double v = ConcreteDIF::compressive(r, fcu) + ConcreteDIF::tensile(r, fc);
      increasing &= v >= previous;
      previous = v;
    }
  check("both factors never decrease with the rate (1 = yes)", increasing, 1., 0.);

  std::printf("== across the lanes (ConcreteDIF::factors) against the functions above\n");
  {
    // Rates from 1e-8 to 1e5 1/s, and each branch's ends exactly.
    std::vector<double> rates = {0., 1e-6, 30e-6, 1., 30., 1e-6 * (1 + 1e-15), 30. * (1 + 1e-15)};
    for (double r = 1e-8; r < 1e5; r *= 1.013)
      rates.push_back(r);
    while (rates.size() % 64 != 0)
      rates.push_back(rates.back() * 1.013);
    std::vector<double> t(rates.size()), c(rates.size());
    ConcreteDIF::factors(rates.data(), rates.size(), fcu, fc, t.data(), c.data());
    double worst = 0;
    for (std::size_t i = 0; i < rates.size(); ++i)
      worst = std::max({worst, std::abs(t[i] / ConcreteDIF::tensile(rates[i], fc) - 1.),
                        std::abs(c[i] / ConcreteDIF::compressive(rates[i], fcu) - 1.)});
    std::printf("  %zu rates\n", rates.size());
    check_below("largest relative difference", worst, 1e-14);
  }

  std::printf("== the seed's printed constants, for the record\n");
  const double seed_lo = std::pow(30. / 30e-6, 1.206 * alpha);
  const double seed_hi = std::pow(10., 6.156 * alpha - 0.49) * std::cbrt(30.);
  std::printf("  1.206 alpha and 0.49 would jump at 30 1/s from %.6f to %.6f (%.2f %%); "
              "1.026 alpha and 0.49 by %.3f %%\n",
              seed_lo, seed_hi, 100. * (seed_hi / seed_lo - 1.),
              100. * (seed_hi / std::pow(30. / 30e-6, 1.026 * alpha) - 1.));
  return anvil::test::finish();
}
