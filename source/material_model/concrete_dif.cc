/**
 * @file
 * The dynamic increase factors of concrete across vector lanes. See
 * concrete_dif.h.
 */
#include <anvil/material_model/concrete_dif.h>

// GCC 12 reports the AVX-512 intrinsics behind xsimd's exp and log as
// (maybe) uninitialized (their undefined pass-through operand).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <anvil/utilities/simd_pack.h>

namespace anvil::MaterialModel::ConcreteDIF
{
  // With y = ln(rate), each factor is one exponential of its branch's
  // exponent: (rate / rate_s)^p = exp(p (y - ln rate_s)), and the upper
  // branches c rate^(1/3) = exp(ln c + y / 3); below its static rate a
  // factor is 1.
  void factors(const double *rate, const unsigned int n, const double f_cu, const double f_c, double *tdif,
               double *cdif)
  {
    using V                  = Simd::Pack<1>;
    constexpr unsigned int L = V::lanes;
    constexpr double       c_static = 30e-6, t_static = 1e-6, ln10 = 2.302585092994045684;
    const double           alpha = 1. / (5. + 0.75 * f_cu / 1e6), delta = 1. / (1. + 8. * (f_c / 1e6) / 10.);
    const double           c_power = 1.026 * alpha, ln_c_static = std::log(c_static),
                           ln_gamma = (6.156 * alpha - std::log10(30.) / 3.) * ln10;
    const double t_power = delta, ln_t_static = std::log(t_static), ln_beta = (6. * delta - 2.) * ln10;
    const double one = 1., third = 1. / 3.;
    for (unsigned int i = 0; i < n; i += L)
      {
        const V r = V::load(rate + i);
        const V y = Simd::log(Simd::max(r, 1e-300));
        const V c = Simd::exp(Simd::select(r <= 30., c_power * (y - ln_c_static), ln_gamma + third * y));
        const V t = Simd::exp(Simd::select(r <= 1., t_power * (y - ln_t_static), ln_beta + third * (y - ln_t_static)));
        Simd::select(r > c_static, c, one).store(cdif + i);
        Simd::select(r > t_static, t, one).store(tdif + i);
      }
  }
} // namespace anvil::MaterialModel::ConcreteDIF
