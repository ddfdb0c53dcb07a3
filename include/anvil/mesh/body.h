/**
 * @file
 * A body of a scene: its mesh source, material, formulation, element
 * integration and initial velocity.
 */
#pragma once

#include <anvil/element/element_group.h>
#include <anvil/material_model/interface.h>
#include <anvil/mesh/source.h>
#include <anvil/rigid_body/rigid_body.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * One deformable body. Its mesh is built serially (generators may refine
   * with their curved manifolds), then flattened into the scene's single
   * distributed triangulation, where the body index is the cell's
   * material id.
   */
  class Body
  {
  public:
    /** Declare the entries of subsection "Body NAME". */
    static void declare_parameters(dealii::ParameterHandler &prm);

    /** Read subsection "Body NAME" (the handler is inside it).
        @p scene_directory resolves relative mesh file names. */
    void parse_parameters(dealii::ParameterHandler &prm,
                          const std::string        &name,
                          const std::string        &scene_directory);

    /** Build this body's mesh (reference configuration); for a mesh file,
        also what it names (@p names, if given). */
    void create_mesh(dealii::Triangulation<3> &tria, MeshNames *names = nullptr) const;

    std::string                                name;
    std::unique_ptr<MaterialModel::Interface> material;
    Formulation                                formulation;
    Element::Integration                       integration;
    Element::HourglassType                     hourglass;
    double                                     hourglass_coefficient;
    /** Bulk viscosity coefficients b_1, b_2 (both 0: off). */
    double                                     bulk_linear = 0.06, bulk_quadratic = 1.2;
    dealii::Tensor<1, 3>                       initial_velocity;
    /** Motion of a body of rigid material (unused otherwise). */
    RigidBody::Motion rigid;

    bool is_rigid() const
    {
      return material->is_rigid();
    }

    /** Strength factor of an element with reference centroid @p centroid:
        the imperfection's inside its box, 1 elsewhere. */
    double strength_factor(const dealii::Point<3> &centroid) const;

    /** Integration of an element with reference centroid @p centroid:
        full inside the 'Full integration region', the body's elsewhere. */
    Element::Integration integration_at(const dealii::Point<3> &centroid) const;

    /** Integration of the element @p cell of this body's mesh: that of
        the element it was made from as the body was built (its level-0
        ancestor, by that one's centroid), so that refinement and
        coarsening never move an element from one group to the other. */
    template <class CellIterator>
    Element::Integration integration_of(const CellIterator &cell) const
    {
      if (cell->level() == 0)
        return integration_at(cell->center());
      auto ancestor = cell->parent();
      while (ancestor->level() > 0)
        ancestor = ancestor->parent();
      return integration_at(ancestor->center());
    }

    /** Whether some elements of this body may be fully integrated while
        the body's integration is one point. */
    bool has_full_integration_region() const
    {
      return has_full_region && integration == Element::Integration::one_point;
    }

    /** Local refinement: the most levels by which any of the body's
        regions ('Refinement region', 'Refinement region 2') halves its
        elements (0: none). */
    unsigned int local_refinement_levels() const
    {
      return std::max(first_region.levels, second_region.levels);
    }

    /** The levels the regions want for an element: the largest 'Levels'
        of the regions whose criteria hold for it (0: none). A box holds
        for the reference centroid @p reference, 'Near body' for the
        current centroid @p current against the boxes @p near (the first
        region's 'Near body', then the second's), and, where
        @p with_indicator (during the run), the first region's 'Indicator'
        for the element's largest value @p indicator. */
    unsigned int wanted_levels(const dealii::Point<3>                               &reference,
                               const dealii::Point<3>                               &current,
                               const std::array<std::array<dealii::Point<3>, 2>, 2> &near,
                               double                                                indicator,
                               bool                                                  with_indicator) const;

    /** The 'Near body' boxes of each of @p bodies (its first region's,
        its second's; an empty box, lower above upper, where there is none),
        from every body's box @p lower, @p upper: wanted_levels()'s @p
        near. */
    static std::vector<std::array<std::array<dealii::Point<3>, 2>, 2>>
    near_boxes(const std::vector<Body>             &bodies,
               const std::vector<dealii::Point<3>> &lower,
               const std::vector<dealii::Point<3>> &upper);

    /** The body whose surroundings 'Refinement region 2' refines (empty:
        none). */
    const std::string &second_near_body() const
    {
      return second_region.near;
    }

    /** The body whose surroundings are refined too (empty: none). */
    const std::string &refinement_near_body() const
    {
      return first_region.near;
    }

    /** The history variable whose value refines an element during the
        run (its index in the material's history_names(); -1: none;
        contact_pressure_indicator: the contact pressure at its nodes). */
    int refinement_indicator() const
    {
      return indicator_index;
    }
    /** refinement_indicator() of 'Indicator = contact_pressure'. */
    static constexpr int contact_pressure_indicator = -2;

  private:
    /** A refinement region: a box (by reference centroid) and the reach
        of a 'Near body' (by current centroid), and how many times it
        halves its elements. */
    struct Region
    {
      unsigned int     levels  = 0;
      bool             has_box = false;
      dealii::Point<3> lower, upper;
      std::string      near;
      double           distance = 0;

      /** Whether it holds for an element with centroids @p reference and
          @p current, the 'Near body''s box being @p near. */
      bool holds(const dealii::Point<3>                  &reference,
                 const dealii::Point<3>                  &current,
                 const std::array<dealii::Point<3>, 2> &near) const;
      /** Its box, 'Near body' and 'Distance' from the current subsection
          (of body @p body, for the error lines @p where starts). */
      void parse(dealii::ParameterHandler &prm, const std::string &where, const std::string &body);
    };

    /** Where the mesh comes from (the plugin 'Source' names). */
    std::unique_ptr<MeshSources::Interface> mesh_source;
    dealii::Tensor<1, 3>                    offset;
    unsigned int                            refinements = 0;
    /** The entries of other sources the scene sets, for the log. */
    std::vector<std::string> ignored_entries;
    bool                 has_imperfection    = false;
    dealii::Point<3>     imperfection_lower, imperfection_upper;
    double               imperfection_factor = 1.;
    bool                 has_full_region     = false;
    dealii::Point<3>     full_region_lower, full_region_upper;
    /** 'Refinement region' (with its 'Indicator') and 'Refinement region
        2' (finer inside the first, say: the nose of an impactor inside the
        struck part of a member). */
    Region               first_region, second_region;
    int                  indicator_index     = -1;
    double               indicator_threshold = 0;
  };
} // namespace anvil
