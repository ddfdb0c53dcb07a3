/**
 * @file
 * Reinforcement layouts. See rebar.h.
 */
#include <anvil/rebar/rebar.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anvil::Rebar
{
  using namespace dealii;

  std::array<double, 8> Trusses::shape_values(const std::array<double, 3> &xi)
  {
    std::array<double, 8> N;
    for (unsigned int I = 0; I < 8; ++I)
      N[I] = 0.125 * (1. + ((I & 1) ? 1. : -1.) * xi[0]) * (1. + ((I & 2) ? 1. : -1.) * xi[1]) *
             (1. + ((I & 4) ? 1. : -1.) * xi[2]);
    return N;
  }


  void Layout::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Host body", "", Patterns::Anything(),
                      "Name of the body the bars are embedded in.");
    prm.declare_entry("Layout",
                      "longitudinal",
                      Patterns::Selection("longitudinal|stirrups|polylines"),
                      "'longitudinal': bars along 'Axis' of the member between "
                      "'Member lower corner' and 'Member upper corner'; "
                      "'stirrups': closed ties around that axis at 'Spacing'; "
                      "'polylines': from 'File name'.");
    prm.declare_entry("Axis", "z", Patterns::Selection("x|y|z"),
                      "Axis of the prismatic member.");
    prm.declare_entry("Member lower corner", "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Lowest corner of the member's bounding box. Units: m.");
    prm.declare_entry("Member upper corner", "1, 1, 1",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Highest corner of the member's bounding box. Units: m.");
    prm.declare_entry("Cover", "0.03", Patterns::Double(0.),
                      "Concrete cover from the member's faces to the bar "
                      "surface. Units: m.");
    prm.declare_entry("Bars per face", "2", Patterns::Integer(1),
                      "Longitudinal bars on each face, corners included (1: a "
                      "single central bar). Units: none.");
    prm.declare_entry("Diameter", "0.016", Patterns::Double(0.),
                      "Bar diameter. Units: m.");
    prm.declare_entry("Spacing", "0.1", Patterns::Double(0.),
                      "Stirrups: spacing along the axis. Units: m.");
    prm.declare_entry("File name", "", Patterns::Anything(),
                      "Polylines: a text file of 'x y z' lines, polylines "
                      "separated by blank lines (relative to the folder of the scene file that names it).");
    prm.declare_entry("Element length", "0.05", Patterns::Double(0.),
                      "Largest truss element length. Units: m.");
    prm.declare_entry("Probe point", "", Patterns::Anything(),
                      "Optional 'x, y, z': rebar_NAME.csv also reports the axial "
                      "force and stress of the truss element nearest to it. Units: m.");
    prm.declare_entry("Coupling",
                      "perfect bond",
                      Patterns::Selection("perfect bond|bond-slip"),
                      "'perfect bond': the bars follow the host (embedded, "
                      "common-node model of the seed). 'bond-slip': the bars "
                      "have their own nodes, tied to the host across the bar "
                      "and along it by the bond law of seed Eq. (68).");
    prm.declare_entry("Bond modulus", "5e10", Patterns::Double(0.),
                      "G_s of seed Eq. (68), bond stress per unit slip (50 MPa/mm). "
                      "Units: Pa/m.");
    prm.declare_entry("Slip at bond strength", "3.6e-4", Patterns::Double(0.),
                      "S_max of seed Eq. (68) (0.36 mm); tau_max = G_s S_max. Units: m.");
    prm.declare_entry("Bond damage rate", "200", Patterns::Double(0.),
                      "h_dmg of seed Eq. (68) per unit of the slip D accumulated beyond "
                      "the elastic range (0.2 per mm). Units: 1/m.");
    prm.declare_entry("Mass scaling time step", "0", Patterns::Double(0.),
                      "Bond-slip bars: the smallest stable step their elements "
                      "may set. An element whose L / c is below it gets "
                      "nonstructural mass, (step c / L)^2 times its own, spread "
                      "to its two nodes, so that it no longer sets the step "
                      "(LS-DYNA's selective mass scaling). The added mass is "
                      "printed and in summary.csv, and moves with the bars (its "
                      "kinetic energy is in the balance). Steel bars of the "
                      "concrete's element length set a step 0.77 times the "
                      "concrete's; doc/accuracy.md measures what scaling them "
                      "costs in accuracy. 0: off. Units: s.");
    prm.declare_entry("Subcycling", "false", Patterns::Bool(),
                      "Bond-slip bars: advance the bars' own nodes in substeps of "
                      "their own stable step inside the scene's step, on the host "
                      "points interpolated linearly across it (the host gets the "
                      "bond reactions of the step's ends), so that bars shorter than "
                      "the host's elements no longer set the scene's step. A step "
                      "takes the fewest substeps that keep each within the bars' "
                      "stable step times 'Time step safety factor'; no mass is "
                      "added. doc/accuracy.md measures what it changes. false: the "
                      "bars' stable step bounds the scene's.");
    prm.declare_entry("Pull velocity", "0, 0, 0", Patterns::List(Patterns::Double(), 3, 3),
                      "Bond-slip: velocity imposed on the last node of every bar from "
                      "t = 0 (a pull-out test); zero: none. Units: m/s.");
    prm.enter_subsection("Material");
    MaterialModel::declare_parameters(prm);
    prm.leave_subsection();
  }


  void Layout::parse_parameters(ParameterHandler &prm,
                                const std::string &layout_name,
                                const std::string &scene_directory)
  {
    name                 = layout_name;
    const std::string at = "subsection 'Rebar " + name + "': ";
    host                 = prm.get("Host body");
    layout               = prm.get("Layout");
    axis                 = prm.get("Axis") == "x" ? 0 : prm.get("Axis") == "y" ? 1 : 2;
    auto point = [&](const std::string &entry) {
      return Point<3>(three_numbers(prm.get(entry), entry, "subsection 'Rebar " + name + "'"));
    };
    lower          = point("Member lower corner");
    upper          = point("Member upper corner");
    cover          = prm.get_double("Cover");
    per_face       = prm.get_integer("Bars per face");
    diameter       = prm.get_double("Diameter");
    spacing        = prm.get_double("Spacing");
    element_length = prm.get_double("Element length");
    file_name      = prm.get("File name");
    if (!Utilities::trim(prm.get("Probe point")).empty())
      {
        has_probe = true;
        probe     = point("Probe point");
      }
    if (!file_name.empty() && file_name[0] != '/')
      file_name = scene_directory + "/" + file_name;
    if (host.empty())
      throw InputError(at + "'Host body' is required");
    if (!(diameter > 0) || !(element_length > 0))
      throw InputError(at + "'Diameter' and 'Element length' must be positive");
    bond_slip    = prm.get("Coupling") == "bond-slip";
    bond_modulus = prm.get_double("Bond modulus");
    slip_at_peak = prm.get_double("Slip at bond strength");
    damage_rate  = prm.get_double("Bond damage rate");
    mass_scaling_step = prm.get_double("Mass scaling time step");
    subcycling        = prm.get_bool("Subcycling");
    {
      const Point<3> v = point("Pull velocity");
      pull_velocity    = v;
      pulled           = v.norm() > 0;
    }
    if (bond_slip && (!(bond_modulus > 0) || !(slip_at_peak > 0)))
      throw InputError(at + "'Bond modulus' and 'Slip at bond strength' must be positive");
    if (mass_scaling_step > 0 && !bond_slip)
      throw InputError(at + "'Mass scaling time step' needs 'Coupling = bond-slip' (perfectly "
                            "bonded bars carry no mass of their own: it is the host's)");
    if (subcycling && !bond_slip)
      throw InputError(at + "'Subcycling' needs 'Coupling = bond-slip' (perfectly bonded "
                            "bars move with the host's step: they have no nodes of their own)");
    if (pulled && !bond_slip)
      throw InputError(at + "'Pull velocity' needs 'Coupling = bond-slip' (perfectly bonded "
                            "bars follow the host)");
    if (layout == "stirrups" && !(spacing > 0))
      throw InputError(at + "stirrups need a positive 'Spacing'");
    if (layout == "polylines" && !std::ifstream(file_name))
      throw InputError(at + "the polyline file '" + file_name + "' cannot be opened");
    for (unsigned int d = 0; d < 3; ++d)
      if (!(upper[d] > lower[d]))
        throw InputError(at + "'Member upper corner' must exceed 'Member lower corner'");
    prm.enter_subsection("Material");
    material                = MaterialModel::create(prm);
    const std::string model = prm.get("Model");
    prm.leave_subsection();
    if (!material->has_uniaxial_form() || material->is_rigid())
      throw InputError(at + "material model '" + model + "' has no uniaxial (truss) form");
    if (polylines().empty())
      throw InputError(at + "the layout has no bar (check the cover and the member size)");
  }


  std::vector<std::vector<Point<3>>> Layout::polylines() const
  {
    std::vector<std::vector<Point<3>>> lines;
    const unsigned int a = axis, b = (axis + 1) % 3, c = (axis + 2) % 3;
    auto               make = [&](const double s_a, const double s_b, const double s_c) {
      Point<3> p;
      p[a] = s_a;
      p[b] = s_b;
      p[c] = s_c;
      return p;
    };
    if (layout == "longitudinal")
      {
        const double inset = cover + 0.5 * diameter;
        const double b0 = lower[b] + inset, b1 = upper[b] - inset;
        const double c0 = lower[c] + inset, c1 = upper[c] - inset;
        if (b1 < b0 || c1 < c0)
          return lines;
        std::vector<std::pair<double, double>> spots;
        if (per_face == 1)
          spots.emplace_back(0.5 * (b0 + b1), 0.5 * (c0 + c1));
        else
          for (unsigned int i = 0; i < per_face; ++i)
            for (unsigned int j = 0; j < per_face; ++j)
              if (i == 0 || j == 0 || i + 1 == per_face || j + 1 == per_face)
                spots.emplace_back(b0 + (b1 - b0) * i / (per_face - 1.),
                                   c0 + (c1 - c0) * j / (per_face - 1.));
        for (const auto &[sb, sc] : spots)
          lines.push_back({make(lower[a], sb, sc), make(upper[a], sb, sc)});
      }
    else if (layout == "stirrups")
      {
        const double inset = cover + 0.5 * diameter;
        const double b0 = lower[b] + inset, b1 = upper[b] - inset;
        const double c0 = lower[c] + inset, c1 = upper[c] - inset;
        if (b1 < b0 || c1 < c0)
          return lines;
        check_size("subsection 'Rebar " + name + "'", "'Spacing' and the member's length", "stirrups",
                   (upper[a] - lower[a]) / spacing, 1024.);
        for (double s = lower[a] + 0.5 * spacing; s < upper[a]; s += spacing)
          lines.push_back({make(s, b0, c0), make(s, b1, c0), make(s, b1, c1), make(s, b0, c1),
                           make(s, b0, c0)});
      }
    else
      {
        std::ifstream            in(file_name);
        std::string              line;
        std::vector<Point<3>>    current;
        while (std::getline(in, line))
          {
            std::istringstream s(line);
            Point<3>           p;
            if (s >> p[0] >> p[1] >> p[2])
              current.push_back(p);
            else if (!current.empty())
              {
                if (current.size() > 1)
                  lines.push_back(current);
                current.clear();
              }
          }
        if (current.size() > 1)
          lines.push_back(current);
      }
    return lines;
  }


  std::string Layout::ratio_summary() const
  {
    const unsigned int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const double       wb = upper[b] - lower[b], wc = upper[c] - lower[c];
    std::ostringstream s;
    s << std::setprecision(3);
    if (layout == "longitudinal")
      s << polylines().size() << " bars of " << 1000 * diameter
        << " mm: longitudinal ratio " << 100. * polylines().size() * area() / (wb * wc) << " %";
    else if (layout == "stirrups")
      s << polylines().size() << " stirrups of " << 1000 * diameter << " mm at " << spacing
        << " m: transverse ratios " << 100. * 2 * area() / (wb * spacing) << " % and "
        << 100. * 2 * area() / (wc * spacing) << " %";
    else
      s << polylines().size() << " polylines of " << 1000 * diameter << " mm";
    return s.str();
  }


  void Trusses::serialize(StateArchive &ar, const std::string &table)
  {
    ar &pvd_records &substeps &substep;
    // The per-node arrays the layout has (some are made at the first
    // evaluation): their sizes are the stream's, their values the
    // tables'.
    std::vector<double> *const per_node[] = {&x, &xs, &vs, &fs, &xh, &plastic_slip, &damage, &bond_stress,
                                             &slip, &bond_force, &pull_reaction, &nodal_force, &x_bond_old};
    std::vector<double> *const per_element[] = {&length, &stress, &force, &energy, &history};
    const std::size_t          n_nodes = X.size(), n_elements = elements.size();
    std::vector<std::uint64_t> sizes;
    for (auto *v : per_node)
      sizes.push_back(v->size());
    for (auto *v : per_element)
      sizes.push_back(v->size());
    sizes.push_back(pulled.size());
    sizes.push_back(tangent.size());
    ar &sizes;
    if (ar.is_loading())
      {
        unsigned int k = 0;
        for (auto *v : per_node)
          v->assign(sizes[k++], 0.);
        for (auto *v : per_element)
          v->assign(sizes[k++], 0.);
        pulled.assign(sizes[k++], false);
        tangent.assign(sizes[k++], dealii::Tensor<1, 3>());
      }
    // Values an item of an array of @p size over @p n items (0: absent).
    const auto width = [](const std::size_t size, const std::size_t n) {
      return n > 0 ? static_cast<unsigned int>(size / n) : 0u;
    };
    unsigned int node_record = (pulled.empty() ? 0 : 1) + (tangent.empty() ? 0 : 3);
    for (auto *v : per_node)
      node_record += width(v->size(), n_nodes);
    unsigned int element_record = 0;
    for (auto *v : per_element)
      element_record += width(v->size(), n_elements);

    // Writing: the own nodes and the elements whose first node is own;
    // reading: all of them (every process holds the arrays whole).
    std::vector<std::uint64_t> nodes, own_elements;
    for (std::size_t i = 0; i < n_nodes; ++i)
      if (ar.is_loading() || (i < host_owned.size() && host_owned[i]))
        nodes.push_back(i);
    for (std::size_t k = 0; k < n_elements; ++k)
      if (ar.is_loading() || host_owned[elements[k][0]])
        own_elements.push_back(k);
    ar.keyed_items(table + " nodes", nodes, node_record, [&](const std::size_t j, RecordCursor &io) {
      const std::size_t i = nodes[j];
      for (auto *v : per_node)
        {
          const unsigned int w = width(v->size(), n_nodes);
          io(*v, w * i, w);
        }
      if (!pulled.empty())
        io(pulled, i, 1);
      if (!tangent.empty())
        for (unsigned int d = 0; d < 3; ++d)
          io(tangent[i][d]);
    });
    ar.keyed_items(table + " elements", own_elements, element_record, [&](const std::size_t j, RecordCursor &io) {
      const std::size_t k = own_elements[j];
      for (auto *v : per_element)
        {
          const unsigned int w = width(v->size(), n_elements);
          io(*v, w * k, w);
        }
    });
  }
} // namespace anvil::Rebar
