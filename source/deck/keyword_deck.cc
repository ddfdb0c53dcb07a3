/**
 * @file
 * An LS-DYNA keyword deck as an Anvil scene. Every part of solid elements
 * becomes a body (its cells the deck's 'PART<pid>'), its *MAT_ and
 * *SECTION_SOLID the body's material and integration; *INITIAL_VELOCITY,
 * *BOUNDARY_SPC, *NODE's TC codes, *RIGIDWALL_PLANAR, *CONTACT_ and
 * *CONTROL_ cards the scene's velocities, boundary conditions, contact
 * pairs and settings. A keyword or option that changes the physics and has
 * no equivalent stops the translation with one line naming it; what is
 * only output is listed in one warning, where Anvil's model differs from
 * LS-DYNA's in another (doc/decks.md).
 */
#include <anvil/deck/deck.h>
#include <anvil/mesh/keyword_file.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>

#include "scene_writer.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

namespace anvil::Deck
{
  using namespace KeywordFile;

  namespace
  {
    const char *supported =
      "*NODE, *ELEMENT_SOLID, *PART, *SECTION_SOLID, *HOURGLASS, *MAT_ELASTIC/_PLASTIC_KINEMATIC/"
      "_PIECEWISE_LINEAR_PLASTICITY/_JOHNSON_COOK/_RIGID/_ADD_EROSION, *EOS_LINEAR_POLYNOMIAL, *SET_, *DEFINE_, *INITIAL_VELOCITY, *BOUNDARY_SPC/_PRESCRIBED_MOTION, "
      "*RIGIDWALL_PLANAR, *CONTACT_, *LOAD_BODY_X/Y/Z, *CONTROL_, *DATABASE_; doc/decks.md lists them";

    // Keywords that request output or describe the run without changing
    // its physics: listed in one warning.
    bool output_only(const std::string &name)
    {
      for (const char *prefix : {"DATABASE_", "TITLE", "CONTROL_OUTPUT", "CONTROL_ENERGY", "CONTROL_PARALLEL",
                                 "CONTROL_CPU", "CONTACT_FORCE_TRANSDUCER", "COMMENT", "CASE", "KEYWORD"})
        if (name.rfind(prefix, 0) == 0)
          return true;
      return false;
    }

    [[noreturn]] void unsupported(const Keyword &kw, const std::string &what)
    {
      throw InputError(kw.line.where() + "*" + kw.name + ": " + what);
    }

    // FIELD may carry what is allowed in parentheses: 'ELFORM (allowed: 0,
    // 1)'.
    [[noreturn]] void not_default(const Keyword &kw, const std::string &field, const std::string &value)
    {
      const auto        open = field.find(" (");
      const std::string name = field.substr(0, open);
      unsupported(kw, name + " = " + printable_excerpt(value) + " is not supported (" +
                        (open == std::string::npos ? "Anvil reads this keyword with " + name + " at its default" :
                                                     field.substr(open + 2, field.size() - open - 3)) +
                        "; doc/decks.md)");
    }

    struct Material
    {
      const Keyword *keyword = nullptr;
    };

    struct Part
    {
      long           pid = 0, secid = 0, mid = 0, eosid = 0, hgid = 0;
      std::string    title, body;
      const Keyword *keyword = nullptr;
      bool           rigid   = false;
      dealii::Tensor<1, 3> velocity;
      bool                 has_velocity = false;
      std::array<bool, 6>  rigid_fixed{{false, false, false, false, false, false}};
      bool                 rigid_prescribed = false;
    };

    std::string body_name(const std::string &title, const long pid, const std::set<std::string> &taken)
    {
      std::string s;
      for (const char c : title)
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')
          s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        else if ((c == ' ' || c == '.') && !s.empty() && s.back() != '_')
          s += '_';
      while (!s.empty() && s.back() == '_')
        s.pop_back();
      if (s.empty() || s.size() > 40 || taken.count(s) || !std::isalpha(static_cast<unsigned char>(s[0])))
        s = "part" + std::to_string(pid);
      return s;
    }
  } // namespace


  Translation translate_keyword_deck(const std::string &file, const std::string &mesh_path)
  {
    const Keywords           deck = KeywordFile::read(file, chosen_case());
    const MeshFile::Contents mesh = MeshFile::read_keyword_deck(file);
    SceneWriter              w;

    if (!deck.cases.empty() && chosen_case() == 0)
      {
        std::string list;
        for (const auto &[id, job] : deck.cases)
          list += (list.empty() ? "" : ", ") + std::to_string(id) + (job.empty() ? "" : " (" + job + ")");
        throw InputError("deck '" + file + "' defines the cases " + list +
                         " (*CASE): choose one with 'anvil DECK --case ID'");
      }

    // @sect4{What the deck defines}
    std::map<long, Part>                        parts;
    std::map<long, const Keyword *>             sections, materials, eoses, hourglasses, curves, systems,
                                                add_erosion;
    std::map<long, std::vector<long>>           part_sets;
    std::vector<const Keyword *>                velocities, spcs, walls, contacts, prescribed, body_loads;
    const Keyword *termination = nullptr, *timestep = nullptr, *bulk = nullptr, *control_hourglass = nullptr,
                  *control_contact = nullptr, *d3plot = nullptr, *glstat = nullptr;

    auto id_of = [](const Keyword &kw, const unsigned int card = 0) {
      if (kw.cards.size() <= card)
        unsupported(kw, "a card is missing");
      return integer(kw.fields(card)[0], kw.cards[card], "*" + kw.name + " ID");
    };

    for (const auto &kw : deck.keywords)
      {
        const std::string &n = kw.name;
        if (n == "NODE" || n == "ELEMENT_SOLID" || n == "DEFINE_BOX" || n.rfind("SET_NODE", 0) == 0 ||
            n == "SET_SEGMENT" || n == "BOUNDARY_SPC_NODE")
          {
            if (n.rfind("SET_NODE", 0) == 0 && n != "SET_NODE" && n != "SET_NODE_LIST" &&
                n != "SET_NODE_LIST_GENERATE" && n != "SET_NODE_GENERAL")
              unsupported(kw, "this set option is not supported (allowed: *SET_NODE_LIST, _GENERATE, _GENERAL)");
            if (n == "BOUNDARY_SPC_NODE")
              spcs.push_back(&kw);
            continue; // the mesh reader's
          }
        if (n == "PART")
          {
            // Pairs of cards: a heading, then PID SECID MID EOSID HGID GRAV ADPOPT TMID.
            for (unsigned int c = 0; c + 1 < kw.cards.size(); c += 2)
              {
                const auto f = kw.fields(c + 1);
                Part       p;
                p.title   = kw.cards[c].text;
                p.keyword = &kw;
                p.pid     = integer(f[0], kw.cards[c + 1], "*PART PID");
                p.secid   = integer(f[1], kw.cards[c + 1], "*PART SECID");
                p.mid     = integer(f[2], kw.cards[c + 1], "*PART MID");
                p.eosid   = integer(f[3], kw.cards[c + 1], "*PART EOSID");
                p.hgid    = integer(f[4], kw.cards[c + 1], "*PART HGID");
                if (integer(f[5], kw.cards[c + 1], "*PART GRAV") != 0)
                  not_default(kw, "GRAV", f[5]);
                if (integer(f[6], kw.cards[c + 1], "*PART ADPOPT") != 0)
                  not_default(kw, "ADPOPT", f[6]);
                if (integer(f[7], kw.cards[c + 1], "*PART TMID") != 0)
                  not_default(kw, "TMID", f[7]);
                if (!parts.emplace(p.pid, p).second)
                  unsupported(kw, "part " + std::to_string(p.pid) + " is defined twice");
              }
            if (kw.cards.size() % 2 != 0 && !kw.cards.back().blank())
              unsupported(kw, "a heading without its card 'PID SECID MID ...'");
          }
        else if (n == "SECTION_SOLID")
          sections[id_of(kw)] = &kw;
        else if (n == "HOURGLASS")
          hourglasses[id_of(kw)] = &kw;
        else if (n == "MAT_ELASTIC" || n == "MAT_001" || n == "MAT_PLASTIC_KINEMATIC" || n == "MAT_003" ||
                 n == "MAT_JOHNSON_COOK" || n == "MAT_015" || n == "MAT_RIGID" || n == "MAT_020" ||
                 n == "MAT_PIECEWISE_LINEAR_PLASTICITY" || n == "MAT_024")
          materials[id_of(kw)] = &kw;
        else if (n == "EOS_LINEAR_POLYNOMIAL" || n == "EOS_001")
          eoses[id_of(kw)] = &kw;
        else if (n == "DEFINE_CURVE")
          curves[id_of(kw)] = &kw;
        else if (n == "DEFINE_COORDINATE_SYSTEM")
          systems[id_of(kw)] = &kw;
        else if (n == "SET_PART_LIST" || n == "SET_PART")
          {
            auto &list = part_sets[id_of(kw)];
            for (unsigned int c = 1; c < kw.cards.size(); ++c)
              for (const auto &x : kw.fields(c))
                if (integer(x, kw.cards[c], "*SET_PART PID") != 0)
                  list.push_back(integer(x, kw.cards[c], "*SET_PART PID"));
          }
        else if (n == "INITIAL_VELOCITY" || n == "INITIAL_VELOCITY_GENERATION" || n == "INITIAL_VELOCITY_NODE")
          velocities.push_back(&kw);
        else if (n == "BOUNDARY_SPC_SET")
          spcs.push_back(&kw);
        else if (n == "BOUNDARY_PRESCRIBED_MOTION_RIGID" || n == "BOUNDARY_PRESCRIBED_MOTION_SET")
          prescribed.push_back(&kw);
        else if (n == "RIGIDWALL_PLANAR")
          walls.push_back(&kw);
        else if (n == "LOAD_BODY_X" || n == "LOAD_BODY_Y" || n == "LOAD_BODY_Z")
          body_loads.push_back(&kw);
        else if (n == "CONTACT_AUTOMATIC_SURFACE_TO_SURFACE" || n == "CONTACT_SURFACE_TO_SURFACE" ||
                 n == "CONTACT_AUTOMATIC_NODES_TO_SURFACE" || n == "CONTACT_NODES_TO_SURFACE" ||
                 n == "CONTACT_ERODING_SURFACE_TO_SURFACE" || n == "CONTACT_ERODING_NODES_TO_SURFACE")
          contacts.push_back(&kw);
        else if (n == "MAT_ADD_EROSION")
          add_erosion[id_of(kw)] = &kw;
        else if (n == "CONTROL_SHELL")
          w.ignore("*CONTROL_SHELL (the deck has no shells)");
        else if (n == "CONTROL_SOLID")
          w.ignore("*CONTROL_SOLID (its options concern tetrahedra, wedges and degenerate elements; Anvil takes "
                   "8-node hexahedra only)");
        else if (n == "CONTROL_ACCURACY")
          w.ignore("*CONTROL_ACCURACY (Anvil's stress update is always objective, Hughes-Winget, and node "
                   "numbering does not change its results)");
        else if (n == "CONTROL_TERMINATION")
          termination = &kw;
        else if (n == "CONTROL_TIMESTEP")
          timestep = &kw;
        else if (n == "CONTROL_BULK_VISCOSITY")
          bulk = &kw;
        else if (n == "CONTROL_HOURGLASS")
          control_hourglass = &kw;
        else if (n == "CONTROL_CONTACT")
          control_contact = &kw;
        else if (n == "DATABASE_BINARY_D3PLOT")
          d3plot = &kw;
        else if (n == "DATABASE_GLSTAT")
          glstat = &kw;
        else if (output_only(n))
          w.ignore("*" + n);
        else
          throw InputError(kw.line.where() + "*" + printable_excerpt(n) +
                           " is not supported (Anvil reads " + supported + ")");
      }
    if (parts.empty())
      throw InputError("deck '" + file + "' has no *PART");

    // Which parts hold the nodes of a node set (by the mesh's sets).
    std::map<long, std::set<unsigned int>> part_vertices;
    for (const auto &[pid, p] : parts)
      {
        const auto cells = mesh.cell_sets.find("PART" + std::to_string(pid));
        if (cells == mesh.cell_sets.end())
          throw InputError(p.keyword->line.where() + "*PART " + std::to_string(pid) +
                           " has no *ELEMENT_SOLID (Anvil reads solid parts only)");
        for (const unsigned int c : cells->second)
          part_vertices[pid].insert(mesh.cells[c].begin(), mesh.cells[c].end());
      }
    auto parts_of_nodes = [&](const std::vector<unsigned int> &nodes) {
      std::vector<long> out;
      for (const auto &[pid, vertices] : part_vertices)
        if (std::any_of(nodes.begin(), nodes.end(), [&](unsigned int v) { return vertices.count(v); }))
          out.push_back(pid);
      return out;
    };
    auto node_set = [&](const long sid, const Keyword &kw) -> const std::vector<unsigned int> & {
      const auto s = mesh.node_sets.find("SET" + std::to_string(sid));
      if (s == mesh.node_sets.end())
        unsupported(kw, "node set " + std::to_string(sid) + " is not defined (*SET_NODE_...)");
      return s->second;
    };
    auto covers_part = [&](const std::vector<unsigned int> &nodes, const long pid) {
      const std::set<unsigned int> in(nodes.begin(), nodes.end());
      return std::all_of(part_vertices[pid].begin(), part_vertices[pid].end(),
                         [&](unsigned int v) { return in.count(v); });
    };
    auto parts_of_set = [&](const long sid, const Keyword &kw) {
      const auto s = part_sets.find(sid);
      if (s == part_sets.end())
        unsupported(kw, "part set " + std::to_string(sid) + " is not defined (*SET_PART_LIST)");
      return s->second;
    };
    auto part = [&](const long pid, const Keyword &kw) -> Part & {
      const auto p = parts.find(pid);
      if (p == parts.end())
        unsupported(kw, "part " + std::to_string(pid) + " is not defined (*PART)");
      return p->second;
    };

    std::set<std::string> taken;
    for (auto &[pid, p] : parts)
      {
        p.body = body_name(p.title, pid, taken);
        taken.insert(p.body);
        const auto m = materials.find(p.mid);
        if (m == materials.end())
          throw InputError(p.keyword->line.where() + "*PART " + std::to_string(pid) + ": material " +
                           std::to_string(p.mid) + " is not defined (supported: *MAT_ELASTIC, "
                           "*MAT_PLASTIC_KINEMATIC, *MAT_JOHNSON_COOK, *MAT_RIGID)");
        p.rigid = m->second->name == "MAT_RIGID" || m->second->name == "MAT_020";
      }

    // @sect4{Initial velocities}
    //
    // Anvil gives every body one initial velocity: a set must hold whole
    // parts. A later card for the same part wins, as in LS-DYNA.
    auto rotate = [&](const long cid, const Keyword &kw, dealii::Tensor<1, 3> v) {
      if (cid == 0)
        return v;
      const auto s = systems.find(cid);
      if (s == systems.end())
        unsupported(kw, "coordinate system " + std::to_string(cid) + " is not defined (*DEFINE_COORDINATE_SYSTEM)");
      const Keyword &cs = *s->second;
      const auto     a = cs.fields(0), b = cs.fields(1);
      if (integer(a[7], cs.cards[0], "CIDL") != 0)
        unsupported(cs, "CIDL (a system defined in another) is not supported");
      dealii::Tensor<1, 3> o, l, p;
      for (unsigned int d = 0; d < 3; ++d)
        {
          o[d] = real(a[1 + d], cs.cards[0], "*DEFINE_COORDINATE_SYSTEM origin");
          l[d] = real(a[4 + d], cs.cards[0], "*DEFINE_COORDINATE_SYSTEM x-axis point");
          p[d] = cs.cards.size() > 1 ? real(b[d], cs.cards[1], "*DEFINE_COORDINATE_SYSTEM xy-plane point") : 0;
        }
      dealii::Tensor<1, 3> e1 = l - o, e3 = dealii::cross_product_3d(l - o, p - o);
      if (e1.norm() == 0 || e3.norm() == 0)
        unsupported(cs, "the three points do not define a coordinate system");
      e1 /= e1.norm();
      e3 /= e3.norm();
      const dealii::Tensor<1, 3> e2 = dealii::cross_product_3d(e3, e1);
      return v[0] * e1 + v[1] * e2 + v[2] * e3;
    };
    unsigned int n_node_velocities = 0;
    for (const Keyword *kwp : velocities)
      {
        const Keyword &kw = *kwp;
        const auto     a = kw.fields(0), b = kw.fields(1);
        if (kw.cards.empty())
          unsupported(kw, "a card is missing");
        std::vector<long>    pids;
        dealii::Tensor<1, 3> v;
        if (kw.name == "INITIAL_VELOCITY_NODE")
          {
            // NID VX VY VZ VXR VYR VZR ICID, a card a node: the nodes of
            // each velocity (the mesh reader's node sets) must hold whole
            // parts, which take that velocity.
            const auto groups = KeywordFile::node_velocity_groups(kw);
            std::vector<const std::vector<unsigned int> *> group_nodes;
            std::map<long, std::vector<unsigned int>>      groups_of_part;
            for (unsigned int g = 0; g < groups.size(); ++g)
              {
                for (unsigned int d = 3; d < 6; ++d)
                  if (groups[g].values[d] != 0)
                    not_default(kw, "VXR/VYR/VZR (an initial rotation)", std::to_string(groups[g].values[d]));
                group_nodes.push_back(&mesh.node_sets.at(KeywordFile::node_velocity_set(n_node_velocities, g)));
                for (const long pid : parts_of_nodes(*group_nodes[g]))
                  groups_of_part[pid].push_back(g);
              }
            for (const auto &[pid, in] : groups_of_part)
              {
                const unsigned int g = in.front();
                if (in.size() > 1 || !covers_part(*group_nodes[g], pid))
                  unsupported(kw, "the nodes of part " + std::to_string(pid) +
                                    (in.size() > 1 ? " are given different velocities" :
                                                     " are not all given a velocity") +
                                    ": Anvil gives initial velocities to whole parts (one velocity a part)");
                dealii::Tensor<1, 3> u;
                for (unsigned int d = 0; d < 3; ++d)
                  u[d] = groups[g].values[d];
                auto &p        = part(pid, kw);
                p.velocity     = rotate(groups[g].icid, kw, u);
                p.has_velocity = true;
              }
            ++n_node_velocities;
            continue;
          }
        if (kw.name == "INITIAL_VELOCITY")
          {
            // NSID NSIDEX BOXID IRIGID ICID / VX VY VZ VXR VYR VZR
            const long nsid = integer(a[0], kw.cards[0], "NSID");
            if (integer(a[1], kw.cards[0], "NSIDEX") != 0)
              not_default(kw, "NSIDEX", a[1]);
            if (integer(a[2], kw.cards[0], "BOXID") != 0)
              not_default(kw, "BOXID", a[2]);
            for (unsigned int d = 0; d < 3; ++d)
              {
                v[d] = real(b[d], kw.cards.size() > 1 ? kw.cards[1] : kw.cards[0], "V");
                if (real(b[3 + d], kw.cards.size() > 1 ? kw.cards[1] : kw.cards[0], "VR") != 0)
                  not_default(kw, "VXR/VYR/VZR", b[3 + d]);
              }
            v = rotate(integer(a[4], kw.cards[0], "ICID"), kw, v);
            if (nsid == 0)
              for (const auto &[pid, p] : parts)
                pids.push_back(pid);
            else
              {
                const auto &nodes = node_set(nsid, kw);
                pids              = parts_of_nodes(nodes);
                for (const long pid : pids)
                  if (!covers_part(nodes, pid))
                    unsupported(kw, "node set " + std::to_string(nsid) + " holds part of part " +
                                      std::to_string(pid) + "'s nodes: Anvil gives initial velocities to whole parts");
              }
          }
        else
          {
            // ID STYP OMEGA VX VY VZ IVATN ICID / XC YC ZC NX NY NZ PHASE IRIGID
            const long id   = integer(a[0], kw.cards[0], "ID");
            const long styp = integer(a[1], kw.cards[0], "STYP", 1);
            if (real(a[2], kw.cards[0], "OMEGA") != 0)
              not_default(kw, "OMEGA (an initial rotation)", a[2]);
            for (unsigned int d = 0; d < 3; ++d)
              v[d] = real(a[3 + d], kw.cards[0], "V");
            v = rotate(integer(a[7], kw.cards[0], "ICID"), kw, v);
            if (styp == 1)
              pids = id == 0 ? std::vector<long>() : parts_of_set(id, kw);
            else if (styp == 2)
              pids = {id};
            else if (styp == 3)
              {
                const auto &nodes = node_set(id, kw);
                pids              = parts_of_nodes(nodes);
                for (const long pid : pids)
                  if (!covers_part(nodes, pid))
                    unsupported(kw, "node set " + std::to_string(id) + " holds part of part " +
                                      std::to_string(pid) + "'s nodes: Anvil gives initial velocities to whole parts");
              }
            else
              not_default(kw, "STYP", a[1]);
            if (id == 0)
              for (const auto &[pid, p] : parts)
                pids.push_back(pid);
          }
        for (const long pid : pids)
          {
            auto &p        = part(pid, kw);
            p.velocity     = v;
            p.has_velocity = true;
          }
      }

    // @sect4{The scene}
    w.from(file, 1);
    w.comment("The LS-DYNA keyword deck " + std::filesystem::path(file).filename().string() +
              " as an Anvil scene (anvil --translate); its mesh is read from the deck.");
    w.comment("Units: the deck's own (LS-DYNA has none); every value below is the deck's.");

    // Boundary conditions: node sets per part that holds their nodes.
    struct Constraint
    {
      std::string          set;
      std::array<bool, 3>  dofs{{false, false, false}};
      const Keyword       *keyword = nullptr;
      bool                 velocity = false;
      dealii::Tensor<1, 3> value;
    };
    std::vector<Constraint> constraints;
    auto constraint = [](const std::string &set, const std::array<bool, 3> &dofs, const Keyword *kw) {
      Constraint k;
      k.set     = set;
      k.dofs    = dofs;
      k.keyword = kw;
      return k;
    };
    for (const auto &[name, nodes] : mesh.node_sets)
      if (name.rfind("NODE_TC", 0) == 0)
        {
          const int           tc   = std::stoi(name.substr(7));
          static const char  *code[8] = {"", "X", "Y", "Z", "XY", "YZ", "XZ", "XYZ"};
          std::array<bool, 3> dofs;
          for (unsigned int d = 0; d < 3; ++d)
            dofs[d] = std::string(code[tc]).find(char('X' + d)) != std::string::npos;
          constraints.push_back(constraint(name, dofs, nullptr));
        }
    for (const Keyword *kwp : spcs)
      {
        const Keyword &kw = *kwp;
        for (unsigned int c = 0; c < kw.cards.size(); ++c)
          {
            if (kw.cards[c].blank())
              continue;
            const auto f = kw.fields(c);
            if (integer(f[1], kw.cards[c], "CID") != 0)
              not_default(kw, "CID (a local system)", f[1]);
            std::array<bool, 3> dofs;
            for (unsigned int d = 0; d < 3; ++d)
              dofs[d] = integer(f[2 + d], kw.cards[c], "DOF") != 0;
            if (dofs == std::array<bool, 3>{{false, false, false}})
              continue;
            if (kw.name == "BOUNDARY_SPC_SET")
              {
                const long sid = integer(f[0], kw.cards[c], "NSID");
                node_set(sid, kw);
                constraints.push_back(constraint("SET" + std::to_string(sid), dofs, &kw));
              }
            else
              constraints.push_back(constraint("SPC_NODE_" + MeshFile::keyword_dofs_name(dofs), dofs, &kw));
          }
      }
    // Prescribed motion: a rigid part's velocity, or a node set's.
    auto constant_curve = [&](const long lcid, const Keyword &kw) {
      const auto c = curves.find(lcid);
      if (c == curves.end())
        unsupported(kw, "curve " + std::to_string(lcid) + " is not defined (*DEFINE_CURVE)");
      const Keyword &curve = *c->second;
      const auto     h     = curve.fields(0);
      const double   sfo = real(h[3], curve.cards[0], "SFO", 1), offo = real(h[5], curve.cards[0], "OFFO");
      std::set<double> ordinates;
      for (unsigned int k = 1; k < curve.cards.size(); ++k)
        if (!curve.cards[k].blank())
          ordinates.insert(real(curve.fields(k, {20, 20})[1], curve.cards[k], "*DEFINE_CURVE O"));
      if (ordinates.size() != 1)
        unsupported(kw, "curve " + std::to_string(lcid) +
                          " is not constant: Anvil prescribes constant velocities only");
      return (sfo == 0 ? 1 : sfo) * *ordinates.begin() + offo;
    };
    // A material's failure plastic strain: its own (0: none) and
    // *MAT_ADD_EROSION's EFFEPS, the smaller where both are given. Of
    // *MAT_ADD_EROSION's criteria only EFFEPS is read; a criterion counts
    // as given when it differs from EXCL (0 by default), and any other
    // given one is refused.
    auto failure_strain = [&](const Keyword &mk, const double own) {
      const auto e = add_erosion.find(id_of(mk));
      if (e == add_erosion.end())
        return own;
      const Keyword &kw   = *e->second;
      const auto     f    = kw.fields(0), g = kw.fields(1);
      const double   excl = real(f[1], kw.cards[0], "EXCL");
      const auto     given = [&](const std::string &field, const Card &card, const std::string &name) {
        const double v = real(field, card, name);
        return v != excl && !(excl == 0 && v == 0);
      };
      static const char *names[2][8] = {{"MID", "EXCL", "MXPRES", "MNEPS", "EFFEPS", "VOLEPS", "NUMFIP", "NCS"},
                                        {"MNPRES", "SIGP1", "SIGVM", "MXEPS", "EPSSH", "SIGTH", "IMPULSE", "FAILTM"}};
      for (unsigned int c = 0; c < 2 && c < kw.cards.size(); ++c)
        for (unsigned int i = 0; i < 8; ++i)
          {
            const std::string name = names[c][i];
            if (name == "MID" || name == "EXCL" || name == "EFFEPS" || name == "NUMFIP" || name == "NCS")
              continue;
            if (given(c == 0 ? f[i] : g[i], kw.cards[c], name))
              not_default(kw, name + " (Anvil's erosion criterion is the effective plastic strain, EFFEPS)",
                          c == 0 ? f[i] : g[i]);
          }
      if (!given(f[4], kw.cards[0], "EFFEPS"))
        return own;
      const double effeps = real(f[4], kw.cards[0], "EFFEPS");
      return own > 0 ? std::min(own, effeps) : effeps;
    };
    for (const Keyword *kwp : prescribed)
      {
        const Keyword &kw = *kwp;
        for (unsigned int c = 0; c < kw.cards.size(); ++c)
          {
            if (kw.cards[c].blank())
              continue;
            // ID DOF VAD LCID SF VID DEATH BIRTH
            const auto f   = kw.fields(c);
            const long id  = integer(f[0], kw.cards[c], "ID");
            const long dof = integer(f[1], kw.cards[c], "DOF");
            if (integer(f[2], kw.cards[c], "VAD") != 0)
              not_default(kw, "VAD (Anvil prescribes velocities: VAD = 0)", f[2]);
            if (dof < 1 || dof > 3)
              not_default(kw, "DOF (allowed: 1, 2, 3)", f[1]);
            if (integer(f[5], kw.cards[c], "VID") != 0)
              not_default(kw, "VID", f[5]);
            if (real(f[6], kw.cards[c], "DEATH", 1e28) < 1e20 || real(f[7], kw.cards[c], "BIRTH") != 0)
              not_default(kw, "DEATH/BIRTH", f[6] + " " + f[7]);
            const double v =
              real(f[4], kw.cards[c], "SF", 1) * constant_curve(integer(f[3], kw.cards[c], "LCID"), kw);
            if (kw.name == "BOUNDARY_PRESCRIBED_MOTION_RIGID")
              {
                auto &p = part(id, kw);
                if (!p.rigid)
                  unsupported(kw, "part " + std::to_string(id) + " is not of *MAT_RIGID");
                p.rigid_prescribed  = true;
                p.velocity[dof - 1] = v;
                p.has_velocity      = true;
              }
            else
              {
                node_set(id, kw);
                std::array<bool, 3> dofs{{false, false, false}};
                dofs[dof - 1] = true;
                Constraint k     = constraint("SET" + std::to_string(id), dofs, &kw);
                k.velocity       = true;
                k.value[dof - 1] = v;
                constraints.push_back(k);
              }
          }
      }
    // Body loads: a base acceleration a along an axis is gravity -a (LS-DYNA's
    // *LOAD_BODY_Z with 9.81 pulls towards -z), for every part.
    dealii::Tensor<1, 3> gravity;
    const Keyword       *gravity_keyword = nullptr;
    for (const Keyword *kwp : body_loads)
      {
        const Keyword &kw = *kwp;
        if (kw.cards.empty())
          unsupported(kw, "a card is missing");
        const auto f = kw.fields(0);
        if (integer(f[2], kw.cards[0], "LCIDDR") != 0)
          not_default(kw, "LCIDDR (dynamic relaxation)", f[2]);
        if (integer(f[6], kw.cards[0], "CID") != 0)
          not_default(kw, "CID (a local system)", f[6]);
        const unsigned int d = kw.name.back() - 'X';
        gravity[d] -= real(f[1], kw.cards[0], "SF", 1) * constant_curve(integer(f[0], kw.cards[0], "LCID"), kw);
        gravity_keyword = &kw;
      }

    std::vector<std::pair<std::string, std::string>> bcs; // name, body
    std::vector<std::pair<Constraint, long>>         bc_of;
    for (const auto &k : constraints)
      for (const long pid : parts_of_nodes(mesh.node_sets.at(k.set)))
        if (!parts[pid].rigid)
          {
            std::string name = "bc_" + k.set + "_" + parts[pid].body;
            for (auto &ch : name)
              ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
            name += "_" + std::to_string(bcs.size() + 1);
            bcs.emplace_back(name, parts[pid].body);
            bc_of.emplace_back(k, pid);
          }

    // Rigid walls: a rigid body carrying the plane, in contact with the
    // parts whose nodes the wall's set holds.
    struct Wall
    {
      std::string          name;
      dealii::Point<3>     point;
      dealii::Tensor<1, 3> normal;
      double               friction = 0;
      std::vector<long>    pids;
      const Keyword       *keyword;
      /** The penalty's scale factor RWPNAL x RWKSF; 0: the nodes are
          constrained (kinematic contact). */
      double               penalty = 0;
    };
    std::vector<Wall> wall_list;
    // *CONTROL_CONTACT's RWPNAL: 0 (the default), the wall constrains the
    // nodes of deformable parts and leaves rigid parts alone (Anvil's
    // kinematic contact); > 0, a penalty of that scale factor on every node;
    // < 0, the penalty on the nodes of rigid parts only.
    double      rwpnal = 0;
    std::string rwpnal_text;
    if (control_contact && !control_contact->cards.empty())
      {
        rwpnal_text = control_contact->fields(0)[1];
        rwpnal      = real(rwpnal_text, control_contact->cards[0], "RWPNAL", 0.);
      }
    double            size = 0;
    {
      dealii::Point<3> lo = mesh.vertices[0], hi = mesh.vertices[0];
      for (const auto &x : mesh.vertices)
        for (unsigned int d = 0; d < 3; ++d)
          lo[d] = std::min(lo[d], x[d]), hi[d] = std::max(hi[d], x[d]);
      size = std::max(1e-30, lo.distance(hi));
    }
    for (const Keyword *kwp : walls)
      {
        const Keyword &kw = *kwp;
        if (kw.cards.size() < 2)
          unsupported(kw, "expected the cards 'NSID NSIDEX BOXID ...' and 'XT YT ZT XH YH ZH FRIC WVEL'");
        const auto a = kw.fields(0), b = kw.fields(1);
        Wall       wall;
        wall.keyword  = &kw;
        wall.name     = "wall" + std::to_string(wall_list.size() + 1);
        const long nsid = integer(a[0], kw.cards[0], "NSID");
        if (integer(a[1], kw.cards[0], "NSIDEX") != 0)
          not_default(kw, "NSIDEX", a[1]);
        if (integer(a[2], kw.cards[0], "BOXID") != 0)
          not_default(kw, "BOXID", a[2]);
        if (real(a[3], kw.cards[0], "OFFSET") != 0)
          not_default(kw, "OFFSET", a[3]);
        if (real(a[4], kw.cards[0], "BIRTH") != 0 || real(a[5], kw.cards[0], "DEATH", 1e20) < 1e20)
          not_default(kw, "BIRTH/DEATH", a[4] + " " + a[5]);
        dealii::Tensor<1, 3> head;
        for (unsigned int d = 0; d < 3; ++d)
          {
            wall.point[d] = real(b[d], kw.cards[1], "XT");
            head[d]       = real(b[3 + d], kw.cards[1], "XH");
          }
        wall.normal = head - wall.point;
        if (wall.normal.norm() == 0)
          unsupported(kw, "the normal's head and tail coincide");
        wall.normal /= wall.normal.norm();
        wall.friction = real(b[6], kw.cards[1], "FRIC");
        if (wall.friction < 0 || wall.friction >= 1)
          not_default(kw, "FRIC (allowed: 0 <= FRIC < 1, a Coulomb coefficient)", b[6]);
        if (real(b[7], kw.cards[1], "WVEL") != 0)
          not_default(kw, "WVEL", b[7]);
        const double rwksf = real(a[6], kw.cards[0], "RWKSF", 1.);
        if (!(rwksf > 0))
          not_default(kw, "RWKSF (allowed: > 0, a scale of the penalty)", a[6]);
        std::vector<long> touched;
        if (nsid == 0)
          for (const auto &[pid, p] : parts)
            touched.push_back(pid);
        else
          touched = parts_of_nodes(node_set(nsid, kw));
        // Anvil has no contact between two rigid bodies: LS-DYNA's penalty
        // on the nodes of rigid parts (RWPNAL other than 0) is refused where
        // the set holds such a part; with RWPNAL = 0 LS-DYNA leaves them
        // alone, as Anvil does.
        bool rigid_left_out = false;
        for (const long pid : touched)
          if (!parts.at(pid).rigid)
            wall.pids.push_back(pid);
          else if (nsid == 0)
            rigid_left_out = true;
          else if (rwpnal != 0)
            unsupported(kw, "the node set holds rigid part " + std::to_string(pid) +
                              ", which a rigid wall meets by penalty with *CONTROL_CONTACT's RWPNAL = " +
                              rwpnal_text +
                              " (supported: RWPNAL = 0, which leaves rigid parts alone, or a set without rigid "
                              "parts)");
        if (rigid_left_out && rwpnal != 0)
          w.differ("*RIGIDWALL_PLANAR: the wall meets no rigid part (LS-DYNA's penalty with RWPNAL = " +
                   rwpnal_text + " would meet their nodes)");
        if (rwpnal > 0)
          wall.penalty = rwpnal * rwksf;
        else if (rwksf != 1)
          w.differ("*RIGIDWALL_PLANAR: RWKSF scales a penalty, and this wall constrains the nodes "
                   "(*CONTROL_CONTACT RWPNAL <= 0): not used");
        if (nsid != 0)
          w.differ("*RIGIDWALL_PLANAR: the wall meets every node of the parts its set touches");
        wall_list.push_back(wall);
      }

    // Contacts: pairs of bodies.
    double slsfac = 0.1;
    if (control_contact)
      {
        const auto f = control_contact->fields(0);
        slsfac       = real(f[0], control_contact->cards.empty() ? control_contact->line : control_contact->cards[0],
                            "SLSFAC", 0.1);
        if (slsfac == 0)
          slsfac = 0.1;
      }
    struct Pair
    {
      std::string    first, second;
      bool           symmetric;
      double         factor, fs, fd, dc, vdc;
      const Keyword *keyword;
      /** SOFT = 1: SOFSCL (0: SOFT = 0). */
      double         sofscl = 0;
    };
    std::vector<Pair> pairs;
    for (const Keyword *kwp : contacts)
      {
        const Keyword &kw = *kwp;
        if (kw.cards.empty())
          unsupported(kw, "a card is missing");
        // (The eroding contacts' fourth card, ISYM EROSOP IADJ, comes
        // before the optional card A: Anvil's surfaces take in the faces an
        // eroded element exposes in every pair, doc/theory.md.)
        const unsigned int card_a = kw.name.find("ERODING") != std::string::npos ? 4 : 3;
        const auto a = kw.fields(0), b = kw.fields(1), c = kw.fields(2), d = kw.fields(card_a);
        auto side = [&](const std::string &id, const std::string &type, const std::string &what) {
          const long        sid = integer(id, kw.cards[0], what + "ID");
          const long        t   = integer(type, kw.cards[0], what + "TYP");
          std::vector<long> out;
          if (t == 3)
            out = {sid};
          else if (t == 2)
            out = parts_of_set(sid, kw);
          else if (t == 5)
            for (const auto &[pid, p] : parts)
              out.push_back(pid);
          else if (t == 4)
            {
              out = parts_of_nodes(node_set(sid, kw));
              w.differ("*" + kw.name + ": a node set stands for the whole surfaces of the parts it touches");
            }
          else if (t == 0)
            {
              const auto s = mesh.surfaces.find("SEGMENTSET" + std::to_string(sid));
              if (s == mesh.surfaces.end())
                unsupported(kw, "segment set " + std::to_string(sid) + " is not defined (*SET_SEGMENT)");
              std::vector<unsigned int> nodes;
              for (const auto &face : mesh.faces)
                if (face.boundary_id == s->second)
                  nodes.insert(nodes.end(), face.vertices.begin(), face.vertices.end());
              out = parts_of_nodes(nodes);
              w.differ("*" + kw.name + ": a segment set stands for the whole surfaces of the parts it touches");
            }
          else
            not_default(kw, what + "TYP (allowed: 0, 2, 3, 4, 5)", type);
          for (const long pid : out)
            part(pid, kw);
          return out;
        };
        const auto slaves  = side(a[0], a[2], "SS");
        const auto masters = side(a[1], a[3], "MS");
        if (integer(a[4], kw.cards[0], "SBOXID") != 0 || integer(a[5], kw.cards[0], "MBOXID") != 0)
          not_default(kw, "SBOXID/MBOXID", a[4] + " " + a[5]);
        const Card  &cb = kw.cards.size() > 1 ? kw.cards[1] : kw.cards[0];
        const double fs = real(b[0], cb, "FS"), fd = real(b[1], cb, "FD"), dc = real(b[2], cb, "DC");
        if (real(b[3], cb, "VC") != 0)
          not_default(kw, "VC (viscous friction)", b[3]);
        const double vdc = real(b[4], cb, "VDC");
        if (real(b[6], cb, "BT") != 0 || real(b[7], cb, "DT", 1e20) < 1e20)
          not_default(kw, "BT/DT", b[6] + " " + b[7]);
        const Card  &cc  = kw.cards.size() > 2 ? kw.cards[2] : kw.cards[0];
        const double sfs = kw.cards.size() > 2 ? real(c[0], cc, "SFS", 1) : 1;
        const double sfm = kw.cards.size() > 2 ? real(c[1], cc, "SFM", 1) : 1;
        // Optional card A: SOFT = 0, or 1 (the penalty from the nodal
        // masses and the step, SOFSCL 0.1 by default).
        const long soft = kw.cards.size() > card_a ? integer(d[0], kw.cards[card_a], "SOFT") : 0;
        if (soft != 0 && soft != 1)
          not_default(kw, "SOFT (allowed: 0, 1)", d[0]);
        double sofscl = 0;
        if (soft == 1)
          {
            sofscl = real(d[1], kw.cards[card_a], "SOFSCL", 0.1);
            if (sofscl == 0)
              sofscl = 0.1;
            if (!(sofscl <= 0.4))
              not_default(kw, "SOFSCL above 0.4", d[1]);
          }
        if (sfs != sfm)
          w.differ("*" + kw.name + ": one penalty factor SLSFAC x SFS for both sides (SFM differs)");
        const bool symmetric = kw.name.find("SURFACE_TO_SURFACE") != std::string::npos;
        for (const long s : slaves)
          for (const long m : masters)
            if (s != m)
              {
                const bool seen = std::any_of(pairs.begin(), pairs.end(), [&](const Pair &p) {
                  return (p.first == parts[m].body && p.second == parts[s].body) ||
                         (p.first == parts[s].body && p.second == parts[m].body);
                });
                if (!seen)
                  pairs.push_back({parts[m].body, parts[s].body, symmetric,
                                   (sfs == 0 ? 1 : sfs) * slsfac, fs, fd, dc, vdc, &kw, sofscl});
              }
      }

    {
      std::string bodies;
      for (const auto &[pid, p] : parts)
        bodies += (bodies.empty() ? "" : ", ") + p.body;
      for (const auto &wall : wall_list)
        bodies += ", " + wall.name;
      w.set("Bodies", bodies);
      std::string list;
      for (const auto &b : bcs)
        list += (list.empty() ? "" : ", ") + b.first;
      if (!list.empty())
        w.set("Boundary conditions", list);
      list.clear();
      for (const auto &p : pairs)
        list += (list.empty() ? "" : ", ") + p.first + "_" + p.second;
      for (const auto &wall : wall_list)
        for (const long pid : wall.pids)
          list += (list.empty() ? "" : ", ") + wall.name + "_" + parts[pid].body;
      if (!list.empty())
        w.set("Contact pairs", list);
    }

    // @sect4{Simulation}
    w.blank();
    w.enter("Simulation");
    if (!termination)
      throw InputError("deck '" + file + "' has no *CONTROL_TERMINATION: Anvil needs the end time");
    {
      const Keyword &kw = *termination;
      if (kw.cards.empty())
        unsupported(kw, "a card is missing");
      const auto f = kw.fields(0);
      w.from(kw.cards[0].file, kw.cards[0].line);
      const double end = real(f[0], kw.cards[0], "ENDTIM");
      if (!(end > 0))
        not_default(kw, "ENDTIM (must be positive)", f[0]);
      w.set("End time", end);
      const long endcyc = integer(f[1], kw.cards[0], "ENDCYC");
      if (endcyc > 0)
        w.set("Maximum number of steps", std::to_string(endcyc));
      const double dtmin = real(f[2], kw.cards[0], "DTMIN");
      if (dtmin > 0)
        w.set("Minimum time step ratio", dtmin);
      if (real(f[3], kw.cards[0], "ENDENG") != 0 || real(f[4], kw.cards[0], "ENDMAS") != 0)
        not_default(kw, "ENDENG/ENDMAS", f[3] + " " + f[4]);
    }
    if (timestep && !timestep->cards.empty())
      {
        const Keyword &kw = *timestep;
        const auto     f  = kw.fields(0);
        w.from(kw.cards[0].file, kw.cards[0].line);
        const double tssfac = real(f[1], kw.cards[0], "TSSFAC");
        w.set("Time step safety factor", tssfac == 0 ? 0.9 : tssfac);
        if (real(f[4], kw.cards[0], "DT2MS") != 0)
          not_default(kw, "DT2MS (mass scaling)", f[4]);
        if (integer(f[5], kw.cards[0], "LCTM") != 0)
          not_default(kw, "LCTM", f[5]);
        if (integer(f[2], kw.cards[0], "ISDO") != 0)
          not_default(kw, "ISDO", f[2]);
      }
    else
      w.set("Time step safety factor", 0.9);
    if (gravity_keyword)
      {
        w.from(gravity_keyword->line.file, gravity_keyword->line.line);
        w.set("Gravity", SceneWriter::vector(gravity[0], gravity[1], gravity[2]));
      }
    if (d3plot && !d3plot->cards.empty())
      {
        w.from(d3plot->cards[0].file, d3plot->cards[0].line);
        w.set("Output interval", real(d3plot->fields(0)[0], d3plot->cards[0], "DT"));
      }
    if (glstat && !glstat->cards.empty())
      {
        w.from(glstat->cards[0].file, glstat->cards[0].line);
        w.set("History interval", real(glstat->fields(0)[0], glstat->cards[0], "DT"));
      }
    w.leave();

    // @sect4{Bodies}
    double q1 = 1.5, q2 = 0.06;
    if (bulk && !bulk->cards.empty())
      {
        const auto f = bulk->fields(0);
        q1           = real(f[0], bulk->cards[0], "Q1", 1.5);
        q2           = real(f[1], bulk->cards[0], "Q2", 0.06);
        const long t = integer(f[2], bulk->cards[0], "TYPE", 1);
        if (t != 1 && t != 0)
          not_default(*bulk, "TYPE (allowed: 1)", f[2]);
        if (q1 == 0 && q2 == 0)
          q1 = 1.5, q2 = 0.06;
      }
    long   default_ihq = 1;
    double default_qh  = 0.1;
    if (control_hourglass && !control_hourglass->cards.empty())
      {
        const auto f = control_hourglass->fields(0);
        default_ihq  = integer(f[0], control_hourglass->cards[0], "IHQ", 1);
        default_qh   = real(f[1], control_hourglass->cards[0], "QH", 0.1);
      }
    double wall_density = 0, wall_modulus = 0;
    for (const auto &[pid, p] : parts)
      {
        const Keyword &pk = *p.keyword;
        w.blank();
        w.from(pk.line.file, pk.line.line);
        w.enter("Body " + p.body);
        w.comment("*PART " + std::to_string(pid) + (p.title.empty() ? "" : " '" + printable_excerpt(p.title) + "'"));
        w.enter("Mesh");
        w.set("Source", "file");
        w.set("File name", mesh_path);
        w.set("Region", "PART" + std::to_string(pid));
        w.leave();
        if (p.has_velocity)
          w.set("Initial velocity", SceneWriter::vector(p.velocity[0], p.velocity[1], p.velocity[2]));

        // Section: the integration.
        if (!p.rigid)
          {
            const auto s = sections.find(p.secid);
            if (s == sections.end())
              throw InputError(pk.line.where() + "*PART " + std::to_string(pid) + ": section " +
                               std::to_string(p.secid) + " is not defined (*SECTION_SOLID)");
            const Keyword &sk     = *s->second;
            const long     elform = integer(sk.fields(0)[1], sk.cards[0], "ELFORM", 1);
            w.from(sk.cards[0].file, sk.cards[0].line);
            // ELFORM 2 is selectively reduced (constant volume strain): it
            // does not lock in plastic flow, Anvil's full 2x2x2 integration
            // does (doc/accuracy.md); the one-point element is the nearer.
            if (elform == 0 || elform == 1 || elform == 2)
              {
                w.set("Integration", "one point");
                if (elform == 2)
                  w.differ("ELFORM 2 (selectively reduced): Anvil's one-point element with hourglass control, "
                           "as its full 2x2x2 integration locks in plastic flow (doc/decks.md)");
              }
            else if (elform == -1 || elform == -2)
              w.set("Integration", "full");
            else
              not_default(sk, "ELFORM (allowed: 0, 1, 2, -1, -2)", sk.fields(0)[1]);

            // Hourglass control of one-point elements.
            long   ihq = default_ihq;
            double qm  = default_qh;
            double hq1 = q1, hq2 = q2;
            if (p.hgid != 0)
              {
                const auto h = hourglasses.find(p.hgid);
                if (h == hourglasses.end())
                  throw InputError(pk.line.where() + "*PART " + std::to_string(pid) + ": hourglass " +
                                   std::to_string(p.hgid) + " is not defined (*HOURGLASS)");
                const auto f = h->second->fields(0);
                ihq          = integer(f[1], h->second->cards[0], "IHQ", default_ihq);
                qm           = real(f[2], h->second->cards[0], "QM", default_qh);
                hq1          = real(f[4], h->second->cards[0], "Q1", q1);
                hq2          = real(f[5], h->second->cards[0], "Q2", q2);
                w.from(h->second->cards[0].file, h->second->cards[0].line);
              }
            w.enter("Hourglass control");
            if (ihq == 0 || ihq == 1 || ihq == 2 || ihq == 3)
              w.set("Type", "viscous");
            else if (ihq == 4 || ihq == 5 || ihq == 6)
              {
                w.set("Type", "stiffness");
                if (ihq == 6)
                  w.differ("IHQ 6: Anvil's Flanagan-Belytschko stiffness form, not Belytschko-Bindeman's");
              }
            else
              throw InputError(pk.line.where() + "*PART " + std::to_string(pid) + ": hourglass type IHQ = " +
                               std::to_string(ihq) + " is not supported (allowed: 0-6)");
            w.set("Coefficient", qm == 0 ? 0.1 : qm);
            w.leave();
            w.enter("Bulk viscosity");
            w.set("Linear coefficient", hq2);
            w.set("Quadratic coefficient", hq1);
            w.leave();
          }

        // The material.
        const Keyword &mk = *materials.at(p.mid);
        w.from(mk.cards.empty() ? mk.line.file : mk.cards[0].file, mk.cards.empty() ? mk.line.line : mk.cards[0].line);
        if (mk.cards.empty())
          unsupported(mk, "a card is missing");
        const auto  a = mk.fields(0), b = mk.fields(1), c = mk.fields(2), d = mk.fields(3);
        if (real(a[2], mk.cards[0], "E") > wall_modulus || wall_modulus == 0)
          {
            wall_modulus = mk.name == "MAT_JOHNSON_COOK" || mk.name == "MAT_015" ?
                             3 * real(a[2], mk.cards[0], "G") : real(a[2], mk.cards[0], "E");
            wall_density = real(a[1], mk.cards[0], "RO");
          }
        if (add_erosion.count(p.mid) && !(mk.name == "MAT_PLASTIC_KINEMATIC" || mk.name == "MAT_003" ||
                                          mk.name == "MAT_PIECEWISE_LINEAR_PLASTICITY" || mk.name == "MAT_024"))
          unsupported(*add_erosion.at(p.mid), "on *" + mk.name + " (Anvil reads it for *MAT_PLASTIC_KINEMATIC and "
                                              "*MAT_PIECEWISE_LINEAR_PLASTICITY; Johnson-Cook erodes at its damage)");
        const Card &c0 = mk.cards[0];
        const Card &c1 = mk.cards.size() > 1 ? mk.cards[1] : c0;
        const Card &c2 = mk.cards.size() > 2 ? mk.cards[2] : c0;
        const Card &c3 = mk.cards.size() > 3 ? mk.cards[3] : c0;
        w.enter("Material");
        if (p.rigid)
          {
            w.set("Model", "rigid");
            w.enter("rigid");
            w.set("Density", real(a[1], c0, "RO"));
            w.set("Young's modulus", real(a[2], c0, "E"));
            w.set("Poisson's ratio", real(a[3], c0, "PR"));
            w.leave();
          }
        else if (mk.name == "MAT_ELASTIC" || mk.name == "MAT_001")
          {
            w.set("Model", "elastic");
            w.enter("elastic");
            w.set("Density", real(a[1], c0, "RO"));
            w.set("Young's modulus", real(a[2], c0, "E"));
            w.set("Poisson's ratio", real(a[3], c0, "PR"));
            w.leave();
          }
        else if (mk.name == "MAT_PLASTIC_KINEMATIC" || mk.name == "MAT_003")
          {
            w.set("Model", "plastic kinematic");
            w.enter("plastic kinematic");
            w.set("Density", real(a[1], c0, "RO"));
            w.set("Young's modulus", real(a[2], c0, "E"));
            w.set("Poisson's ratio", real(a[3], c0, "PR"));
            w.set("Yield stress", real(a[4], c0, "SIGY"));
            w.set("Tangent modulus", real(a[5], c0, "ETAN"));
            w.set("Hardening parameter beta", real(a[6], c0, "BETA"));
            const double src = real(b[0], c1, "SRC"), srp = real(b[1], c1, "SRP"), fs = real(b[2], c1, "FS");
            const double vp = real(b[3], c1, "VP");
            if (src > 0 && srp > 0)
              {
                w.set("Cowper-Symonds C", src);
                w.set("Cowper-Symonds p", srp);
                w.set("Strain rate effects", "Cowper-Symonds");
                if (vp == 0)
                  w.differ("*MAT_PLASTIC_KINEMATIC VP = 0: Anvil's rate is the plastic strain rate (VP = 1)");
              }
            else
              w.set("Strain rate effects", "none");
            if (const double f = failure_strain(mk, fs); f > 0)
              {
                w.set("Failure strain", f);
                w.set("Erosion", "true");
              }
            w.leave();
          }
        else if (mk.name == "MAT_PIECEWISE_LINEAR_PLASTICITY" || mk.name == "MAT_024")
          {
            // MID RO E PR SIGY ETAN FAIL TDEL / C P LCSS LCSR VP /
            // EPS1 ... EPS8 / ES1 ... ES8. The flow curve: LCSS's
            // *DEFINE_CURVE, else the EPS-ES pairs, else SIGY and the
            // hardening modulus E ETAN / (E - ETAN); beyond its end
            // LS-DYNA continues the last slope.
            const double E = real(a[2], c0, "E"), sigy = real(a[4], c0, "SIGY"), etan = real(a[5], c0, "ETAN");
            std::vector<std::pair<double, double>> points;
            const long lcss = integer(b[2], c1, "LCSS");
            if (lcss != 0)
              {
                const auto cv = curves.find(lcss);
                if (cv == curves.end())
                  unsupported(mk, "LCSS " + std::to_string(lcss) + " is not a *DEFINE_CURVE (a *DEFINE_TABLE of "
                                  "curves by strain rate is not supported)");
                const Keyword &curve = *cv->second;
                const auto     h     = curve.fields(0);
                const double   sfa = real(h[2], curve.cards[0], "SFA", 1), sfo = real(h[3], curve.cards[0], "SFO", 1),
                             offa = real(h[4], curve.cards[0], "OFFA"), offo = real(h[5], curve.cards[0], "OFFO");
                for (unsigned int k = 1; k < curve.cards.size(); ++k)
                  if (!curve.cards[k].blank())
                    {
                      const auto xy = curve.fields(k, {20, 20});
                      points.emplace_back((sfa == 0 ? 1 : sfa) * (real(xy[0], curve.cards[k], "*DEFINE_CURVE A") + offa),
                                          (sfo == 0 ? 1 : sfo) * (real(xy[1], curve.cards[k], "*DEFINE_CURVE O") + offo));
                    }
                if (points.empty() || points[0].first != 0)
                  unsupported(mk, "LCSS " + std::to_string(lcss) + ": the curve must start at zero plastic strain");
              }
            else if (mk.cards.size() > 3 && real(d[0], c3, "ES1") > 0)
              {
                for (unsigned int i = 0; i < 8; ++i)
                  {
                    const double eps = real(c[i], c2, "EPS"), es = real(d[i], c3, "ES");
                    if (i > 0 && eps == 0 && es == 0)
                      break;
                    points.emplace_back(eps, es);
                  }
              }
            else
              {
                points.emplace_back(0., sigy);
                if (etan > 0)
                  points.emplace_back(1., sigy + E * etan / (E - etan));
              }
            std::string flow_curve;
            for (const auto &[eps, es] : points)
              flow_curve += (flow_curve.empty() ? "" : ", ") + w.number(eps) + ":" + w.number(es);
            if (integer(b[3], c1, "LCSR") != 0)
              not_default(mk, "LCSR", b[3]);
            if (real(a[7], c0, "TDEL") != 0)
              not_default(mk, "TDEL", a[7]);
            w.set("Model", "piecewise linear plasticity");
            w.enter("piecewise linear plasticity");
            w.set("Density", real(a[1], c0, "RO"));
            w.set("Young's modulus", E);
            w.set("Poisson's ratio", real(a[3], c0, "PR"));
            w.set("Flow curve", flow_curve);
            w.set("Beyond the curve", "extrapolate");
            const double C = real(b[0], c1, "C"), P = real(b[1], c1, "P"), vp = real(b[4], c1, "VP");
            if (C > 0 && P > 0)
              {
                w.set("Cowper-Symonds C", C);
                w.set("Cowper-Symonds p", P);
                if (vp != 1)
                  w.differ("*MAT_PIECEWISE_LINEAR_PLASTICITY VP = " + b[4] +
                           ": Anvil's rate is the plastic strain rate (VP = 1)");
              }
            const double fail = real(a[6], c0, "FAIL");
            if (fail < 0)
              not_default(mk, "FAIL (allowed: a plastic strain >= 0)", a[6]);
            if (const double f = failure_strain(mk, fail < 1e20 ? fail : 0.); f > 0)
              w.set("Failure strain", f);
            w.leave();
          }
        else if (mk.name == "MAT_JOHNSON_COOK" || mk.name == "MAT_015")
          {
            // MID RO G E PR DTF VP RATEOP / A B N C M TM TR EPSO /
            // CP PC SPALL IT D1 D2 D3 D4 / D5 C2 EROD EFMIN NUMINT
            const double G = real(a[2], c0, "G");
            double       E = real(a[3], c0, "E"), nu = real(a[4], c0, "PR");
            if (p.eosid != 0)
              {
                const auto e = eoses.find(p.eosid);
                if (e == eoses.end())
                  throw InputError(pk.line.where() + "*PART " + std::to_string(pid) + ": equation of state " +
                                   std::to_string(p.eosid) + " is not defined (*EOS_LINEAR_POLYNOMIAL)");
                const Keyword &ek = *e->second;
                const auto     f  = ek.fields(0);
                for (const unsigned int i : {1u, 3u, 4u, 5u, 6u, 7u})
                  if (real(f[i], ek.cards[0], "C") != 0)
                    not_default(ek, "C" + std::to_string(i - 1) + " (Anvil's pressure is linear: C1 only)", f[i]);
                const double K = real(f[2], ek.cards[0], "C1");
                if (!(K > 0) || !(G > 0))
                  unsupported(mk, "G and the EOS's C1 (bulk modulus) must be positive");
                E  = 9 * K * G / (3 * K + G);
                nu = (3 * K - 2 * G) / (2 * (3 * K + G));
              }
            else if (!(E > 0))
              unsupported(mk, "solids need an equation of state (EOSID on *PART) or E and PR");
            if (integer(a[7], c0, "RATEOP") != 0)
              not_default(mk, "RATEOP", a[7]);
            w.set("Model", "johnson cook");
            w.enter("johnson cook");
            w.set("Density", real(a[1], c0, "RO"));
            w.set("Young's modulus", E);
            w.set("Poisson's ratio", nu);
            w.set("A", real(b[0], c1, "A"));
            w.set("B", real(b[1], c1, "B"));
            w.set("n", real(b[2], c1, "N"));
            w.set("C", real(b[3], c1, "C"));
            w.set("m", real(b[4], c1, "M", 1));
            w.set("Melting temperature", real(b[5], c1, "TM"));
            w.set("Transition temperature", real(b[6], c1, "TR"));
            w.set("Initial temperature", real(b[6], c1, "TR"));
            w.set("Reference strain rate", real(b[7], c1, "EPSO", 1));
            w.set("Specific heat", real(c[0], c2, "CP"));
            w.set("Inelastic heat fraction", 1.0);
            bool damage = false;
            for (unsigned int i = 0; i < 5; ++i)
              {
                const double Di = i < 4 ? real(c[4 + i], c2, "D") : real(d[0], c3, "D5");
                w.set("D" + std::to_string(i + 1), Di);
                damage = damage || Di != 0;
              }
            if (damage && real(d[2], c3, "EROD") == 0)
              w.set("Erosion", "true");
            if (real(d[1], c3, "C2/P") != 0)
              not_default(mk, "C2/P/XNP", d[1]);
            // VP = 0 (the default): the total strain rate scales the yield
            // stress; VP = 1: the plastic strain rate, solved with the
            // return.
            w.set("Rate form", real(a[6], c0, "VP") == 0 ? "total" : "plastic");
            if (real(c[1], c2, "PC") != 0)
              w.differ("*MAT_JOHNSON_COOK PC/SPALL: no spall model (no pressure cutoff)");
            w.differ("*MAT_JOHNSON_COOK: all plastic work turns to heat (LS-DYNA's adiabatic rule)");
            w.leave();
          }
        w.leave();

        if (p.rigid)
          {
            // CMO CON1 CON2: constraints of the rigid body.
            const long cmo = integer(b[0], c1, "CMO");
            std::string constraints;
            if (cmo == 1)
              {
                static const char *code[8] = {"", "x", "y", "z", "x, y", "y, z", "z, x", "x, y, z"};
                const long         t = integer(b[1], c1, "CON1"), r = integer(b[2], c1, "CON2");
                if (t < 0 || t > 7 || r < 0 || r > 7)
                  not_default(mk, "CON1/CON2 (allowed: 0 to 7)", b[1] + " " + b[2]);
                constraints = code[t];
                std::string rot = code[r];
                for (auto &ch : rot)
                  if (ch >= 'x' && ch <= 'z')
                    constraints += std::string(constraints.empty() ? "" : ", ") + "r" + ch, ch = ' ';
              }
            else if (cmo != 0)
              not_default(mk, "CMO (allowed: 0, 1)", b[0]);
            w.enter("Rigid body");
            const bool held = constraints == "x, y, z, rx, ry, rz";
            w.set("Motion", (p.rigid_prescribed || held) ? "prescribed" : "free");
            if (!(p.rigid_prescribed || held) && !constraints.empty())
              w.set("Constraints", constraints);
            if (p.rigid_prescribed && !held && cmo == 1 && !constraints.empty())
              w.differ("*MAT_RIGID with *BOUNDARY_PRESCRIBED_MOTION_RIGID: the whole motion is prescribed");
            w.leave();
          }
        w.leave();
      }

    // The rigid walls' bodies: a thin block behind the plane.
    for (const auto &wall : wall_list)
      {
        w.blank();
        w.from(wall.keyword->line.file, wall.keyword->line.line);
        w.enter("Body " + wall.name);
        w.comment("*RIGIDWALL_PLANAR: an exact plane through the tail point, its normal towards the head");
        const double     h = 0.05 * size;
        dealii::Point<3> lo, hi;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double centre = wall.point[d] - 0.5 * h * wall.normal[d];
            lo[d]               = centre - 0.5 * h;
            hi[d]               = centre + 0.5 * h;
          }
        w.enter("Mesh");
        w.set("Source", "box");
        w.set("Lower corner", SceneWriter::vector(lo[0], lo[1], lo[2]));
        w.set("Upper corner", SceneWriter::vector(hi[0], hi[1], hi[2]));
        w.leave();
        // In the deck's units: the density and modulus of the stiffest part.
        w.enter("Material");
        w.set("Model", "rigid");
        if (wall_density > 0 && wall_modulus > 0)
          {
            w.enter("rigid");
            w.set("Density", wall_density);
            w.set("Young's modulus", wall_modulus);
            w.leave();
          }
        w.leave();
        w.enter("Rigid body");
        w.set("Motion", "prescribed");
        w.set("Contact shape", "plane");
        w.set("Shape point", SceneWriter::vector(wall.point[0], wall.point[1], wall.point[2]));
        w.set("Shape direction", SceneWriter::vector(wall.normal[0], wall.normal[1], wall.normal[2]));
        w.leave();
        w.leave();
      }

    // @sect4{Boundary conditions and contact pairs}
    for (unsigned int i = 0; i < bcs.size(); ++i)
      {
        const auto &k = bc_of[i].first;
        if (k.keyword)
          w.from(k.keyword->line.file, k.keyword->line.line);
        const double v[3] = {k.value[0], k.value[1], k.value[2]};
        w.node_set_condition(bcs[i].first, bcs[i].second, k.set, k.dofs, k.velocity, v);
      }
    for (const auto &pr : pairs)
      {
        w.blank();
        w.from(pr.keyword->line.file, pr.keyword->line.line);
        w.enter("Contact pair " + pr.first + "_" + pr.second);
        w.set("First body", pr.first);
        w.set("Second body", pr.second);
        w.set("Algorithm", "penalty");
        w.set("Symmetric", pr.symmetric ? "true" : "false");
        w.set("Penalty scale factor", pr.factor);
        if (pr.sofscl > 0)
          {
            w.set("Penalty stiffness", "nodal mass");
            w.set("Mass penalty scale factor", pr.sofscl);
          }
        w.set("Static friction coefficient", pr.fs);
        w.set("Dynamic friction coefficient", pr.fd);
        w.set("Friction decay coefficient", pr.dc);
        w.set("Normal damping", pr.vdc / 100);
        w.leave();
      }
    for (const auto &wall : wall_list)
      for (const long pid : wall.pids)
        {
          w.blank();
          w.from(wall.keyword->line.file, wall.keyword->line.line);
          w.enter("Contact pair " + wall.name + "_" + parts[pid].body);
          w.set("First body", wall.name);
          w.set("Second body", parts[pid].body);
          if (wall.penalty > 0)
            {
              w.comment("*CONTROL_CONTACT RWPNAL > 0: a penalty of scale factor RWPNAL x RWKSF (seed Eq. (59))");
              w.set("Algorithm", "penalty");
              w.set("Penalty scale factor", wall.penalty);
            }
          else
            {
              w.comment("*CONTROL_CONTACT RWPNAL <= 0: the wall constrains the nodes (kinematic contact: no "
                        "springs, the elements' time step)");
              w.set("Algorithm", "kinematic");
            }
          w.set("Static friction coefficient", wall.friction);
          w.set("Dynamic friction coefficient", wall.friction);
          w.leave();
        }
    return w.result();
  }


  bool is_deck(const std::string &file)
  {
    const auto dot = file.find_last_of('.');
    const auto ext = dot == std::string::npos ? std::string() : MeshFile::key(file.substr(dot + 1));
    return MeshFile::is_keyword_deck(file) || ext == "INP";
  }


  Translation translate(const std::string &file, const std::string &mesh_path)
  {
    if (MeshFile::is_keyword_deck(file))
      return translate_keyword_deck(file, mesh_path);
    return translate_abaqus_deck(file, mesh_path);
  }
} // namespace anvil::Deck
