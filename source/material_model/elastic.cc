#include <anvil/material_model/elastic.h>
#include <anvil/utilities/input_error.h>

#include <cmath>

namespace anvil::MaterialModel
{
  void Elastic::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Density",
                      "7850",
                      dealii::Patterns::Double(0.),
                      "Reference mass density. Units: kg/m^3.");
    prm.declare_entry("Young's modulus",
                      "2.06e11",
                      dealii::Patterns::Double(0.),
                      "Young's modulus E. Units: Pa.");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      dealii::Patterns::Double(-1., 0.5),
                      "Poisson's ratio nu, -1 < nu < 0.5. Units: none.");
  }


  void Elastic::parse_parameters(dealii::ParameterHandler &prm)
  {
    const double nu = prm.get_double("Poisson's ratio");
    if (nu <= -1. || nu >= 0.5)
      throw InputError("entry 'Poisson's ratio' = " + std::to_string(nu) +
                       " is outside the allowed range -1 < nu < 0.5");
    const double E = prm.get_double("Young's modulus");
    if (E <= 0)
      throw InputError("entry 'Young's modulus' must be positive");
    const double density = prm.get_double("Density");
    if (density <= 0)
      throw InputError("entry 'Density' must be positive");
    set(density, E, nu);
  }


  void Elastic::set(const double density,
                    const double youngs_modulus,
                    const double poissons_ratio)
  {
    rho    = density;
    lambda = youngs_modulus * poissons_ratio /
             ((1. + poissons_ratio) * (1. - 2. * poissons_ratio));
    mu = youngs_modulus / (2. * (1. + poissons_ratio));
  }


  void Elastic::update_cauchy_stress(const double *D,
                                     const double  dt,
                                     double       *stress,
                                     double *) const
  {
    const double ltr = lambda * dt * (D[0] + D[1] + D[2]);
    stress[0] += ltr + 2. * mu * dt * D[0];
    stress[1] += ltr + 2. * mu * dt * D[1];
    stress[2] += ltr + 2. * mu * dt * D[2];
    stress[3] += 2. * mu * dt * D[3];
    stress[4] += 2. * mu * dt * D[4];
    stress[5] += 2. * mu * dt * D[5];
  }


  void Elastic::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                           const double (&)[3][batch_size],
                                           const double dt,
                                           double (&stress)[6][batch_size],
                                           const BatchHistory &) const
  {
    for (unsigned int l = 0; l < batch_size; ++l)
      {
        const double ltr = lambda * dt * (D[0][l] + D[1][l] + D[2][l]);
        stress[0][l] += ltr + 2. * mu * dt * D[0][l];
        stress[1][l] += ltr + 2. * mu * dt * D[1][l];
        stress[2][l] += ltr + 2. * mu * dt * D[2][l];
        stress[3][l] += 2. * mu * dt * D[3][l];
        stress[4][l] += 2. * mu * dt * D[4][l];
        stress[5][l] += 2. * mu * dt * D[5][l];
      }
  }


  double Elastic::update_uniaxial_stress(const double strain_increment,
                                         const double,
                                         const double stress,
                                         double *) const
  {
    return stress + youngs_modulus() * strain_increment;
  }


  void Elastic::compute_pk2_stress(const double *,
                                   const double *E,
                                   double       *S,
                                   double *) const
  {
    const double ltr = lambda * (E[0] + E[1] + E[2]);
    S[0]             = ltr + 2. * mu * E[0];
    S[1]             = ltr + 2. * mu * E[1];
    S[2]             = ltr + 2. * mu * E[2];
    S[3]             = 2. * mu * E[3];
    S[4]             = 2. * mu * E[4];
    S[5]             = 2. * mu * E[5];
  }


  void NeoHookean::declare_parameters(dealii::ParameterHandler &prm)
  {
    Elastic::declare_parameters(prm);
  }


  void NeoHookean::compute_pk2_stress(const double *F,
                                      const double *,
                                      double *S,
                                      double *) const
  {
    // C = F^T F (row-major F: F[3*i+j] = F_ij).
    double C[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        C[i][j] = F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
    const double J =
      F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
      F[2] * (F[3] * F[7] - F[4] * F[6]);
    const double detC = J * J;
    // Inverse of the symmetric C by cofactors.
    const double Ci00 = (C[1][1] * C[2][2] - C[1][2] * C[2][1]) / detC;
    const double Ci11 = (C[0][0] * C[2][2] - C[0][2] * C[2][0]) / detC;
    const double Ci22 = (C[0][0] * C[1][1] - C[0][1] * C[1][0]) / detC;
    const double Ci01 = (C[0][2] * C[2][1] - C[0][1] * C[2][2]) / detC;
    const double Ci12 = (C[0][2] * C[1][0] - C[0][0] * C[1][2]) / detC;
    const double Ci02 = (C[0][1] * C[1][2] - C[0][2] * C[1][1]) / detC;
    const double a    = lambda * std::log(J) - mu;
    S[0]              = mu + a * Ci00;
    S[1]              = mu + a * Ci11;
    S[2]              = mu + a * Ci22;
    S[3]              = a * Ci01;
    S[4]              = a * Ci12;
    S[5]              = a * Ci02;
  }

  void Rigid::declare_parameters(dealii::ParameterHandler &prm)
  {
    Elastic::declare_parameters(prm);
  }

  ANVIL_REGISTER_MATERIAL_MODEL(
    Rigid,
    "rigid",
    "a rigid body of prescribed motion (its 'Initial velocity', constant; "
    "zero: a fixed wall); elastic constants only for the penalty stiffness "
    "of its faces (seed Eq. (59)).")
  ANVIL_REGISTER_MATERIAL_MODEL(
    Elastic,
    "elastic",
    "isotropic linear elasticity: Jaumann-rate hypoelastic in the updated "
    "Lagrangian formulation, St. Venant-Kirchhoff in the total Lagrangian one.")
  ANVIL_REGISTER_MATERIAL_MODEL(
    NeoHookean,
    "neo-Hookean",
    "compressible neo-Hookean hyperelasticity (total Lagrangian only).")
} // namespace anvil::MaterialModel
