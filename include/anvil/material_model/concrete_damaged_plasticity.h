/**
 * @file
 * Concrete damaged plasticity (Lubliner et al. 1989, Lee & Fenves 1998), the
 * model ABAQUS calls *CONCRETE DAMAGED PLASTICITY and the seed uses for its
 * column (section 5.2), with uniaxial curves generated from f'c by the fib
 * Model Code 2010, crack-band regularisation of tension softening and the
 * dynamic increase factors of seed Eqs. (64)-(67).
 */
#pragma once

#include <anvil/material_model/rate_form_elastic.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace anvil::MaterialModel
{
  /** A piecewise-linear function, constant beyond its last point. */
  class PiecewiseLinear
  {
  public:
    PiecewiseLinear() = default;
    PiecewiseLinear(std::vector<double> x, std::vector<double> y);

    double operator()(const double x) const
    {
      double slope;
      return (*this)(x, slope);
    }

    /** The value at @p x and the slope of the piece that holds it (0
        beyond the table's ends, where the value is held), from one
        search. (No division in the return mapping's inner loop: the
        slopes are kept.) */
    double operator()(const double x, double &slope) const
    {
      if (x <= xs.front())
        {
          slope = 0;
          return ys.front();
        }
      if (x >= xs.back())
        {
          slope = 0;
          return ys.back();
        }
      const unsigned int i = std::upper_bound(xs.begin(), xs.end(), x) - xs.begin();
      slope                = slopes[i - 1];
      return ys[i - 1] + (x - xs[i - 1]) * slopes[i - 1];
    }

    const std::vector<double> &abscissae() const
    {
      return xs;
    }
    const std::vector<double> &values() const
    {
      return ys;
    }

  private:
    std::vector<double> xs, ys, slopes;
  };


  /**
   * The uniaxial behaviour of one concrete: elastic constants, strengths
   * and the two softening curves, in the form the model consumes.
   *
   * - compression: nominal stress against inelastic strain
   *   eps_in = eps - sigma / E (starting at the initial yield stress
   *   sigma_c0 at eps_in = 0);
   * - tension: nominal stress against crack opening w (m), which the model
   *   turns into a cracking strain w / h over the element's characteristic
   *   length h (crack band, Bazant & Oh 1983).
   */
  struct ConcreteCurves
  {
    double          youngs_modulus   = 0;
    double          compressive_strength = 0;
    double          tensile_strength = 0;
    double          fracture_energy  = 0;
    PiecewiseLinear compression;
    PiecewiseLinear tension;

    /**
     * Curves of fib Model Code 2010 (section 5.1) from the mean cylinder
     * strength @p f_cm (Pa), for 20 MPa <= f_cm <= 128 MPa:
     * - E_ci = 21.5 GPa (f_cm / 10 MPa)^(1/3), eps_c1 and eps_c,lim from
     *   Table 5.1-8 (linear in f_ck = f_cm - 8 MPa);
     * - compression: Eq. (5.1-26), sigma / f_cm = (k eta - eta^2) /
     *   (1 + (k - 2) eta), eta = eps / eps_c1, k = E_ci eps_c1 / f_cm, up to
     *   eps_c,lim; beyond, an exponential decay with the same tangent
     *   towards 0.1 f_cm. Linear up to 0.4 f_cm: E is the secant modulus of
     *   Eq. (5.1-26) at 0.4 f_cm (0.4 f_cm is the elastic limit sigma_c0);
     * - tension: f_ctm = 0.3 f_ck^(2/3) (f_ck <= 50 MPa) or
     *   2.12 ln(1 + f_cm / 10) (Eqs. 5.1-3a,b); linear up to f_ctm, then the
     *   bilinear softening of Eq. (5.1-9), sigma = f_ctm (1 - 0.8 w / w1)
     *   up to w1 = G_F / f_ctm and f_ctm (0.25 - 0.05 w / w1) up to
     *   w_c = 5 G_F / f_ctm, with G_F = 73 f_cm^0.18 N/m (Eq. 5.1-9).
     * Entries given (> 0) override E, f_t and G_F.
     */
    static ConcreteCurves model_code_2010(double f_cm,
                                          double youngs_modulus   = 0,
                                          double tensile_strength = 0,
                                          double fracture_energy  = 0);

    /** Nominal compressive stress of Eq. (5.1-26) and its tail at total
        strain @p eps (positive in compression), for tests and plots. */
    static double model_code_2010_stress(double f_cm, double eps);
  };


  /**
   * The model.
   *
   * Effective stress sigma_bar = D_0 : (eps - eps_p) (hypoelastic rate form,
   * rotated with the material like the stress); nominal stress
   * sigma = (1 - d) sigma_bar.
   *
   * Yield function (Lee & Fenves 1998, ABAQUS Theory Manual 4.5.2):
   *   F = [q - 3 alpha p + beta <s_max> - gamma <-s_max>] / (1 - alpha)
   *       - c_c,
   *   alpha = (r_b - 1) / (2 r_b - 1), r_b = sigma_b0 / sigma_c0,
   *   beta  = c_c / c_t (1 - alpha) - (1 + alpha),
   *   gamma = 3 (1 - K_c) / (2 K_c - 1),
   * with p = -tr(sigma_bar) / 3, q the von Mises stress and s_max the
   * largest principal value of sigma_bar; c_c, c_t the effective cohesions.
   *
   * Flow potential (non-associated, hyperbolic Drucker-Prager):
   *   G = sqrt((e f_t tan psi)^2 + q^2) - p tan psi.
   *
   * Hardening: eps_t_p grows by r(sigma) times the largest principal plastic
   * strain increment, eps_c_p by -(1 - r) times the smallest, with
   * r = sum <s_i> / sum |s_i|.
   *
   * Damage: a fraction b of the inelastic strain is plastic (Birtel & Mark
   * 2006), eps_p = b eps_in, so that on the uniaxial curve
   *   d = (1 - b) E eps_in / (sigma + (1 - b) E eps_in),
   *   c  = sigma / (1 - d) = sigma + (1 - b) E eps_in,
   * and 1 - d = (1 - s_t d_c)(1 - s_c d_t), s_t = 1 - w_t r,
   * s_c = 1 - w_c (1 - r), sigma = (1 - d) sigma_bar where the principal
   * effective stresses share a sign. Where they do not, the combination
   * acts per principal direction with r_i = 1 (sigma_bar_i > 0) or 0: with
   * ABAQUS's r an open crack under a compression across it would carry a
   * tension near that compression (doc/theory.md).
   *
   * Return mapping: the potential depends on invariants and D_0 is
   * isotropic, so the return keeps the principal directions of the trial
   * stress; the deviator scales by q / q_trial and the mean stress shifts
   * by -K tan psi dlambda. One scalar equation F(dlambda) = 0 remains,
   * solved by bracketing (Anderson-Bjoerck) with the hardening variables advanced
   * implicitly; q(dlambda) of the hyperbola by Newton. No eigenvectors are
   * needed, and the apex and pure tension need no special case.
   *
   * Tension cut-off: max sigma_bar_i <= c_t (Rankine, associated flow).
   * The growing effective tensile cohesion makes beta negative and F
   * non-convex, open in multiaxial tension; the cut-off closes it and
   * touches F on the uniaxial tension meridian (doc/theory.md).
   *
   * Strain-rate effects: the cohesions scale with CDIF and TDIF (seed
   * Eqs. (64)-(67), concrete_dif.h) of the largest principal strain rate
   * |D|_max, low-pass filtered with time constant tau.
   *
   * Dissipation: per unit volume, sigma : D dt minus the change of the
   * stored energy sigma : C_0^-1 : sigma_bar / 2.
   *
   * History per point: see the indices below; total Lagrangian adds the
   * previous F - I (9).
   */
  class ConcreteDamagedPlasticity : public RateFormElastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    /** Every constant of the model (unit tests set them directly). */
    struct Parameters
    {
      double         density              = 2400;
      double         poissons_ratio       = 0.2;
      ConcreteCurves curves;
      double         dilation_angle       = 36. * 3.14159265358979323846 / 180.;
      double         eccentricity         = 0.1;
      double         biaxial_ratio        = 1.16;
      double         K_c                  = 2. / 3.;
      double         viscosity            = 0;
      double         compressive_plastic_fraction = 0.7;
      double         tensile_plastic_fraction     = 0.1;
      double         tensile_recovery     = 0;
      double         compressive_recovery = 1;
      bool           rate_effects         = false;
      double         cube_strength        = 0;
      /** The cylinder strength of the rate curves (TDIF; CDIF through the
          cube strength); 0: f'c. Units: Pa. */
      double         dif_strength         = 0;
      double         rate_filter_time     = 0;
      bool           erosion              = false;
      double         erosion_principal_strain = 0;
      double         erosion_damage       = 0;
      /** 'Crush band length' l_c: the length over which the compression
          curve's softening branch holds; 0: none (the curve as given in
          every element). Units: m. */
      double         crush_band_length    = 0;
    };

    void set(const Parameters &p);
    const Parameters &get_parameters() const
    {
      return par;
    }

    // History layout of one point: first the values the batched update
    // reads at every step (n_hot_history(): the elastic test of an
    // undamaged point needs no others), then what only damaged points,
    // inelastic steps and output read. Without viscosity, the stress of an
    // undamaged point (d_t = d_c = 0) is its effective stress, bit for bit
    // (1 - d = 1 in every branch of the update), so the stored effective
    // stress is valid only once the point is damaged: the batched update
    // takes an undamaged point's effective stress from its stress and
    // does not store it while the point stays inside its surfaces, and the
    // one-point update copies it from the stress.
    /** The effective cohesions c_t(kappa_t), c_c(kappa_c) with the
        strength factor, before rate effects (kept so that the elastic test
        needs no curve lookup). */
    static constexpr unsigned int i_tensile_cohesion     = 0;
    static constexpr unsigned int i_compressive_cohesion = 1;
    static constexpr unsigned int i_tensile_damage       = 2;
    static constexpr unsigned int i_compressive_damage   = 3;
    /** Filtered strain rate; negative until the first step sets it. */
    static constexpr unsigned int i_rate                 = 4;
    static constexpr unsigned int n_hot                  = 5;
    static constexpr unsigned int i_effective_stress     = 5;
    static constexpr unsigned int i_kappa_t              = 11;
    static constexpr unsigned int i_kappa_c              = 12;
    static constexpr unsigned int i_damage               = 13;
    static constexpr unsigned int i_dissipation          = 14;
    static constexpr unsigned int i_strength_factor      = 15;
    static constexpr unsigned int i_length               = 16;
    /** The values every point has; what only some scenes need follows
        them (the indices below, set by set()). */
    static constexpr unsigned int n_base_history       = 17;

    /** Index of the largest principal strain and of the total strain
        (6), kept only for erosion by principal strain. */
    unsigned int max_strain_index() const
    {
      return i_max_strain;
    }
    /** Index of the first of the two derived values of history_value()
        past the stored ones: the compressive and tensile dynamic increase
        factors of the filtered rate. */
    unsigned int compressive_dif_index() const
    {
      return n_ul_history;
    }
    unsigned int tensile_dif_index() const
    {
      return n_ul_history + 1;
    }

    unsigned int n_updated_lagrangian_history() const override
    {
      return n_ul_history;
    }
    unsigned int n_hot_history(const Formulation) const override
    {
      return n_hot;
    }
    std::vector<std::string> history_names() const override;
    double history_value(const double *history, unsigned int k) const override;
    std::vector<unsigned int> geometric_history() const override
    {
      return {i_length, i_strength_factor};
    }
    int dissipation_index() const override
    {
      return i_dissipation;
    }

    void initialize_history(double *history, const PointData &data) const override;
    bool accepts_strength_factor() const override
    {
      return true;
    }

    bool has_uniaxial_form() const override
    {
      return false;
    }
    bool erodes() const override
    {
      return par.erosion;
    }
    bool rate_dependent() const override
    {
      return par.rate_effects;
    }
    std::string rate_law() const override
    {
      return par.rate_effects ? "concrete DIF (seed Eqs. (64)-(67))" : "";
    }
    bool point_failed(const double *history) const override;
    bool degrades() const override
    {
      return true;
    }
    /** (1 - d_t)(1 - d_c), the stiffness without recovery: it never
        grows (the stiffness recovery depends on the stress state, and a
        hourglass spring whose stiffness came back while it is stretched
        would return more work than it took), and at least 0.1 (a fully
        cracked one-point element must keep some hourglass resistance, or
        it collapses in its hourglass modes). */
    double stiffness_fraction(const double *history) const override
    {
      return std::max((1. - history[i_tensile_damage]) * (1. - history[i_compressive_damage]), 0.1);
    }

    bool has_tensorial_history() const override
    {
      return true;
    }
    void rotate_history(double w01, double w12, double w02, double dt,
                        double *history) const override;

    void update_cauchy_stress(const double *D,
                              double        dt,
                              double       *stress,
                              double       *history) const override;

    /** The batched update: the elastic trial, the rate filter and the test
        for a point inside its current surfaces across the batch; the
        others' returns to Lubliner's surface together, the rest of their
        update one point at a time (see the .cc). */
    void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                    const double (&spin)[3][batch_size],
                                    double dt,
                                    double (&stress)[6][batch_size],
                                    const BatchHistory &history) const override;

    /** Static tensile damage and effective cohesion at hardening variable
        @p kappa_t, characteristic length @p h and strength factor @p f. */
    void tension(double kappa_t, double h, double f, double &damage, double &cohesion) const;
    /** Static compressive damage and effective cohesion. */
    void compression(double kappa_c, double h, double f, double &damage, double &cohesion) const;

    /** The cohesion of tension() alone (the return mapping's iterations
        need no damage). */
    double tensile_cohesion(const double kappa_t, const double h, const double f) const
    {
      double derivative;
      return tensile_cohesion(kappa_t, h, f, derivative);
    }
    /** The cohesion of compression() alone. */
    double compressive_cohesion(const double kappa_c, const double h, const double f) const
    {
      double derivative;
      return compressive_cohesion(kappa_c, h, f, derivative);
    }
    /** The two cohesions with their derivatives by kappa (the return
        mapping's Newton iteration), each from one table search. */
    double tensile_cohesion(const double kappa_t, const double h, const double f,
                            double &derivative) const
    {
      const double b    = par.tensile_plastic_fraction;
      const double e_in = kappa_t / b;
      double       slope;
      const double c = f * par.curves.tension(h * e_in, slope) + (1. - b) * youngs_modulus() * e_in;
      derivative    = (f * slope * h + (1. - b) * youngs_modulus()) / b;
      return c;
    }
    /** (With a 'Crush band length' l_c, the inelastic strain beyond the
        curve's peak e_p is read on the curve at e_p + (e_in - e_p) h / l_c
        in an element of characteristic length @p h: the crushed element's
        shortening beyond the peak is that of a band l_c long, and the
        energy it dissipates per unit area does not depend on h.) */
    double compressive_cohesion(const double kappa_c, const double h, const double f,
                                double &derivative) const
    {
      const double b     = par.compressive_plastic_fraction;
      const double e_in  = kappa_c / b;
      const bool   band  = par.crush_band_length > 0 && e_in > crush_peak_strain;
      const double scale = band ? h / par.crush_band_length : 1.;
      const double e_c   = band ? crush_peak_strain + (e_in - crush_peak_strain) * scale : e_in;
      double       slope;
      const double c = f * par.curves.compression(e_c, slope) + (1. - b) * youngs_modulus() * e_in;
      derivative    = (f * slope * scale + (1. - b) * youngs_modulus()) / b;
      return c;
    }

    /** The yield function's alpha and gamma. */
    double get_alpha() const
    {
      return alpha;
    }
    double get_gamma() const
    {
      return gamma;
    }

    /** The return to Lubliner's surface stops at |F| <= return_tolerance
        f'c (F in stress units): the stress it leaves lies that share of
        the strength off the surface, its plastic strain about
        return_tolerance f'c / E (1.5e-9 for the seed's concrete) from the
        exact one (doc/theory.md, "Return mapping"). */
    static constexpr double return_tolerance = 1e-6;

    /** How hard the return to Lubliner's surface works: the returns made
        so far and the evaluations of F they took (benchmarks print the
        ratio). */
    unsigned long n_lubliner_returns() const
    {
      return lubliner_returns;
    }
    unsigned long n_lubliner_evaluations() const
    {
      return lubliner_evaluations;
    }

  private:
    /** Return to Lubliner's surface alone; false if the trial was inside.
        @p principal: the principal values of @p sbar, on entry and exit. */
    bool lubliner_return(double *sbar, double *h, double cdif, double tdif,
                         double (&principal)[3]) const;

    /** The same for the points in the lanes of @p active (nonzero) at
        once, with effective stresses @p sbar, histories @p h and the
        factors @p cdif, @p tdif of each lane; @p principal as above,
        lane by lane. @p returned: 1 where a lane's trial was outside;
        @p tensile, @p compressive: the static cohesions at each lane's
        hardening variables on exit (the return has them from its last
        evaluation: no curve lookup for the caller). (The one-point form
        is lane 0 of this; the batched update returns its inelastic points
        together.) */
    void lubliner_return_lanes(double *const (&sbar)[batch_size],
                               double *const (&h)[batch_size],
                               const double (&cdif)[batch_size],
                               const double (&tdif)[batch_size],
                               double (&principal)[3][batch_size],
                               const std::uint64_t (&active)[batch_size],
                               std::uint64_t (&returned)[batch_size],
                               double (&tensile)[batch_size],
                               double (&compressive)[batch_size]) const;

    /** The return of the effective stress @p sbar to the yield surface
        after the first return to Lubliner's surface (@p lubliner: whether
        it returned): the tension cut-off, and the two surfaces in turn
        where one leaves the other violated. Advances the hardening
        variables in @p h; @p principal: the principal values of @p sbar,
        on entry and exit. */
    void complete_return(double *sbar, double *h, double cdif, double tdif,
                         double (&principal)[3], bool lubliner) const;

    /** Return to the tension cut-off max sigma_bar_i <= c_t alone; false
        if the trial was inside. @p principal as above. */
    bool tension_cutoff(double *sbar, double *h, double tdif, double (&principal)[3]) const;

    /** The weight r = sum <s_i> / sum |s_i| of principal values @p s0,
        @p s1, @p s2 (0 at zero stress; inline and of scalars, so that a
        loop over a batch vectorises). */
    static double tension_weight(const double s0, const double s1, const double s2)
    {
      const double num = std::max(s0, 0.) + std::max(s1, 0.) + std::max(s2, 0.);
      const double den = std::abs(s0) + std::abs(s1) + std::abs(s2);
      return den > 0 ? num / den : 0.;
    }

    /** sigma : C_0^-1 : sigma_bar / 2, the energy stored in the point. */
    double stored_energy(const double *sigma, const double *sbar) const
    {
      return stored_energy(sigma[0], sigma[1], sigma[2], sigma[3], sigma[4], sigma[5],
                           sbar[0], sbar[1], sbar[2], sbar[3], sbar[4], sbar[5]);
    }

    /** The same from the components (inline, so that a loop over a batch
        vectorises). */
    double stored_energy(const double s0, const double s1, const double s2,
                         const double s3, const double s4, const double s5,
                         const double b0, const double b1, const double b2,
                         const double b3, const double b4, const double b5) const
    {
      const double nu  = par.poissons_ratio;
      const double tr  = b0 + b1 + b2;
      const double sum = s0 * ((1. + nu) * b0 - nu * tr) + s1 * ((1. + nu) * b1 - nu * tr) +
                         s2 * ((1. + nu) * b2 - nu * tr) +
                         2. * (1. + nu) * (s3 * b3 + s4 * b4 + s5 * b5);
      return 0.5 * sum / par.curves.youngs_modulus;
    }

    /** Whether a trial stress (von Mises stress @p q, mean stress @p mean,
        tension positive, largest principal value @p s1) lies inside
        Lubliner's surface and the tension cut-off at the cohesions @p c_t,
        @p c_c by at least @p margin. Units: Pa. */
    bool inside_surfaces(const double q, const double mean, const double s1, const double c_t,
                         const double c_c, const double margin) const
    {
      return (s1 <= c_t - margin) & (yield_function(q, mean, s1, c_t, c_c) <= -margin);
    }

    /** Lubliner's F at von Mises stress @p q, mean stress @p mean (tension
        positive), largest principal value @p s_max and cohesions @p c_t,
        @p c_c. Units: Pa. */
    double yield_function(const double q, const double mean, const double s_max, const double c_t,
                          const double c_c) const
    {
      const double beta = c_c / c_t * (1. - alpha) - (1. + alpha);
      return (q + 3. * alpha * mean + beta * std::max(s_max, 0.) + gamma * std::min(s_max, 0.)) /
               (1. - alpha) -
             c_c;
    }

    /** The uniaxial damage at hardening variable @p kappa with plastic
        fraction @p b, Young's modulus @p E and effective cohesion
        @p cohesion there: d = (1 - b) E (kappa / b) / c (0 at c = 0). */
    static double damage_at(const double kappa, const double b, const double E,
                            const double cohesion)
    {
      const double X = (1. - b) * E * (kappa / b);
      return cohesion > 0 ? X / cohesion : 0.;
    }

    /** Damage @p d, nominal stress @p nominal and the step's dissipation
        (added to @p dissipated where @p add is 1) of a batch's lanes at
        effective stress @p x with principal values @p p (largest first)
        and damage variables @p d_t, @p d_c, the step from stress @p old
        with deformation rate @p D over @p dt, stored energy @p stored_old
        before it. The batched update's code for its trial and its
        returned points; the one-point update runs it on its point in
        every lane. (Defined, always inlined, where it is used.) */
    inline void damage_lanes(const double (&x)[6][batch_size], const double (&p)[3][batch_size],
                             const double (&d_t)[batch_size], const double (&d_c)[batch_size],
                             const double (&old)[6][batch_size], const double (&D)[6][batch_size],
                             double dt, const double (&stored_old)[batch_size],
                             const double (&add)[batch_size], double (&d)[batch_size],
                             double (&nominal)[6][batch_size],
                             double (&dissipated)[batch_size]) const;

    /** 1 - d of ABAQUS's combination, (1 - s_t d_c)(1 - s_c d_t) with
        s_t = 1 - w_t r, s_c = 1 - w_c (1 - r), at tension weight @p r. */
    double intact_fraction(const double r, const double d_t, const double d_c) const
    {
      return (1. - (1. - par.tensile_recovery * r) * d_c) *
             (1. - (1. - par.compressive_recovery * (1. - r)) * d_t);
    }

    /** The low-pass filter of the strain rate: @p now at the first step
        (@p rate < 0), else rate + (now - rate) w with the weight
        w = rate_filter_weight(dt) = dt / (tau + dt) (taken once for a
        batch). */
    double rate_filter_weight(const double dt) const
    {
      return dt / (par.rate_filter_time + dt);
    }
    static double filtered_rate(const double rate, const double now, const double weight)
    {
      return rate < 0 ? now : rate + (now - rate) * weight;
    }

    /** The filtered strain rate of a batch after the step with
        deformation rates @p D: the largest principal |D| through the
        filter. */
    void update_rate(const double (&D)[6][batch_size], double dt, double (&rate)[batch_size]) const;

    /** The total strain and its largest principal value (erosion by
        principal strain only). */
    void track_strain(const double *D, double dt, double *h) const;

    /** Everything after the elastic trial (in the history's effective
        stress) and the first return to Lubliner's surface, which the
        one-point update makes (@p lubliner: whether it returned, @p principal: the
        principal effective stresses after it): the rest of the return at
        the dynamic increase factors @p cdif, @p tdif (1 without rate
        effects), damage, nominal stress @p stress and dissipation. */
    void inelastic_update(const double *D, double dt, const double *dsig,
                          const double *old_stress, double stored_old,
                          double cdif, double tdif, bool lubliner,
                          double (&principal)[3], double *stress, double *h) const;

    Parameters par;
    mutable unsigned long lubliner_returns = 0, lubliner_evaluations = 0;
    double     alpha = 0, gamma = 0, tan_psi = 0, eccentric_term = 0;
    /** The inelastic strain at the compression curve's peak (set()). */
    double     crush_peak_strain = 0;

    /** The history's optional parts, after the n_base_history values
        every point has: the total strain and its largest principal value
        (erosion by principal strain), the viscous stress (Duvaut-Lions
        viscosity); a scene without them stores 17 values a point, not 30
        (the explicit step's traffic, doc/performance.md). */
    unsigned int i_max_strain     = n_base_history;
    unsigned int i_strain         = n_base_history + 1;
    unsigned int i_viscous_stress = n_base_history + 7;
    unsigned int n_ul_history     = n_base_history + 13;

  };
} // namespace anvil::MaterialModel
