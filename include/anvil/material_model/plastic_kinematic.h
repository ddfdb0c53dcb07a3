/**
 * @file
 * Bilinear elastic-plastic steel with mixed kinematic-isotropic hardening,
 * Cowper-Symonds strain-rate scaling of the yield stress and failure
 * (seed section 5.2, Eq. (63), Table 1; LS-DYNA's *MAT_PLASTIC_KINEMATIC).
 */
#pragma once

#include <anvil/material_model/rate_form_elastic.h>

#include <string>

namespace anvil::MaterialModel
{
  /**
   * The hardening and rate law of seed Eq. (63), shared by the 3D material
   * point and the uniaxial (truss) form so that neither duplicates it:
   *
   *   sigma_y = R(eps_dot) (sigma_0 + beta E_p eps_p),   E_p = E E_t / (E - E_t),
   *
   * with the rate factor R of one of two laws:
   * - Cowper-Symonds (seed Eq. (63)): R = 1 + (eps_dot / C)^(1/p);
   * - Malvar and Crawford's dynamic increase factor of the yield stress of
   *   reinforcing bars (Malvar 1998, ACI Materials Journal 95(5)):
   *   R = max(1, (eps_dot / 1e-4 1/s)^alpha), alpha = 0.074 - 0.040
   *   sigma_0 / 414 MPa (sigma_0 / 60 ksi), fitted to bars of
   *   290-710 MPa at 1e-4 to 225 1/s;
   *
   * with the back stress moving by (1 - beta) E_p per unit effective plastic
   * strain (Prager's rule). beta = 0 is kinematic, beta = 1 isotropic
   * hardening.
   */
  struct PlasticKinematicLaw
  {
    double sigma_0 = 0;
    double plastic_modulus = 0;
    double beta = 0;
    /** The rate laws; rate_effects is (rate_law != none), kept for the
        element loop's tests. */
    enum class RateLaw
    {
      none,
      cowper_symonds,
      malvar_crawford
    };
    RateLaw rate_law     = RateLaw::none;
    bool    rate_effects = false;
    double  C = 0;
    double  p = 1;
    /** Malvar and Crawford's exponent alpha (from sigma_0). */
    double alpha = 0;
    double failure_strain = 0;

    /** Set the Cowper-Symonds law (C, p > 0). */
    void set_cowper_symonds(double C, double p);
    /** Set Malvar and Crawford's law for the current sigma_0 (alpha > 0,
        i.e. sigma_0 < 765 MPa; throws std::invalid_argument otherwise). */
    void set_malvar_crawford();

    /** Rate factor R of the effective strain rate @p rate (1 without rate
        effects or at rate <= 0). */
    double rate_factor(const double rate) const;

    /** The law acting, with its constants, for the run's summary ("" when
        none). */
    std::string describe_rate_law() const;

    /** Radius of the yield surface (in effective stress) at plastic
        strain @p eps_p and rate factor @p R. Units: Pa. */
    double yield_stress(const double eps_p, const double R) const
    {
      return R * (sigma_0 + beta * plastic_modulus * eps_p);
    }

    /**
     * Effective plastic strain increment of the radial return from the
     * trial effective (relative) stress @p q_trial: the consistency
     * condition q_trial - elastic_term dep - (1 - beta) E_p dep =
     * yield_stress(eps_p + dep, R), linear in dep. @p elastic_term is 3G
     * for a 3D point and E for a uniaxial one. Returns 0 when elastic.
     */
    double plastic_increment(const double q_trial,
                             const double eps_p,
                             const double R,
                             const double elastic_term) const
    {
      const double excess = q_trial - yield_stress(eps_p, R);
      if (!(excess > 0))
        return 0.;
      return excess / (elastic_term + (1. - beta) * plastic_modulus +
                       R * beta * plastic_modulus);
    }

    /**
     * The same return with the rate factor of the effective plastic strain
     * rate dep / dt of this very increment (the rate of ABAQUS's *Rate
     * Dependent and of LS-DYNA's viscoplastic option VP = 1): the
     * consistency condition
     *   q_trial - (elastic_term + (1 - beta) E_p) dep
     *     = R(dep / dt) (sigma_0 + beta E_p (eps_p + dep))
     * is solved for dep: with Cowper-Symonds (p >= 1) by Newton's method in
     * y = (dep / C dt)^(1/p) (cowper_symonds_increment()), otherwise in dep
     * inside the bracket [0, rate-free increment] (bisection where a step
     * leaves it). R(0) = 1, so a point
     * within the static yield stress is elastic at any rate. Rate-free
     * (no rate law or dt = 0): plastic_increment with R = 1. Returns dep
     * and sets @p R to the factor at the solution.
     */
    double rate_dependent_increment(double  q_trial,
                                    double  eps_p,
                                    double  dt,
                                    double  elastic_term,
                                    double &R) const;

    /** rate_dependent_increment() for Cowper-Symonds with p >= 1, @p K
        the elastic term plus the back stress's modulus and @p d0 the
        rate-free increment. */
    double cowper_symonds_increment(double q_trial, double eps_p, double dt, double K, double d0, double &R) const;

    /** Back-stress modulus (1 - beta) E_p. Units: Pa. */
    double kinematic_modulus() const
    {
      return (1. - beta) * plastic_modulus;
    }
  };


  /**
   * Plastic-kinematic steel (seed Eq. (63)).
   *
   * - Updated Lagrangian: the Cauchy stress arrives rotated by the spin
   *   (Jaumann, as for the elastic model); the elastic trial stress from D dt
   *   is returned radially to the von Mises surface around the back stress.
   *   The back stress is rotated with the stress.
   * - Total Lagrangian: the same rate-form (hypoelastic-plastic) update,
   *   evaluated on the reference mesh: the Cauchy stress is recovered from
   *   S and the previous F, rotated and updated with the D and W of the
   *   mid-step F, and pulled back to S = J F^-1 sigma F^-T. This is the
   *   plasticity of ABAQUS/Explicit and LS-DYNA, against which the seed
   *   computes; a hyperelastic multiplicative model would answer a
   *   different question.
   * - Uniaxial (truss): the same law in one dimension.
   *
   * The rate entering R is the effective plastic strain rate of the
   * increment, dep / dt, solved with the return
   * (PlasticKinematicLaw::rate_dependent_increment): ABAQUS's definition
   * of the Cowper-Symonds overstress law, LS-DYNA's VP = 1. (The total
   * strain rate known before the return, LS-DYNA's VP = 0, feeds the rate
   * back explicitly: at the low rates of a bar yielding in a slow push the
   * slope dR/d eps_dot is large, and the step of a 20 mm bar element is
   * then hundreds of times too long for that feedback: doc/theory.md.)
   *
   * History per point: back stress (6), effective plastic strain,
   * plastic work density, effective plastic strain rate (with rate
   * effects); total Lagrangian adds the
   * previous F - I (9) and the back stress is kept in the rotated frame
   * like the stress.
   *
   * The elastic constants and what derives from them (density, bulk, wave
   * and Young's modulus) are the Elastic model's; every stress update is
   * overridden here.
   */
  class PlasticKinematic : public RateFormElastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    /** Set the constants directly (unit tests). */
    void set(double density, double youngs_modulus, double poissons_ratio,
             const PlasticKinematicLaw &law, bool erosion);

    unsigned int n_updated_lagrangian_history() const override
    {
      return 9;
    }
    std::vector<std::string> history_names() const override
    {
      return {"back_stress_xx", "back_stress_yy", "back_stress_zz",
              "back_stress_xy", "back_stress_yz", "back_stress_xz",
              "effective_plastic_strain", "plastic_work_density",
              "effective_plastic_strain_rate"};
    }
    int dissipation_index() const override
    {
      return 7;
    }
    unsigned int n_uniaxial_history() const override
    {
      return 3;
    }
    std::vector<std::string> uniaxial_history_names() const override
    {
      return {"back_stress", "effective_plastic_strain", "plastic_work_density"};
    }
    bool erodes() const override
    {
      return erosion;
    }
    bool rate_dependent() const override
    {
      return law.rate_effects;
    }
    std::string rate_law() const override
    {
      return law.describe_rate_law();
    }
    bool point_failed(const double *history) const override
    {
      return history[6] >= law.failure_strain;
    }

    bool has_tensorial_history() const override
    {
      return law.beta < 1.;
    }
    void rotate_history(double w01, double w12, double w02, double dt,
                        double *history) const override;

    void update_cauchy_stress(const double *D,
                              double        dt,
                              double       *stress,
                              double       *history) const override;

    /** The radial return for a batch of points, written across lanes
        (branch-free: an elastic lane gets dep = 0) so that it vectorises. */
    void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                    const double (&spin)[3][batch_size],
                                    double dt,
                                    double (&stress)[6][batch_size],
                                    const BatchHistory &history) const override;

    double update_uniaxial_stress(double  strain_increment,
                                  double  dt,
                                  double  stress,
                                  double *history) const override;

    const PlasticKinematicLaw &get_law() const
    {
      return law;
    }

  private:
    PlasticKinematicLaw law;
    bool                erosion = false;
  };
} // namespace anvil::MaterialModel
