/**
 * @file
 * Johnson-Cook plasticity, adiabatic heating and damage. See johnson_cook.h.
 */
#include <anvil/material_model/johnson_cook.h>
#include <anvil/utilities/input_error.h>

// GCC 12 reports the AVX-512 intrinsics behind xsimd's min, max, exp and
// sqrt as (maybe) uninitialized (their undefined pass-through operand).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <anvil/utilities/simd_pack.h>

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


  double JohnsonCookLaw::flow_stress(const double eps_p, const double rate, const double T) const
  {
    return flow_stress_at(eps_p, rate, thermal_factor(T));
  }


  double JohnsonCookLaw::flow_stress_at(const double eps_p, const double rate, const double thermal) const
  {
    const double ratio = rate / reference_rate;
    return (A + B * (eps_p > 0 ? std::pow(eps_p, n) : 0.)) * (ratio > 1. ? 1. + C * std::log(ratio) : 1.) * thermal;
  }


  double JohnsonCookLaw::plastic_increment(const double q_trial,
                                           const double eps_p,
                                           const double thermal,
                                           const double dt,
                                           const double three_G,
                                           const double guess) const
  {
    // The temperature is that of the start of the step: its factor given.
    const double eps_n = eps_p > 0 ? std::pow(eps_p, n) : 0.;
    if (!(q_trial > (A + B * eps_n) * thermal))
      return 0.;
    // g(d) = q_trial - 3G d - (A + B x^n) R(d / dt) theta, x = eps_p + d,
    // falls monotonically in d: g(0) > 0, g(q_trial / 3G) <= 0.
    const double scale     = q_trial / three_G;
    const double tolerance = return_tolerance * scale;
    const double inv_dt    = dt > 0 ? 1. / dt : 0.;
    const double slope_at_zero = n < 1. ? 1e30 : (n == 1. ? B : 0.);
    // The first guess: the increment of the step before at its plastic
    // rate where there is one (steady flow changes it little from step to
    // step); else the root of the hardening alone, (A + B x^n) theta =
    // q_trial, which lies at or beyond the root (the rate term and the
    // elastic unloading only lower it) and is the root itself where the
    // point first yields at a small increment; else the linearised return.
    const double se = (eps_p > 0 ? n * B * eps_n / eps_p : slope_at_zero) * thermal;
    double       d  = std::min((q_trial - (A + B * eps_n) * thermal) / (three_G + std::min(se, 1e3 * three_G)), scale);
    if (guess > 0 && guess < scale)
      d = guess;
    else if (B > 0 && thermal > 0 && q_trial / thermal > A)
      {
        const double d_h = std::pow((q_trial / thermal - A) / B, 1. / n) - eps_p;
        if (d_h > 0)
          d = std::min(d_h, scale);
      }
    // Newton's method inside the bracket [0, q_trial / 3G], bisection where
    // a step leaves it. A Newton step from d leaves an error of about
    // |g'' / 2 g'| step^2: the iteration stops when that is below the
    // tolerance (and the step does not cross the rate term's kink), so
    // that the last evaluation is not spent confirming a converged step.
    double lo = 0., hi = scale;
    for (unsigned int it = 0; it < newton_steps(); ++it)
      {
        const double x     = eps_p + d;
        const double xn    = x > 0 ? std::pow(x, n) : 0.;
        const double H     = A + B * xn;
        const double H1    = x > 0 ? n * B * xn / x : slope_at_zero;
        const double H2    = x > 0 ? (n - 1.) * H1 / x : 0.;
        const double ratio = d * inv_dt / reference_rate;
        const bool   fast  = ratio > 1.;
        const double R     = fast ? 1. + C * std::log(ratio) : 1.;
        const double R1    = fast ? C / d : 0.;
        const double R2    = fast ? -C / (d * d) : 0.;
        const double g     = q_trial - three_G * d - thermal * H * R;
        if (g == 0.)
          break;
        const double g1    = -three_G - thermal * (H1 * R + H * R1);
        const double g2    = -thermal * (H2 * R + 2. * H1 * R1 + H * R2);
        (g > 0 ? lo : hi)  = d;
        const double step   = -g / g1;
        const bool   inside = d + step > lo && d + step < hi;
        // A step within the tolerance ends the iteration even where
        // round-off puts it on the bracket's end.
        const bool newton_done = std::abs(step) <= tolerance ||
                                 (inside && std::abs(g2) * step * step <= 2. * tolerance * std::abs(g1) &&
                                  ((d + step) * inv_dt / reference_rate > 1.) == fast);
        if (newton_done)
          return d + step;
        if (inside)
          d += step;
        else
          {
            d = 0.5 * (lo + hi);
            if (hi - lo <= tolerance)
              break;
          }
      }
    return d;
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
    prm.declare_entry("Rate form", "plastic", Patterns::Selection("plastic|total"),
                      "Which strain rate the rate term and the damage's take: 'plastic', the effective plastic "
                      "strain rate, solved with the return (ABAQUS; LS-DYNA's VP = 1); 'total', the effective "
                      "total strain rate of the step, sqrt(2/3 D':D'), which scales the yield stress before the "
                      "return (LS-DYNA's default VP = 0). Units: none.");
    prm.declare_entry("Return iterations", "0", Patterns::Integer(0, 100),
                      "Newton steps the radial return may take: 0, until the plastic increment is found to "
                      "1e-12 of its bound q_trial / 3G (the default); N > 0, at most N, as the explicit codes' "
                      "returns with a fixed number of iterations (1: the return linearised about its first "
                      "guess), with 'Rate form = total' only. A capped return leaves the stress off the yield "
                      "surface by what its last step left, and the next step takes it back; doc/theory.md "
                      "measures the error and doc/performance.md the time. Units: none.");
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
    l.total_rate           = prm.get("Rate form") == "total";
    l.max_iterations       = prm.get_integer("Return iterations");
    l.m                    = prm.get_double("m");
    l.melting_temperature  = prm.get_double("Melting temperature");
    l.transition_temperature = prm.get_double("Transition temperature");
    l.density              = density;
    l.specific_heat        = prm.get_double("Specific heat");
    l.heat_fraction        = prm.get_double("Inelastic heat fraction");
    for (unsigned int i = 0; i < 5; ++i)
      l.D[i] = prm.get_double("D" + std::to_string(i + 1));
    if (l.max_iterations > 0 && !l.total_rate)
      throw InputError(where + "entry 'Return iterations' = " + prm.get("Return iterations") +
                       " needs 'Rate form = total' (0 allowed with 'plastic'): with the plastic strain rate "
                       "the rate term is solved with the return, and a fixed number of Newton steps leaves it "
                       "far from its root (doc/theory.md)");
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
    s << "Johnson-Cook (C = " << law.C << ", reference rate " << law.reference_rate << " 1/s, of the "
      << (law.total_rate ? "total" : "plastic") << " strain rate)";
    return s.str();
  }


  void JohnsonCook::initialize_history(double *history, const PointData &) const
  {
    history[2] = initial_temperature;
    history[6] = law.thermal_factor(initial_temperature);
    history[5] = law.flow_stress_at(0., 0., history[6]);
  }


  // @sect3{The update}
  //
  // The return of one point beyond its yield stress: s holds the trial
  // stress. Radial return of the deviator by 3G dep / q; then the plastic
  // work, the temperature (explicit: the flow stress of the step used the
  // temperature at its start, as LS-DYNA and ABAQUS/Explicit's adiabatic
  // analysis do) and the damage at the triaxiality of the returned stress.
  void JohnsonCook::plastic_update(const double dt,
                                   double      *s,
                                   double      *h,
                                   const double previous_rate,
                                   const double total_rate) const
  {
    const double p = (s[0] + s[1] + s[2]) / 3.;
    double       xi[6];
    for (unsigned int k = 0; k < 6; ++k)
      xi[k] = s[k] - (k < 3 ? p : 0.);
    const double q   = std::sqrt(1.5 * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                                      2. * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5])));
    // (The total strain rate's factor scales the yield stress; the return
    // then has no rate term of its own: dt = 0 to it.)
    const double dep = law.total_rate ?
                         law.plastic_increment(q, h[0], h[6] * law.rate_factor(total_rate), 0., 3. * mu,
                                               previous_rate * dt) :
                         law.plastic_increment(q, h[0], h[6], dt, 3. * mu, previous_rate * dt);
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
        const double eps_f = law.failure_strain(q_new > 0 ? p / q_new : 0., law.total_rate ? total_rate : rate, h[2]);
        h[3] += eps_f > 0 ? dep / eps_f : 1.;
      }
    if (law.heating())
      {
        h[2] += law.heat_fraction * q_new * dep / (law.density * law.specific_heat);
        h[6] = law.thermal_factor(h[2]);
      }
    h[5] = law.flow_stress_at(h[0], 0., h[6]);
  }


  namespace
  {
    /** The effective total strain rate sqrt(2/3 D':D'). */
    inline double effective_rate(const double D0, const double D1, const double D2, const double D3,
                                 const double D4, const double D5)
    {
      const double m = (D0 + D1 + D2) / 3.;
      return std::sqrt(2. / 3. * ((D0 - m) * (D0 - m) + (D1 - m) * (D1 - m) + (D2 - m) * (D2 - m) +
                                  2. * (D3 * D3 + D4 * D4 + D5 * D5)));
    }
  } // namespace


  void JohnsonCook::update_cauchy_stress(const double *D, const double dt, double *s, double *h) const
  {
    add_elastic_trial(D, dt, s);
    const double previous_rate = h[4];
    h[4]                       = 0.;
    const double p   = (s[0] + s[1] + s[2]) / 3.;
    const double dev = (s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) + (s[2] - p) * (s[2] - p) +
                       2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    if (1.5 * dev > h[5] * h[5])
      plastic_update(dt, s, h, previous_rate,
                     law.total_rate ? effective_rate(D[0], D[1], D[2], D[3], D[4], D[5]) : 0.);
  }


  bool JohnsonCook::elastic_trial_batch(const double (&D)[6][batch_size],
                                        const double dt,
                                        double (&s)[6][batch_size],
                                        const BatchHistory &history,
                                        std::uint64_t (&flag)[batch_size],
                                        double (&rate)[batch_size],
                                        double (&total)[batch_size]) const
  {
    constexpr unsigned int W = batch_size;
    // The elastic trial and the yield check across the lanes (the stress
    // arrives rotated; no tensorial history).
    alignas(64) double yield[W];
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
      return false;
    for (unsigned int l = 0; l < W; ++l)
      total[l] = law.total_rate ? effective_rate(D[0][l], D[1][l], D[2][l], D[3][l], D[4][l], D[5][l]) : 0.;
    return true;
  }


  void JohnsonCook::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                               const double (&)[3][batch_size],
                                               const double dt,
                                               double (&s)[6][batch_size],
                                               const BatchHistory &history) const
  {
    alignas(64) double        rate[batch_size], total[batch_size];
    alignas(64) std::uint64_t flag[batch_size];
    if (elastic_trial_batch(D, dt, s, history, flag, rate, total))
      plastic_update_batch(dt, flag, rate, total, s, history);
  }


  // @sect4{The return across the lanes}
  //
  // The same return as plastic_update(), lane by lane in vector registers
  // (xsimd: 8 lanes a register with AVX-512, 4 with AVX2): the same first
  // guesses and Newton's method in the bracket [0, q / 3G] for every lane
  // at once, each lane stopping where the scalar iteration stops; the
  // powers and logarithms are xsimd's, which agree with the C library's to
  // an ulp or two, so the batched and the point-by-point update agree to
  // round-off (tests/unit/fast_path.cc). The state's hardening B eps_p^n
  // comes from the stored flow stress and thermal factor, so that a
  // yielding point evaluates the transcendental functions of its Newton
  // steps and of its new state only.
  //
  // The return is a chain of dependent operations (exp, log, divisions),
  // bound by their latency, not by the arithmetic: its lanes are a Pack of
  // R registers (anvil/utilities/simd_pack.h) that go through the chain
  // side by side (R = 2 with AVX2, 1 with AVX-512). A lane's result
  // depends on its own values only.
  namespace
  {
    // (one_step: 'Return iterations = 1', the iteration's bound a constant,
    // so that the compiler drops the stopping rule's work and the
    // re-anchoring a single step does not need.)
    template <unsigned int R, bool one_step>
    void plastic_return(const JohnsonCookLaw &law,
                        const double          mu,
                        const double          dt,
                        const double         *active_lanes,
                        const double         *previous_rate,
                        const double         *total_rate,
                        double               *s,
                        double               *h,
                        JohnsonCook::ReturnCounts &counts)
    {
      using V                  = Simd::Pack<R>;
      using M                  = Simd::Mask<R>;
      constexpr unsigned int L = V::lanes;
      using Simd::any, Simd::all, Simd::select;

      // (Constants are numbers, broadcast where they are used.)
      const double three_G = 3. * mu, A = law.A, B = law.B, n_exp = law.n, one = 1., zero = 0., tiny = 1e-300;
      const bool thermal_on = law.thermal_softening();
      const double T_t = law.transition_temperature, m_exp = law.m;
      const double slope_at_zero =
        law.n < 1. ? 1e30 : (law.n == 1. ? law.B : 0.); // d(B eps^n)/d eps at eps = 0
      // (With the total strain rate's factor, the return has no rate term of
      // its own: inv_rate = 0.)
      // (Divisions by constants as products, and 1/theta with 1/eps_0,
      // 1/x with 1/d from one division each: fewer of the slowest
      // operation; doc/performance.md measures it.)
      const double inv_3G = 1. / (3. * mu), inv_B = law.B > 0 ? 1. / law.B : 0.,
                   inv_span = thermal_on ? 1. / (law.melting_temperature - law.transition_temperature) : 1.,
                   heat     = law.heating() ? law.heat_fraction / (law.density * law.specific_heat) : 0.,
                   floor    = 1e-150;
      const double inv_dt = dt > 0 ? 1. / dt : 0.,
                   inv_rate = dt > 0 && !law.total_rate ? 1. / (dt * law.reference_rate) : 0., C = law.C,
                   inv_n = 1. / law.n;

      // T* and the thermal factor 1 - T*^m.
      auto homologous = [&](const V &T) {
        return thermal_on ? Simd::min(Simd::max((T - T_t) * inv_span, zero), one) : zero;
      };
      auto thermal_factor = [&](const V &Ts) {
        return select(Ts > zero, one - Simd::exp(m_exp * Simd::log(Simd::max(Ts, tiny))), one);
      };
      // eps^n (0 at eps = 0).
      auto power = [&](const V &eps, const double exponent) {
        return select(eps > zero, Simd::exp(exponent * Simd::log(Simd::max(eps, tiny))), zero);
      };
      // (1 + u)^n and ln(1 + u) for |u| <= series_reach: their series to
      // u^11, the first term left off below 1e-18 of the value.
      constexpr unsigned int series_terms = 11;
      constexpr double       series_reach = 0.03;
      double                 binomial[series_terms], binomial_m[series_terms];
      for (unsigned int k = 0; k < series_terms; ++k)
        {
          binomial[k]   = (law.n - k) / (k + 1.);
          binomial_m[k] = (law.m - k) / (k + 1.);
        }
      auto power_series = [&](const V &u, const double (&c)[series_terms]) {
        V r = one;
        for (unsigned int k = series_terms; k-- > 0;)
          r = one + c[k] * u * r;
        return r;
      };
      auto log1p_series = [&](const V &u) {
        V r(1. / series_terms);
        for (unsigned int k = series_terms - 1; k > 0; --k)
          r = 1. / k - u * r;
        return u * r;
      };
      const auto row = [&](double *a, const unsigned int k) { return a + std::size_t(k) * L; };

      M active = V::load(active_lanes) != zero;
      V sv[6];
      for (unsigned int k = 0; k < 6; ++k)
        sv[k] = V::load(row(s, k));
      const V p = (sv[0] + sv[1] + sv[2]) / V(3.);
      V       xi[6];
      for (unsigned int k = 0; k < 6; ++k)
        xi[k] = k < 3 ? sv[k] - p : sv[k];
      const V q = Simd::sqrt(V(1.5) * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] +
                                       V(2.) * (xi[3] * xi[3] + xi[4] * xi[4] + xi[5] * xi[5])));

      const V eps0    = V::load(row(h, 0));
      const V T0      = V::load(row(h, 2));
      const V s0      = V::load(row(h, 5));
      const V thermal = V::load(row(h, 6));
      // The total strain rate's factor of the yield stress (1 with the
      // plastic rate's form): 'scaled' is what multiplies the hardening
      // in the return.
      V total = zero, rate_factor = one;
      if (law.total_rate)
        {
          total         = V::load(total_rate);
          const V ratio = total / V(law.reference_rate);
          const M fast  = ratio > one;
          if (any(fast && active))
            rate_factor = select(fast, one + C * Simd::log(Simd::max(ratio, tiny)), one);
        }
      const V scaled = thermal * rate_factor;
      active         = active && (q > s0 * rate_factor);
      if (!any(active))
        return;
      ++counts.packs;
      // 1 / theta and 1 / eps_0 from one division.
      const V theta_m = Simd::max(thermal, floor), eps0_m = Simd::max(eps0, floor);
      const V r0 = one / (theta_m * eps0_m), inv_theta = eps0_m * r0, inv_eps0 = theta_m * r0;
      // B eps_0^n from the stored flow stress (A + B eps_0^n) theta.
      const V Be0n = select(thermal > zero, Simd::max(s0 * inv_theta - A, zero), zero);

      // The first guesses of plastic_increment().
      const V scale      = q * inv_3G;
      const V inv_q      = one / Simd::max(q, tiny);
      const V tol        = V(JohnsonCookLaw::return_tolerance) * scale;
      const V guess      = V::load(previous_rate) * V(dt);
      const M take_guess = (guess > zero) && (guess < scale);
      const V se0 = select(eps0 > zero, n_exp * Be0n * inv_eps0, V(slope_at_zero)) * scaled;
      V       d   = Simd::min((q - s0 * rate_factor) / (three_G + Simd::min(se0, V(1e3) * three_G)), scale);
      if (law.B > 0 && !all(take_guess || !active))
        {
          const V over = (law.total_rate ? q / Simd::max(scaled, tiny) : q * inv_theta) - A;
          const V d_h  = power(over * inv_B, inv_n) - eps0;
          ++counts.flow_stress_functions;
          d = select((scaled > zero) && (over > zero) && (d_h > zero), Simd::min(d_h, scale), d);
        }
      d = select(take_guess, guess, d);

      // Newton's method in the bracket, as plastic_increment() per lane.
      // x^n and ln(d / dt eps_0_dot) are evaluated at the first point and
      // wherever a lane's step leaves the reach of the series about that
      // point (|d - d_a| <= 0.03 of x_a and of d_a, on the same side of the
      // rate term's kink); between, their series. Once every running lane
      // is within reach, the steps that polish the roots cost no
      // transcendental function.
      //
      // The first point of evaluation is the stored state itself where the
      // lane has one (x_a = eps_0, whose x_a^n = B eps_0^n / B is known) and
      // the first guess (ln(d / dt eps_0_dot), needed there in any case): a
      // lane in steady flow, whose increment is a small part of its plastic
      // strain, then evaluates no power at all.
      V       lo = zero, hi = scale;
      M       running = active;
      const M stored  = (eps0 > zero) && (thermal > zero);
      V       x_a = select(stored, eps0, zero), xn_a = Be0n * inv_B, dx_a = zero, d_a = d,
        inv_x_a = select(stored, inv_eps0, zero), inv_d_a = zero;
      const V ratio_0 = d * inv_rate;
      M       fast_a  = ratio_0 > one;
      const bool log_0_needed = any(fast_a && running);
      V       log_a   = log_0_needed ? Simd::log(Simd::max(ratio_0, tiny)) : zero;
      counts.flow_stress_functions += log_0_needed;
      const V log_0   = log_a;
      const unsigned int steps = one_step ? 1 : law.newton_steps();
      for (unsigned int it = 0; it < steps && any(running); ++it)
        {
          const V x     = eps0 + d;
          const V ratio = d * inv_rate;
          const M fast  = ratio > one;
          // Each lane takes the series or the functions by its own step
          // alone, so that its result does not depend on the other points
          // of its batch (np = 2 gives np = 1's bits).
          // 1 / x and 1 / d from one division.
          const V x_m = Simd::max(x, floor), d_m = Simd::max(d, floor), r_xd = one / (x_m * d_m);
          const V inv_x = d_m * r_xd, inv_d = x_m * r_xd;
          if (it == 0)
            inv_d_a = inv_d; // (d_a = d: u_d = 0 whatever it is)
          const V u_x   = (d - dx_a) * inv_x_a;
          const V u_d   = (d - d_a) * inv_d_a;
          const M small = (x_a > zero) && (Simd::abs(u_x) <= V(series_reach)) && (fast == fast_a) &&
                          (!fast || ((d_a > zero) && (Simd::abs(u_d) <= V(series_reach))));
          V       xn        = xn_a * power_series(u_x, binomial);
          V       log_ratio = log_a + log1p_series(u_d);
          if (!all(small || !running))
            {
              ++counts.flow_stress_functions;
              const V xn_f  = power(x, n_exp);
              // (At the first guess, the logarithm computed above.)
              const V log_f = it == 0 ? log_0 : any(fast && running) ? Simd::log(Simd::max(ratio, tiny)) : zero;
              xn            = select(small, xn, xn_f);
              log_ratio     = select(small, log_ratio, log_f);
              // (A lane that has stopped keeps its point of evaluation:
              // its new flow stress below takes the series about it, so
              // that the functions other lanes still evaluate do not
              // change its last bits.)
              const M keep = small || !running;
              x_a          = select(keep, x_a, x);
              dx_a         = select(keep, dx_a, d);
              xn_a         = select(keep, xn_a, xn_f);
              d_a          = select(keep, d_a, d);
              inv_x_a      = select(keep, inv_x_a, inv_x);
              inv_d_a      = select(keep, inv_d_a, inv_d);
              log_a        = select(keep, log_a, log_f);
              fast_a       = (keep && fast_a) || (!keep && fast);
            }
          const M pos    = x > zero;
          const V H      = A + B * xn;
          const V H1     = select(pos, n_exp * B * xn * inv_x, V(slope_at_zero));
          const V H2     = select(pos, (n_exp - one) * H1 * inv_x, zero);
          const V Rf     = select(fast, one + C * log_ratio, one);
          const V R1     = select(fast, C * inv_d, zero);
          const V R2     = select(fast, -C * inv_d * inv_d, zero);
          const V g      = q - three_G * d - scaled * H * Rf;
          const V g1     = -three_G - scaled * (H1 * Rf + H * R1);
          const V g2     = -scaled * (H2 * Rf + V(2.) * H1 * R1 + H * R2);
          const M root   = g == zero;
          const M above  = g > zero;
          lo             = select(running && above, d, lo);
          hi             = select(running && !above, d, hi);
          const V step   = -g / g1;
          const M inside = (d + step > lo) && (d + step < hi);
          const M newton_done =
            (Simd::abs(step) <= tol) ||
            (inside && (Simd::abs(g2) * step * step <= V(2.) * tol * Simd::abs(g1)) &&
             (((d + step) * inv_rate > one) == fast));
          const V next = select(inside || newton_done, d + step, V(0.5) * (lo + hi));
          const M done = root || newton_done || (!inside && (hi - lo <= tol));
          d            = select(running && !root, next, d);
          running      = running && !done;
        }
      const V dep = select(active, d, zero);
      active      = active && (dep != zero);

      const V q_new  = q - three_G * dep;
      const V factor = one - three_G * dep * inv_q;
      for (unsigned int k = 0; k < 6; ++k)
        select(active, factor * xi[k] + (k < 3 ? p : zero), sv[k]).store(row(s, k));
      const V rate = dep * inv_dt;
      const V eps1 = eps0 + dep;
      select(active, eps1, eps0).store(row(h, 0));
      const V work = V::load(row(h, 1));
      select(active, work + q_new * dep, work).store(row(h, 1));
      select(active, rate, V::load(row(h, 4))).store(row(h, 4));
      if (law.damage())
        {
          const V triax = select(q_new > zero, p / Simd::max(q_new, tiny), zero);
          const V ratio = Simd::max((law.total_rate ? total : rate) / V(law.reference_rate), one);
          const V eps_f = (V(law.D[0]) + V(law.D[1]) * Simd::exp(V(law.D[2]) * triax)) *
                          (one + V(law.D[3]) * Simd::log(ratio)) * (one + V(law.D[4]) * homologous(T0));
          const V d_old = V::load(row(h, 3));
          select(active, d_old + select(eps_f > zero, dep / eps_f, one), d_old).store(row(h, 3));
        }
      V thermal1 = thermal;
      if (law.heating())
        {
          const V T1 =
            select(active, T0 + heat * q_new * dep, T0);
          T1.store(row(h, 2));
          if (thermal_on)
            {
              // 1 - T_1*^m from the stored T_0*^m = 1 - theta_0 and the
              // series of (1 + u)^m, u = (T_1* - T_0*) / T_0*, where the
              // step's heating is within its reach (a point heated over
              // many steps); else the functions.
              const V Ts0  = homologous(T0), Ts1 = homologous(T1);
              const V u_T  = (Ts1 - Ts0) / Simd::max(Ts0, tiny);
              const M near = (Ts0 > zero) && (Ts1 < one) && (Simd::abs(u_T) <= V(series_reach));
              V       th   = one - (one - thermal) * power_series(u_T, binomial_m);
              if (!all(near || !active))
                {
                  ++counts.thermal_functions;
                  th = select(near, th, thermal_factor(Ts1));
                }
              thermal1 = select(active, th, thermal);
              thermal1.store(row(h, 6));
            }
        }
      // eps_1^n by the series about the lane's last point of evaluation
      // where it is within its reach, as in the iteration.
      const V u_x    = (dep - dx_a) * inv_x_a;
      const M small  = (x_a > zero) && (Simd::abs(u_x) <= V(series_reach));
      V       eps1_n = xn_a * power_series(u_x, binomial);
      if (!all(small || !active))
        eps1_n = select(small, eps1_n, power(eps1, n_exp));
      const V flow = (A + B * eps1_n) * thermal1;
      select(active, flow, s0).store(row(h, 5));
    }
  } // namespace


  // The history values the return reads and writes.
  constexpr unsigned int n_return_history = 7;

  void JohnsonCook::plastic_update_batch(const double dt,
                                         const std::uint64_t (&flag)[batch_size],
                                         const double (&previous_rate)[batch_size],
                                         const double (&total_rate)[batch_size],
                                         double (&s)[6][batch_size],
                                         const BatchHistory &history) const
  {
    static_assert(batch_size % Simd::register_lanes == 0, "a batch is a whole number of vector registers");
    constexpr unsigned int W = batch_size;
    alignas(64) double     h[n_return_history][W], active[W];
    for (unsigned int k = 0; k < n_return_history; ++k)
      history.load(k, h[k]);
    for (unsigned int l = 0; l < W; ++l)
      active[l] = flag[l] != 0 ? 1. : 0.;
    constexpr unsigned int R = W / Simd::register_lanes;
    if (law.max_iterations == 1)
      plastic_return<R, true>(law, mu, dt, active, previous_rate, total_rate, &s[0][0], &h[0][0], counts);
    else
      plastic_return<R, false>(law, mu, dt, active, previous_rate, total_rate, &s[0][0], &h[0][0], counts);
    for (unsigned int k = 0; k < n_return_history; ++k)
      history.store(k, h[k]);
  }


  ANVIL_REGISTER_MATERIAL_MODEL(JohnsonCook,
                                "johnson cook",
                                "Johnson-Cook metal: power-law hardening, logarithmic rate term, thermal softening "
                                "with adiabatic heating, Johnson-Cook damage and erosion (LS-DYNA "
                                "*MAT_JOHNSON_COOK, ABAQUS *Plastic, hardening=JOHNSON COOK).")
} // namespace anvil::MaterialModel
