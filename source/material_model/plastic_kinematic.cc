/**
 * @file
 * Plastic-kinematic steel, seed Eq. (63). See plastic_kinematic.h.
 */
#include <anvil/kinematics/rotation.h>
#include <anvil/kinematics/tensor3.h>
#include <anvil/material_model/plastic_kinematic.h>
#include <anvil/utilities/bracketed_newton.h>
#include <anvil/utilities/input_error.h>

// GCC 12 reports the AVX-512 intrinsics behind xsimd's min, max, exp and
// log as (maybe) uninitialized (their undefined pass-through operand).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <anvil/utilities/simd_pack.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace anvil::MaterialModel
{
  namespace
  {
    // @sect3{Presets}
    //
    // A preset fills every entry the scene leaves empty. "Table 1 steel" is
    // the reinforcement of the seed's Table 1 (density: steel's usual
    // 7850 kg/m^3, which the table does not give).
    struct Preset
    {
      std::map<std::string, double> values;
    };

    const std::map<std::string, Preset> &presets()
    {
      static const std::map<std::string, Preset> p = {
        {"Table 1 steel",
         {{{"Density", 7850.},
           {"Young's modulus", 206e9},
           {"Poisson's ratio", 0.3},
           {"Yield stress", 335e6},
           {"Tangent modulus", 1.2e9},
           {"Hardening parameter beta", 0.},
           {"Cowper-Symonds C", 40.},
           {"Cowper-Symonds p", 5.},
           {"Failure strain", 0.12}}}}};
      return p;
    }

    const char *numeric_entries[][3] = {
      {"Density", "Reference mass density. Units: kg/m^3.", "0"},
      {"Young's modulus", "Young's modulus E. Units: Pa.", "0"},
      {"Poisson's ratio", "Poisson's ratio nu, -1 < nu < 0.5. Units: none.", "-1"},
      {"Yield stress", "Initial yield stress sigma_0 (seed Eq. (63)). Units: Pa.", "0"},
      {"Tangent modulus",
       "Tangent modulus E_t of the bilinear uniaxial curve, 0 <= E_t < E; the "
       "plastic hardening modulus is E_p = E E_t / (E - E_t). Units: Pa.",
       "0"},
      {"Hardening parameter beta",
       "beta of seed Eq. (63): 0 kinematic, 1 isotropic hardening, between "
       "them mixed. Units: none.",
       "0"},
      {"Cowper-Symonds C",
       "Strain-rate parameter C of the Cowper-Symonds factor "
       "1 + (eps_dot / C)^(1/p). Units: 1/s.",
       "0"},
      {"Cowper-Symonds p", "Strain-rate exponent p. Units: none.", "0"},
      {"Failure strain",
       "Effective plastic strain f_s at which a material point fails "
       "(used when 'Erosion' is on; 0: never). Units: none.",
       "0"}};
  } // namespace


  void PlasticKinematicLaw::set_cowper_symonds(const double C_, const double p_)
  {
    rate_law     = RateLaw::cowper_symonds;
    rate_effects = true;
    C            = C_;
    p            = p_;
  }


  // Malvar (1998), the yield stress's fit: alpha_fy = 0.074 - 0.040 f_y /
  // 60 ksi, with 60 ksi = 413.7 MPa; the reference rate of the quasi-static
  // tests is 1e-4 1/s, below which the factor stays 1.
  void PlasticKinematicLaw::set_malvar_crawford()
  {
    const double a = 0.074 - 0.040 * sigma_0 / 413.7e6;
    if (!(a > 0))
      throw std::invalid_argument("Malvar and Crawford's exponent 0.074 - 0.040 f_y / 413.7 MPa "
                                  "is not positive for f_y = " +
                                  std::to_string(sigma_0 / 1e6) + " MPa");
    rate_law     = RateLaw::malvar_crawford;
    rate_effects = true;
    alpha        = a;
  }


  double PlasticKinematicLaw::rate_factor(const double rate) const
  {
    if (!(rate > 0))
      return 1.;
    switch (rate_law)
      {
        case RateLaw::cowper_symonds:
          return 1. + std::pow(rate / C, 1. / p);
        case RateLaw::malvar_crawford:
          return rate > 1e-4 ? std::pow(rate / 1e-4, alpha) : 1.;
        case RateLaw::none:
          break;
      }
    return 1.;
  }


  double PlasticKinematicLaw::rate_dependent_increment(const double q_trial,
                                                       const double eps_p,
                                                       const double dt,
                                                       const double elastic_term,
                                                       double      &R) const
  {
    R               = 1.;
    const double d0 = plastic_increment(q_trial, eps_p, 1., elastic_term);
    if (d0 == 0. || !rate_effects || !(dt > 0))
      return d0;
    // g(d) = q_trial - K d - R(d / dt) sigma(d), decreasing in d, with
    // g(0) > 0 (beyond the static yield stress) and g(d0) <= 0 (R >= 1):
    // the root lies in [0, d0].
    const double K = elastic_term + (1. - beta) * plastic_modulus;
    if (rate_law == RateLaw::cowper_symonds && p >= 1.)
      return cowper_symonds_increment(q_trial, eps_p, dt, K, d0, R);
    auto g = [&](const double d, double &slope) {
      const double rate = d / dt;
      double       Rd = 1., dR = 0.;
      if (rate_law == RateLaw::cowper_symonds && rate > 0)
        {
          const double x = std::pow(rate / C, 1. / p);
          Rd             = 1. + x;
          dR             = x / (p * rate);
        }
      else if (rate_law == RateLaw::malvar_crawford && rate > 1e-4)
        {
          Rd = std::pow(rate / 1e-4, alpha);
          dR = alpha * Rd / rate;
        }
      const double sy = sigma_0 + beta * plastic_modulus * (eps_p + d);
      slope           = -K - dR / dt * sy - Rd * beta * plastic_modulus;
      return q_trial - K * d - Rd * sy;
    };
    const double d = bracketed_newton(g, 0., d0, d0, 1e-14 * d0);
    R              = rate_factor(d / dt);
    return d;
  }


  // Cowper-Symonds' increment in the rate term's own variable
  // y = (dep / (C dt))^(1/p): R = 1 + y, dep = C dt y^p, and
  //   g(y) = q_trial - K C dt y^p - (1 + y) (sigma_0 + beta E_p (eps_p + C dt y^p)).
  // In dep the rate term has the infinite slope of dep^(1/p) at 0, and
  // Newton's method in dep stalled next to the root and bisected, 4 to 32
  // evaluations of a pow a point; in y, g is smooth, decreasing and (for
  // p >= 1) concave. Newton's step from y = 0 lands at or beyond the root
  // (the tangent of a concave function lies above it), and from there every
  // step stays beyond it and approaches it quadratically: no bracket, no
  // bisection, 1 to 6 evaluations (doc/performance.md).
  double PlasticKinematicLaw::cowper_symonds_increment(const double q_trial,
                                                       const double eps_p,
                                                       const double dt,
                                                       const double K,
                                                       const double d0,
                                                       double      &R) const
  {
    const double Cdt = C * dt, Hb = beta * plastic_modulus;
    const double static_yield = sigma_0 + Hb * eps_p;
    // g and dep at y, and the slopes dg/dy and d dep/dy.
    double     d = 0, slope = 0, dd = 0;
    const auto g = [&](const double y) {
      const double y_p1 = std::pow(y, p - 1.); // y^(p-1)
      d                 = Cdt * y_p1 * y;
      dd                = p * Cdt * y_p1;
      const double sy   = static_yield + Hb * d;
      slope             = -K * dd - sy - (1. + y) * Hb * dd;
      return q_trial - K * d - (1. + y) * sy;
    };
    // y of the rate-free increment d0 (R >= 1 there, so g <= 0: at or
    // beyond the root), and Newton's first step from y = 0, where
    // g = q_trial - static_yield and dg/dy = -static_yield (p > 1).
    const double y_max = std::pow(d0 / Cdt, 1. / p);
    double       y =
      p > 1. ? (q_trial - static_yield) / static_yield : (q_trial - static_yield) / (K * Cdt + static_yield + Hb * Cdt);
    y                = std::min(y, y_max);
    const double tolerance = 1e-14 * d0;
    for (unsigned int it = 0; it < 60; ++it)
      {
        const double value = g(y);
        // (At the root to round-off, value may come out >= 0: the step is
        // then as small as the round-off, and ends the iteration.)
        const double step = std::max(-y, -value / slope);
        y += step;
        if (std::abs(dd * step) <= tolerance)
          {
            d += dd * step;
            break;
          }
      }
    R = 1. + y;
    return std::min(std::max(d, 0.), d0);
  }


  std::string PlasticKinematicLaw::describe_rate_law() const
  {
    std::ostringstream s;
    switch (rate_law)
      {
        case RateLaw::cowper_symonds:
          s << "Cowper-Symonds (C = " << C << " 1/s, p = " << p << ")";
          break;
        case RateLaw::malvar_crawford:
          s << "Malvar-Crawford (alpha = " << std::setprecision(4) << alpha << ")";
          break;
        case RateLaw::none:
          break;
      }
    return s.str();
  }


  void PlasticKinematic::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    std::string names = "none";
    for (const auto &[n, preset] : presets())
      names += "|" + n;
    prm.declare_entry("Preset",
                      "none",
                      Patterns::Selection(names),
                      "A named parameter set that fills every entry left "
                      "empty. 'Table 1 steel': the seed's reinforcement "
                      "(E 206 GPa, nu 0.3, sigma_0 335 MPa, E_t 1.2 GPa, "
                      "C 40 1/s, p 5, f_s 0.12, beta 0; density 7850 kg/m^3).");
    for (const auto &e : numeric_entries)
      prm.declare_entry(e[0],
                        "",
                        Patterns::Anything(),
                        std::string(e[1]) +
                          " Empty: the preset's value.");
    prm.declare_entry("Strain rate effects",
                      "auto",
                      Patterns::Selection("auto|none|Cowper-Symonds|Malvar-Crawford|true|false"),
                      "Which law scales the yield stress with the effective "
                      "total strain rate sqrt(2/3 D':D'). 'auto': "
                      "Cowper-Symonds whenever 'Cowper-Symonds C' and "
                      "'Cowper-Symonds p' are given and positive (by the "
                      "scene or the preset), none otherwise, as LS-DYNA's "
                      "*MAT_PLASTIC_KINEMATIC does with SRC and SRP. "
                      "'Cowper-Symonds': 1 + (eps_dot / C)^(1/p) (seed Eq. "
                      "(63)). 'Malvar-Crawford': the dynamic increase factor "
                      "of reinforcing bars, (eps_dot / 1e-4 1/s)^alpha, "
                      "alpha = 0.074 - 0.040 sigma_0 / 414 MPa, at least 1 "
                      "(Malvar 1998; fitted to bars of 290-710 MPa). 'none': "
                      "no rate is computed. 'true' and 'false' are the "
                      "earlier spellings of 'Cowper-Symonds' and 'none'. The "
                      "run's summary of its step names the law that acts. "
                      "Units: none.");
    prm.declare_entry("Erosion",
                      "false",
                      Patterns::Bool(),
                      "Erode an element when its mean effective plastic "
                      "strain reaches 'Failure strain': it stops carrying "
                      "force and leaves contact, and its energy moves to the "
                      "'eroded' column of energy.csv.");
  }


  void PlasticKinematic::parse_parameters(dealii::ParameterHandler &prm)
  {
    const std::string preset = prm.get("Preset");
    auto value = [&](const std::string &entry) {
      const std::string text = dealii::Utilities::trim(prm.get(entry));
      if (text.empty())
        {
          if (preset == "none")
            throw InputError("subsection 'plastic kinematic': entry '" + entry +
                             "' is empty and 'Preset' is none; give a number or "
                             "choose a preset (" + std::string("Table 1 steel") + ")");
          return presets().at(preset).values.at(entry);
        }
      try
        {
          std::size_t used = 0;
          const double v   = std::stod(text, &used);
          if (used != text.size())
            throw std::invalid_argument(text);
          return v;
        }
      catch (const std::exception &)
        {
          throw InputError("subsection 'plastic kinematic': entry '" + entry +
                           "' = '" + text +
                           "' is not a number (allowed: a number, or empty for "
                           "the preset's value)");
        }
    };
    auto positive = [&](const std::string &entry) {
      const double v = value(entry);
      if (!(v > 0))
        throw InputError("subsection 'plastic kinematic': entry '" + entry +
                         "' must be positive");
      return v;
    };

    PlasticKinematicLaw l;
    const double density = positive("Density");
    const double youngs  = positive("Young's modulus");
    const double poisson = value("Poisson's ratio");
    if (poisson <= -1. || poisson >= 0.5)
      throw InputError("subsection 'plastic kinematic': entry 'Poisson's ratio' = " +
                       std::to_string(poisson) + " is outside -1 < nu < 0.5");
    l.sigma_0        = positive("Yield stress");
    const double Et  = value("Tangent modulus");
    if (Et < 0 || Et >= youngs)
      throw InputError("subsection 'plastic kinematic': entry 'Tangent modulus' "
                       "must satisfy 0 <= E_t < E");
    l.plastic_modulus = youngs * Et / (youngs - Et);
    l.beta            = value("Hardening parameter beta");
    if (l.beta < 0 || l.beta > 1)
      throw InputError("subsection 'plastic kinematic': entry 'Hardening "
                       "parameter beta' must lie in [0, 1]");
    // Whether an entry has a value, from the scene or the preset.
    auto given = [&](const std::string &entry) {
      return !dealii::Utilities::trim(prm.get(entry)).empty() || preset != "none";
    };
    std::string rate = prm.get("Strain rate effects");
    if (rate == "true")
      rate = "Cowper-Symonds";
    else if (rate == "false")
      rate = "none";
    else if (rate == "auto")
      rate = given("Cowper-Symonds C") && given("Cowper-Symonds p") &&
                 value("Cowper-Symonds C") > 0 && value("Cowper-Symonds p") > 0 ?
               "Cowper-Symonds" :
               "none";
    if (rate == "Cowper-Symonds")
      l.set_cowper_symonds(positive("Cowper-Symonds C"), positive("Cowper-Symonds p"));
    else if (rate == "Malvar-Crawford")
      {
        try
          {
            l.set_malvar_crawford();
          }
        catch (const std::invalid_argument &e)
          {
            throw InputError("subsection 'plastic kinematic': entry 'Strain rate effects' = "
                             "'Malvar-Crawford': " + std::string(e.what()) +
                             " (the law is fitted to bars of 290-710 MPa)");
          }
      }
    const bool erode = prm.get_bool("Erosion");
    l.failure_strain = erode ? positive("Failure strain") : 0.;
    set(density, youngs, poisson, l, erode);
  }


  void PlasticKinematic::set(const double               density,
                             const double               youngs_modulus,
                             const double               poissons_ratio,
                             const PlasticKinematicLaw &l,
                             const bool                 erode)
  {
    Elastic::set(density, youngs_modulus, poissons_ratio);
    law     = l;
    erosion = erode && l.failure_strain > 0;
  }


  void PlasticKinematic::rotate_history(const double w01,
                                        const double w12,
                                        const double w02,
                                        const double dt,
                                        double      *history) const
  {
    Kinematics::rotate_stress(w01, w12, w02, dt, history);
  }


  // @sect3{The 3D radial return}
  //
  // Trial stress sigma* = sigma + (lambda tr(D) I + 2 mu D) dt; relative
  // deviator xi = dev(sigma*) - alpha; q = sqrt(3/2 xi:xi). Plastic flow
  // along n = xi / |xi| with the increment of PlasticKinematicLaw:
  //   sigma = sigma* - 2 mu sqrt(3/2) dep n,
  //   alpha += sqrt(2/3) (1 - beta) E_p dep n,
  // which puts the relative stress exactly on the updated yield surface
  // (linear hardening: the return is exact, no iteration).
  void PlasticKinematic::update_cauchy_stress(const double *D,
                                              const double  dt,
                                              double       *s,
                                              double       *h) const
  {
    add_elastic_trial(D, dt, s);


    const double p = (s[0] + s[1] + s[2]) / 3.;
    double       xi[6];
    for (unsigned int k = 0; k < 6; ++k)
      xi[k] = s[k] - (k < 3 ? p : 0.) - h[k];
    const double xx = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                      2. * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5]);
    const double q = std::sqrt(1.5 * xx);
    // As in the batch: the same return for the same inputs.
    double       R;
    const double dep = law.rate_effects ? law.rate_dependent_increment(q, h[6], dt, 3. * mu, R) :
                                          law.plastic_increment(q, h[6], 1., 3. * mu);
    if (law.rate_effects)
      h[8] = dt > 0 ? dep / dt : 0.;
    if (dep == 0.)
      return;
    const double norm = std::sqrt(xx);
    const double a    = 2. * mu * std::sqrt(1.5) * dep / norm;
    const double b    = std::sqrt(2. / 3.) * law.kinematic_modulus() * dep / norm;
    double       work = 0;
    for (unsigned int k = 0; k < 6; ++k)
      {
        s[k] -= a * xi[k];
        h[k] += b * xi[k];
        // Plastic work sigma : d eps_p with d eps_p = sqrt(3/2) dep n.
        work += (k < 3 ? 1. : 2.) * s[k] * std::sqrt(1.5) * dep * xi[k] / norm;
      }
    h[6] += dep;
    h[7] += work;
  }


  // @sect4{Cowper-Symonds across the lanes}
  //
  // cowper_symonds_increment() for the lanes of a batch at once, in vector
  // registers (xsimd: a Pack of R registers, R = 2 with AVX2, 1 with
  // AVX-512): the same start, the same Newton steps in y and the same
  // stopping rule per lane, y^(p-1) as exp((p-1) ln y). A lane's result
  // depends on its own values only (np = 2 gives np = 1's bits); against
  // the point-by-point update (the C library's pow) it agrees to round-off
  // (tests/unit/fast_path).
  namespace
  {
    template <unsigned int R>
    void cowper_symonds_lanes(const PlasticKinematicLaw &law,
                              const double               elastic_term,
                              const double               dt,
                              const double              *q_trial,
                              const double              *eps_p,
                              const double              *active_lanes,
                              double                    *increment)
    {
      using V = Simd::Pack<R>;
      using M = Simd::Mask<R>;
      using Simd::any, Simd::select;
      const double p = law.p, Cdt = law.C * dt, Hb = law.beta * law.plastic_modulus;
      const double K = elastic_term + (1. - law.beta) * law.plastic_modulus, zero = 0., one = 1.;
      const V      q = V::load(q_trial), yield = V::load(eps_p) * Hb + law.sigma_0;
      // The rate-free increment (plastic_increment() with R = 1).
      const V d0 = (q - yield) / (K + Hb);
      M       running = (V::load(active_lanes) != zero) && (d0 > zero);
      if (!any(running))
        {
          V(zero).store(increment);
          return;
        }
      const V d0_m  = Simd::max(d0, 1e-300);
      const V y_max = Simd::exp(Simd::log(d0_m / Cdt) * (1. / p));
      // (The start of cowper_symonds_increment(), its sums in its order.)
      V y = Simd::min(p > 1. ? (q - yield) / yield : (q - yield) / (yield + K * Cdt + Hb * Cdt), y_max);
      y       = select(running, y, zero);
      V d = zero;
      const V tolerance = d0_m * 1e-14;
      for (unsigned int it = 0; it < 60 && any(running); ++it)
        {
          // y^(p-1): 0 at y = 0 for p > 1, 1 for p = 1.
          const V y_p1 =
            select(y > zero, Simd::exp(Simd::log(Simd::max(y, 1e-300)) * (p - 1.)), p > 1. ? zero : one);
          const V dy    = y_p1 * Cdt;
          const V d_y   = dy * y;
          const V dd    = dy * p;
          const V sy    = yield + d_y * Hb;
          const V slope = -(dd * K) - sy - (y + one) * (dd * Hb);
          const V value = q - d_y * K - (y + one) * sy;
          const V step  = Simd::max(-y, -value / slope);
          const M done  = running && (Simd::abs(dd * step) <= tolerance);
          d             = select(done, d_y + dd * step, select(running, d_y, d));
          y             = select(running, y + step, y);
          running       = running && !done;
        }
      Simd::min(Simd::max(d, zero), select(d0 > zero, d0, zero)).store(increment);
    }
  } // namespace


  void PlasticKinematic::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                                    const double (&spin)[3][batch_size],
                                                    const double dt,
                                                    double (&s)[6][batch_size],
                                                    const BatchHistory &history) const
  {
    constexpr unsigned int W = batch_size;
    // The history (back stress, eps_p, plastic work, rate) into lanes.
    // (The whole history is hot: n_hot_history() is n_history().)
    alignas(64) double alpha[6][W], eps_p[W], work[W], rate[W];
    for (unsigned int k = 0; k < 6; ++k)
      history.load(k, alpha[k]);
    history.load(6, eps_p);
    history.load(7, work);
    history.load(8, rate);
    // The back stress rotates with the material, like the stress (it is
    // zero until the point first yields): rotated across the batch when a
    // point of it has yielded, kept in the lanes of those that have not
    // (a select, so that the loop vectorises).
    // (Lane flags as integers, OR-reduced: a loop of vector operations,
    // where a reduction of bools stays scalar.)
    alignas(64) std::uint64_t flag[W];
    std::uint64_t             any_yielded = 0;
    for (unsigned int l = 0; l < W; ++l)
      flag[l] = eps_p[l] > 0 ? 1 : 0;
    for (unsigned int l = 0; l < W; ++l)
      any_yielded |= flag[l];
    if (any_yielded != 0)
      for (unsigned int l = 0; l < W; ++l)
        {
          double a[6] = {alpha[0][l], alpha[1][l], alpha[2][l], alpha[3][l], alpha[4][l], alpha[5][l]};
          Kinematics::rotate_stress(spin[0][l], spin[1][l], spin[2][l], dt, a[0], a[1], a[2], a[3],
                                    a[4], a[5]);
          for (unsigned int k = 0; k < 6; ++k)
            alpha[k][l] = eps_p[l] > 0 ? a[k] : alpha[k][l];
        }
    for (unsigned int l = 0; l < W; ++l)
      add_elastic_trial(D, dt, s, l);
    const double Hk = law.kinematic_modulus();
    // The relative stress xi = dev(sigma) - alpha of the trial, and its
    // von Mises norm.
    alignas(64) double xi[6][W], norm[W];
    for (unsigned int l = 0; l < W; ++l)
      {
        const double p = (s[0][l] + s[1][l] + s[2][l]) / 3.;
        for (unsigned int k = 0; k < 6; ++k)
          xi[k][l] = s[k][l] - (k < 3 ? p : 0.) - alpha[k][l];
        norm[l] = std::sqrt(xi[0][l] * xi[0][l] + xi[1][l] * xi[1][l] + xi[2][l] * xi[2][l] +
                            2. * (xi[3][l] * xi[3][l] + xi[4][l] * xi[4][l] + xi[5][l] * xi[5][l]));
      }
    // A batch whose trial stresses are all within the static yield surface
    // keeps them (the return below would change nothing: dep = 0; R >= 1,
    // so a point within it is elastic at any rate, and the elastic range
    // pays no rate effects).
    std::uint64_t any_plastic = 0;
    for (unsigned int l = 0; l < W; ++l)
      flag[l] = std::sqrt(1.5) * norm[l] > law.yield_stress(eps_p[l], 1.) ? 1 : 0;
    for (unsigned int l = 0; l < W; ++l)
      any_plastic |= flag[l];
    if (law.rate_effects)
      for (unsigned int l = 0; l < W; ++l)
        rate[l] = 0.;
    if (any_plastic != 0)
      {
        // The radial return of every lane at once (dep = 0 leaves an
        // elastic lane's stress, back stress and work as they are), in
        // loops over the lanes that vectorise.
        // With rate effects the increment of each plastic lane comes from
        // the rate-dependent return (an iteration), the same function as
        // the single point's; rate-free, from the linear consistency
        // condition across the lanes.
        alignas(64) double a[W], b[W], c[W], increment[W];
        if (law.rate_effects && law.rate_law == PlasticKinematicLaw::RateLaw::cowper_symonds && law.p >= 1. &&
            dt > 0)
          {
            alignas(64) double q[W], active[W];
            for (unsigned int l = 0; l < W; ++l)
              {
                q[l]      = std::sqrt(1.5) * norm[l];
                active[l] = flag[l] != 0 ? 1. : 0.;
              }
            cowper_symonds_lanes<W / Simd::register_lanes>(law, 3. * mu, dt, q, eps_p, active, increment);
            for (unsigned int l = 0; l < W; ++l)
              rate[l] = increment[l] / dt;
          }
        else if (law.rate_effects)
          for (unsigned int l = 0; l < W; ++l)
            {
              double R;
              increment[l] =
                flag[l] != 0 ? law.rate_dependent_increment(std::sqrt(1.5) * norm[l], eps_p[l], dt, 3. * mu, R) : 0.;
              rate[l] = dt > 0 ? increment[l] / dt : 0.;
            }
        else
          for (unsigned int l = 0; l < W; ++l)
            {
              const double excess = std::sqrt(1.5) * norm[l] - law.yield_stress(eps_p[l], 1.);
              increment[l]        = excess > 0 ? excess / (3. * mu + Hk + law.beta * law.plastic_modulus) : 0.;
            }
        for (unsigned int l = 0; l < W; ++l)
          {
            const double dep = increment[l];
            const double inv = norm[l] > 0 ? 1. / norm[l] : 0.;
            a[l]             = 2. * mu * std::sqrt(1.5) * dep * inv;
            b[l]             = std::sqrt(2. / 3.) * Hk * dep * inv;
            c[l]             = std::sqrt(1.5) * dep * inv;
            eps_p[l] += dep;
          }
        for (unsigned int k = 0; k < 6; ++k)
          for (unsigned int l = 0; l < W; ++l)
            {
              s[k][l] -= a[l] * xi[k][l];
              alpha[k][l] += b[l] * xi[k][l];
            }
        // The plastic work sigma : d eps_p, d eps_p = sqrt(3/2) dep xi / |xi|.
        for (unsigned int l = 0; l < W; ++l)
          work[l] += c[l] * (s[0][l] * xi[0][l] + s[1][l] * xi[1][l] + s[2][l] * xi[2][l] +
                             2. * (s[3][l] * xi[3][l] + s[4][l] * xi[4][l] + s[5][l] * xi[5][l]));
      }
    // A batch whose points never yielded keeps its zeros: only the rate
    // is new, and only with rate effects. (A lane that never yielded in a
    // batch that did stores its zeros again.)
    if (any_yielded != 0 || any_plastic != 0)
      {
        for (unsigned int k = 0; k < 6; ++k)
          history.store(k, alpha[k]);
        history.store(6, eps_p);
        history.store(7, work);
      }
    if (law.rate_effects)
      history.store(8, rate);
  }


  // @sect3{The uniaxial form}
  //
  // History: back stress (axial), effective plastic strain, plastic work
  // density. The same law with E in place of 3G.
  double PlasticKinematic::update_uniaxial_stress(const double d_eps,
                                                  const double dt,
                                                  const double stress,
                                                  double      *h) const
  {
    const double E       = youngs_modulus();
    const double s_trial = stress + E * d_eps;
    const double xi      = s_trial - h[0];
    double       R;
    const double dep     = law.rate_dependent_increment(std::abs(xi), h[1], dt, E, R);
    if (dep == 0.)
      return s_trial;
    const double sign = xi > 0 ? 1. : -1.;
    const double s    = s_trial - E * dep * sign;
    h[0] += law.kinematic_modulus() * dep * sign;
    h[1] += dep;
    h[2] += s * dep * sign;
    return s;
  }


  ANVIL_REGISTER_MATERIAL_MODEL(
    PlasticKinematic,
    "plastic kinematic",
    "bilinear steel with mixed kinematic-isotropic hardening, "
    "Cowper-Symonds rate effects and failure (seed Eq. (63); LS-DYNA "
    "*MAT_PLASTIC_KINEMATIC).")
} // namespace anvil::MaterialModel
