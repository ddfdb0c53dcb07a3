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

#include <anvil/utilities/registry.h>

#include <deal.II/base/parameter_handler.h>

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

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
     * What the mesh tells a material point when its history is set up.
     */
    struct PointData
    {
      /** Characteristic length of the point's element (cube root of its
          reference volume), for crack-band regularisation. Units: m. */
      double characteristic_length = 1.;
      /** Factor on the strengths of the point (an imperfection), 1 where
          the scene asks for none. Units: none. */
      double strength_factor = 1.;
    };

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

      /** Young's modulus E of the uniaxial (truss) form and its wave
          speed sqrt(E / rho). Units: Pa. */
      virtual double youngs_modulus() const = 0;

      /** Number of history variables per material point of a body in
          formulation @p f. */
      virtual unsigned int n_history(const Formulation f = Formulation::updated_lagrangian) const
      {
        (void)f;
        return 0;
      }

      /**
       * Number of leading values of a point's history (of n_history(f))
       * that the batched update reads at every step. The element kernels
       * store these of all points in one array and the rest in another, so
       * that a step over points that need no more streams only the first
       * (concrete inside its surfaces: 5 values of 17). The default: all.
       */
      virtual unsigned int n_hot_history(const Formulation f = Formulation::updated_lagrangian) const
      {
        return n_history(f);
      }

      /**
       * Set up the history of one point (after it is zeroed) from what the
       * mesh knows of it. The default leaves the zeros.
       */
      virtual void initialize_history(double *history, const PointData &data) const
      {
        (void)history, (void)data;
      }

      /** Whether the model scales its strengths by
          PointData::strength_factor (an imperfection region of a body). */
      virtual bool accepts_strength_factor() const
      {
        return false;
      }

      /** Names of the history variables that output shows, e.g.
          "effective_plastic_strain": entry k names history variable k; an
          empty name is not shown (a variable the scene did not ask for). */
      virtual std::vector<std::string> history_names() const
      {
        return {};
      }

      /** Value of the variable named history_names()[k] at a point with
          history @p history. The default reads the stored value; names
          past n_history() are derived from the stored ones here. */
      virtual double history_value(const double *history, const unsigned int k) const
      {
        return history[k];
      }

      /** The history variables that the element's geometry and place set
          at setup (a crack band's characteristic length, an imperfection's
          strength factor): an element made by refinement or coarsening
          during the run keeps its own, where it takes the rest of its
          history from the elements before it. */
      virtual std::vector<unsigned int> geometric_history() const
      {
        return {};
      }

      /** Index of the history variable holding the energy dissipated per
          unit volume (plastic work, damage), or -1. Units: J/m^3. */
      virtual int dissipation_index() const
      {
        return -1;
      }

      /** Whether the model has a uniaxial (truss) form. */
      virtual bool has_uniaxial_form() const
      {
        return false;
      }

      /** Number of history variables of the uniaxial form. */
      virtual unsigned int n_uniaxial_history() const
      {
        return 0;
      }

      /** Names of the history variables of the uniaxial form. */
      virtual std::vector<std::string> uniaxial_history_names() const
      {
        return {};
      }

      /** Whether material points of this model can fail and their
          elements be eroded (asked once per element group, so that a
          model without failure costs nothing in the element loop). */
      virtual bool erodes() const
      {
        return false;
      }

      /** Whether the stress depends on the strain rate (rate effects
          asked for): the run's summary of what its step computes says
          so, and a model without them computes no rate. */
      virtual bool rate_dependent() const
      {
        return false;
      }

      /** The rate law that acts, with its constants, as the run's summary
          of its step names it (e.g. "Cowper-Symonds, C = 40 1/s, p = 5");
          empty when rate_dependent() is false. */
      virtual std::string rate_law() const
      {
        return "";
      }

      /** Whether the point with history @p history has failed. */
      virtual bool point_failed(const double *history) const
      {
        (void)history;
        return false;
      }

      /** Whether the point's elastic stiffness can fall below the
          initial one (damage), so that stiffness hourglass control must
          follow it (asked once per element group). */
      virtual bool degrades() const
      {
        return false;
      }

      /** The point's current elastic stiffness over the initial one, in
          [0, 1] (1 - d for a damaged material): the factor on the
          stiffness hourglass control of its element, which otherwise
          gives a cracked element the strength of an intact one. It reads
          only the first n_hot_history() values of @p history (the
          kernels pass those, at every step). */
      virtual double stiffness_fraction(const double *history) const
      {
        (void)history;
        return 1.;
      }

      /** Whether a body of this material is rigid: it gets no element
          forces, and its nodes follow its prescribed rigid motion. */
      virtual bool is_rigid() const
      {
        return false;
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

      /**
       * Whether the history holds tensors (a back stress) that must rotate
       * with the material like the stress; the updated Lagrangian kernels
       * then call rotate_history() with the spin before the update.
       */
      virtual bool has_tensorial_history() const
      {
        return false;
      }

      /** Number of material points the batched updates handle at once. */
      static constexpr unsigned int batch_size = 8;

      /**
       * The history of a batch's points, as the element kernels store it:
       * the first n_hot values of point l (n_hot_history()) at hot[l],
       * value k at hot[l][k * hot_stride]; the other n_cold at cold[l],
       * contiguous. The kernels store the hot values by batch (value k of
       * lanes 0..7 side by side, hot_stride = batch_size), so that where
       * the lanes are one stored batch in order (the usual case: not the
       * padding of the last batch, nor a batch with eroded elements)
       * hot_batch points at it and load() and store() move value k of all
       * lanes as one vector.
       */
      struct BatchHistory
      {
        double      *hot[batch_size];
        double      *cold[batch_size];
        unsigned int n_hot      = 0;
        unsigned int n_cold     = 0;
        unsigned int hot_stride = 1;
        /** hot[0] where hot[l] = hot[0] + l and hot_stride = batch_size,
            else nullptr. */
        double *hot_batch = nullptr;

        /** Hot value k of lane l. */
        double &hot_value(const unsigned int l, const unsigned int k) const
        {
          return hot[l][std::size_t(k) * hot_stride];
        }
        /** Hot value k of every lane into @p v. */
        void load(const unsigned int k, double (&v)[batch_size]) const
        {
          if (hot_batch != nullptr)
            for (unsigned int l = 0; l < batch_size; ++l)
              v[l] = hot_batch[k * batch_size + l];
          else
            for (unsigned int l = 0; l < batch_size; ++l)
              v[l] = hot_value(l, k);
        }
        /** And back. */
        void store(const unsigned int k, const double (&v)[batch_size]) const
        {
          if (hot_batch != nullptr)
            for (unsigned int l = 0; l < batch_size; ++l)
              hot_batch[k * batch_size + l] = v[l];
          else
            for (unsigned int l = 0; l < batch_size; ++l)
              hot_value(l, k) = v[l];
        }
        /** Point l's whole history (n_hot + n_cold values) into @p h. */
        void gather(const unsigned int l, double *h) const
        {
          for (unsigned int k = 0; k < n_hot; ++k)
            h[k] = hot_value(l, k);
          for (unsigned int k = 0; k < n_cold; ++k)
            h[n_hot + k] = cold[l][k];
        }
        /** And back. */
        void scatter(const unsigned int l, const double *h) const
        {
          for (unsigned int k = 0; k < n_hot; ++k)
            hot_value(l, k) = h[k];
          for (unsigned int k = 0; k < n_cold; ++k)
            cold[l][k] = h[n_hot + k];
        }
      };

      /** The largest n_history() of any model (the kernels' buffers for
          one point's history). */
      static constexpr unsigned int max_history = 64;

      /** Rotate the tensorial history by the spin W (components W_01,
          W_12, W_02) over @p dt, as the kernel rotates the stress. */
      virtual void rotate_history(const double w01,
                                  const double w12,
                                  const double w02,
                                  const double dt,
                                  double      *history) const
      {
        (void)w01, (void)w12, (void)w02, (void)dt, (void)history;
      }

      /**
       * The updated Lagrangian update for a batch of points, laid out so
       * that the compiler can vectorise across them: component k of point
       * l is D[k][l], stress[k][l] (already rotated by the kernel), and
       * spin[0][l] = W_01, spin[1][l] = W_12, spin[2][l] = W_02. The
       * model rotates its own tensorial history with the spin (one pass
       * over the history for both). The default calls rotate_history() and
       * the one-point update for each point; models override it for speed.
       */
      virtual void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                              const double (&spin)[3][batch_size],
                                              const double dt,
                                              double (&stress)[6][batch_size],
                                              const BatchHistory &history) const;

      /**
       * Total Lagrangian evaluation: second Piola-Kirchhoff stress @p S
       * from the deformation gradient @p F (row major 3x3) and the
       * Green-Lagrange strain @p E (Voigt).
       */
      virtual void compute_pk2_stress(const double *F,
                                      const double *E,
                                      double       *S,
                                      double       *history) const;

      /**
       * Total Lagrangian evaluation of a rate-dependent or path-dependent
       * model, which needs the time step @p dt (0 on the first call). The
       * default ignores @p dt and calls compute_pk2_stress().
       */
      virtual void update_pk2_stress(const double *F,
                                     const double *E,
                                     const double  dt,
                                     double       *S,
                                     double       *history) const
      {
        (void)dt;
        compute_pk2_stress(F, E, S, history);
      }

      /**
       * The uniaxial (truss) form: axial stress after the axial logarithmic
       * strain increment @p strain_increment over @p dt, from @p stress.
       * Returns the new axial stress.
       */
      virtual double update_uniaxial_stress(const double strain_increment,
                                            const double dt,
                                            const double stress,
                                            double      *history) const;

    protected:
      /**
       * Total Lagrangian evaluation of a rate-form (hypoelastic-plastic)
       * model, for update_pk2_stress() overrides: the Cauchy stress is
       * recovered from @p S and the previous F (kept in @p history at
       * @p F_offset as F - I), the stress and tensorial history are rotated
       * and updated by update_cauchy_stress() with the D and W of the
       * mid-step velocity gradient (F - F_old) F_mid^-1 / dt, and pulled
       * back to S = J F^-1 sigma F^-T. With @p dt = 0 it only records F.
       */
      void update_pk2_by_rate_form(const double *F,
                                   double        dt,
                                   double       *S,
                                   double       *history,
                                   unsigned int  F_offset) const;
    };


    /** The registered models, by name (ANVIL_REGISTER_MATERIAL_MODEL). */
    using Registry = ::anvil::Registry<Interface>;

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

  // The table is the executable's (source/material_model/interface.cc).
  extern template class Registry<MaterialModel::Interface>;
} // namespace anvil

/**
 * Register material model @p classname under @p name. Put this at the bottom
 * of the model's .cc file, in namespace anvil::MaterialModel.
 */
#define ANVIL_REGISTER_MATERIAL_MODEL(classname, name, description) \
  namespace                                                          \
  {                                                                  \
    const bool anvil_registered_##classname =                        \
      ::anvil::MaterialModel::Registry::add(                         \
        name,                                                        \
        {description,                                                \
         &classname::declare_parameters,                             \
         []() { return std::make_unique<classname>(); }});           \
  }
