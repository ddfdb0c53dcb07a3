/**
 * @file
 * Uniaxial concrete curves: piecewise-linear tables and their generation
 * from f'c by fib Model Code 2010. See concrete_damaged_plasticity.h.
 */
#include <anvil/material_model/concrete_damaged_plasticity.h>
#include <anvil/utilities/input_error.h>

#include <algorithm>
#include <cmath>

namespace anvil::MaterialModel
{
  PiecewiseLinear::PiecewiseLinear(std::vector<double> x, std::vector<double> y)
    : xs(std::move(x))
    , ys(std::move(y))
  {
    for (unsigned int i = 0; i + 1 < xs.size(); ++i)
      slopes.push_back((ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i]));
  }


  namespace
  {
    // fib Model Code 2010, Table 5.1-8: f_ck (MPa), eps_c1 and eps_c,lim
    // (per mille).
    constexpr double mc2010_table[][3] = {
      {12, 1.8, 3.5}, {16, 1.9, 3.5}, {20, 2.1, 3.5}, {25, 2.2, 3.5},
      {30, 2.3, 3.5}, {35, 2.3, 3.5}, {40, 2.4, 3.5}, {45, 2.5, 3.5},
      {50, 2.6, 3.4}, {55, 2.6, 3.4}, {60, 2.7, 3.3}, {70, 2.7, 3.2},
      {80, 2.8, 3.1}, {90, 2.9, 3.0}, {100, 3.0, 3.0}, {110, 3.0, 3.0},
      {120, 3.0, 3.0}};

    struct CompressionConstants
    {
      double f_cm, E_ci, eps_c1, eps_lim, k;
    };

    CompressionConstants compression_constants(const double f_cm)
    {
      const double f_ck = f_cm / 1e6 - 8.;
      if (f_ck < 12. || f_ck > 120.)
        throw InputError("the Model Code 2010 curves need 20 MPa <= f'c <= 128 MPa (f'c = " +
                         std::to_string(f_cm / 1e6) +
                         " MPa); give 'Curves = tabulated' instead");
      unsigned int i = 0;
      while (i + 2 < std::size(mc2010_table) && mc2010_table[i + 1][0] < f_ck)
        ++i;
      const double t = (f_ck - mc2010_table[i][0]) / (mc2010_table[i + 1][0] - mc2010_table[i][0]);
      CompressionConstants c;
      c.f_cm    = f_cm;
      c.E_ci    = 21.5e9 * std::cbrt(f_cm / 10e6);
      c.eps_c1  = 1e-3 * (mc2010_table[i][1] + t * (mc2010_table[i + 1][1] - mc2010_table[i][1]));
      c.eps_lim = 1e-3 * (mc2010_table[i][2] + t * (mc2010_table[i + 1][2] - mc2010_table[i][2]));
      c.k       = c.E_ci * c.eps_c1 / f_cm;
      return c;
    }

    // Eq. (5.1-26) and its exponential tail beyond eps_c,lim.
    double compression_stress(const CompressionConstants &c, const double eps)
    {
      auto sargin = [&](const double e) {
        const double eta = e / c.eps_c1;
        return c.f_cm * (c.k * eta - eta * eta) / (1. + (c.k - 2.) * eta);
      };
      if (eps <= c.eps_lim)
        return sargin(eps);
      const double s_lim = sargin(c.eps_lim);
      const double h     = 1e-7 * c.eps_c1;
      const double slope = (sargin(c.eps_lim) - sargin(c.eps_lim - h)) / h; // < 0
      const double r     = 0.1 * c.f_cm;
      if (s_lim <= r)
        return s_lim;
      return r + (s_lim - r) * std::exp(slope * (eps - c.eps_lim) / (s_lim - r));
    }
  } // namespace


  double ConcreteCurves::model_code_2010_stress(const double f_cm, const double eps)
  {
    return compression_stress(compression_constants(f_cm), eps);
  }


  ConcreteCurves ConcreteCurves::model_code_2010(const double f_cm,
                                                 const double youngs_modulus,
                                                 const double tensile_strength,
                                                 const double fracture_energy)
  {
    const CompressionConstants c = compression_constants(f_cm);
    ConcreteCurves             curves;
    curves.compressive_strength = f_cm;

    // The elastic limit 0.4 f_cm and the strain where Eq. (5.1-26) reaches
    // it (the smaller root of eta^2 - (k + 0.4 (k - 2)) eta + 0.4 = 0).
    const double s0  = 0.4 * f_cm;
    const double bq  = c.k - 0.4 * (c.k - 2.);
    const double eta = 0.5 * (bq - std::sqrt(bq * bq - 1.6));
    const double E   = youngs_modulus > 0 ? youngs_modulus : s0 / (eta * c.eps_c1);
    curves.youngs_modulus = E;

    // Compression: sample the total-strain curve from 0.4 f_cm on, densely
    // near the peak, and convert to inelastic strain eps - sigma / E. (A
    // user modulus above the secant one makes eps_in negative at first:
    // clipped at zero.)
    std::vector<double> e_in{0.}, s{s0};
    const double        e0 = eta * c.eps_c1, e_end = c.eps_lim + 20. * c.eps_c1;
    const unsigned int  n  = 400;
    for (unsigned int i = 1; i <= n; ++i)
      {
        const double t   = double(i) / n;
        const double eps = i <= n / 2 ? e0 + (c.eps_lim - e0) * (2. * t) :
                                        c.eps_lim + (e_end - c.eps_lim) * std::pow(2. * t - 1., 2);
        const double sig = compression_stress(c, eps);
        const double ein = std::max(eps - sig / E, 0.);
        if (ein > e_in.back())
          {
            e_in.push_back(ein);
            s.push_back(sig);
          }
      }
    curves.compression = PiecewiseLinear(e_in, s);

    // Tension.
    const double f_ck = f_cm / 1e6 - 8.;
    const double f_t  = tensile_strength > 0 ?
                          tensile_strength :
                          1e6 * (f_ck <= 50. ? 0.3 * std::pow(f_ck, 2. / 3.) :
                                               2.12 * std::log(1. + f_cm / 10e6));
    const double G_f = fracture_energy > 0 ? fracture_energy : 73. * std::pow(f_cm / 1e6, 0.18);
    curves.tensile_strength = f_t;
    curves.fracture_energy  = G_f;
    const double w1         = G_f / f_t;
    curves.tension = PiecewiseLinear({0., w1, 5. * w1}, {f_t, 0.2 * f_t, 0.});
    return curves;
  }
} // namespace anvil::MaterialModel
