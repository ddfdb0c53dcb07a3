#include <anvil/kinematics/rotation.h>
#include <anvil/kinematics/tensor3.h>
#include <anvil/material_model/interface.h>
#include <anvil/utilities/input_error.h>

namespace anvil
{
  std::string to_string(const Formulation f)
  {
    return f == Formulation::updated_lagrangian ? "updated Lagrangian" :
                                                  "total Lagrangian";
  }

  namespace MaterialModel
  {
    void Interface::update_cauchy_stress(const double *,
                                         const double,
                                         double *,
                                         double *) const
    {
      throw InputError("this material model has no updated Lagrangian form");
    }


    void Interface::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                               const double (&spin)[3][batch_size],
                                               const double dt,
                                               double (&stress)[6][batch_size],
                                               const BatchHistory &history) const
    {
      const bool rotate = has_tensorial_history();
      for (unsigned int l = 0; l < batch_size; ++l)
        {
          // The point's history in one piece (a copy: the hot values are
          // stored by batch).
          double h[max_history];
          history.gather(l, h);
          if (rotate)
            rotate_history(spin[0][l], spin[1][l], spin[2][l], dt, h);
          double d[6], s[6];
          for (unsigned int k = 0; k < 6; ++k)
            {
              d[k] = D[k][l];
              s[k] = stress[k][l];
            }
          update_cauchy_stress(d, dt, s, h);
          for (unsigned int k = 0; k < 6; ++k)
            stress[k][l] = s[k];
          history.scatter(l, h);
        }
    }


    void Interface::compute_pk2_stress(const double *,
                                       const double *,
                                       double *,
                                       double *) const
    {
      throw InputError("this material model has no total Lagrangian form");
    }


    void Interface::update_pk2_by_rate_form(const double      *F,
                                            const double       dt,
                                            double            *S,
                                            double            *h,
                                            const unsigned int F_offset) const
    {
      using Kinematics::congruence;
      using Kinematics::determinant;
      using Kinematics::invert;
      double *Fold_minus_I = h + F_offset;
      double  Fold[9];
      for (unsigned int k = 0; k < 9; ++k)
        Fold[k] = Fold_minus_I[k] + (k % 4 == 0 ? 1. : 0.);
      if (dt > 0)
        {
          // Cauchy stress of the previous step, sigma = F S F^T / J.
          double sigma[6];
          congruence(Fold, S, determinant(Fold), sigma);
          // L dt = (F - F_old) F_mid^-1 (the mid-step velocity gradient).
          double Fmid[9], Fmi[9], dF[9], Ldt[9];
          for (unsigned int k = 0; k < 9; ++k)
            {
              Fmid[k] = 0.5 * (F[k] + Fold[k]);
              dF[k]   = F[k] - Fold[k];
            }
          invert(Fmid, Fmi);
          Kinematics::multiply(dF, Fmi, Ldt);
          const double w01 = 0.5 * (Ldt[1] - Ldt[3]);
          const double w12 = 0.5 * (Ldt[5] - Ldt[7]);
          const double w02 = 0.5 * (Ldt[2] - Ldt[6]);
          Kinematics::rotate_stress(w01, w12, w02, 1., sigma);
          if (has_tensorial_history())
            rotate_history(w01, w12, w02, 1., h);
          const double D[6] = {Ldt[0] / dt,
                               Ldt[4] / dt,
                               Ldt[8] / dt,
                               0.5 * (Ldt[1] + Ldt[3]) / dt,
                               0.5 * (Ldt[5] + Ldt[7]) / dt,
                               0.5 * (Ldt[2] + Ldt[6]) / dt};
          update_cauchy_stress(D, dt, sigma, h);
          // S = J F^-1 sigma F^-T.
          double Fi[9];
          invert(F, Fi);
          congruence(Fi, sigma, 1. / determinant(F), S);
        }
      for (unsigned int k = 0; k < 9; ++k)
        Fold_minus_I[k] = F[k] - (k % 4 == 0 ? 1. : 0.);
    }


    double Interface::update_uniaxial_stress(const double,
                                             const double,
                                             const double,
                                             double *) const
    {
      throw InputError("this material model has no uniaxial (truss) form");
    }


    void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Model",
                        "elastic",
                        dealii::Patterns::Selection(Registry::names()),
                        Registry::documentation("The material model. Choices:"));
      Registry::declare_parameters(prm, true);
    }


    std::unique_ptr<Interface> create(dealii::ParameterHandler &prm)
    {
      const std::string name  = prm.get("Model");
      auto              model = Registry::get(name, "entry 'Model'").create();
      prm.enter_subsection(name);
      model->parse_parameters(prm);
      prm.leave_subsection();
      return model;
    }
  } // namespace MaterialModel

  template class Registry<MaterialModel::Interface>;
} // namespace anvil
