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
                                               const double dt,
                                               double (&stress)[6][batch_size],
                                               double *const (&history)[batch_size]) const
    {
      for (unsigned int l = 0; l < batch_size; ++l)
        {
          double d[6], s[6];
          for (unsigned int k = 0; k < 6; ++k)
            {
              d[k] = D[k][l];
              s[k] = stress[k][l];
            }
          update_cauchy_stress(d, dt, s, history[l]);
          for (unsigned int k = 0; k < 6; ++k)
            stress[k][l] = s[k];
        }
    }


    void Interface::compute_pk2_stress(const double *,
                                       const double *,
                                       double *,
                                       double *) const
    {
      throw InputError("this material model has no total Lagrangian form");
    }


    double Interface::update_uniaxial_stress(const double,
                                             const double,
                                             const double,
                                             double *) const
    {
      throw InputError("this material model has no uniaxial (truss) form");
    }


    std::map<std::string, RegistryEntry> &registry()
    {
      // A function-local static: safe to use from static initialisers of
      // other translation units.
      static std::map<std::string, RegistryEntry> models;
      return models;
    }


    bool register_model(const std::string &name, RegistryEntry entry)
    {
      registry()[name] = std::move(entry);
      return true;
    }


    std::string model_name_pattern()
    {
      std::string pattern;
      for (const auto &[name, entry] : registry())
        pattern += (pattern.empty() ? "" : "|") + name;
      return pattern;
    }


    void declare_parameters(dealii::ParameterHandler &prm)
    {
      std::string doc = "The material model. Choices:";
      for (const auto &[name, entry] : registry())
        doc += " '" + name + "': " + entry.description;
      prm.declare_entry("Model",
                        "elastic",
                        dealii::Patterns::Selection(model_name_pattern()),
                        doc);
      for (const auto &[name, entry] : registry())
        {
          prm.enter_subsection(name);
          entry.declare_parameters(prm);
          prm.leave_subsection();
        }
    }


    std::unique_ptr<Interface> create(dealii::ParameterHandler &prm)
    {
      const std::string name  = prm.get("Model");
      auto              model = registry().at(name).create();
      prm.enter_subsection(name);
      model->parse_parameters(prm);
      prm.leave_subsection();
      return model;
    }
  } // namespace MaterialModel
} // namespace anvil
