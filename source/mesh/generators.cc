/**
 * @file
 * Mesh sources built by deal.II's generators: 'box', 'cylinder' and
 * 'sphere' (MeshSources::Interface).
 */
#include <anvil/mesh/source.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace anvil::MeshSources
{
  namespace
  {
    void declare_radius(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Radius", "0.5", dealii::Patterns::Double(0.), "Cylinder and sphere: radius. Units: m.");
    }
  } // namespace


  /** A block between two corners, its element sizes graded along each axis. */
  class Box : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.declare_entry("Lower corner", "0, 0, 0", Patterns::List(Patterns::Double(), 3, 3),
                        "Box: lowest corner. Units: m.");
      prm.declare_entry("Upper corner", "1, 1, 1", Patterns::List(Patterns::Double(), 3, 3),
                        "Box: highest corner. Units: m.");
      prm.declare_entry("Subdivisions", "1, 1, 1", Patterns::List(Patterns::Integer(1), 3, 3),
                        "Box: number of elements along x, y, z before refinement. Units: none.");
      prm.declare_entry("Grading", "1, 1, 1", Patterns::List(Patterns::Double(0.), 3, 3),
                        "Box: ratio of successive element sizes along x, y, z, from the lower to the "
                        "upper corner (a geometric mesh bias; 1: uniform, < 1: finer towards the upper "
                        "corner). Units: none.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const Context &context) override
    {
      lower = dealii::Point<3>(three_numbers(prm.get("Lower corner"), "Lower corner", context.where));
      upper = dealii::Point<3>(three_numbers(prm.get("Upper corner"), "Upper corner", context.where));
      subdivisions.clear();
      for (const auto &s : dealii::Utilities::split_string_list(prm.get("Subdivisions")))
        subdivisions.push_back(dealii::Utilities::string_to_int(s));
      grading = three_numbers(prm.get("Grading"), "Grading", context.where);
      // About 4 kB per hexahedron: deal.II's cell, vertices and degrees of
      // freedom, and Anvil's state.
      check_size(context.where,
                 "'Subdivisions' and 'Global refinements'",
                 "elements",
                 double(subdivisions[0]) * subdivisions[1] * subdivisions[2] * std::pow(8., context.refinements),
                 4096.);
      for (unsigned int d = 0; d < 3; ++d)
        if (!(upper[d] > lower[d]))
          throw InputError(context.where + ": 'Upper corner' must exceed 'Lower corner' in every component");
    }

    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *) const override
    {
      // Element sizes in geometric progression along each axis.
      std::vector<std::vector<double>> steps(3);
      for (unsigned int d = 0; d < 3; ++d)
        {
          double size = 1, total = 0;
          for (unsigned int i = 0; i < subdivisions[d]; ++i, size *= grading[d])
            {
              steps[d].push_back(size);
              total += size;
            }
          for (auto &h : steps[d])
            h *= (upper[d] - lower[d]) / total;
        }
      dealii::GridGenerator::subdivided_hyper_rectangle(tria, steps, lower, upper, /*colorize=*/true);
      tria.refine_global(refinements);
    }

  private:
    dealii::Point<3>          lower, upper;
    std::vector<unsigned int> subdivisions;
    dealii::Tensor<1, 3>      grading;
  };


  /** A circular cylinder along x, centred on the origin. */
  class Cylinder : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      declare_radius(prm);
      prm.declare_entry("Length", "1", Patterns::Double(0.), "Cylinder: length along x. Units: m.");
      prm.declare_entry("Axial subdivisions", "1", Patterns::Integer(1),
                        "Cylinder: elements along the axis before refinement. Units: none.");
      prm.declare_entry("Section refinements", "0", Patterns::Integer(0, 6),
                        "Cylinder: times every element is split into four across the axis (not along "
                        "it), besides 'Global refinements'. The hull has 4 x 2^(section + global "
                        "refinements) faces, their corners on the circle; the log gives the section's "
                        "area against pi r^2. Units: none.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const Context &context) override
    {
      radius              = prm.get_double("Radius");
      length              = prm.get_double("Length");
      axial_subdivisions  = prm.get_integer("Axial subdivisions");
      section_refinements = prm.get_integer("Section refinements");
      // deal.II's disk has five cells.
      check_size(context.where,
                 "'Axial subdivisions', 'Section refinements' and 'Global refinements'",
                 "elements",
                 5. * axial_subdivisions * std::pow(4., section_refinements) * std::pow(8., context.refinements),
                 4096.);
      if (!(radius > 0) || !(length > 0))
        throw InputError(context.where + ": cylinder needs positive 'Radius' and 'Length'");
    }

    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *names) const override
    {
      using namespace dealii;
      // The section: deal.II's disk of five cells refined along its circle
      // (its corners stay on it), then extruded along the axis (here z,
      // turned onto x below). Refinement happens here, in the section
      // (section and global refinements) and along the axis (global ones),
      // so the cells stay conforming.
      Triangulation<2> disk, flat;
      GridGenerator::hyper_ball(disk, Point<2>(), radius);
      disk.refine_global(section_refinements + refinements);
      GridGenerator::flatten_triangulation(disk, flat);
      const unsigned int along = axial_subdivisions * (1u << refinements);
      GridGenerator::extrude_triangulation(flat, along + 1, length, tria);
      const double half = 0.5 * length;
      GridTools::transform([half](const Point<3> &p) { return Point<3>(p[2] - half, p[0], p[1]); }, tria);
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const double x = cell->face(f)->center()[0];
              cell->face(f)->set_boundary_id(x < -half * (1. - 1e-12) ? 1 : x > half * (1. - 1e-12) ? 2 : 0);
            }
      if (names)
        {
          // The hull's faces are planar, their corners on the circle: the
          // section is a regular polygon.
          const double       n    = 4. * std::pow(2., section_refinements + refinements);
          const double       area = 0.5 * n * std::sin(2. * M_PI / n) / M_PI;
          std::ostringstream info;
          info << "cylinder section: a " << n << "-gon with its corners on the circle, area "
               << std::setprecision(4) << 100. * (1. - area) << " % below pi r^2";
          names->info = info.str();
        }
    }

  private:
    double       radius = 0, length = 0;
    unsigned int axial_subdivisions = 1, section_refinements = 0;
  };


  /** A ball centred on the origin. */
  class Sphere : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      declare_radius(prm);
    }

    void parse_parameters(dealii::ParameterHandler &prm, const Context &context) override
    {
      radius = prm.get_double("Radius");
      // deal.II's balanced ball has 32 cells.
      check_size(context.where, "'Global refinements'", "elements", 32. * std::pow(8., context.refinements), 4096.);
      if (!(radius > 0))
        throw InputError(context.where + ": sphere needs a positive 'Radius'");
    }

    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *) const override
    {
      dealii::GridGenerator::hyper_ball_balanced(tria, dealii::Point<3>(), radius);
      tria.refine_global(refinements);
    }

  private:
    double radius = 0;
  };


  ANVIL_REGISTER_MESH_SOURCE(Box, "box",
                             "a subdivided rectangular block between two corners; boundary ids 0..5 on "
                             "the faces x-, x+, y-, y+, z-, z+.")
  ANVIL_REGISTER_MESH_SOURCE(Cylinder, "cylinder",
                             "axis along x, centred on the origin before the offset; boundary ids 0 hull, "
                             "1 at x-, 2 at x+.")
  ANVIL_REGISTER_MESH_SOURCE(Sphere, "sphere",
                             "a ball of 'Radius' centred on the origin before the offset; boundary id 0.")
} // namespace anvil::MeshSources
