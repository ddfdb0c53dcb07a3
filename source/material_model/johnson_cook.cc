/**
 * @file
 * Johnson-Cook plasticity, adiabatic heating and damage. See johnson_cook.h.
 */
#include <anvil/material_model/johnson_cook.h>
#include <anvil/utilities/bracketed_newton.h>
#include <anvil/utilities/input_error.h>

#include <xsimd/xsimd.hpp>

// GCC 12 reports the AVX-512 intrinsics behind xsimd's min, max and
// exp as maybe uninitialized (their undefined pass-through operand).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace anvil::MaterialModel
{
  // @sect3{The law}

  double JohnsonCookLaw::homologous_temperature(const double T) const
  {
    if (!thermal_softening() || T <= transition_temperature)
      return 0.;
    return std::min((T - transition_temperature) / (melting_temperature - transition_temperature), 1.);
  }


  double JohnsonCookLaw::thermal_factor(const double T) const
  {
    const double Ts = homologous_temperature(T);
    return Ts > 0 ? 1. - std::pow(Ts, m) : 1.;
  }


  double JohnsonCookLaw::flow_stress(const double eps_p,
                                     const double rate,
                                     const double T,
                                     double      *slope_eps,
                                     double      *slope_rate) const
  {
    return flow_stress_at(eps_p, rate, thermal_factor(T), slope_eps, slope_rate);
  }


  double JohnsonCookLaw::flow_stress_at(const double eps_p,
                                        const double rate,
                                        const double thermal,
                                        double      *slope_eps,
                                        double      *slope_rate) const
  {
    const double eps_n   = eps_p > 0 ? std::pow(eps_p, n) : 0.;
    const double harden  = A + B * eps_n;
    const double ratio   = rate / reference_rate;
    const double rate_f  = ratio > 1. ? 1. + C * std::log(ratio) : 1.;
    if (slope_eps != nullptr)
      // d(B eps^n)/d eps = n B eps^n / eps; at eps = 0 (n < 1) infinite: a
      // large finite slope keeps Newton's step inside the bracket.
      *slope_eps = (eps_p > 0 ? n * B * eps_n / eps_p : (n < 1. ? 1e30 : n == 1. ? B : 0.)) * rate_f * thermal;
    if (slope_rate != nullptr)
      *slope_rate = ratio > 1. ? harden * C / rate * thermal : 0.;
    return harden * rate_f * thermal;
  }


  double JohnsonCookLaw::plastic_increment(const double q_trial,
                                           const double eps_p,
                                           const double T,
                                           const double dt,
                                           const double three_G,
                                           const double guess) const
  {
    // The temperature is that of the start of the step: its factor once.
    const double thermal = thermal_factor(T);
    if (!(q_trial > flow_stress_at(eps_p, 0., thermal)))
      return 0.;
    // g(d) = q_trial - 3G d - sigma_y(eps_p + d, d / dt, T) falls
    // monotonically in d: g(0) > 0, g(q_trial / 3G) <= 0.
    const double scale = q_trial / three_G;
    auto         g     = [&](const double d, double &slope) {
      double       se, sr;
      const double s = flow_stress_at(eps_p + d, dt > 0 ? d / dt : 0., thermal, &se, &sr);
      slope          = -three_G - se - (dt > 0 ? sr / dt : 0.);
      return q_trial - three_G * d - s;
    };
    // The first guess: the rate-free return with the current slope.
    double       se, sr;
    const double s0 = flow_stress_at(eps_p, 0., thermal, &se, &sr);
    // The first guess: the increment of the step before at its plastic
    // rate where there is one (steady flow changes it little from step to
    // step), else the linearised return at the step's start.
    const double d0 = guess > 0 && guess < scale ?
                        guess :
                        std::min((q_trial - s0) / (three_G + std::min(se, 1e3 * three_G)), scale);
    return bracketed_newton(g, 0., scale, d0, 1e-14 * scale);
  }


  double JohnsonCookLaw::failure_strain(const double triaxiality, const double rate, const double T) const
  {
    const double ratio = rate / reference_rate;
    return (D[0] + D[1] * std::exp(D[2] * triaxiality)) * (1. + D[3] * std::log(std::max(ratio, 1.))) *
           (1. + D[4] * homologous_temperature(T));
  }


  // @sect3{Parameters}

  void JohnsonCook::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Density", "0", Patterns::Double(0.), "Reference mass density (required). Units: kg/m^3.");
    prm.declare_entry("Young's modulus", "0", Patterns::Double(0.), "Young's modulus E (required). Units: Pa.");
    prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(-1., 0.5), "Poisson's ratio nu. Units: none.");
    prm.declare_entry("A", "0", Patterns::Double(0.), "Yield stress A at the reference rate and the transition "
                      "temperature (required). Units: Pa.");
    prm.declare_entry("B", "0", Patterns::Double(0.), "Hardening modulus B. Units: Pa.");
    prm.declare_entry("n", "1", Patterns::Double(0.), "Hardening exponent n. Units: none.");
    prm.declare_entry("C", "0", Patterns::Double(0.),
                      "Strain-rate coefficient C of 1 + C ln(eps_p_dot / eps_0_dot) (1 below the reference "
                      "rate); 0: no rate effects. Units: none.");
    prm.declare_entry("Reference strain rate", "1", Patterns::Double(0.),
                      "eps_0_dot of the rate term and of the damage's. Units: 1/s.");
    prm.declare_entry("m", "1", Patterns::Double(0.), "Thermal softening exponent m of 1 - T*^m. Units: none.");
    prm.declare_entry("Melting temperature", "0", Patterns::Double(),
                      "T_m; at or below 'Transition temperature' (the default 0): no thermal softening. "
                      "Temperatures in any one unit (K or degrees C), the same for all four entries. "
                      "Units: K.");
    prm.declare_entry("Transition temperature", "293.15", Patterns::Double(),
                      "T_t (ABAQUS's theta_transition, LS-DYNA's TR): no softening below it. Units: K.");
    prm.declare_entry("Initial temperature", "293.15", Patterns::Double(),
                      "Temperature of every point at the start. Units: K.");
    prm.declare_entry("Specific heat", "0", Patterns::Double(0.),
                      "c_p of the adiabatic heating; 0: isothermal (the temperature stays the initial one). "
                      "Units: J/(kg K).");
    prm.declare_entry("Inelastic heat fraction", "0.9", Patterns::Double(0., 1.),
                      "chi, the fraction of the plastic work that heats the point (Taylor-Quinney; "
                      "ABAQUS's default 0.9). Units: none.");
    for (unsigned int i = 1; i <= 5; ++i)
      prm.declare_entry("D" + std::to_string(i), "0", Patterns::Double(),
                        "Johnson-Cook damage constant D" + std::to_string(i) +
                          " of eps_f = (D1 + D2 exp(D3 sigma*)) (1 + D4 ln max(eps_p_dot*, 1)) (1 + D5 T*); "
                          "D1 = D2 = 0: no damage. Units: none.");
    prm.declare_entry("Erosion", "false", Patterns::Bool(),
                      "Erode an element when the Johnson-Cook damage of its points reaches 1: it stops "
                      "carrying force and leaves contact, and its energy moves to the 'eroded' column of "
                      "energy.csv. Needs D1 or D2.");
  }


  void JohnsonCook::parse_parameters(dealii::ParameterHandler &prm)
  {
    const std::string where = "subsection 'johnson cook': ";
    auto positive = [&](const std::string &entry) {
      const double v = prm.get_double(entry);
      if (!(v > 0))
        throw InputError(where + "entry '" + entry + "' = " + prm.get(entry) + " must be positive");
      return v;
    };
    JohnsonCookLaw l;
    const double   density = positive("Density");
    const double   youngs  = positive("Young's modulus");
    const double   poisson = prm.get_double("Poisson's ratio");
    l.A                    = positive("A");
    l.B                    = prm.get_double("B");
    l.n                    = positive("n");
    l.C                    = prm.get_double("C");
    l.reference_rate       = positive("Reference strain rate");
    l.m                    = prm.get_double("m");
    l.melting_temperature  = prm.get_double("Melting temperature");
    l.transition_temperature = prm.get_double("Transition temperature");
    l.density              = density;
    l.specific_heat        = prm.get_double("Specific heat");
    l.heat_fraction        = prm.get_double("Inelastic heat fraction");
    for (unsigned int i = 0; i < 5; ++i)
      l.D[i] = prm.get_double("D" + std::to_string(i + 1));
    const bool erode = prm.get_bool("Erosion");
    if (erode && !l.damage())
      throw InputError(where + "'Erosion = true' needs the damage constants (D1 or D2 not 0)");
    if (l.melting_temperature > 0 && !l.thermal_softening())
      throw InputError(where + "entry 'Melting temperature' = " + prm.get("Melting temperature") +
                       " must lie above 'Transition temperature' = " + prm.get("Transition temperature") +
                       " (or be 0: no thermal softening)");
    set(density, youngs, poisson, l, prm.get_double("Initial temperature"), erode);
  }


  void JohnsonCook::set(const double          density,
                        const double          youngs_modulus,
                        const double          poissons_ratio,
                        const JohnsonCookLaw &l,
                        const double          T0,
                        const bool            erode)
  {
    Elastic::set(density, youngs_modulus, poissons_ratio);
    law                 = l;
    law.density         = density;
    initial_temperature = T0;
    erosion             = erode && l.damage();
  }


  std::string JohnsonCook::rate_law() const
  {
    if (!rate_dependent())
      return "";
    std::ostringstream s;
    s << "Johnson-Cook (C = " << law.C << ", reference rate " << law.reference_rate << " 1/s)";
    return s.str();
  }


  void JohnsonCook::initialize_history(double *history, const PointData &) const
  {
    history[2] = initial_temperature;
    history[5] = law.flow_stress(0., 0., initial_temperature);
  }


  // @sect3{The update}
  //
  // The return of one point beyond its yield stress: s holds the trial
  // stress. Radial return of the deviator by 3G dep / q; then the plastic
  // work, the temperature (explicit: the flow stress of the step used the
  // temperature at its start, as LS-DYNA and ABAQUS/Explicit's adiabatic
  // analysis do) and the damage at the triaxiality of the returned stress.
  void JohnsonCook::plastic_update(const double dt, double *s, double *h, const double previous_rate) const
  {
    const double p = (s[0] + s[1] + s[2]) / 3.;
    double       xi[6];
    for (unsigned int k = 0; k < 6; ++k)
      xi[k] = s[k] - (k < 3 ? p : 0.);
    const double q   = std::sqrt(1.5 * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                                      2. * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5])));
    const double dep = law.plastic_increment(q, h[0], h[2], dt, 3. * mu, previous_rate * dt);
    if (dep == 0.)
      return;
    const double q_new  = q - 3. * mu * dep;
    const double factor = q_new / q;
    for (unsigned int k = 0; k < 6; ++k)
      s[k] = factor * xi[k] + (k < 3 ? p : 0.);
    const double rate = dt > 0 ? dep / dt : 0.;
    h[0] += dep;
    h[1] += q_new * dep;
    h[4] = rate;
    if (law.damage())
      {
        const double eps_f = law.failure_strain(q_new > 0 ? p / q_new : 0., rate, h[2]);
        h[3] += eps_f > 0 ? dep / eps_f : 1.;
      }
    if (law.heating())
      h[2] += law.heat_fraction * q_new * dep / (law.density * law.specific_heat);
    h[5] = law.flow_stress(h[0], 0., h[2]);
  }


  void JohnsonCook::update_cauchy_stress(const double *D, const double dt, double *s, double *h) const
  {
    add_elastic_trial(D, dt, s);
    const double previous_rate = h[4];
    h[4]                       = 0.;
    const double p   = (s[0] + s[1] + s[2]) / 3.;
    const double dev = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p) +
                       2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    if (1.5 * dev > h[5] * h[5])
      plastic_update(dt, s, h, previous_rate);
  }


  void JohnsonCook::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                               const double (&)[3][batch_size],
                                               const double dt,
                                               double (&s)[6][batch_size],
                                               const BatchHistory &history) const
  {
    constexpr unsigned int W = batch_size;
    // The elastic trial and the yield check across the lanes (the stress
    // arrives rotated; no tensorial history).
    alignas(64) double     yield[W], rate[W];
    alignas(64) std::uint64_t flag[W];
    history.load(5, yield);
    std::uint64_t any_plastic = 0;
    for (unsigned int l = 0; l < W; ++l)
      {
        add_elastic_trial(D, dt, s, l);
        const double p   = (s[0][l] + s[1][l] + s[2][l]) / 3.;
        const double dev = (s[0][l] - p) * (s[0][l] - p) + (s[1][l] - p) * (s[1][l] - p) +
                           (s[2][l] - p) * (s[2][l] - p) +
                           2. * (s[3][l] * s[3][l] + s[4][l] * s[4][l] + s[5][l] * s[5][l]);
        flag[l] = 1.5 * dev > yield[l] * yield[l] ? 1 : 0;
      }
    for (unsigned int l = 0; l < W; ++l)
      any_plastic |= flag[l];
    // The rate of the step: 0 where a point stays elastic.
    history.load(4, rate);
    std::uint64_t any_rate = 0;
    for (unsigned int l = 0; l < W; ++l)
      any_rate |= rate[l] != 0. ? 1 : 0;
    if (any_rate != 0)
      {
        alignas(64) double zero[W] = {};
        history.store(4, zero);
      }
    if (any_plastic == 0)
      return;
    plastic_update_batch(dt, flag, rate, s, history);
  }


  // @sect4{The return across the lanes}
  //
  // The same return as plastic_update(), lane by lane in vector registers
  // (xsimd: 8 lanes a register with AVX-512, 4 with AVX2): Newton's method
  // in the bracket [0, q / 3G] for every lane at once, each lane stopping
  // where the scalar iteration stops; the powers and logarithms are
  // xsimd's, which agree with the C library's to an ulp or two, so the
  // batched and the point-by-point update agree to round-off
  // (tests/unit/fast_path.cc).
  void JohnsonCook::plastic_update_batch(const double dt,
                                         const std::uint64_t (&flag)[batch_size],
                                         const double (&previous_rate)[batch_size],
                                         double (&s)[6][batch_size],
                                         const BatchHistory &history) const
  {
    using V                = xsimd::batch<double>;
    using M                = xsimd::batch_bool<double>;
    constexpr unsigned int n = V::size;
    static_assert(batch_size % n == 0, "a batch is a whole number of vector registers");

    alignas(64) double h[6][batch_size];
    for (unsigned int k = 0; k < 6; ++k)
      history.load(k, h[k]);

    const V    three_G(3. * mu), A(law.A), B(law.B), n_exp(law.n), one(1.), zero(0.);
    const bool thermal_on = law.thermal_softening();
    const V    T_t(law.transition_temperature),
      T_span(thermal_on ? law.melting_temperature - law.transition_temperature : 1.), m_exp(law.m);
    const double slope_at_zero =
      law.n < 1. ? 1e30 : (law.n == 1. ? law.B : 0.); // d(B eps^n)/d eps at eps = 0
    const V inv_dt(dt > 0 ? 1. / dt : 0.), inv_ref(1. / law.reference_rate), C(law.C);

    // T* and the thermal factor 1 - T*^m.
    auto homologous = [&](const V &T) {
      return thermal_on ? xsimd::min(xsimd::max((T - T_t) / T_span, zero), one) : zero;
    };
    auto thermal_factor = [&](const V &Ts) {
      return xsimd::select(Ts > zero, one - xsimd::exp(m_exp * xsimd::log(xsimd::max(Ts, V(1e-300)))), one);
    };
    // eps^n (0 at eps = 0).
    auto power = [&](const V &eps) {
      return xsimd::select(eps > zero, xsimd::exp(n_exp * xsimd::log(xsimd::max(eps, V(1e-300)))), zero);
    };

    for (unsigned int c = 0; c < batch_size; c += n)
      {
        alignas(64) double active_mask[n];
        bool               any = false;
        for (unsigned int l = 0; l < n; ++l)
          {
            active_mask[l] = flag[c + l] != 0 ? 1. : 0.;
            any            = any || flag[c + l] != 0;
          }
        if (!any)
          continue;
        M active = V::load_aligned(active_mask) != zero;

        V sv[6];
        for (unsigned int k = 0; k < 6; ++k)
          sv[k] = V::load_unaligned(&s[k][c]);
        const V p = (sv[0] + sv[1] + sv[2]) / V(3.);
        V       xi[6];
        for (unsigned int k = 0; k < 6; ++k)
          xi[k] = k < 3 ? sv[k] - p : sv[k];
        const V q = xsimd::sqrt(V(1.5) * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                                          V(2.) * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5])));

        const V eps0    = V::load_aligned(&h[0][c]);
        const V T0      = V::load_aligned(&h[2][c]);
        const V Ts0     = homologous(T0);
        const V thermal = thermal_factor(Ts0);
        const V e0n     = power(eps0);
        const V s0      = (A + B * e0n) * thermal;
        active          = active && (q > s0);
        if (!xsimd::any(active))
          continue;

        // Newton's method in the bracket, as bracketed_newton() per lane.
        const V scale = q / three_G;
        const V tol   = V(1e-14) * scale;
        const V se0 =
          xsimd::select(eps0 > zero, n_exp * B * e0n / xsimd::max(eps0, V(1e-300)), V(slope_at_zero)) * thermal;
        const V guess = V::load_unaligned(&previous_rate[c]) * V(dt);
        V       d     = xsimd::select((guess > zero) && (guess < scale), guess,
                                xsimd::min((q - s0) / (three_G + xsimd::min(se0, V(1e3) * three_G)), scale));
        V lo = zero, hi = scale;
        M running = active;
        for (unsigned int it = 0; it < 100 && xsimd::any(running); ++it)
          {
            const V x      = eps0 + d;
            const V xn     = power(x);
            const V harden = A + B * xn;
            const V rate   = d * inv_dt;
            const V ratio  = rate * inv_ref;
            const M fast   = ratio > one;
            const V rate_f = xsimd::select(fast, one + C * xsimd::log(xsimd::max(ratio, V(1e-300))), one);
            const V se =
              xsimd::select(x > zero, n_exp * B * xn / xsimd::max(x, V(1e-300)), V(slope_at_zero)) * rate_f * thermal;
            const V sr    = xsimd::select(fast, harden * C / xsimd::max(rate, V(1e-300)) * thermal, zero);
            const V g     = q - three_G * d - harden * rate_f * thermal;
            const V slope = -three_G - se - sr * inv_dt;
            const M above = g > zero;
            lo            = xsimd::select(running && above, d, lo);
            hi            = xsimd::select(running && !above, d, hi);
            V next        = d - g / slope;
            next          = xsimd::select((next > lo) && (next < hi), next, V(0.5) * (lo + hi));
            const M done  = (xsimd::abs(next - d) <= tol) || (hi - lo <= tol);
            d             = xsimd::select(running, next, d);
            running       = running && !done;
          }
        const V dep = xsimd::select(active, d, zero);
        active      = active && (dep != zero);

        const V q_new  = q - three_G * dep;
        const V factor = q_new / q;
        for (unsigned int k = 0; k < 6; ++k)
          xsimd::select(active, factor * xi[k] + (k < 3 ? p : zero), sv[k]).store_unaligned(&s[k][c]);
        const V rate   = dep * inv_dt;
        const V eps1   = eps0 + dep;
        V       T1     = T0;
        xsimd::select(active, eps1, eps0).store_aligned(&h[0][c]);
        xsimd::select(active, V::load_aligned(&h[1][c]) + q_new * dep, V::load_aligned(&h[1][c]))
          .store_aligned(&h[1][c]);
        xsimd::select(active, rate, V::load_aligned(&h[4][c])).store_aligned(&h[4][c]);
        if (law.damage())
          {
            const V triax = xsimd::select(q_new > zero, p / xsimd::max(q_new, V(1e-300)), zero);
            const V ratio = xsimd::max(rate * inv_ref, one);
            const V eps_f = (V(law.D[0]) + V(law.D[1]) * xsimd::exp(V(law.D[2]) * triax)) *
                            (one + V(law.D[3]) * xsimd::log(ratio)) * (one + V(law.D[4]) * Ts0);
            const V d_old = V::load_aligned(&h[3][c]);
            xsimd::select(active, d_old + xsimd::select(eps_f > zero, dep / eps_f, one), d_old)
              .store_aligned(&h[3][c]);
          }
        if (law.heating())
          T1 = xsimd::select(active,
                             T0 + V(law.heat_fraction) * q_new * dep / V(law.density * law.specific_heat), T0);
        T1.store_aligned(&h[2][c]);
        const V flow = (A + B * power(eps1)) * thermal_factor(homologous(T1));
        xsimd::select(active, flow, V::load_aligned(&h[5][c])).store_aligned(&h[5][c]);
      }
    for (unsigned int k = 0; k < 6; ++k)
      history.store(k, h[k]);
  }


  ANVIL_REGISTER_MATERIAL_MODEL(JohnsonCook,
                                "johnson cook",
                                "Johnson-Cook metal: power-law hardening, logarithmic rate term, thermal softening "
                                "with adiabatic heating, Johnson-Cook damage and erosion (LS-DYNA "
                                "*MAT_JOHNSON_COOK, ABAQUS *Plastic, hardening=JOHNSON COOK).")
} // namespace anvil::MaterialModel
