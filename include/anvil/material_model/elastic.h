/**
 * @file
 * Isotropic linear elasticity in the form each formulation needs.
 */
#pragma once

#include <anvil/material_model/interface.h>

namespace anvil::MaterialModel
{
  /**
   * Isotropic elasticity, Young's modulus E and Poisson's ratio nu.
   *
   * - Updated Lagrangian: hypoelastic Jaumann-rate law (seed Eq. (15)),
   *   sigma^nabla = lambda tr(D) I + 2 mu D, the law ABAQUS/Explicit and
   *   LS-DYNA (*MAT_ELASTIC) use for solids.
   * - Total Lagrangian: St. Venant-Kirchhoff, S = lambda tr(E) I + 2 mu E
   *   (seed Eqs. (7), (14)).
   */
  class Elastic : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    /** Set the constants directly (unit tests, material-point driver). */
    void set(double density, double youngs_modulus, double poissons_ratio);

    double density() const override
    {
      return rho;
    }
    double bulk_modulus() const override
    {
      return lambda + 2. / 3. * mu;
    }
    double wave_modulus() const override
    {
      return lambda + 2. * mu;
    }
    double youngs_modulus() const override
    {
      return mu * (3. * lambda + 2. * mu) / (lambda + mu);
    }
    bool supports(const Formulation) const override
    {
      return true;
    }

    bool has_uniaxial_form() const override
    {
      return true;
    }

    double update_uniaxial_stress(double  strain_increment,
                                  double  dt,
                                  double  stress,
                                  double *history) const override;

    void update_cauchy_stress(const double *D,
                              double        dt,
                              double       *stress,
                              double       *history) const override;

    void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                    const double (&spin)[3][batch_size],
                                    double dt,
                                    double (&stress)[6][batch_size],
                                    const BatchHistory &history) const override;

    void compute_pk2_stress(const double *F,
                            const double *E,
                            double       *S,
                            double       *history) const override;

  protected:
    double rho    = 0;
    double lambda = 0;
    double mu     = 0;
  };


  /**
   * Compressible neo-Hookean hyperelasticity on the reference configuration:
   * S = mu (I - C^-1) + lambda ln(J) C^-1 (Belytschko, Liu & Moran,
   * Nonlinear Finite Elements, Eq. 5.4.57). Total Lagrangian only.
   */
  class NeoHookean : public Elastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);

    bool supports(const Formulation f) const override
    {
      return f == Formulation::total_lagrangian;
    }

    void compute_pk2_stress(const double *F,
                            const double *E,
                            double       *S,
                            double       *history) const override;
  };


  /**
   * A rigid body (seed section 5.2: the impactor "is rigid"). Its elements
   * carry no force and its nodes move with the body's 'Initial velocity'
   * for the whole run: a fixed or moving rigid wall or impactor of
   * prescribed motion. Young's modulus and Poisson's ratio serve only the
   * penalty stiffness of its faces (seed Eq. (59)); give the struck body's.
   * (Free rigid-body dynamics driven by contact forces is a separate
   * capability.)
   */
  class Rigid : public Elastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    bool        is_rigid() const override
    {
      return true;
    }
  };
} // namespace anvil::MaterialModel
