/**
 * @file
 * The material interface: one material point at a time, plain arrays in and
 * out, so that the same code serves the element kernels, the material-point
 * driver and unit tests without a mesh.
 *
 * Stresses and symmetric strain measures are stored in Voigt order
 * [xx, yy, zz, xy, yz, xz] (tensor components, no engineering factor 2).
 */
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace anvil
{
  /** Which Lagrangian description a body uses (seed section 3.5). */
  enum class Formulation
  {
    /** Cauchy stress, deformation rate D and spin W, Jaumann rate (seed
        Eqs. (5), (15), (23)-(28)). */
    updated_lagrangian,
    /** Second Piola-Kirchhoff stress and Green-Lagrange strain on the
        reference configuration (seed Eqs. (7), (14), (36)-(37)). */
    total_lagrangian
  };

  std::string to_string(Formulation f);

  namespace MaterialModel
  {
    /**
     * Base class of all material models. A model registers itself with
     * ANVIL_REGISTER_MATERIAL_MODEL at the bottom of its .cc file; the
     * selection in the parameter file is built from the registry.
     */
    class Interface
    {
    public:
      virtual ~Interface() = default;

      /** Read this model's subsection (the handler is already inside it). */
      virtual void parse_parameters(dealii::ParameterHandler &prm) = 0;

      /** Reference mass density. Units: kg/m^3. */
      virtual double density() const = 0;

      /** Initial bulk modulus K, for contact stiffness (seed Eq. (59)).
          Units: Pa. */
      virtual double bulk_modulus() const = 0;

      /** Initial P-wave (constrained) modulus lambda + 2 mu, for the
          dilatational wave speed, the stable time step and hourglass
          control. Units: Pa. */
      virtual double wave_modulus() const = 0;

      /** Number of history variables per material point. */
      virtual unsigned int n_history() const
      {
        return 0;
      }

      /** Whether this model can be used with formulation @p f. */
      virtual bool supports(const Formulation f) const = 0;

      /**
       * Updated Lagrangian update. On entry @p stress holds the Cauchy
       * stress of the previous step already rotated objectively by the
       * spin (Jaumann rate, seed Eq. (15)); the model adds its response to
       * the deformation rate @p D (Voigt, tensor components) over @p dt.
       */
      virtual void update_cauchy_stress(const double *D,
                                        const double  dt,
                                        double       *stress,
                                        double       *history) const;

      /** Number of material points the batched update handles at once. */
      static constexpr unsigned int batch_size = 8;

      /**
       * The updated Lagrangian update for a batch of points, laid out so
       * that the compiler can vectorise across them: component k of point
       * l is D[k][l], stress[k][l]. The default calls the one-point
       * version for each point; models override it for speed.
       */
      virtual void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                              const double dt,
                                              double (&stress)[6][batch_size],
                                              double *const (&history)[batch_size]) const;

      /**
       * Total Lagrangian evaluation: second Piola-Kirchhoff stress @p S
       * from the deformation gradient @p F (row major 3x3) and the
       * Green-Lagrange strain @p E (Voigt).
       */
      virtual void compute_pk2_stress(const double *F,
                                      const double *E,
                                      double       *S,
                                      double       *history) const;
    };


    /** What the registry knows of one model. */
    struct RegistryEntry
    {
      std::string description;
      std::function<void(dealii::ParameterHandler &)> declare_parameters;
      std::function<std::unique_ptr<Interface>()>     create;
    };

    /** All registered models, by name. */
    std::map<std::string, RegistryEntry> &registry();

    /** Called by ANVIL_REGISTER_MATERIAL_MODEL. */
    bool register_model(const std::string &name, RegistryEntry entry);

    /** "elastic|neo-Hookean|...", for Patterns::Selection. */
    std::string model_name_pattern();

    /**
     * Declare the "Model" selection and one subsection per registered
     * model (named after it) in the current subsection of @p prm.
     */
    void declare_parameters(dealii::ParameterHandler &prm);

    /**
     * Create the model selected in the current subsection of @p prm and
     * let it parse its own subsection.
     */
    std::unique_ptr<Interface> create(dealii::ParameterHandler &prm);
  } // namespace MaterialModel
} // namespace anvil

/**
 * Register material model @p classname under @p name. Put this at the bottom
 * of the model's .cc file, in namespace anvil::MaterialModel.
 */
#define ANVIL_REGISTER_MATERIAL_MODEL(classname, name, description) \
  namespace                                                          \
  {                                                                  \
    const bool anvil_registered_##classname =                        \
      ::anvil::MaterialModel::register_model(                        \
        name,                                                        \
        {description,                                                \
         &classname::declare_parameters,                             \
         []() { return std::make_unique<classname>(); }});           \
  }
