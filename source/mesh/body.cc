#include <anvil/mesh/body.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/grid/grid_tools.h>

#include <algorithm>

namespace anvil
{


  void Body::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.enter_subsection("Mesh");
    {
      prm.declare_entry("Source",
                        "box",
                        Patterns::Selection(MeshSources::Registry::names()),
                        MeshSources::Registry::documentation("Where the mesh comes from:"));
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
      MeshSources::Registry::declare_parameters(prm, false);
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
                      "elements (by the centroid of the element as built: its "
                      "children keep its integration) use full 2x2x2 integration "
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
    prm.declare_entry("Indicator",
                      "",
                      Patterns::Anything(),
                      "During the run ('Simulation/Adapt interval'), also refine "
                      "the elements where this history variable of the body's "
                      "material (a name its output shows: damage, "
                      "effective_plastic_strain, strain_rate, ...) exceeds "
                      "'Indicator threshold' at any point, or, with "
                      "'contact_pressure', where a node of the element carries a "
                      "contact force above the threshold times the element's "
                      "face area (V^(2/3)). Empty: none. Units: none.");
    prm.declare_entry("Indicator threshold",
                      "0",
                      Patterns::Double(),
                      "The value of 'Indicator' above which an element is "
                      "refined (and below which it may be coarsened). Units: "
                      "those of the variable (contact_pressure: Pa).");
    prm.leave_subsection();
    prm.enter_subsection("Refinement region 2");
    prm.declare_entry("Lower corner",
                      "",
                      Patterns::Anything(),
                      "A second region with its own 'Levels', usually finer "
                      "inside the first (the nose of an impactor inside the "
                      "struck part of a member): the lower corner of its box "
                      "(reference coordinates, by element centroid). An element "
                      "is halved up to the largest 'Levels' of the regions that "
                      "hold for it, at the start and during the run. Empty: none. "
                      "Units: m.");
    prm.declare_entry("Upper corner", "", Patterns::Anything(), "Upper corner of the second box. Units: m.");
    prm.declare_entry("Near body",
                      "",
                      Patterns::Anything(),
                      "As in 'Refinement region': also the elements within "
                      "'Distance' of this body's box (during the run, its "
                      "current box). Empty: none. Units: none.");
    prm.declare_entry("Distance", "0", Patterns::Double(0.), "The reach of 'Near body'. Units: m.");
    prm.declare_entry("Levels", "2", Patterns::Integer(0, 4), "How many times the second region halves its "
                      "elements. Units: none.");
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


  bool Body::Region::holds(const dealii::Point<3>                  &reference,
                           const dealii::Point<3>                  &current,
                           const std::array<dealii::Point<3>, 2> &near_box) const
  {
    if (levels == 0)
      return false;
    if (has_box && inside(reference, lower, upper))
      return true;
    // Within 'Distance' of the 'Near body''s box (an empty box, lower
    // above upper: none).
    if (near.empty() || !(near_box[0][0] <= near_box[1][0]))
      return false;
    double d2 = 0;
    for (unsigned int d = 0; d < 3; ++d)
      {
        const double out = std::max({near_box[0][d] - current[d], 0., current[d] - near_box[1][d]});
        d2 += out * out;
      }
    return d2 <= distance * distance;
  }


  void Body::Region::parse(dealii::ParameterHandler &prm, const std::string &where, const std::string &body)
  {
    has_box  = parse_box(prm, where, lower, upper);
    near     = dealii::Utilities::trim(prm.get("Near body"));
    distance = prm.get_double("Distance");
    if (!near.empty() && !(distance > 0))
      throw InputError(where + "'Near body' needs a 'Distance' > 0");
    if (near == body)
      throw InputError(where + "'Near body' names the body itself (use the box)");
    levels = 0;
  }


  std::vector<std::array<std::array<dealii::Point<3>, 2>, 2>>
  Body::near_boxes(const std::vector<Body>             &bodies,
                   const std::vector<dealii::Point<3>> &lower,
                   const std::vector<dealii::Point<3>> &upper)
  {
    const dealii::Point<3> none(1e300, 1e300, 1e300), none_upper(-1e300, -1e300, -1e300);
    std::vector<std::array<std::array<dealii::Point<3>, 2>, 2>> near(bodies.size());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      for (unsigned int r = 0; r < 2; ++r)
        {
          const std::string &other = (r == 0 ? bodies[b].first_region : bodies[b].second_region).near;
          near[b][r]               = {{none, none_upper}};
          for (unsigned int o = 0; o < bodies.size(); ++o)
            if (!other.empty() && bodies[o].name == other)
              near[b][r] = {{lower[o], upper[o]}};
        }
    return near;
  }


  unsigned int Body::wanted_levels(const dealii::Point<3>                               &reference,
                                   const dealii::Point<3>                               &current,
                                   const std::array<std::array<dealii::Point<3>, 2>, 2> &near,
                                   const double                                          indicator,
                                   const bool                                            with_indicator) const
  {
    unsigned int levels = 0;
    if (first_region.holds(reference, current, near[0]) ||
        (with_indicator && first_region.levels > 0 && indicator_index != -1 && indicator > indicator_threshold))
      levels = first_region.levels;
    if (second_region.levels > levels && second_region.holds(reference, current, near[1]))
      levels = second_region.levels;
    return levels;
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
      const std::string where  = "subsection 'Body " + name + "/Mesh'";
      const std::string source = prm.get("Source");
      offset                   = three_numbers(prm.get("Offset"), "Offset", where);
      refinements              = prm.get_integer("Global refinements");
      ignored_entries = MeshSources::foreign_entries(prm, source, {"Source", "Offset", "Global refinements"});
      mesh_source = MeshSources::Registry::get(source, where + ": entry 'Source'").create();
      mesh_source->parse_parameters(prm, {where, name, scene_directory, refinements});
    }
    prm.leave_subsection();

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
    first_region.parse(prm, "subsection 'Body " + name + "/Refinement region': ", name);
    const std::string indicator = dealii::Utilities::trim(prm.get("Indicator"));
    indicator_index             = -1;
    indicator_threshold         = prm.get_double("Indicator threshold");
    if (indicator == "contact_pressure")
      indicator_index = contact_pressure_indicator;
    else if (!indicator.empty())
      {
        const auto names = material->history_names();
        const auto at    = std::find(names.begin(), names.end(), indicator);
        if (at == names.end())
          {
            std::string known;
            for (const auto &n : names)
              if (!n.empty())
                known += (known.empty() ? "" : ", ") + n;
            throw InputError("subsection 'Body " + name + "/Refinement region': 'Indicator' names '" +
                             printable_excerpt(indicator) + "', which the body's material does not have (its " +
                             "variables: " + (known.empty() ? std::string("none") : known) +
                             "; or contact_pressure)");
          }
        indicator_index = at - names.begin();
      }
    if (first_region.has_box || !first_region.near.empty() || indicator_index != -1)
      first_region.levels = prm.get_integer("Levels");
    prm.leave_subsection();
    prm.enter_subsection("Refinement region 2");
    second_region.parse(prm, "subsection 'Body " + name + "/Refinement region 2': ", name);
    if (second_region.has_box || !second_region.near.empty())
      second_region.levels = prm.get_integer("Levels");
    prm.leave_subsection();
    for (const auto &[region, levels] : {std::pair{"Refinement region", first_region.levels},
                                         std::pair{"Refinement region 2", second_region.levels}})
      if (levels > 0 && material->is_rigid())
        throw InputError("subsection 'Body " + name + "/" + region + "': a rigid body moves as one and needs no "
                         "finer elements (allowed on deformable bodies)");
    rigid.parse_parameters(prm, name);
    if (!material->is_rigid() && rigid.shape.type != RigidBody::Shape::Type::mesh)
      throw InputError("subsection 'Body " + name + "/Rigid body': a 'Contact shape' "
                       "other than mesh needs the material 'rigid'");
  }


  void Body::create_mesh(dealii::Triangulation<3> &tria, MeshNames *names) const
  {
    mesh_source->create(tria, refinements, names);
    if (offset.norm() > 0)
      dealii::GridTools::shift(offset, tria);
    if (names)
      {
        for (auto &set : names->node_sets)
          for (auto &x : set.second)
            x = x + offset;
        for (const auto &sentence : ignored_entries)
          names->note += (names->note.empty() ? "" : "; ") + sentence;
      }
  }
} // namespace anvil
