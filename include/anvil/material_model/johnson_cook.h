/**
 * @file
 * Johnson-Cook plasticity with adiabatic heating and Johnson-Cook damage
 * (LS-DYNA *MAT_JOHNSON_COOK, ABAQUS *Plastic, hardening=JOHNSON COOK with
 * *Rate Dependent, type=JOHNSON COOK, OpenRadioss LAW2).
 */
#pragma once

#include <cmath>
#include <cstdint>

#include <anvil/material_model/rate_form_elastic.h>

#include <string>

namespace anvil::MaterialModel
{
  /**
   * The Johnson-Cook law (G. R. Johnson, W. H. Cook, 7th Int. Symp.
   * Ballistics, 1983; fracture: Eng. Fract. Mech. 21 (1985) 31-48), shared by
   * the material point and unit tests:
   *
   *   sigma_y = (A + B eps_p^n) (1 + C ln(eps_p_dot / eps_0_dot)) (1 - T*^m),
   *   T* = (T - T_t) / (T_m - T_t), clipped to [0, 1],
   *
   * the rate term 1 below the reference rate eps_0_dot (ABAQUS's form), no
   * thermal softening below the transition temperature T_t, no strength at
   * and above the melting temperature T_m. Adiabatic heating: a fraction
   * chi (the inelastic heat fraction, Taylor-Quinney) of the plastic work
   * heats the point, dT = chi sigma_y d eps_p / (rho c_p). Damage
   * D = sum d eps_p / eps_f with
   *
   *   eps_f = (D1 + D2 exp(D3 sigma*)) (1 + D4 ln max(eps_p_dot / eps_0_dot, 1)) (1 + D5 T*),
   *
   * sigma* = sigma_m / sigma_eq the stress triaxiality; the point fails at
   * D = 1.
   */
  struct JohnsonCookLaw
  {
    double A = 0, B = 0, n = 1, C = 0, reference_rate = 1;
    double m = 1, melting_temperature = 0, transition_temperature = 0;
    double density = 0, specific_heat = 0, heat_fraction = 0;
    double D[5] = {0, 0, 0, 0, 0};
    /** Which strain rate the rate term (and the damage's) takes: false,
        the effective plastic strain rate, solved with the return (ABAQUS,
        LS-DYNA's VP = 1); true, the effective total strain rate of the
        step, sqrt(2/3 D':D'), which scales the yield stress before the
        return (LS-DYNA's default VP = 0). */
    bool total_rate = false;
    /** Newton steps the return may take: 0, as many as it needs to meet
        return_tolerance (the default); N > 0, at most N, as the explicit
        codes' returns with a fixed number of iterations (1: the return
        linearised about its first guess). A capped return leaves the
        stress off the yield surface by what its last step left; the next
        step's return starts from the stored state and takes it back, so
        the error does not accumulate. Only with total_rate: with the
        plastic rate's term in the iteration, capped returns stay far
        from the root (doc/theory.md measures both). */
    unsigned int max_iterations = 0;

    /** The bound of the return's Newton loop: max_iterations, or 100
        where it is 0 (the converged return stops on its tolerance long
        before). */
    unsigned int newton_steps() const
    {
      return max_iterations > 0 ? max_iterations : 100;
    }

    /** Whether the flow stress softens with temperature. */
    bool thermal_softening() const
    {
      return melting_temperature > transition_temperature && m > 0;
    }

    /** Whether plastic work heats the point. */
    bool heating() const
    {
      return heat_fraction > 0 && specific_heat > 0;
    }

    /** The rate factor 1 + C ln(rate / eps_0_dot), 1 below the reference
        rate. */
    double rate_factor(const double rate) const
    {
      const double ratio = rate / reference_rate;
      return ratio > 1. ? 1. + C * std::log(ratio) : 1.;
    }

    /** Whether damage accumulates (some D_i given). */
    bool damage() const
    {
      return D[0] != 0 || D[1] != 0;
    }

    /** T*, in [0, 1]. */
    double homologous_temperature(const double T) const;

    /** 1 - T*^m. */
    double thermal_factor(double T) const;

    /** Flow stress at plastic strain @p eps_p, plastic strain rate @p rate
        and temperature @p T. Units: Pa. */
    double flow_stress(double eps_p, double rate, double T) const;

    /** The same with the thermal factor 1 - T*^m given. */
    double flow_stress_at(double eps_p, double rate, double thermal) const;

    /** Accuracy of the return's plastic increment, as a share of its
        bound q_trial / 3G (the stress it leaves is that share of q_trial
        off the yield surface). */
    static constexpr double return_tolerance = 1e-12;

    /**
     * Effective plastic strain increment of the radial return from the
     * trial effective stress @p q_trial over @p dt at the thermal factor
     * @p thermal (1 - T*^m of the step's start): the root of
     * q_trial - 3G dep = flow_stress_at(eps_p + dep, dep / dt, thermal),
     * by Newton's method inside the bracket [0, q_trial / 3G] (bisection
     * where a step leaves it), from @p guess where it lies in the bracket.
     * 0 when the point is within the yield stress at the reference rate
     * (elastic). At most max_iterations steps where that is not 0.
     */
    double plastic_increment(double q_trial, double eps_p, double thermal, double dt, double three_G,
                             double guess = 0) const;

    /** Strain to failure at triaxiality @p triaxiality, plastic strain rate
        @p rate and temperature @p T. */
    double failure_strain(double triaxiality, double rate, double T) const;
  };


  /**
   * Johnson-Cook metal (updated and total Lagrangian, the rate form of the
   * other metals): elastic trial stress from D dt, J2 radial return with
   * the flow stress of the effective plastic strain, of the effective
   * plastic strain rate of the increment (solved with the return, so the
   * rate term adds no explicit feedback: doc/theory.md) and of the
   * temperature at the start of the step; then adiabatic heating and
   * damage. Isotropic hardening: no back stress, so nothing to rotate
   * besides the stress.
   *
   * With LS-DYNA's VP = 0 ('Rate form = total') the rate term is that of
   * the step's effective total strain rate, known before the return: the
   * yield stress is scaled, and the return solves the hardening alone.
   *
   * History per point: effective plastic strain, plastic work density,
   * temperature, damage, effective plastic strain rate, and the
   * rate-free flow stress (A + B eps_p^n)(1 - T*^m) of the current state,
   * so that an elastic point is recognised without a pow. The total
   * Lagrangian form adds the previous F - I (9).
   */
  class JohnsonCook : public RateFormElastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    /** Set the constants directly (unit tests, benchmarks). */
    void set(double density, double youngs_modulus, double poissons_ratio, const JohnsonCookLaw &law,
             double initial_temperature, bool erosion);

    unsigned int n_updated_lagrangian_history() const override
    {
      return 7;
    }
    std::vector<std::string> history_names() const override
    {
      return {"effective_plastic_strain", "plastic_work_density", "temperature", "damage",
              "effective_plastic_strain_rate", "", ""};
    }
    void initialize_history(double *history, const PointData &data) const override;
    int  dissipation_index() const override
    {
      return 1;
    }
    bool has_uniaxial_form() const override
    {
      return false;
    }
    bool erodes() const override
    {
      return erosion;
    }
    bool point_failed(const double *history) const override
    {
      return history[3] >= 1.;
    }
    bool rate_dependent() const override
    {
      return law.C > 0;
    }
    std::string rate_law() const override;

    void update_cauchy_stress(const double *D, double dt, double *stress, double *history) const override;

    /** The elastic trial across the lanes; the return, heating and damage
        lane by lane where a trial stress is beyond the yield stress. */
    void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                    const double (&spin)[3][batch_size],
                                    double dt,
                                    double (&stress)[6][batch_size],
                                    const BatchHistory &history) const override;

    const JohnsonCookLaw &get_law() const
    {
      return law;
    }

    /** What the batched returns cost so far (tests, benchmarks): the
        vector register packs that returned; the packs' evaluations of the
        transcendental functions of the flow stress (the first guess's
        power and logarithm, and x^n with the logarithm at each point of
        the iteration that the series about the last evaluation do not
        reach); those of the thermal factor. A pack in steady flow
        evaluates one logarithm, at its first guess (doc/performance.md). */
    struct ReturnCounts
    {
      unsigned long packs = 0, flow_stress_functions = 0, thermal_functions = 0;
    };
    const ReturnCounts &return_counts() const
    {
      return counts;
    }

  private:
    /** The return, heating and damage of one point whose trial stress is
        @p s (updated in place) and history @p h. */
    void plastic_update(double dt, double *s, double *h, double previous_rate = 0, double total_rate = 0) const;
    /** The elastic trial and the yield check of a batch: @p flag the
        lanes beyond their yield stress, @p rate their plastic rate of the
        step before (the history's is set to 0), @p total their total
        strain rate (with 'Rate form = total'). Whether any lane yields. */
    bool elastic_trial_batch(const double (&D)[6][batch_size], double dt, double (&s)[6][batch_size],
                             const BatchHistory &history, std::uint64_t (&flag)[batch_size],
                             double (&rate)[batch_size], double (&total)[batch_size]) const;
    /** The same for the lanes of a batch whose @p flag is set, in vector
        registers. */
    void plastic_update_batch(double dt, const std::uint64_t (&flag)[batch_size],
                              const double (&previous_rate)[batch_size], const double (&total_rate)[batch_size],
                              double (&s)[6][batch_size], const BatchHistory &history) const;

    JohnsonCookLaw       law;
    double               initial_temperature = 0;
    bool                 erosion             = false;
    mutable ReturnCounts counts;
  };
} // namespace anvil::MaterialModel
