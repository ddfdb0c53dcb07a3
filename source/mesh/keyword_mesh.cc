/**
 * @file
 * The mesh of an LS-DYNA keyword deck: *NODE, *ELEMENT_SOLID (one card, or
 * the two-card and ten-nodes formats), parts as groups of cells, node sets
 * (*SET_NODE_LIST, _GENERATE, _GENERAL with ALL, NODE, PART and BOX),
 * segment sets as surfaces, and the nodes that *NODE's TC codes and
 * *BOUNDARY_SPC_NODE constrain and those *INITIAL_VELOCITY_NODE moves, as
 * node sets the deck translator names.
 */
#include <anvil/mesh/keyword_file.h>
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>

#include <algorithm>
#include <map>
#include <set>

namespace anvil::MeshFile
{
  using namespace KeywordFile;

  std::string keyword_dofs_name(const std::array<bool, 3> &dofs)
  {
    std::string s;
    for (unsigned int d = 0; d < 3; ++d)
      if (dofs[d])
        s += char('X' + d);
    return s;
  }


  Contents read_keyword_deck(const std::string &file_name)
  {
    const Keywords deck = KeywordFile::read(file_name, chosen_case());
    Contents   out;

    std::map<long, unsigned int>             vertex_of;
    std::map<long, std::vector<unsigned int>> part_cells;
    std::map<long, std::array<double, 6>>    boxes;
    std::map<long, std::set<unsigned int>>   node_sets;
    std::map<std::string, std::set<unsigned int>> constrained; // "NODE_TC<k>", "SPC_NODE_<dofs>"

    auto vertex = [&](const long nid, const Card &card) {
      const auto v = vertex_of.find(nid);
      if (v == vertex_of.end())
        throw InputError(card.where() + "node " + std::to_string(nid) + " is not defined by *NODE");
      return v->second;
    };

    // Nodes first: elements and sets may come before the nodes they name.
    for (const auto &kw : deck.keywords)
      if (kw.name == "NODE")
        for (unsigned int c = 0; c < kw.cards.size(); ++c)
          {
            const Card &card = kw.cards[c];
            if (card.blank())
              continue;
            const auto f   = kw.fields(c, {8, 16, 16, 16, 8, 8});
            const long nid = integer(f[0], card, "*NODE NID");
            dealii::Point<3> x;
            for (unsigned int d = 0; d < 3; ++d)
              x[d] = real(f[1 + d], card, std::string("*NODE ") + char('X' + d));
            if (!vertex_of.emplace(nid, out.vertices.size()).second)
              throw InputError(card.where() + "node " + std::to_string(nid) + " is defined twice");
            const long tc = integer(f[4], card, "*NODE TC");
            if (tc < 0 || tc > 7)
              throw InputError(card.where() + "*NODE TC = " + std::to_string(tc) + " (allowed: 0 to 7)");
            if (tc != 0)
              constrained["NODE_TC" + std::to_string(tc)].insert(out.vertices.size());
            out.vertices.push_back(x);
          }
    if (out.vertices.empty())
      throw InputError("deck '" + file_name + "' has no *NODE");

    for (const auto &kw : deck.keywords)
      if (kw.name == "ELEMENT_SOLID")
        for (unsigned int c = 0; c < kw.cards.size(); ++c)
          {
            const Card &card = kw.cards[c];
            if (card.blank())
              continue;
            auto       f   = kw.fields(c, std::vector<unsigned int>(10, 8));
            const long eid = integer(f[0], card, "*ELEMENT_SOLID EID");
            const long pid = integer(f[1], card, "*ELEMENT_SOLID PID");
            // The two-card format (and LS-PrePost's 'ten nodes format'):
            // EID and PID alone on the first card, the nodes on the next.
            if (std::all_of(f.begin() + 2, f.end(), [](const std::string &s) { return s.empty(); }))
              {
                if (++c == kw.cards.size())
                  throw InputError(card.where() + "*ELEMENT_SOLID: element " + std::to_string(eid) +
                                   " has no card of nodes");
                f = kw.fields(c, std::vector<unsigned int>(10, 8));
              }
            else
              f.erase(f.begin(), f.begin() + 2);
            const Card &nodes = kw.cards[c];
            std::array<unsigned int, 8> v;
            std::set<long>              distinct;
            for (unsigned int i = 0; i < 8; ++i)
              {
                const long nid = integer(f[i], nodes, "*ELEMENT_SOLID N" + std::to_string(i + 1));
                distinct.insert(nid);
                v[i] = nid == 0 ? 0 : vertex(nid, nodes);
              }
            for (unsigned int i = 8; i < f.size(); ++i)
              if (integer(f[i], nodes, "*ELEMENT_SOLID N" + std::to_string(i + 1)) != 0)
                throw InputError(nodes.where() + "*ELEMENT_SOLID: element " + std::to_string(eid) +
                                 " has more than 8 nodes: Anvil has 8-node hexahedra only");
            if (distinct.size() != 8 || distinct.count(0))
              throw InputError(nodes.where() + "*ELEMENT_SOLID: element " + std::to_string(eid) +
                               " repeats or omits a node (a tetrahedron, pentahedron or degenerate "
                               "hexahedron): Anvil has 8-node hexahedra only");
            part_cells[pid].push_back(out.cells.size());
            out.cells.push_back({{v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]}});
            out.labels.push_back(eid);
          }
    if (out.cells.empty())
      throw InputError("deck '" + file_name + "' has no *ELEMENT_SOLID");

    for (const auto &kw : deck.keywords)
      if (kw.name == "DEFINE_BOX" && !kw.cards.empty())
        {
          const auto f  = kw.fields(0);
          const long id = integer(f[0], kw.cards[0], "*DEFINE_BOX BOXID");
          auto      &b  = boxes[id];
          for (unsigned int i = 0; i < 6; ++i)
            b[i] = real(f[1 + i], kw.cards[0], "*DEFINE_BOX");
        }

    // Node sets, and segment sets as surfaces.
    std::map<std::array<unsigned int, 4>, unsigned int> face_cell;
    auto sorted = [](std::array<unsigned int, 4> v) {
      std::sort(v.begin(), v.end());
      return v;
    };
    for (const auto &kw : deck.keywords)
      {
        const bool list     = kw.name == "SET_NODE_LIST" || kw.name == "SET_NODE";
        const bool generate = kw.name == "SET_NODE_LIST_GENERATE";
        const bool general  = kw.name == "SET_NODE_GENERAL";
        const bool segments = kw.name == "SET_SEGMENT";
        if (!(list || generate || general || segments) || kw.cards.empty())
          continue;
        const long sid = integer(kw.fields(0)[0], kw.cards[0], "*" + kw.name + " SID");
        if (segments)
          {
            if (face_cell.empty())
              for (unsigned int cell = 0; cell < out.cells.size(); ++cell)
                for (unsigned int f = 0; f < 6; ++f)
                  {
                    static constexpr unsigned int face_vertices[6][4] = {
                      {0, 2, 4, 6}, {1, 3, 5, 7}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}};
                    std::array<unsigned int, 4> face;
                    for (unsigned int i = 0; i < 4; ++i)
                      face[i] = out.cells[cell][face_vertices[f][i]];
                    face_cell[sorted(face)] = cell;
                  }
            const unsigned int id = 100 + out.surfaces.size();
            out.surfaces["SEGMENTSET" + std::to_string(sid)] = id;
            for (unsigned int c = 1; c < kw.cards.size(); ++c)
              {
                if (kw.cards[c].blank())
                  continue;
                const auto                  f = kw.fields(c);
                std::array<unsigned int, 4> face;
                for (unsigned int i = 0; i < 4; ++i)
                  face[i] = vertex(integer(f[i], kw.cards[c], "*SET_SEGMENT N" + std::to_string(i + 1)),
                                   kw.cards[c]);
                const auto cell = face_cell.find(sorted(face));
                if (cell == face_cell.end())
                  throw InputError(kw.cards[c].where() + "*SET_SEGMENT " + std::to_string(sid) +
                                   ": the segment is no face of a solid element");
                out.faces.push_back({cell->second, face, id});
              }
            continue;
          }
        auto &set = node_sets[sid];
        for (unsigned int c = 1; c < kw.cards.size(); ++c)
          {
            const Card &card = kw.cards[c];
            if (card.blank())
              continue;
            const auto f = kw.fields(c);
            if (list)
              for (const auto &x : f)
                {
                  const long nid = integer(x, card, "*" + kw.name + " NID");
                  if (nid != 0)
                    set.insert(vertex(nid, card));
                }
            else if (generate)
              for (unsigned int i = 0; i + 1 < f.size(); i += 2)
                {
                  const long b = integer(f[i], card, "*SET_NODE_LIST_GENERATE B"),
                             e = integer(f[i + 1], card, "*SET_NODE_LIST_GENERATE E");
                  if (b == 0 && e == 0)
                    continue;
                  if (e < b || e - b > 100000000)
                    throw InputError(card.where() + "*SET_NODE_LIST_GENERATE: the range " +
                                     std::to_string(b) + " to " + std::to_string(e) + " is empty or too long");
                  for (const auto &[nid, v] : vertex_of)
                    if (nid >= b && nid <= e)
                      set.insert(v);
                }
            else
              {
                const std::string option = f[0];
                std::string       o      = option;
                for (auto &ch : o)
                  ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
                std::vector<long> e;
                for (unsigned int i = 1; i < f.size(); ++i)
                  if (!f[i].empty())
                    e.push_back(integer(f[i], card, "*SET_NODE_GENERAL E" + std::to_string(i)));
                if (o == "ALL")
                  for (unsigned int v = 0; v < out.vertices.size(); ++v)
                    set.insert(v);
                else if (o == "NODE")
                  for (const long nid : e)
                    set.insert(vertex(nid, card));
                else if (o == "PART")
                  for (const long pid : e)
                    {
                      const auto p = part_cells.find(pid);
                      if (p == part_cells.end())
                        throw InputError(card.where() + "*SET_NODE_GENERAL: part " + std::to_string(pid) +
                                         " has no elements");
                      for (const unsigned int cell : p->second)
                        set.insert(out.cells[cell].begin(), out.cells[cell].end());
                    }
                else if (o == "BOX")
                  for (const long id : e)
                    {
                      const auto b = boxes.find(id);
                      if (b == boxes.end())
                        throw InputError(card.where() + "*SET_NODE_GENERAL: box " + std::to_string(id) +
                                         " is not defined by *DEFINE_BOX");
                      for (unsigned int v = 0; v < out.vertices.size(); ++v)
                        {
                          const auto &x  = out.vertices[v];
                          bool        in = true;
                          for (unsigned int d = 0; d < 3; ++d)
                            in = in && x[d] >= b->second[2 * d] && x[d] <= b->second[2 * d + 1];
                          if (in)
                            set.insert(v);
                        }
                    }
                else
                  throw InputError(card.where() + "*SET_NODE_GENERAL: option '" + printable_excerpt(option) +
                                   "' is not supported (allowed: ALL, NODE, PART, BOX)");
              }
          }
      }

    for (const auto &kw : deck.keywords)
      if (kw.name == "BOUNDARY_SPC_NODE")
        for (unsigned int c = 0; c < kw.cards.size(); ++c)
          {
            const Card &card = kw.cards[c];
            if (card.blank())
              continue;
            const auto          f = kw.fields(c);
            std::array<bool, 3> dofs;
            for (unsigned int d = 0; d < 3; ++d)
              dofs[d] = integer(f[2 + d], card, "*BOUNDARY_SPC_NODE DOF") != 0;
            const std::string name = keyword_dofs_name(dofs);
            if (!name.empty())
              constrained["SPC_NODE_" + name].insert(
                vertex(integer(f[0], card, "*BOUNDARY_SPC_NODE NID"), card));
          }

    // *INITIAL_VELOCITY_NODE: a node set per velocity (the translator
    // gives it to the parts the set holds whole).
    unsigned int n_node_velocities = 0;
    for (const auto &kw : deck.keywords)
      if (kw.name == "INITIAL_VELOCITY_NODE")
        {
          const auto groups = node_velocity_groups(kw);
          for (unsigned int g = 0; g < groups.size(); ++g)
            {
              auto &set = constrained[node_velocity_set(n_node_velocities, g)];
              for (std::size_t i = 0; i < groups[g].nids.size(); ++i)
                set.insert(vertex(groups[g].nids[i], *groups[g].cards[i]));
            }
          ++n_node_velocities;
        }

    for (const auto &[pid, cells] : part_cells)
      {
        const std::string name = "PART" + std::to_string(pid);
        out.cell_sets[name]    = cells;
        out.regions.push_back(name);
      }
    for (const auto &[sid, set] : node_sets)
      out.node_sets["SET" + std::to_string(sid)] = std::vector<unsigned int>(set.begin(), set.end());
    for (const auto &[name, set] : constrained)
      out.node_sets[name] = std::vector<unsigned int>(set.begin(), set.end());
    return out;
  }
} // namespace anvil::MeshFile
