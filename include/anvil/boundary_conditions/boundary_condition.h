/**
 * @file
 * Kinematic boundary conditions: the nodes of named boundary ids, surfaces
 * or node sets of a mesh file, or inside a box, whose chosen velocity
 * components follow the boundary-condition plugin 'Type' names (fixed, a
 * constant velocity, a velocity function of t, or a plugin's).
 */
#pragma once

#include <anvil/boundary_conditions/interface.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  struct MeshNames;

  /** One kinematic boundary condition of a scene (seed Eq. (28b)). */
  class BoundaryCondition
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &name);

    /** Turn the names of surfaces and node sets into boundary ids and
        reference positions, from what the body's mesh file names. */
    void resolve_names(const MeshNames &mesh);

    /** Whether a node of body @p body_name at reference position @p X on
        boundary ids @p ids (empty for interior nodes) is constrained. */
    bool selects(const std::string                      &body_name,
                 const dealii::Point<3>                 &X,
                 const std::vector<unsigned int>        &ids) const;

    /** The prescribed velocity at time @p t. */
    dealii::Tensor<1, 3> velocity(const double t) const
    {
      return motion->velocity(t);
    }

    /** Whether it changes in time (BoundaryConditions::Interface). */
    bool time_dependent() const
    {
      return motion->time_dependent();
    }

    std::string            name;
    std::string            body;
    std::array<bool, 3>    components = {{true, true, true}};

  private:
    /** The plugin 'Type' names. */
    std::shared_ptr<const BoundaryConditions::Interface> motion;
    bool                      by_box = false, by_node_set = false;
    /** Names of surfaces or node sets, until resolve_names. */
    std::vector<std::string>  names;
    /** Node sets: their reference positions, sorted by x. */
    std::vector<dealii::Point<3>> positions;
    double                    tolerance = 0;
    std::vector<unsigned int> boundary_ids;
    dealii::Point<3>          lower, upper;
  };
} // namespace anvil
