/**
 * @file
 * Boundary-condition plugins: what a boundary condition prescribes on the
 * velocity components of the nodes it selects (seed Eq. (28b)). The
 * selection (body, boundary ids, surfaces, node sets, box, components) is
 * the BoundaryCondition's; the plugin named by its 'Type' gives the
 * velocity at time t. Anvil's own: 'fixed', 'velocity' (constant) and
 * 'velocity function' (expressions in t); a plugin library registers more
 * with ANVIL_REGISTER_BOUNDARY_CONDITION (doc/extending.md).
 */
#pragma once

#include <anvil/utilities/registry.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace anvil::BoundaryConditions
{
  class Interface
  {
  public:
    virtual ~Interface() = default;

    /** Read the entries its static declare_parameters() declared, in the
        condition's subsection; @p where names that subsection for an
        InputError. */
    virtual void parse_parameters(dealii::ParameterHandler &prm, const std::string &where)
    {
      (void)prm, (void)where;
    }

    /** The velocity prescribed at time @p t (of the components the
        condition constrains). Units: m/s. */
    virtual dealii::Tensor<1, 3> velocity(double t) const = 0;

    /** Whether velocity() changes with t: the step then evaluates it at
        every half step t^{n+1/2}; otherwise once. */
    virtual bool time_dependent() const
    {
      return false;
    }
  };

  /** The registered boundary conditions, by name. */
  using Registry = ::anvil::Registry<Interface>;
} // namespace anvil::BoundaryConditions

namespace anvil
{
  // The table is the executable's (source/boundary_conditions/motions.cc).
  extern template class Registry<BoundaryConditions::Interface>;
}

/**
 * Register boundary condition @p classname (with a static
 * declare_parameters(dealii::ParameterHandler &) declaring its entries in
 * the condition's subsection, beside those of the selection) under
 * @p name, the value of 'Type' that selects it. At the bottom of its .cc
 * file, in namespace anvil::BoundaryConditions.
 */
#define ANVIL_REGISTER_BOUNDARY_CONDITION(classname, name, description) \
  namespace                                                              \
  {                                                                      \
    const bool anvil_registered_boundary_condition_##classname =         \
      ::anvil::BoundaryConditions::Registry::add(                        \
        name,                                                            \
        {description,                                                    \
         &classname::declare_parameters,                                 \
         []() { return std::make_unique<classname>(); }});               \
  }
