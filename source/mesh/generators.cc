/**
 * @file
 * Mesh sources built by deal.II's generators: 'box', 'cylinder', 'sphere'
 * and the graded 'ball' (MeshSources::Interface).
 */
#include <anvil/mesh/source.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <iomanip>
#include <sstream>

namespace anvil::MeshSources
{
  namespace
  {
    /** The largest ratio of element sizes that m elements, each r times
        the one before, may span: beyond it the smallest would set a step
        a million times too small, or have no volume at all. */
    constexpr double largest_size_ratio = 1e6;

    /** An InputError naming @p entry unless m elements graded by r stay
        within largest_size_ratio. */
    void check_grading(const std::string &where, const std::string &entry, const double r, const unsigned int m)
    {
      const double span = std::pow(std::max(r, 1. / r), double(m) - 1.);
      if (!(span <= largest_size_ratio))
        {
          std::ostringstream s;
          s.precision(3);
          s << where << ": '" << entry << "' = " << r << " over " << m << " elements makes the largest "
            << span << " times the smallest; at most " << largest_size_ratio
            << " (the smallest element sets the time step)";
          throw InputError(s.str());
        }
    }


    /** @p m element sizes in geometric progression, each @p r times the
        one before, that fill @p extent. */
    std::vector<double> graded_sizes(const unsigned int m, const double r, const double extent)
    {
      std::vector<double> h;
      double              size = 1, total = 0;
      for (unsigned int i = 0; i < m; ++i, size *= r)
        {
          h.push_back(size);
          total += size;
        }
      for (double &x : h)
        x *= extent / total;
      return h;
    }


    void declare_radius(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Radius", "0.5", dealii::Patterns::Double(0.), "Cylinder, sphere and ball: radius. Units: m.");
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
      for (unsigned int d = 0; d < 3; ++d)
        check_grading(context.where, "Grading", grading[d], subdivisions[d]);
    }

    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *) const override
    {
      // Element sizes in geometric progression along each axis.
      std::vector<std::vector<double>> steps(3);
      for (unsigned int d = 0; d < 3; ++d)
        steps[d] = graded_sizes(subdivisions[d], grading[d], upper[d] - lower[d]);
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


  /**
   * A ball graded towards its south pole (0, 0, -R), for an impact on it
   * there (Hertz): a block of hexahedra, graded, mapped onto the ball by
   * p -> R p |p|_inf / |p|_2, which takes each cube shell |p|_inf = c to
   * the sphere of radius c R. 'Part = quarter' keeps x, y >= 0 (symmetry
   * planes x = 0 and y = 0): the block [0, 1]^2 x [-1, 1] of n x n x 2n
   * cells; 'full' the block [-1, 1]^3 of 2n x 2n x 2n. Across the axis the
   * cells grow by 'Ball grading' from the axis outwards, along it by its
   * square root from the south pole to the north.
   */
  class GradedBall : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      declare_radius(prm);
      prm.declare_entry("Ball part", "full", Patterns::Selection("full|quarter"),
                        "Ball: 'full', or 'quarter' (x >= 0 and y >= 0, for a model with symmetry planes x = 0 "
                        "and y = 0; boundary ids 1 on x = 0, 2 on y = 0).");
      prm.declare_entry("Ball subdivisions", "8", Patterns::Integer(1, 512),
                        "Ball: elements along a radius across the axis (x and y); 2n from pole to pole along "
                        "z. Units: none.");
      prm.declare_entry("Ball grading", "1", Patterns::Double(0.),
                        "Ball: ratio of successive element sizes across the axis from the axis outwards; "
                        "along the axis its square root, from the south pole (0, 0, -R) to the north (> 1: "
                        "finest at the south pole and on the axis, where an impact from below meets the "
                        "ball). Units: none.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const Context &context) override
    {
      radius  = prm.get_double("Radius");
      quarter = prm.get("Ball part") == "quarter";
      n       = prm.get_integer("Ball subdivisions");
      grading = prm.get_double("Ball grading");
      check_size(context.where, "'Ball subdivisions' and 'Global refinements'", "elements",
                 (quarter ? 2. : 8.) * double(n) * n * n * std::pow(8., context.refinements), 4096.);
      if (!(radius > 0))
        throw InputError(context.where + ": the ball needs a positive 'Radius'");
      if (!(grading > 0))
        throw InputError(context.where + ": 'Ball grading' must be positive");
      check_grading(context.where, "Ball grading", grading, n);
      check_grading(context.where, "Ball grading", std::sqrt(grading), 2 * n);
    }

    void create(dealii::Triangulation<3> &tria, const unsigned int refinements, MeshNames *) const override
    {
      using namespace dealii;
      // Across the axis from it outwards (mirrored for the whole ball);
      // along it from the south pole.
      const std::vector<double> out = graded_sizes(n, grading, 1.);
      std::vector<double>       across(out);
      if (!quarter)
        across.insert(across.begin(), out.rbegin(), out.rend());
      const std::vector<double> along = graded_sizes(2 * n, std::sqrt(grading), 2.);
      const double lo = quarter ? 0. : -1.;
      GridGenerator::subdivided_hyper_rectangle(tria, {across, across, along}, Point<3>(lo, lo, -1.),
                                                Point<3>(1., 1., 1.), /*colorize=*/false);
      const double R = radius;
      GridTools::transform(
        [R](const Point<3> &p) {
          const double norm = p.norm();
          const double inf  = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
          return norm > 0 ? Point<3>(p * (R * inf / norm)) : p;
        },
        tria);
      // Boundary ids: 0 on the sphere, 1 and 2 on the symmetry planes.
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const Point<3> c = cell->face(f)->center();
              cell->face(f)->set_boundary_id(quarter && std::abs(c[0]) < 1e-12 * R ? 1 :
                                             quarter && std::abs(c[1]) < 1e-12 * R ? 2 :
                                                                                     0);
            }
      tria.refine_global(refinements);
    }

  private:
    double       radius = 0, grading = 1;
    bool         quarter = false;
    unsigned int n       = 8;
  };


  ANVIL_REGISTER_MESH_SOURCE(Box, "box",
                             "a subdivided rectangular block between two corners; boundary ids 0..5 on "
                             "the faces x-, x+, y-, y+, z-, z+.")
  ANVIL_REGISTER_MESH_SOURCE(Cylinder, "cylinder",
                             "axis along x, centred on the origin before the offset; boundary ids 0 hull, "
                             "1 at x-, 2 at x+.")
  ANVIL_REGISTER_MESH_SOURCE(GradedBall, "ball",
                             "a ball of 'Radius' centred on the origin before the offset, graded towards its "
                             "south pole, whole or a quarter; boundary id 0 on the sphere.")
  ANVIL_REGISTER_MESH_SOURCE(Sphere, "sphere",
                             "a ball of 'Radius' centred on the origin before the offset; boundary id 0.")
} // namespace anvil::MeshSources
