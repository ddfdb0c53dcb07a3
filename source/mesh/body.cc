#include <anvil/mesh/body.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <deal.II/grid/tria_description.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace anvil
{


  void Body::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.enter_subsection("Mesh");
    {
      prm.declare_entry(
        "Source",
        "box",
        Patterns::Selection("box|cylinder|sphere|file"),
        "Where the mesh comes from: 'box' (a subdivided rectangular block "
        "between two corners; boundary ids 0..5 on the faces x-, x+, y-, "
        "y+, z-, z+), 'cylinder' (axis along x, centred on the origin "
        "before the offset; boundary ids 0 hull, 1 at x-, 2 at x+), "
        "'sphere' (a ball of 'Radius' centred on the origin before the "
        "offset; boundary id 0), or "
        "'file' (ABAQUS .inp with parts, instances, sets and surfaces, or "
        "ASCII Gmsh .msh 2.2/4.1 with physical groups; named surfaces "
        "become boundary ids, see 'Region').");
      prm.declare_entry("Lower corner",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Box: lowest corner. Units: m.");
      prm.declare_entry("Upper corner",
                        "1, 1, 1",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Box: highest corner. Units: m.");
      prm.declare_entry("Subdivisions",
                        "1, 1, 1",
                        Patterns::List(Patterns::Integer(1), 3, 3),
                        "Box: number of elements along x, y, z before "
                        "refinement. Units: none.");
      prm.declare_entry("Grading",
                        "1, 1, 1",
                        Patterns::List(Patterns::Double(0.), 3, 3),
                        "Box: ratio of successive element sizes along x, y, "
                        "z, from the lower to the upper corner (a geometric "
                        "mesh bias; 1: uniform, < 1: finer towards the upper "
                        "corner). Units: none.");
      prm.declare_entry("Radius",
                        "0.5",
                        Patterns::Double(0.),
                        "Cylinder: radius. Units: m.");
      prm.declare_entry("Length",
                        "1",
                        Patterns::Double(0.),
                        "Cylinder: length along x. Units: m.");
      prm.declare_entry("Axial subdivisions",
                        "1",
                        Patterns::Integer(1),
                        "Cylinder: elements along the axis before "
                        "refinement. Units: none.");
      prm.declare_entry("Section refinements",
                        "0",
                        Patterns::Integer(0, 6),
                        "Cylinder: times every element is split into four "
                        "across the axis (not along it), besides 'Global "
                        "refinements'. The hull has 4 x 2^(section + global "
                        "refinements) faces, their corners on the circle; the "
                        "log gives the section's area against pi r^2. Units: "
                        "none.");
      prm.declare_entry("File name",
                        "",
                        Patterns::Anything(),
                        "File: mesh file (.msh or .inp), relative to the "
                        "scene file's directory.");
      prm.declare_entry("Region",
                        "",
                        Patterns::Anything(),
                        "File: the cells this body takes, as a comma-separated "
                        "list of names the file gives to groups of cells "
                        "(ABAQUS: instances, parts, element sets, 'INSTANCE.SET'; "
                        "Gmsh: physical volumes by name or number); matched "
                        "without regard to case. Empty: every cell of the file.");
      prm.declare_entry("Scale",
                        "1",
                        Patterns::Double(0.),
                        "File: factor applied to the coordinates read "
                        "(e.g. 0.001 for a mesh in mm). Units: none.");
      prm.declare_entry("Offset",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Translation applied to the generated or read "
                        "mesh. Units: m.");
      prm.declare_entry("Global refinements",
                        "0",
                        Patterns::Integer(0, 8),
                        "Times every element is split into eight. "
                        "Units: none.");
    }
    prm.leave_subsection();

    prm.enter_subsection("Material");
    MaterialModel::declare_parameters(prm);
    prm.leave_subsection();

    prm.declare_entry("Formulation",
                      "updated Lagrangian",
                      Patterns::Selection("updated Lagrangian|total Lagrangian"),
                      "Lagrangian description (seed section 3.5): 'updated "
                      "Lagrangian' (Cauchy stress, Jaumann rate) or 'total "
                      "Lagrangian' (second Piola-Kirchhoff stress, "
                      "Green-Lagrange strain). Updated Lagrangian is the "
                      "default: the accuracy study found the two within 1.5 % "
                      "of each other on every case, total Lagrangian at 1.7 to "
                      "2.6 times the cost per element-cycle (doc/accuracy.md).");
    prm.declare_entry("Integration",
                      "one point",
                      Patterns::Selection("one point|full"),
                      "Element integration: 'one point' (centroid, seed "
                      "Eq. (39), with hourglass control) or 'full' (2x2x2 "
                      "Gauss). One point is the default: full integration "
                      "costs 6 to 9 times as much per element-cycle and "
                      "locks in plastic flow (the Taylor bar's foot 21 % too "
                      "small, doc/accuracy.md).");
    prm.enter_subsection("Hourglass control");
    prm.declare_entry("Type",
                      "viscous",
                      Patterns::Selection("viscous|stiffness|none"),
                      "Flanagan-Belytschko hourglass control of one-point "
                      "elements: 'viscous' (seed Eq. (44)), 'stiffness', or "
                      "'none'. Viscous is the default: in impact its "
                      "force fades with the motion, while the stiffness form "
                      "holds the plastic foot of the Taylor bar back (25 % "
                      "too small, doc/accuracy.md).");
    prm.declare_entry("Coefficient",
                      "0.1",
                      Patterns::Double(0., 1.),
                      "Q_hg of seed Eq. (44), typically 0.05-0.15; for the "
                      "stiffness form the force is Q_hg (lambda + 2 mu) "
                      "V^(1/3) / 4 per unit hourglass displacement. 0.1 (LS-DYNA's "
                      "default): 0.03 and 0.3 moved the accuracy study's "
                      "results by a few percent either way, and 0.3 bounds "
                      "the step (dt <= V^(1/3) / (8 Q_hg c)): 1.5 times the "
                      "steps (doc/accuracy.md). Units: none.");
    prm.leave_subsection();
    prm.enter_subsection("Bulk viscosity");
    prm.declare_entry("Linear coefficient",
                      "0.06",
                      Patterns::Double(0., 10.),
                      "b_1 of the artificial bulk viscosity q = rho L (b_2^2 L "
                      "(tr D)^2 - b_1 c tr D), applied in compression (tr D < 0) "
                      "and booked as viscous energy (ABAQUS/Explicit's default "
                      "0.06; LS-DYNA's Q2). 0 together with the quadratic "
                      "coefficient: off. Units: none.");
    prm.declare_entry("Quadratic coefficient",
                      "1.2",
                      Patterns::Double(0., 10.),
                      "b_2 of the bulk viscosity: smears a shock front over a "
                      "few elements (ABAQUS/Explicit's default 1.2; LS-DYNA's "
                      "Q1 = 1.5). On by default: switching it off saved 5 % "
                      "of the steps and changed the accuracy study's results "
                      "by at most 2 %, but it damps the ringing of cracked "
                      "concrete (doc/accuracy.md). Units: none.");
    prm.leave_subsection();
    prm.declare_entry("Initial velocity",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Initial velocity of every node of the body (of the "
                      "centre of mass of a rigid body). Units: m/s.");
    prm.enter_subsection("Imperfection");
    prm.declare_entry("Lower corner",
                      "",
                      Patterns::Anything(),
                      "Lower corner of a box (reference coordinates) whose "
                      "elements (by their centroid) get weaker material, to "
                      "place where a crack or crushing band forms. Empty: no "
                      "imperfection. Only models with strengths (concrete "
                      "damaged plasticity) accept one. Units: m.");
    prm.declare_entry("Upper corner",
                      "",
                      Patterns::Anything(),
                      "Upper corner of the imperfection box. Units: m.");
    prm.declare_entry("Strength factor",
                      "0.95",
                      Patterns::Double(0.),
                      "Factor on the tensile and compressive strength curves "
                      "inside the box, 0 < factor <= 1. Units: none.");
    prm.leave_subsection();
    prm.enter_subsection("Full integration region");
    prm.declare_entry("Lower corner",
                      "",
                      Patterns::Anything(),
                      "Lower corner of a box (reference coordinates) whose "
                      "elements (by their centroid) use full 2x2x2 integration "
                      "in a body of one-point elements: where a concentrated "
                      "load (a contact under a small nose, a support) would "
                      "excite hourglass modes of one-point elements. Empty: "
                      "none. Units: m.");
    prm.declare_entry("Upper corner",
                      "",
                      Patterns::Anything(),
                      "Upper corner of the full integration box. Units: m.");
    prm.leave_subsection();
    prm.enter_subsection("Refinement region");
    prm.declare_entry("Lower corner",
                      "",
                      Patterns::Anything(),
                      "Lower corner of a box (reference coordinates) whose "
                      "elements (by their centroid) are halved in every "
                      "direction 'Levels' times, once the body's mesh is built: "
                      "finer elements where the scene needs them (under an "
                      "impactor), the body's own size elsewhere. Where a refined "
                      "element meets a coarser one, the nodes in the middle of "
                      "the coarse face or edge hang: they follow the coarse "
                      "face (doc/adaptivity.md). Empty: none. Units: m.");
    prm.declare_entry("Upper corner",
                      "",
                      Patterns::Anything(),
                      "Upper corner of the refinement box. Units: m.");
    prm.declare_entry("Near body",
                      "",
                      Patterns::Anything(),
                      "Also refine the elements whose reference centroid lies "
                      "within 'Distance' of this other body's box (the "
                      "smallest box around its reference mesh): ahead of an "
                      "impactor, before the wave arrives. Empty: none. Units: "
                      "none.");
    prm.declare_entry("Distance",
                      "0",
                      Patterns::Double(0.),
                      "The reach of 'Near body' (the gap to the impactor and "
                      "the depth to refine). Units: m.");
    prm.declare_entry("Levels",
                      "1",
                      Patterns::Integer(0, 4),
                      "How many times the elements in the region (the box and "
                      "the reach of 'Near body') are halved; 0: none. Each "
                      "level refines the elements of the last whose centroid "
                      "is in the region; neighbours differ by one level at "
                      "most, so a ring of elements outside it may be refined "
                      "too. Units: none.");
    prm.leave_subsection();
    RigidBody::Motion::declare_parameters(prm);
  }


  namespace
  {
    // A box of the current subsection ('Lower corner', 'Upper corner'):
    // false when both are empty.
    bool parse_box(dealii::ParameterHandler &prm,
                   const std::string        &where,
                   dealii::Point<3>         &lower,
                   dealii::Point<3>         &upper)
    {
      const std::string lo = dealii::Utilities::trim(prm.get("Lower corner"));
      const std::string hi = dealii::Utilities::trim(prm.get("Upper corner"));
      if (lo.empty() && hi.empty())
        return false;
      if (lo.empty() || hi.empty())
        throw InputError(where + "give both 'Lower corner' and 'Upper corner', or neither");
      const std::string subsection = where.substr(0, where.size() - 2); // without ": "
      lower = dealii::Point<3>(three_numbers(lo, "Lower corner", subsection));
      upper = dealii::Point<3>(three_numbers(hi, "Upper corner", subsection));
      for (unsigned int d = 0; d < 3; ++d)
        if (!(lower[d] < upper[d]))
          throw InputError(where + "'Lower corner' must lie below 'Upper corner' in every "
                                   "coordinate");
      return true;
    }


    bool inside(const dealii::Point<3> &p, const dealii::Point<3> &lo, const dealii::Point<3> &hi)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (p[d] < lo[d] || p[d] > hi[d])
          return false;
      return true;
    }
  } // namespace


  Element::Integration Body::integration_at(const dealii::Point<3> &centroid) const
  {
    return has_full_region && inside(centroid, full_region_lower, full_region_upper) ?
             Element::Integration::full :
             integration;
  }


  bool Body::in_refinement_region(const dealii::Point<3> &centroid,
                                  const dealii::Point<3> &near_lower,
                                  const dealii::Point<3> &near_upper) const
  {
    if (refinement_levels == 0)
      return false;
    if (has_refinement_box && inside(centroid, refinement_lower, refinement_upper))
      return true;
    if (refinement_near.empty())
      return false;
    double d2 = 0;
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double out = std::max({near_lower[d] - centroid[d], 0., centroid[d] - near_upper[d]});
        d2 += out * out;
      }
    return d2 <= refinement_distance * refinement_distance;
  }


  double Body::strength_factor(const dealii::Point<3> &centroid) const
  {
    return has_imperfection && inside(centroid, imperfection_lower, imperfection_upper) ?
             imperfection_factor :
             1.;
  }


  void Body::parse_parameters(dealii::ParameterHandler &prm,
                              const std::string        &body_name,
                              const std::string        &scene_directory)
  {
    name = body_name;
    prm.enter_subsection("Mesh");
    {
      const std::string where = "subsection 'Body " + name + "/Mesh'";
      mesh_source             = prm.get("Source");
      lower       = dealii::Point<3>(three_numbers(prm.get("Lower corner"), "Lower corner", where));
      upper       = dealii::Point<3>(three_numbers(prm.get("Upper corner"), "Upper corner", where));
      subdivisions.clear();
      for (const auto &s :
           dealii::Utilities::split_string_list(prm.get("Subdivisions")))
        subdivisions.push_back(dealii::Utilities::string_to_int(s));
      grading            = three_numbers(prm.get("Grading"), "Grading", where);
      radius             = prm.get_double("Radius");
      length             = prm.get_double("Length");
      axial_subdivisions = prm.get_integer("Axial subdivisions");
      section_refinements = prm.get_integer("Section refinements");
      if (mesh_source != "cylinder" && section_refinements > 0)
        throw InputError(where + ": 'Section refinements' needs 'Source = cylinder'");
      file_name          = prm.get("File name");
      if (!file_name.empty() && file_name[0] != '/')
        file_name = scene_directory + "/" + file_name;
      region.clear();
      for (const auto &r : dealii::Utilities::split_string_list(prm.get("Region")))
        if (!r.empty())
          region.push_back(MeshFile::key(r));
      if (mesh_source != "file" && !region.empty())
        throw InputError(where + ": 'Region' needs 'Source = file'");
      scale       = prm.get_double("Scale");
      offset      = three_numbers(prm.get("Offset"), "Offset", where);
      refinements = prm.get_integer("Global refinements");
    }
    prm.leave_subsection();

    // About 4 kB per hexahedron: deal.II's cell, vertices and degrees of
    // freedom, and Anvil's state.
    const double fine = std::pow(8., refinements);
    check_size("subsection 'Body " + name + "/Mesh'",
               mesh_source == "box" ? "'Subdivisions' and 'Global refinements'" :
                                      "'Axial subdivisions' and 'Global refinements'",
               "elements",
               (mesh_source == "box" ? double(subdivisions[0]) * subdivisions[1] * subdivisions[2] :
                                       std::max(1., double(axial_subdivisions)) * 12. *
                                         std::pow(4., section_refinements)) *
                 fine,
               4096.);
    if (mesh_source == "box")
      for (unsigned int d = 0; d < 3; ++d)
        if (!(upper[d] > lower[d]))
          throw InputError("subsection 'Body " + name +
                           "/Mesh': 'Upper corner' must exceed 'Lower "
                           "corner' in every component");
    if (mesh_source == "sphere" && radius <= 0)
      throw InputError("subsection 'Body " + name + "/Mesh': sphere needs a positive 'Radius'");
    if (mesh_source == "cylinder" && (radius <= 0 || length <= 0))
      throw InputError("subsection 'Body " + name +
                       "/Mesh': cylinder needs positive 'Radius' and 'Length'");
    if (mesh_source == "file")
      {
        if (file_name.empty())
          throw InputError("subsection 'Body " + name +
                           "/Mesh': 'Source = file' needs 'File name'");
        if (!std::ifstream(file_name))
          throw InputError("subsection 'Body " + name + "/Mesh': mesh file '" +
                           file_name + "' cannot be opened");
      }

    prm.enter_subsection("Material");
    material                     = MaterialModel::create(prm);
    const std::string model_name = prm.get("Model");
    prm.leave_subsection();

    formulation = prm.get("Formulation") == "total Lagrangian" ?
                    Formulation::total_lagrangian :
                    Formulation::updated_lagrangian;
    if (!material->supports(formulation))
      throw InputError("subsection 'Body " + name + "': material model '" +
                       model_name + "' does not support the " +
                       to_string(formulation) + " formulation");
    integration = prm.get("Integration") == "full" ?
                    Element::Integration::full :
                    Element::Integration::one_point;
    prm.enter_subsection("Hourglass control");
    {
      const std::string t = prm.get("Type");
      hourglass = (t == "viscous"   ? Element::HourglassType::viscous :
                   t == "stiffness" ? Element::HourglassType::stiffness :
                                      Element::HourglassType::none);
      hourglass_coefficient = prm.get_double("Coefficient");
    }
    prm.leave_subsection();
    prm.enter_subsection("Bulk viscosity");
    bulk_linear    = prm.get_double("Linear coefficient");
    bulk_quadratic = prm.get_double("Quadratic coefficient");
    prm.leave_subsection();
    initial_velocity =
      three_numbers(prm.get("Initial velocity"), "Initial velocity", "subsection 'Body " + name + "'");
    prm.enter_subsection("Imperfection");
    {
      has_imperfection = parse_box(prm,
                                   "subsection 'Body " + name + "/Imperfection': ",
                                   imperfection_lower,
                                   imperfection_upper);
      if (has_imperfection)
        {
          const std::string where = "subsection 'Body " + name + "/Imperfection': ";
          imperfection_factor = prm.get_double("Strength factor");
          if (!(imperfection_factor > 0) || imperfection_factor > 1)
            throw InputError(where + "'Strength factor' must satisfy 0 < factor <= 1");
          if (!material->accepts_strength_factor())
            throw InputError(where + "the material model '" + model_name +
                             "' has no strengths to weaken (allowed with: "
                             "concrete damaged plasticity)");
        }
    }
    prm.leave_subsection();
    prm.enter_subsection("Full integration region");
    has_full_region = parse_box(prm,
                                "subsection 'Body " + name + "/Full integration region': ",
                                full_region_lower,
                                full_region_upper);
    prm.leave_subsection();
    prm.enter_subsection("Refinement region");
    refinement_levels = 0;
    has_refinement_box =
      parse_box(prm, "subsection 'Body " + name + "/Refinement region': ", refinement_lower, refinement_upper);
    refinement_near     = dealii::Utilities::trim(prm.get("Near body"));
    refinement_distance = prm.get_double("Distance");
    if (!refinement_near.empty() && !(refinement_distance > 0))
      throw InputError("subsection 'Body " + name + "/Refinement region': 'Near body' needs a 'Distance' > 0");
    if (refinement_near == name)
      throw InputError("subsection 'Body " + name + "/Refinement region': 'Near body' names the body itself "
                       "(use the box)");
    if (has_refinement_box || !refinement_near.empty())
      refinement_levels = prm.get_integer("Levels");
    prm.leave_subsection();
    if (refinement_levels > 0 && material->is_rigid())
      throw InputError("subsection 'Body " + name + "/Refinement region': a rigid body moves as one and needs no "
                       "finer elements (allowed on deformable bodies)");
    rigid.parse_parameters(prm, name);
    if (!material->is_rigid() && rigid.shape.type != RigidBody::Shape::Type::mesh)
      throw InputError("subsection 'Body " + name + "/Rigid body': a 'Contact shape' "
                       "other than mesh needs the material 'rigid'");
  }


  void Body::create_mesh(dealii::Triangulation<3> &tria, MeshNames *names) const
  {
    using namespace dealii;
    if (mesh_source == "box")
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
        GridGenerator::subdivided_hyper_rectangle(tria, steps, lower, upper, /*colorize=*/true);
      }
    else if (mesh_source == "sphere")
      GridGenerator::hyper_ball_balanced(tria, Point<3>(), radius);
    else if (mesh_source == "cylinder")
      {
        // The section: deal.II's disk of five cells refined along its
        // circle (its corners stay on it), then extruded along the axis
        // (here z, turned onto x below). Refinement happens here, in the
        // section (section and global refinements) and along the axis
        // (global ones), so the cells stay conforming.
        Triangulation<2> disk, flat;
        GridGenerator::hyper_ball(disk, Point<2>(), radius);
        disk.refine_global(section_refinements + refinements);
        GridGenerator::flatten_triangulation(disk, flat);
        const unsigned int along = axial_subdivisions * (1u << refinements);
        GridGenerator::extrude_triangulation(flat, along + 1, length, tria);
        const double half = 0.5 * length;
        GridTools::transform([half](const Point<3> &p) { return Point<3>(p[2] - half, p[0], p[1]); },
                             tria);
        for (const auto &cell : tria.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const double x = cell->face(f)->center()[0];
                cell->face(f)->set_boundary_id(x < -half * (1. - 1e-12) ? 1 :
                                               x > half * (1. - 1e-12)  ? 2 :
                                                                          0);
              }
        if (names)
          {
            // The hull's faces are planar, their corners on the circle: the
            // section is a regular polygon.
            const double n    = 4. * std::pow(2., section_refinements + refinements);
            const double area = 0.5 * n * std::sin(2. * M_PI / n) / M_PI;
            std::ostringstream info;
            info << "cylinder section: a " << n << "-gon with its corners on the circle, area "
                 << std::setprecision(4) << 100. * (1. - area) << " % below pi r^2";
            names->info = info.str();
          }
      }
    else
      create_mesh_from_file(tria, names);
    if (mesh_source != "cylinder") // refined in the section and along the axis above
      tria.refine_global(refinements);
    if (offset.norm() > 0)
      GridTools::shift(offset, tria);
    if (names)
      for (auto &set : names->node_sets)
        for (auto &x : set.second)
          x = x * scale + offset;
  }


  // The cells of the file's 'Region' (all if empty) become this body's
  // mesh, with the file's surfaces as boundary ids on their faces that lie
  // on its boundary.
  void Body::create_mesh_from_file(dealii::Triangulation<3> &tria, MeshNames *names) const
  {
    using namespace dealii;
    const MeshFile::Contents file  = MeshFile::read(file_name);
    const std::string        where = "subsection 'Body " + name + "/Mesh': ";
    std::vector<bool>        take(file.cells.size(), region.empty());
    for (const auto &r : region)
      {
        const auto set = file.cell_sets.find(r);
        if (set == file.cell_sets.end())
          throw InputError(where + "'Region' names '" + printable_excerpt(r) +
                           "', which mesh file '" + file_name +
                           "' does not define (its groups of cells: " +
                           MeshFile::names_of(file.cell_sets) + ")");
        for (const unsigned int c : set->second)
          take[c] = true;
      }

    std::vector<unsigned int> index(file.vertices.size(), numbers::invalid_unsigned_int);
    std::vector<Point<3>>     vertices;
    std::vector<CellData<3>>  cells;
    // Faces of the cells taken, by their sorted vertices: a face two cells
    // share is interior and keeps no boundary id.
    std::map<std::array<unsigned int, 4>, unsigned int> face_count;
    auto sorted = [](std::array<unsigned int, 4> v) {
      std::sort(v.begin(), v.end());
      return v;
    };
    for (unsigned int c = 0; c < file.cells.size(); ++c)
      if (take[c])
        {
          CellData<3> cell(8);
          for (unsigned int v = 0; v < 8; ++v)
            {
              const unsigned int g = file.cells[c][v];
              if (index[g] == numbers::invalid_unsigned_int)
                {
                  index[g] = vertices.size();
                  vertices.push_back(file.vertices[g]);
                }
              cell.vertices[v] = index[g];
            }
          cells.push_back(cell);
          for (const unsigned int f : GeometryInfo<3>::face_indices())
            {
              std::array<unsigned int, 4> face;
              for (unsigned int v = 0; v < 4; ++v)
                face[v] = file.cells[c][GeometryInfo<3>::face_to_cell_vertices(f, v)];
              ++face_count[sorted(face)];
            }
        }
    std::map<std::array<unsigned int, 4>, CellData<2>> boundary;
    std::set<unsigned int>                            ids_on_body;
    for (const auto &face : file.faces)
      if (take[face.cell] && face_count[sorted(face.vertices)] == 1)
        {
          CellData<2> quad(4);
          for (unsigned int v = 0; v < 4; ++v)
            quad.vertices[v] = index[face.vertices[v]];
          quad.boundary_id             = face.boundary_id;
          boundary[sorted(face.vertices)] = quad;
          ids_on_body.insert(face.boundary_id);
        }
    SubCellData subcell;
    for (const auto &b : boundary)
      subcell.boundary_quads.push_back(b.second);

    try
      {
        // Every corner of every cell must have a positive Jacobian: a cell
        // written the other way round (all eight negative) is turned, a
        // flat or twisted one (mixed signs, or zero) would have no mass or
        // a negative volume.
        std::vector<unsigned int> taken;
        for (unsigned int c = 0; c < file.cells.size(); ++c)
          if (take[c])
            taken.push_back(c);
        auto corner_signs = [&](const CellData<3> &cell, unsigned int &positive) {
          positive = 0;
          for (unsigned int corner = 0; corner < 8; ++corner)
            {
              Tensor<2, 3> J;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const unsigned int bit  = 1u << d;
                  const Tensor<1, 3> edge = vertices[cell.vertices[corner ^ bit]] -
                                            vertices[cell.vertices[corner]];
                  for (unsigned int e = 0; e < 3; ++e)
                    J[e][d] = (corner & bit) ? -edge[e] : edge[e];
                }
              const double det = determinant(J);
              if (det > 0)
                ++positive;
              else if (!(det < 0))
                return false;
            }
          return true;
        };
        for (unsigned int i = 0; i < cells.size(); ++i)
          {
            unsigned int positive = 0;
            bool         nonzero  = corner_signs(cells[i], positive);
            if (nonzero && positive == 0)
              {
                // Mirrored: swap the two ends along the cell's x.
                for (unsigned int v = 0; v < 8; v += 2)
                  std::swap(cells[i].vertices[v], cells[i].vertices[v + 1]);
                nonzero = corner_signs(cells[i], positive);
              }
            if (!nonzero || positive != 8)
              throw InputError("mesh file '" + file_name + "': element " +
                               std::to_string(file.labels.empty() ? long(taken[i]) :
                                                                    file.labels[taken[i]]) +
                               " (body '" + name + "') is flat or twisted: the Jacobian "
                               "is not positive at all its corners");
          }
        GridTools::consistently_order_cells(cells);
        tria.create_triangulation(vertices, cells, subcell);
      }
    catch (const ExceptionBase &e)
      {
        throw InputError("mesh file '" + file_name + "' (body '" + name +
                         "'): not a valid hexahedral mesh: " + one_line_message(e).substr(0, 300));
      }
    if (scale != 1.)
      GridTools::scale(scale, tria);

    if (!names)
      return;
    for (const auto &s : file.surfaces)
      if (ids_on_body.count(s.second))
        names->surfaces[s.first] = s.second;
    for (const auto &s : file.node_sets)
      {
        std::vector<Point<3>> positions;
        for (const unsigned int v : s.second)
          if (index[v] != numbers::invalid_unsigned_int)
            positions.push_back(file.vertices[v]);
        if (!positions.empty())
          names->node_sets[s.first] = positions;
      }
    names->note.clear();
    if (!file.skipped.empty())
      names->note = "mesh file '" + file_name + "': skipped " + file.skipped +
                    " (a scene takes from a mesh file its mesh, sets and surfaces only)";
    if (region.empty() && file.regions.size() > 1)
      {
        std::string list;
        for (const auto &r : file.regions)
          list += (list.empty() ? "" : ", ") + r;
        names->note += std::string(names->note.empty() ? "" : "; ") + "mesh file '" + file_name +
                       "' holds " + std::to_string(file.regions.size()) + " regions (" +
                       printable_excerpt(list) +
                       "), all taken as this one body ('Region' takes one)";
      }
  }
} // namespace anvil
