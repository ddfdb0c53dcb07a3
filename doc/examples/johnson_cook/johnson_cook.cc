/**
 * @file
 * A Johnson-Cook metal as an Anvil plugin: the code of doc/extending.md.
 *
 * Flow stress (Johnson and Cook, 1983, without the thermal term):
 *   sigma_y = (A + B eps_p^n) (1 + C ln max(eps_p_dot / eps_0_dot, 1)),
 * J2 plasticity with isotropic hardening, updated Lagrangian (the kernels
 * hand the model the rate of deformation D and the step; they rotate the
 * stress with the spin themselves).
 */
#include <anvil/material_model/interface.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>

namespace johnson_cook
{
  using namespace anvil;
  using namespace anvil::MaterialModel;

  class JohnsonCook : public Interface
  {
  public:
    // @sect3{Parameters}
    //
    // The registry calls this inside the model's own subsection
    // ('subsection Johnson-Cook' below 'subsection Material').
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      prm.declare_entry("Density", "7850", Double(0.), "Units: kg/m^3.");
      prm.declare_entry("Young's modulus", "2.1e11", Double(0.), "Units: Pa.");
      prm.declare_entry("Poisson's ratio", "0.3", Double(-1., 0.5), "Units: none.");
      prm.declare_entry("A", "350e6", Double(0.), "Yield stress. Units: Pa.");
      prm.declare_entry("B", "275e6", Double(0.), "Hardening modulus. Units: Pa.");
      prm.declare_entry("n", "0.36", Double(0.), "Hardening exponent. Units: none.");
      prm.declare_entry("C", "0.022", Double(0.), "Strain-rate coefficient. Units: none.");
      prm.declare_entry("Reference strain rate", "1", Double(0.), "Units: 1/s.");
    }

    void parse_parameters(dealii::ParameterHandler &prm) override
    {
      rho    = prm.get_double("Density");
      E      = prm.get_double("Young's modulus");
      nu     = prm.get_double("Poisson's ratio");
      A      = prm.get_double("A");
      B      = prm.get_double("B");
      n      = prm.get_double("n");
      C      = prm.get_double("C");
      rate_0 = prm.get_double("Reference strain rate");
      mu     = E / (2. * (1. + nu));
      lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    }

    // @sect3{What the solver asks of every model}
    //
    // Density, and the moduli for the stable time step, hourglass control
    // and contact stiffness.
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
      return E;
    }
    bool supports(const Formulation f) const override
    {
      return f == Formulation::updated_lagrangian;
    }

    // One history variable per point: the effective plastic strain, shown
    // in the VTU output and the driver's CSV under this name.
    unsigned int n_history(const Formulation) const override
    {
      return 1;
    }
    std::vector<std::string> history_names() const override
    {
      return {"effective_plastic_strain"};
    }

    // @sect3{The stress update}
    //
    // Elastic trial stress, then the radial return: the plastic multiplier
    // dg solves
    //   g(dg) = q_trial - 3 mu dg - sigma_y(eps_p + dg, dg / dt) = 0,
    // g falls monotonically in dg, so Newton's steps are kept inside a
    // bracket that bisection shrinks when Newton would leave it.
    void update_cauchy_stress(const double *D, const double dt, double *stress, double *history) const override
    {
      const double trD = D[0] + D[1] + D[2];
      for (unsigned int k = 0; k < 3; ++k)
        stress[k] += (lambda * trD + 2. * mu * D[k]) * dt;
      for (unsigned int k = 3; k < 6; ++k)
        stress[k] += 2. * mu * D[k] * dt;

      const double p = (stress[0] + stress[1] + stress[2]) / 3.;
      double       s[6];
      for (unsigned int k = 0; k < 6; ++k)
        s[k] = stress[k] - (k < 3 ? p : 0.);
      const double q =
        std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
      const double eps_p = history[0];
      if (q <= flow_stress(eps_p, 0.) || dt <= 0.)
        return;

      double lo = 0., hi = q / (3. * mu), dg = 0.;
      for (unsigned int it = 0; it < 100; ++it)
        {
          const double g = q - 3. * mu * dg - flow_stress(eps_p + dg, dg / dt);
          if (g > 0.)
            lo = dg;
          else
            hi = dg;
          if (std::abs(g) < 1e-12 * q || hi - lo < 1e-15 * (1. + hi))
            break;
          // Newton, with the slope by a difference quotient.
          const double h     = 1e-8 * (dg + 1e-10);
          const double slope = -3. * mu - (flow_stress(eps_p + dg + h, (dg + h) / dt) -
                                           flow_stress(eps_p + dg, dg / dt)) / h;
          double next = dg - g / slope;
          if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
          dg = next;
        }
      const double factor = 1. - 3. * mu * dg / q;
      for (unsigned int k = 0; k < 6; ++k)
        stress[k] = factor * s[k] + (k < 3 ? p : 0.);
      history[0] = eps_p + dg;
    }

  private:
    double flow_stress(const double eps_p, const double rate) const
    {
      const double ratio = rate / rate_0;
      return (A + B * std::pow(eps_p, n)) * (1. + C * std::log(std::max(ratio, 1.)));
    }

    double rho = 0, E = 0, nu = 0, A = 0, B = 0, n = 0, C = 0, rate_0 = 1, mu = 0, lambda = 0;
  };
} // namespace johnson_cook

// @sect3{Registration}
//
// One line makes the model selectable as 'set Model = Johnson-Cook'; it
// runs when the scene loads the library.
namespace johnson_cook
{
  ANVIL_REGISTER_MATERIAL_MODEL(JohnsonCook,
                                "Johnson-Cook",
                                "Johnson-Cook metal (a plugin: doc/extending.md), updated Lagrangian.")
}
