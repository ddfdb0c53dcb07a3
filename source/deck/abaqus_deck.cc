/**
 * @file
 * A whole ABAQUS/Explicit deck as an Anvil scene: every *Solid Section of
 * every instance becomes a body (its cells the instance's set), its
 * *Material the body's model (*Elastic; *Plastic bilinear or Johnson-Cook
 * with *Rate Dependent, adiabatic heating and Johnson-Cook damage), and
 * *Initial Conditions, *Boundary, *Dynamic, Explicit, *Bulk Viscosity,
 * general contact and the output requests the scene's velocities,
 * boundary conditions, end time, pairs and intervals (doc/decks.md).
 */
#include <anvil/deck/deck.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>

#include "scene_writer.h"

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

namespace anvil::Deck
{
  using MeshFile::Abaqus::Keyword;
  using MeshFile::Abaqus::Line;

  namespace
  {
    const char *supported_keywords =
      "the mesh, *Solid Section, *Section Controls, *Material (*Density, *Elastic, *Plastic, *Rate Dependent, "
      "heat, Johnson-Cook damage), *Initial Conditions, *Boundary, *Dload (GRAV), *Step, *Dynamic, *Bulk Viscosity, contact, "
      "output; doc/decks.md lists them";

    [[noreturn]] void unsupported(const Keyword &kw, const std::string &what)
    {
      throw InputError(kw.line.where() + "*" + kw.written + ": " + what);
    }

    double value(const std::string &field, const Line &line, const std::string &what)
    {
      char        *end = nullptr;
      const double x   = std::strtod(field.c_str(), &end);
      if (field.empty() || *end != '\0' || !std::isfinite(x))
        throw InputError(line.where() + what + ": '" + printable_excerpt(field) + "' is not a number");
      return x;
    }

    std::string sanitized(const std::string &name)
    {
      std::string s;
      for (const char c : name)
        s += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : '_';
      if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0])))
        s = "b_" + s;
      return s;
    }

    struct Material
    {
      const Keyword *keyword = nullptr;
      std::map<std::string, const Keyword *> options; // sub-keyword name -> keyword
    };

    struct Section
    {
      std::string    elset, material, controls, part; // part empty: a flat deck
      const Keyword *keyword;
    };
  } // namespace


  Translation translate_abaqus_deck(const std::string &file, const std::string &mesh_path)
  {
    const auto               keywords = MeshFile::Abaqus::read_keywords(file);
    const MeshFile::Contents mesh     = MeshFile::read(file);
    SceneWriter              w;

    std::vector<Section>                            sections;
    std::map<std::string, Material>                 materials;
    std::map<std::string, std::string>              hourglass_of; // section controls -> type
    std::map<std::string, std::vector<std::string>> instances_of; // part -> instances
    std::map<std::string, std::set<std::string>>    element_types; // part ("" flat) -> types
    std::vector<const Keyword *>                    initial, boundaries, pairs_kw;
    std::vector<std::pair<const Keyword *, std::string>> rigid_kw; // *Rigid Body, its part
    std::map<std::string, double>                   friction_of; // interaction -> mu
    std::string                                     general_property;
    bool                                            general_all = false;
    double                                          end_time = 0, b1 = 0.06, b2 = 1.2;
    double                                          output_interval = 0, history_interval = 0;
    unsigned int                                    output_number = 0;
    const Keyword                                  *step = nullptr;
    std::vector<const Keyword *>                    dloads;

    std::string part, material, interaction;
    bool        in_step = false;
    for (const auto &kw : keywords)
      {
        const std::string &n = kw.name;
        // Sub-keywords of a *Material until the next other keyword.
        static const std::set<std::string> material_options = {
          "DENSITY", "ELASTIC", "PLASTIC", "RATE DEPENDENT", "INELASTIC HEAT FRACTION", "SPECIFIC HEAT",
          "CONDUCTIVITY", "EXPANSION", "DAMAGE INITIATION", "DAMAGE EVOLUTION"};
        if (!material.empty() && material_options.count(n))
          {
            materials[material].options[n] = &kw;
            continue;
          }
        material.clear();
        if (!interaction.empty() && n == "FRICTION")
          {
            if (kw.data.empty())
              unsupported(kw, "needs a line with the friction coefficient");
            const auto f = MeshFile::Abaqus::fields(kw.data[0].text);
            friction_of[interaction] = value(f.empty() ? "" : f[0], kw.data[0], "friction coefficient");
            if (kw.has("SLIP TOLERANCE") || kw.data.size() > 1 || f.size() > 1)
              w.differ("*Friction: one Coulomb coefficient (Anvil's), no slip tolerance or table");
            continue;
          }
        interaction.clear();
        if (n == "PART")
          part = MeshFile::key(kw.required("NAME"));
        else if (n == "END PART")
          part.clear();
        else if (n == "INSTANCE")
          instances_of[MeshFile::key(kw.required("PART"))].push_back(kw.required("NAME"));
        else if (n == "ELEMENT")
          element_types[part].insert(MeshFile::key(kw.get("TYPE")));
        else if (n == "NODE" || n == "NSET" || n == "ELSET" || n == "SURFACE" || n == "ASSEMBLY" ||
                 n == "END ASSEMBLY" || n == "END INSTANCE" || n == "INCLUDE")
          continue;
        else if (n == "SOLID SECTION")
          sections.push_back({MeshFile::key(kw.required("ELSET")), MeshFile::key(kw.required("MATERIAL")),
                              MeshFile::key(kw.get("CONTROLS")), part, &kw});
        else if (n == "SECTION CONTROLS")
          {
            const std::string h = MeshFile::key(kw.get("HOURGLASS"));
            hourglass_of[MeshFile::key(kw.required("NAME"))] = h.empty() ? "RELAX STIFFNESS" : h;
          }
        else if (n == "MATERIAL")
          {
            material            = MeshFile::key(kw.required("NAME"));
            materials[material].keyword = &kw;
          }
        else if (n == "INITIAL CONDITIONS")
          initial.push_back(&kw);
        else if (n == "BOUNDARY")
          boundaries.push_back(&kw);
        else if (n == "STEP")
          {
            if (step)
              unsupported(kw, "a second step: Anvil runs decks of one *Step (a scene's 'Stages' run several)");
            step    = &kw;
            in_step = true;
          }
        else if (n == "END STEP")
          in_step = false;
        else if (n == "DYNAMIC")
          {
            const std::string options = MeshFile::key(kw.line.text);
            if (options.find("EXPLICIT") == std::string::npos)
              unsupported(kw, "Anvil runs explicit dynamics only ('*Dynamic, Explicit')");
            if (options.find("FIXED TIME INCREMENTATION") != std::string::npos ||
                options.find("DIRECT USER CONTROL") != std::string::npos)
              unsupported(kw, "fixed or user time increments are not supported (Anvil takes the stable step)");
            if (kw.data.empty())
              unsupported(kw, "needs the data line ', TIME PERIOD'");
            const auto f = MeshFile::Abaqus::fields(kw.data[0].text);
            end_time     = value(f.size() > 1 ? f[1] : "", kw.data[0], "the time period");
            if (!(end_time > 0))
              unsupported(kw, "the time period must be positive");
          }
        else if (n == "DLOAD")
          dloads.push_back(&kw);
        else if (n == "BULK VISCOSITY")
          {
            if (!kw.data.empty())
              {
                const auto f = MeshFile::Abaqus::fields(kw.data[0].text);
                if (!f.empty() && !f[0].empty())
                  b1 = value(f[0], kw.data[0], "the linear bulk viscosity");
                if (f.size() > 1 && !f[1].empty())
                  b2 = value(f[1], kw.data[0], "the quadratic bulk viscosity");
              }
          }
        else if (n == "OUTPUT")
          {
            const bool field = kw.has("FIELD");
            if (kw.has("TIME INTERVAL"))
              (field ? output_interval : history_interval) =
                value(kw.get("TIME INTERVAL"), kw.line, "time interval");
            else if (field && kw.has("NUMBER INTERVAL"))
              output_number = static_cast<unsigned int>(
                std::max(1.0, value(kw.get("NUMBER INTERVAL"), kw.line, "number interval")));
            w.ignore("*Output's variables (Anvil writes its own fields and histories)");
          }
        else if (n == "CONTACT")
          general_all = false;
        else if (n == "CONTACT INCLUSIONS")
          {
            if (kw.has("ALL EXTERIOR"))
              general_all = true;
            else
              unsupported(kw, "Anvil's general contact takes 'ALL EXTERIOR' (pairs of surfaces: *Contact Pair)");
          }
        else if (n == "CONTACT PROPERTY ASSIGNMENT")
          {
            for (const auto &line : kw.data)
              {
                const auto f = MeshFile::Abaqus::fields(line.text);
                if (f.size() < 3 || !f[0].empty() || !f[1].empty())
                  unsupported(kw, "Anvil assigns one property to all of general contact (', , PROPERTY')");
                general_property = MeshFile::key(f[2]);
              }
          }
        else if (n == "RIGID BODY")
          {
            if (kw.has("ANALYTICAL SURFACE"))
              unsupported(kw, "analytical rigid surfaces are not supported (Anvil's rigid bodies are meshed)");
            kw.required("REF NODE");
            kw.required("ELSET");
            rigid_kw.emplace_back(&kw, part);
          }
        else if (n == "CONTACT PAIR")
          pairs_kw.push_back(&kw);
        else if (n == "SURFACE INTERACTION")
          interaction = MeshFile::key(kw.required("NAME"));
        else if (n == "HEADING" || n == "PREPRINT" || n == "RESTART" || n == "ELEMENT OUTPUT" ||
                 n == "NODE OUTPUT" || n == "ENERGY OUTPUT" || n == "CONTACT OUTPUT" ||
                 n == "INCREMENTATION OUTPUT" || n == "MONITOR" || n == "AMPLITUDE" ||
                 n == "PHYSICAL CONSTANTS" || n == "DIAGNOSTICS" || n == "FILE OUTPUT")
          w.ignore("*" + kw.written);
        else
          throw InputError(kw.line.where() + "*" + printable_excerpt(kw.written) +
                           (in_step ? " (in the step)" : "") + " is not supported (Anvil reads " +
                           supported_keywords + ")");
      }
    if (!step || end_time == 0)
      throw InputError("deck '" + file + "' has no '*Step' with '*Dynamic, Explicit': Anvil needs its time period");
    if (sections.empty())
      throw InputError("deck '" + file + "' has no *Solid Section: no body to run");

    // @sect4{Bodies: one per section and instance}
    struct Body
    {
      std::string            name, region, material;
      const Section         *section;
      std::set<unsigned int> vertices;
      dealii::Tensor<1, 3>   velocity;
      bool                   has_velocity = false;
      double                 temperature  = 0;
      bool                   has_temperature = false;
      std::string            part;
      bool                   rigid = false;
      /** A rigid body's reference node(s). */
      std::set<unsigned int> reference;
      std::array<bool, 6>    held{{false, false, false, false, false, false}};
    };
    std::vector<Body> bodies;
    for (const auto &s : sections)
      {
        std::vector<std::pair<std::string, std::string>> placed; // body name, region
        if (s.part.empty())
          placed.emplace_back(sanitized(s.elset), s.elset);
        else
          for (const auto &instance : instances_of[s.part])
            placed.emplace_back(sanitized(instance) +
                                  (std::count_if(sections.begin(), sections.end(),
                                                 [&](const Section &o) { return o.part == s.part; }) > 1 ?
                                     "_" + sanitized(s.elset) :
                                     std::string()),
                                MeshFile::key(instance) + "." + s.elset);
        if (placed.empty())
          unsupported(*s.keyword, "part '" + s.part + "' has no *Instance in the assembly");
        for (const auto &[name, region] : placed)
          {
            const auto cells = mesh.cell_sets.find(region);
            if (cells == mesh.cell_sets.end())
              unsupported(*s.keyword, "element set '" + s.elset + "' is not defined");
            Body b;
            b.name     = name;
            b.region   = region;
            b.material = s.material;
            b.section  = &s;
            b.part     = s.part;
            for (const unsigned int c : cells->second)
              b.vertices.insert(mesh.cells[c].begin(), mesh.cells[c].end());
            bodies.push_back(b);
          }
      }

    auto node_set = [&](const std::string &name, const Keyword &kw) -> const std::vector<unsigned int> & {
      const auto s = mesh.node_sets.find(MeshFile::key(name));
      if (s == mesh.node_sets.end())
        unsupported(kw, "node set '" + printable_excerpt(name) + "' is not defined (Anvil takes node sets here, not node labels)");
      return s->second;
    };
    // The bodies a node set touches: by their nodes, or a rigid body by
    // its reference node. A set that touches none is an error, not a
    // condition silently dropped.
    auto bodies_of = [&](const std::vector<unsigned int> &nodes, const Keyword &kw, const std::string &name) {
      std::vector<unsigned int> out;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (std::any_of(nodes.begin(), nodes.end(), [&](unsigned int v) {
              return bodies[b].vertices.count(v) || bodies[b].reference.count(v);
            }))
          out.push_back(b);
      if (out.empty())
        unsupported(kw, "set '" + printable_excerpt(name) + "' holds no node of a body (nor a rigid body's "
                        "reference node)");
      return out;
    };

    // Rigid bodies: the bodies whose cells the element set holds.
    for (const auto &[kwp, part_name] : rigid_kw)
      {
        const Keyword &kw = *kwp;
        std::vector<std::string> regions;
        if (part_name.empty())
          regions.push_back(MeshFile::key(kw.get("ELSET")));
        else
          for (const auto &instance : instances_of[part_name])
            regions.push_back(MeshFile::key(instance) + "." + MeshFile::key(kw.get("ELSET")));
        for (const auto &region : regions)
          {
            const auto cells = mesh.cell_sets.find(region);
            if (cells == mesh.cell_sets.end())
              unsupported(kw, "element set '" + kw.get("ELSET") + "' is not defined");
            std::set<unsigned int> vertices;
            for (const unsigned int c : cells->second)
              vertices.insert(mesh.cells[c].begin(), mesh.cells[c].end());
            const std::string ref = region.substr(0, region.size() - MeshFile::key(kw.get("ELSET")).size()) +
                                    MeshFile::key(kw.get("REF NODE"));
            const auto reference = mesh.node_sets.find(mesh.node_sets.count(ref) ? ref : MeshFile::key(kw.get("REF NODE")));
            if (reference == mesh.node_sets.end())
              unsupported(kw, "ref node '" + printable_excerpt(kw.get("REF NODE")) +
                                "' must name a node set of the reference node");
            bool found = false;
            for (auto &b : bodies)
              if (std::all_of(b.vertices.begin(), b.vertices.end(), [&](unsigned int v) { return vertices.count(v); }))
                {
                  b.rigid = found = true;
                  b.reference.insert(reference->second.begin(), reference->second.end());
                }
            if (!found)
              unsupported(kw, "element set '" + kw.get("ELSET") + "' holds no body (a *Solid Section's elements)");
          }
      }

    // Initial conditions: whole bodies.
    for (const Keyword *kwp : initial)
      {
        const Keyword    &kw   = *kwp;
        const std::string type = MeshFile::key(kw.get("TYPE"));
        if (type != "VELOCITY" && type != "TEMPERATURE")
          unsupported(kw, "type=" + printable_excerpt(type) + " is not supported (allowed: VELOCITY, TEMPERATURE)");
        for (const auto &line : kw.data)
          {
            const auto  f     = MeshFile::Abaqus::fields(line.text);
            const auto &nodes = node_set(f.empty() ? "" : f[0], kw);
            const std::set<unsigned int> in(nodes.begin(), nodes.end());
            for (const unsigned int b : bodies_of(nodes, kw, f[0]))
              {
                const bool by_reference = std::any_of(bodies[b].reference.begin(), bodies[b].reference.end(),
                                                      [&](unsigned int v) { return in.count(v); });
                if (!by_reference && !std::all_of(bodies[b].vertices.begin(), bodies[b].vertices.end(),
                                                  [&](unsigned int v) { return in.count(v); }))
                  unsupported(kw, "set '" + f[0] + "' holds part of body '" + bodies[b].name +
                                    "': Anvil gives initial conditions to whole bodies");
                if (type == "VELOCITY")
                  {
                    if (f.size() != 3)
                      throw InputError(line.where() + "expected 'SET, DOF, VELOCITY'");
                    const double dof = value(f[1], line, "the degree of freedom");
                    if (dof != 1 && dof != 2 && dof != 3)
                      throw InputError(line.where() + "degree of freedom " + f[1] + " (allowed: 1, 2, 3)");
                    bodies[b].velocity[int(dof) - 1] = value(f[2], line, "the velocity");
                    bodies[b].has_velocity           = true;
                  }
                else
                  {
                    if (f.size() != 2)
                      throw InputError(line.where() + "expected 'SET, TEMPERATURE'");
                    bodies[b].temperature     = value(f[1], line, "the temperature");
                    bodies[b].has_temperature = true;
                  }
              }
          }
      }

    // Boundary conditions.
    struct Constraint
    {
      std::string          set, body;
      std::array<bool, 3>  dofs{{false, false, false}};
      bool                 velocity = false;
      dealii::Tensor<1, 3> value;
      const Line          *line;
    };
    std::vector<Constraint> constraints;
    for (const Keyword *kwp : boundaries)
      {
        const Keyword    &kw   = *kwp;
        const std::string type = MeshFile::key(kw.get("TYPE"));
        if (kw.has("AMPLITUDE"))
          unsupported(kw, "amplitudes are not supported (Anvil prescribes constant values)");
        if (!type.empty() && type != "DISPLACEMENT" && type != "VELOCITY")
          unsupported(kw, "type=" + type + " is not supported (allowed: DISPLACEMENT, VELOCITY)");
        for (const auto &line : kw.data)
          {
            const auto f = MeshFile::Abaqus::fields(line.text);
            if (f.size() < 2)
              throw InputError(line.where() + "expected 'SET, FIRST DOF[, LAST DOF[, VALUE]]' or 'SET, XSYMM'");
            Constraint k;
            k.set  = f[0];
            k.line = &line;
            const std::string t = MeshFile::key(f[1]);
            static const std::map<std::string, std::string> named = {
              {"XSYMM", "x"}, {"YSYMM", "y"}, {"ZSYMM", "z"}, {"XASYMM", "yz"}, {"YASYMM", "xz"},
              {"ZASYMM", "xy"}, {"ENCASTRE", "xyz"}, {"PINNED", "xyz"}};
            if (named.count(t))
              for (const char c : named.at(t))
                k.dofs[c - 'x'] = true;
            else
              {
                const double first = value(f[1], line, "the first degree of freedom");
                const double last  = f.size() > 2 && !f[2].empty() ? value(f[2], line, "the last degree of freedom") : first;
                const double v     = f.size() > 3 ? value(f[3], line, "the value") : 0;
                if (first < 1 || last > 6 || last < first || first != std::floor(first) || last != std::floor(last))
                  throw InputError(line.where() + "degrees of freedom " + f[1] + " to " +
                                   (f.size() > 2 ? f[2] : f[1]) + " (allowed: 1 to 6)");
                for (int d = int(first); d <= int(last) && d <= 3; ++d)
                  {
                    k.dofs[d - 1]  = true;
                    k.value[d - 1] = v;
                  }
                if (type == "VELOCITY")
                  k.velocity = true;
                else if (v != 0)
                  throw InputError(line.where() + "a prescribed displacement of " + f[3] +
                                   " (Anvil prescribes velocities: type=VELOCITY)");
              }
            std::array<bool, 6> held{{false, false, false, false, false, false}};
            if (named.count(t))
              for (const char ch : named.at(t))
                held[ch - 'x'] = true;
            if (t == "ENCASTRE")
              held = {{true, true, true, true, true, true}};
            else if (!named.count(t))
              for (int d = int(value(f[1], line, "dof")); d <= int(f.size() > 2 && !f[2].empty() ? value(f[2], line, "dof") : value(f[1], line, "dof")); ++d)
                held[d - 1] = true;
            for (const unsigned int b : bodies_of(node_set(k.set, kw), kw, k.set))
              {
                if (bodies[b].rigid)
                  {
                    // The reference node's conditions: the rigid body's.
                    for (unsigned int d = 0; d < 6; ++d)
                      bodies[b].held[d] = bodies[b].held[d] || held[d];
                    for (unsigned int d = 0; d < 3; ++d)
                      if (k.dofs[d] && k.velocity)
                        {
                          bodies[b].velocity[d] = k.value[d];
                          bodies[b].has_velocity = true;
                        }
                    continue;
                  }
                if (k.dofs == std::array<bool, 3>{{false, false, false}})
                  continue; // rotations of solids' nodes: nothing to hold
                Constraint kb = k;
                kb.body       = bodies[b].name;
                constraints.push_back(kb);
              }
          }
      }

    // Contact pairs: general contact between all bodies, and *Contact Pair.
    struct Pair
    {
      std::string first, second;
      double      mu;
      std::string algorithm;
    };
    std::vector<Pair> pairs;
    auto add_pair = [&](const std::string &a, const std::string &b, const double mu,
                        const std::string &algorithm) {
      if (a == b)
        return;
      for (const auto &p : pairs)
        if ((p.first == a && p.second == b) || (p.first == b && p.second == a))
          return;
      pairs.push_back({a, b, mu, algorithm});
    };
    if (general_all)
      {
        const double mu = friction_of.count(general_property) ? friction_of[general_property] : 0;
        for (unsigned int i = 0; i < bodies.size(); ++i)
          for (unsigned int j = i + 1; j < bodies.size(); ++j)
            add_pair(bodies[i].name, bodies[j].name, mu, "penalty");
        w.differ("general contact: penalty pairs between the bodies (Anvil's node-to-segment penalty, not "
                 "ABAQUS's kinematic-penalty general contact)");
      }
    for (const Keyword *kwp : pairs_kw)
      {
        const Keyword &kw = *kwp;
        const double   mu = friction_of.count(MeshFile::key(kw.get("INTERACTION"))) ?
                              friction_of[MeshFile::key(kw.get("INTERACTION"))] :
                              0;
        // ABAQUS/Explicit enforces a contact pair kinematically unless it
        // says MECHANICAL CONSTRAINT=PENALTY.
        const std::string constraint = MeshFile::key(kw.get("MECHANICAL CONSTRAINT"));
        if (!constraint.empty() && constraint != "KINEMATIC" && constraint != "PENALTY")
          unsupported(kw, "mechanical constraint=" + constraint + " is not supported (allowed: KINEMATIC, PENALTY)");
        const std::string algorithm = constraint == "PENALTY" ? "penalty" : "kinematic";
        w.differ("*Contact Pair: Anvil's node-to-segment " + algorithm +
                 " pairs between the bodies that hold the surfaces");
        for (const auto &line : kw.data)
          {
            const auto f = MeshFile::Abaqus::fields(line.text);
            if (f.size() < 2)
              throw InputError(line.where() + "expected 'SURFACE, SURFACE'");
            std::string side[2];
            for (unsigned int s = 0; s < 2; ++s)
              {
                const auto id = mesh.surfaces.find(MeshFile::key(f[s]));
                if (id == mesh.surfaces.end())
                  throw InputError(line.where() + "surface '" + printable_excerpt(f[s]) + "' is not defined");
                std::vector<unsigned int> nodes;
                for (const auto &face : mesh.faces)
                  if (face.boundary_id == id->second)
                    nodes.insert(nodes.end(), face.vertices.begin(), face.vertices.end());
                const auto owners = bodies_of(nodes, kw, f[s]);
                if (owners.size() != 1)
                  throw InputError(line.where() + "surface '" + f[s] + "' must lie on one body");
                side[s] = bodies[owners[0]].name;
              }
            add_pair(side[0], side[1], mu, algorithm);
          }
      }

    // Gravity: *Dload, SET, GRAV, g, nx, ny, nz on sets that hold every body.
    dealii::Tensor<1, 3> gravity;
    const Line          *gravity_line = nullptr;
    for (const Keyword *kwp : dloads)
      {
        const Keyword &kw = *kwp;
        if (kw.has("AMPLITUDE"))
          unsupported(kw, "amplitudes are not supported (Anvil's gravity is constant)");
        for (const auto &line : kw.data)
          {
            const auto f = MeshFile::Abaqus::fields(line.text);
            if (f.size() != 6 || MeshFile::key(f[1]) != "GRAV")
              throw InputError(line.where() + "*Dload: Anvil takes gravity only, 'SET, GRAV, g, nx, ny, nz'");
            if (!f[0].empty())
              {
                const auto cells = mesh.cell_sets.find(MeshFile::key(f[0]));
                if (cells == mesh.cell_sets.end())
                  throw InputError(line.where() + "*Dload: element set '" + printable_excerpt(f[0]) + "' is not defined");
                std::set<unsigned int> in;
                for (const unsigned int c : cells->second)
                  in.insert(mesh.cells[c].begin(), mesh.cells[c].end());
                for (const auto &b : bodies)
                  if (!b.rigid && !std::all_of(b.vertices.begin(), b.vertices.end(),
                                               [&](unsigned int v) { return in.count(v); }))
                    throw InputError(line.where() + "*Dload: set '" + f[0] + "' leaves out body '" + b.name +
                                     "': Anvil's gravity acts on every body");
              }
            const double         g = value(f[2], line, "the magnitude");
            dealii::Tensor<1, 3> n;
            for (unsigned int d = 0; d < 3; ++d)
              n[d] = value(f[3 + d], line, "the direction");
            if (n.norm() == 0)
              throw InputError(line.where() + "*Dload: the direction of gravity is zero");
            gravity += g * n / n.norm();
            gravity_line = &line;
          }
      }

    // @sect4{The scene}
    w.from(file, 1);
    w.comment("The ABAQUS deck " + std::filesystem::path(file).filename().string() +
              " as an Anvil scene (anvil --translate); its mesh is read from the deck.");
    w.comment("Units: the deck's own; every value below is the deck's.");
    {
      std::string list;
      for (const auto &b : bodies)
        list += (list.empty() ? "" : ", ") + b.name;
      w.set("Bodies", list);
      list.clear();
      for (unsigned int i = 0; i < constraints.size(); ++i)
        list += (list.empty() ? "" : ", ") + ("bc" + std::to_string(i + 1) + "_" + sanitized(constraints[i].set));
      if (!list.empty())
        w.set("Boundary conditions", list);
      list.clear();
      for (const auto &p : pairs)
        list += (list.empty() ? "" : ", ") + p.first + "_" + p.second;
      if (!list.empty())
        w.set("Contact pairs", list);
    }
    w.blank();
    w.from(step->line.file, step->line.number);
    w.enter("Simulation");
    w.set("End time", end_time);
    if (output_interval > 0)
      w.set("Output interval", output_interval);
    else if (output_number > 0)
      w.set("Output interval", end_time / output_number);
    if (history_interval > 0)
      w.set("History interval", history_interval);
    if (gravity_line)
      {
        w.from(gravity_line->file, gravity_line->number);
        w.set("Gravity", SceneWriter::vector(gravity[0], gravity[1], gravity[2]));
      }
    w.leave();

    for (const auto &b : bodies)
      {
        const Section &s = *b.section;
        w.blank();
        w.from(s.keyword->line.file, s.keyword->line.number);
        w.enter("Body " + b.name);
        w.comment("*Solid Section, elset=" + s.elset + ", material=" + s.material);
        w.enter("Mesh");
        w.set("Source", "file");
        w.set("File name", mesh_path);
        w.set("Region", b.region);
        w.leave();
        if (b.has_velocity)
          w.set("Initial velocity", SceneWriter::vector(b.velocity[0], b.velocity[1], b.velocity[2]));
        if (b.rigid)
          {
            const auto m = materials.find(b.material);
            if (m == materials.end() || !m->second.options.count("DENSITY") || !m->second.options.count("ELASTIC"))
              unsupported(*s.keyword, "the rigid body's material '" + b.material + "' needs *Density and *Elastic");
            const Keyword &dk = *m->second.options.at("DENSITY"), &ek = *m->second.options.at("ELASTIC");
            const auto     df = MeshFile::Abaqus::fields(dk.data.empty() ? "" : dk.data[0].text);
            const auto     ef = MeshFile::Abaqus::fields(ek.data.empty() ? "" : ek.data[0].text);
            if (df.empty() || ef.size() < 2)
              unsupported(dk, "expected the density, and *Elastic's E and nu");
            w.enter("Material");
            w.set("Model", "rigid");
            w.enter("rigid");
            w.set("Density", value(df[0], dk.data[0], "density"));
            w.set("Young's modulus", value(ef[0], ek.data[0], "E"));
            w.set("Poisson's ratio", value(ef[1], ek.data[0], "nu"));
            w.leave();
            w.leave();
            std::string held;
            static const char *dof_name[6] = {"x", "y", "z", "rx", "ry", "rz"};
            bool all = true;
            for (unsigned int d = 0; d < 6; ++d)
              {
                all = all && b.held[d];
                if (b.held[d])
                  held += std::string(held.empty() ? "" : ", ") + dof_name[d];
              }
            w.enter("Rigid body");
            w.set("Motion", all ? "prescribed" : "free");
            if (!all && !held.empty())
              w.set("Constraints", held);
            w.leave();
            w.leave();
            continue;
          }
        const auto &types = element_types[b.part];
        // ABAQUS/Explicit's C3D8 is selectively reduced (constant volume
        // strain): it does not lock in plastic flow, Anvil's full 2x2x2
        // integration does (doc/accuracy.md); the one-point element with
        // hourglass control is the nearer of Anvil's two.
        w.set("Integration", "one point");
        if (types.count("C3D8"))
          w.differ("C3D8 (selectively reduced in ABAQUS/Explicit): Anvil's one-point element with hourglass "
                   "control, as its full 2x2x2 integration locks in plastic flow (doc/decks.md)");
        std::string hourglass = s.controls.empty() ? "" : hourglass_of[s.controls];
        w.enter("Hourglass control");
        if (hourglass == "VISCOUS")
          w.set("Type", "viscous");
        else if (hourglass == "STIFFNESS" || hourglass == "ENHANCED" || hourglass == "RELAX STIFFNESS")
          {
            w.set("Type", "stiffness");
            if (hourglass != "STIFFNESS")
              w.differ("hourglass=" + hourglass + ": Anvil's Flanagan-Belytschko stiffness form");
          }
        else
          {
            w.set("Type", "viscous");
            w.differ("ABAQUS's default hourglass control (RELAX STIFFNESS): Anvil's default, viscous "
                     "Flanagan-Belytschko (doc/accuracy.md)");
          }
        w.leave();
        w.enter("Bulk viscosity");
        w.set("Linear coefficient", b1);
        w.set("Quadratic coefficient", b2);
        w.leave();

        // The material.
        const auto m = materials.find(b.material);
        if (m == materials.end())
          unsupported(*s.keyword, "material '" + b.material + "' is not defined");
        const Material &mat = m->second;
        auto option = [&](const std::string &name) -> const Keyword * {
          const auto o = mat.options.find(name);
          return o == mat.options.end() ? nullptr : o->second;
        };
        auto numbers = [&](const Keyword &kw, const unsigned int n_min, const unsigned int n_max) {
          if (kw.data.empty())
            unsupported(kw, "needs a data line");
          const auto          f = MeshFile::Abaqus::fields(kw.data[0].text);
          std::vector<double> out;
          for (const auto &x : f)
            out.push_back(value(x, kw.data[0], "*" + kw.written));
          if (out.size() < n_min || out.size() > n_max)
            throw InputError(kw.data[0].where() + "*" + kw.written + ": expected " + std::to_string(n_min) +
                             (n_max > n_min ? " to " + std::to_string(n_max) : std::string()) +
                             " values (temperature-dependent data is not supported)");
          out.resize(n_max);
          return out;
        };
        const Keyword *density = option("DENSITY"), *elastic = option("ELASTIC"), *plastic = option("PLASTIC"),
                      *rate = option("RATE DEPENDENT");
        if (!density || !elastic)
          unsupported(*mat.keyword, "Anvil needs *Density and *Elastic");
        if (!MeshFile::key(elastic->get("TYPE")).empty() && MeshFile::key(elastic->get("TYPE")) != "ISOTROPIC")
          unsupported(*elastic, "only type=ISOTROPIC is supported");
        const double rho = numbers(*density, 1, 1)[0];
        const auto   el  = numbers(*elastic, 2, 2);
        if (option("EXPANSION"))
          w.differ("*Expansion: Anvil has no thermal strain");
        if (option("CONDUCTIVITY"))
          w.ignore("*Conductivity (adiabatic: no heat flows within a step this short)");
        if (option("DAMAGE EVOLUTION"))
          w.differ("*Damage Evolution: Anvil erodes an element when Johnson-Cook damage reaches 1");
        w.from(mat.keyword->line.file, mat.keyword->line.number);
        w.enter("Material");
        const std::string hardening = plastic ? MeshFile::key(plastic->get("HARDENING")) : std::string();
        if (!plastic)
          {
            w.set("Model", "elastic");
            w.enter("elastic");
            w.set("Density", rho);
            w.set("Young's modulus", el[0]);
            w.set("Poisson's ratio", el[1]);
            w.leave();
          }
        else if (hardening == "JOHNSON COOK")
          {
            const auto jc = numbers(*plastic, 6, 6); // A, B, n, m, T_melt, T_transition
            w.set("Model", "johnson cook");
            w.enter("johnson cook");
            w.set("Density", rho);
            w.set("Young's modulus", el[0]);
            w.set("Poisson's ratio", el[1]);
            w.set("A", jc[0]);
            w.set("B", jc[1]);
            w.set("n", jc[2]);
            w.set("m", jc[3]);
            w.set("Melting temperature", jc[4]);
            w.set("Transition temperature", jc[5]);
            w.set("Initial temperature", b.has_temperature ? b.temperature : jc[5]);
            if (rate)
              {
                if (MeshFile::key(rate->get("TYPE")) != "JOHNSON COOK")
                  unsupported(*rate, "with Johnson-Cook hardening, type=JOHNSON COOK");
                const auto r = numbers(*rate, 2, 2);
                w.set("C", r[0]);
                w.set("Reference strain rate", r[1]);
              }
            const Keyword *heat = option("INELASTIC HEAT FRACTION"), *cp = option("SPECIFIC HEAT");
            if (cp)
              {
                w.set("Specific heat", numbers(*cp, 1, 1)[0]);
                w.set("Inelastic heat fraction", heat ? numbers(*heat, 1, 1)[0] : 0.9);
              }
            if (const Keyword *damage = option("DAMAGE INITIATION"))
              {
                if (MeshFile::key(damage->get("CRITERION")) != "JOHNSON COOK")
                  unsupported(*damage, "only criterion=JOHNSON COOK is supported");
                const auto d = numbers(*damage, 5, 8);
                for (unsigned int i = 0; i < 5; ++i)
                  w.set("D" + std::to_string(i + 1), d[i]);
                w.set("Erosion", "true");
              }
            w.leave();
          }
        else if (hardening.empty() || hardening == "ISOTROPIC" || hardening == "KINEMATIC")
          {
            // Rows 'yield stress, plastic strain' (a third field is a
            // temperature: not supported), the first at plastic strain 0.
            std::vector<std::array<double, 2>> rows;
            for (const auto &line : plastic->data)
              {
                const auto f = MeshFile::Abaqus::fields(line.text);
                if (f.size() < 1 || f.size() > 2)
                  throw InputError(line.where() + "expected 'YIELD STRESS, PLASTIC STRAIN' (temperature-dependent "
                                   "data is not supported)");
                rows.push_back({{value(f[0], line, "the yield stress"),
                                 f.size() > 1 ? value(f[1], line, "the plastic strain") : 0.}});
              }
            if (rows.empty())
              unsupported(*plastic, "needs a row 'YIELD STRESS, PLASTIC STRAIN'");
            if (rows[0][1] != 0)
              throw InputError(plastic->data[0].where() + "the first row's plastic strain must be 0");
            // Isotropic: the table as ABAQUS reads it, straight between
            // the rows and constant beyond the last. Kinematic: bilinear,
            // one row (perfectly plastic) or two.
            const bool isotropic = hardening != "KINEMATIC";
            if (!isotropic && rows.size() > 2)
              unsupported(*plastic, "with hardening=KINEMATIC Anvil's plasticity is bilinear: one or two rows "
                                    "(tables of more rows: isotropic hardening)");
            const std::string model = isotropic ? "piecewise linear plasticity" : "plastic kinematic";
            w.set("Model", model);
            w.enter(model);
            w.set("Density", rho);
            w.set("Young's modulus", el[0]);
            w.set("Poisson's ratio", el[1]);
            if (isotropic)
              {
                std::string table;
                for (const auto &r : rows)
                  table += (table.empty() ? "" : ", ") + w.number(r[1]) + ":" + w.number(r[0]);
                w.set("Flow curve", table);
                w.set("Beyond the curve", "constant");
              }
            else
              {
                double Et = 0;
                if (rows.size() == 2)
                  {
                    if (!(rows[1][1] > 0))
                      throw InputError(plastic->data[1].where() + "the plastic strain must grow");
                    const double H = (rows[1][0] - rows[0][0]) / rows[1][1];
                    Et             = el[0] * H / (el[0] + H);
                    w.differ("*Plastic: the second row continues as a straight line (bilinear steel)");
                  }
                w.set("Yield stress", rows[0][0]);
                w.set("Tangent modulus", Et);
                w.set("Hardening parameter beta", 0.0);
                w.set("Strain rate effects", rate ? "Cowper-Symonds" : "none");
              }
            if (rate)
              {
                if (MeshFile::key(rate->get("TYPE")) != "POWER LAW" && !rate->get("TYPE").empty())
                  unsupported(*rate, "with tabular plasticity, type=POWER LAW (Cowper-Symonds)");
                const auto r = numbers(*rate, 2, 2);
                w.set("Cowper-Symonds C", r[0]);
                w.set("Cowper-Symonds p", r[1]);
              }
            w.leave();
          }
        else
          unsupported(*plastic, "hardening=" + hardening + " is not supported (allowed: ISOTROPIC, KINEMATIC, "
                                "JOHNSON COOK)");
        w.leave();
        w.leave();
      }

    for (unsigned int i = 0; i < constraints.size(); ++i)
      {
        const auto &k = constraints[i];
        w.from(k.line->file, k.line->number);
        const double v[3] = {k.value[0], k.value[1], k.value[2]};
        w.node_set_condition("bc" + std::to_string(i + 1) + "_" + sanitized(k.set), k.body, k.set, k.dofs,
                             k.velocity, v);
      }
    for (const auto &p : pairs)
      {
        w.blank();
        w.enter("Contact pair " + p.first + "_" + p.second);
        w.set("First body", p.first);
        w.set("Second body", p.second);
        w.set("Algorithm", p.algorithm);
        w.set("Static friction coefficient", p.mu);
        w.set("Dynamic friction coefficient", p.mu);
        w.leave();
      }
    return w.result();
  }
} // namespace anvil::Deck
