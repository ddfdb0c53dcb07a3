/**
 * @file
 * Reading hexahedral meshes from ABAQUS input decks (flat, or as
 * Abaqus/CAE writes them: parts, an assembly of translated and rotated
 * instances, sets and element-based surfaces) and from Gmsh files
 * (physical volumes and surfaces by number and by name).
 */
#include <anvil/mesh/mesh_file.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/text.h>


#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <type_traits>

namespace anvil::MeshFile
{
  std::string key(const std::string &name)
  {
    std::string k = name;
    for (auto &c : k)
      c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return k;
  }


  using Abaqus::Keyword;
  using Abaqus::Line;

  namespace
  {
    // @sect3{ABAQUS input decks}
    //
    std::vector<std::string> split_commas(const std::string &text)
    {
      std::vector<std::string> tokens;
      std::stringstream        in(text);
      std::string              token;
      while (std::getline(in, token, ','))
        {
          token = trim(token);
          if (!token.empty())
            tokens.push_back(token);
        }
      return tokens;
    }

    // The lines of a deck, with the decks it includes (*Include,
    // input=FILE, relative to the including file) in their place.
    void read_lines(const std::string &file, std::vector<Line> &lines, const unsigned int depth)
    {
      std::ifstream in(file);
      if (!in)
        throw InputError("mesh file '" + file + "' cannot be opened");
      std::string  text;
      unsigned int number = 0;
      while (std::getline(in, text))
        {
          ++number;
          const std::string t = trim(text);
          if (t.empty() || t.rfind("**", 0) == 0)
            continue;
          const std::string k = key(t);
          if (k.rfind("*INCLUDE", 0) == 0)
            {
              const auto at = k.find("INPUT");
              const auto eq = t.find('=', at == std::string::npos ? 0 : at);
              if (at == std::string::npos || eq == std::string::npos || depth >= 10)
                throw InputError("mesh file '" + file + "', line " + std::to_string(number) +
                                 ": *Include needs 'input=FILE' (at most 10 levels deep)");
              std::string name = trim(t.substr(eq + 1));
              name.erase(std::remove(name.begin(), name.end(), '"'), name.end());
              const std::filesystem::path path(name);
              read_lines(path.is_absolute() ?
                           name :
                           (std::filesystem::path(file).parent_path() / path).string(),
                         lines, depth + 1);
              continue;
            }
          lines.push_back({t, file, number});
        }
    }

    std::vector<Keyword> keywords_of(const std::vector<Line> &lines)
    {
      std::vector<Keyword> keywords;
      for (const auto &line : lines)
        if (line.text[0] == '*')
          {
            Keyword    kw;
            const auto parts = split_commas(line.text.substr(1));
            kw.written       = parts.empty() ? std::string() : parts[0];
            kw.name          = key(kw.written);
            for (unsigned int i = 1; i < parts.size(); ++i)
              {
                const auto eq = parts[i].find('=');
                if (eq == std::string::npos)
                  kw.parameters[key(trim(parts[i]))] = "";
                else
                  {
                    std::string value = trim(parts[i].substr(eq + 1));
                    value.erase(std::remove(value.begin(), value.end(), '"'), value.end());
                    kw.parameters[key(trim(parts[i].substr(0, eq)))] = value;
                  }
              }
            kw.line = line;
            keywords.push_back(kw);
          }
        else if (keywords.empty())
          throw InputError(line.where() + "data before the first keyword");
        else
          keywords.back().data.push_back(line);
      return keywords;
    }

    double number(const std::string &token, const Line &line)
    {
      char        *end   = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
        throw InputError(line.where() + "'" + printable_excerpt(token) + "' is not a number");
      return value;
    }

    bool is_label(const std::string &token)
    {
      return !token.empty() &&
             std::all_of(token.begin(), token.end(), [](const char c) { return std::isdigit(c); });
    }

    long label(const std::string &token, const Line &line)
    {
      if (!is_label(token) || token.size() > 9)
        throw InputError(line.where() + "'" + printable_excerpt(token) +
                         "' is not a label (a positive integer below 10^9)");
      return std::stol(token);
    }

    // Local nodes (0-based, ABAQUS order) of the faces S1 ... S6 of C3D8.
    constexpr unsigned int abaqus_face[6][4] = {
      {0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};

    // A set or surface entry before its labels are resolved: labels, or
    // names of other sets (in the same scope, or 'INSTANCE.SET').
    struct SetEntry
    {
      std::vector<long>        labels;
      std::vector<std::string> names;
      std::string              instance; // assembly sets: instance=...
    };

    struct SurfaceEntry
    {
      std::string  set_or_label; // an element set's name, or one label
      unsigned int face;         // 0 ... 5 for S1 ... S6
      Line         line;
    };

    struct Part
    {
      std::string                                      name;
      std::map<long, dealii::Point<3>>                 nodes;
      std::vector<std::pair<long, std::array<long, 8>>> elements;
      std::map<std::string, std::vector<SetEntry>>     elsets, nsets;
      std::vector<std::pair<std::string, std::vector<SurfaceEntry>>> surfaces;
      Line                                             line;
    };

    struct Instance
    {
      std::string          name, part;
      dealii::Tensor<1, 3> translation;
      bool                 rotated = false;
      dealii::Point<3>     a, b;
      double               angle = 0;
      Line                 line;

      dealii::Point<3> place(const dealii::Point<3> &x) const
      {
        dealii::Point<3> y = x + translation;
        if (!rotated)
          return y;
        // Rodrigues: rotation by 'angle' (degrees) about the axis a -> b.
        dealii::Tensor<1, 3> k = b - a;
        k /= k.norm();
        const dealii::Tensor<1, 3> v = y - a;
        const double               t = angle * M_PI / 180.;
        return a + v * std::cos(t) + dealii::cross_product_3d(k, v) * std::sin(t) +
               k * ((k * v) * (1. - std::cos(t)));
      }
    };

    SetEntry set_entry(const Keyword &kw)
    {
      SetEntry entry;
      entry.instance = key(kw.get("INSTANCE"));
      for (const auto &line : kw.data)
        {
          const auto tokens = split_commas(line.text);
          if (kw.has("GENERATE"))
            {
              if (tokens.size() < 2 || tokens.size() > 3)
                throw InputError(line.where() + "*" + kw.name +
                                 ", generate needs 'first, last[, increment]'");
              const long first = label(tokens[0], line), last = label(tokens[1], line);
              const long step  = tokens.size() == 3 ? label(tokens[2], line) : 1;
              if (step == 0 || last < first || (last - first) / step > 100000000)
                throw InputError(line.where() + "*" + kw.name + ", generate: '" +
                                 printable_excerpt(line.text) +
                                 "' is not first <= last with an increment >= 1");
              for (long l = first; l <= last; l += step)
                entry.labels.push_back(l);
            }
          else
            for (const auto &t : tokens)
              if (is_label(t))
                entry.labels.push_back(label(t, line));
              else
                entry.names.push_back(key(t));
        }
      return entry;
    }


    Contents read_abaqus(const std::string &file_name)
    {
      std::vector<Line> lines;
      read_lines(file_name, lines, 0);
      const auto keywords = keywords_of(lines);

      // Pass 1: parts, instances and assembly-level sets, as written.
      std::vector<Part>                            parts;
      std::vector<Instance>                        instances;
      std::map<std::string, std::vector<SetEntry>> assembly_elsets, assembly_nsets;
      std::vector<std::pair<std::string, std::vector<SurfaceEntry>>> assembly_surfaces;
      std::map<std::string, unsigned int>          skipped;

      enum class Scope
      {
        top,
        part,
        assembly,
        instance,
        step
      } scope          = Scope::top;
      Part *part       = nullptr; // where nodes, elements and sets go
      auto  flat_part  = [&]() -> Part * {
        // Nodes and elements outside any *Part: one implicit part.
        for (auto &p : parts)
          if (p.name.empty())
            return &p;
        parts.push_back(Part());
        return &parts.back();
      };
      for (const auto &kw : keywords)
        {
          const std::string &k = kw.name;
          if (scope == Scope::step)
            {
              if (k == "END STEP")
                scope = Scope::top;
              continue;
            }
          if (k == "PART")
            {
              parts.push_back(Part());
              parts.back().name = key(kw.required("NAME"));
              parts.back().line = kw.line;
              part              = &parts.back();
              scope             = Scope::part;
            }
          else if (k == "END PART")
            {
              part  = nullptr;
              scope = Scope::top;
            }
          else if (k == "ASSEMBLY")
            scope = Scope::assembly;
          else if (k == "END ASSEMBLY")
            scope = Scope::top;
          else if (k == "INSTANCE")
            {
              if (scope != Scope::assembly)
                throw InputError(kw.line.where() + "*Instance outside *Assembly");
              Instance in;
              in.name = key(kw.required("NAME"));
              in.part = key(kw.required("PART"));
              in.line = kw.line;
              if (kw.data.size() > 2)
                throw InputError(kw.line.where() + "*Instance has " +
                                 std::to_string(kw.data.size()) +
                                 " data lines (allowed: a translation, then a rotation)");
              for (unsigned int i = 0; i < kw.data.size(); ++i)
                {
                  const auto t = split_commas(kw.data[i].text);
                  if (t.size() != (i == 0 ? 3u : 7u))
                    throw InputError(kw.data[i].where() + "*Instance " +
                                     (i == 0 ? "translation needs 3 numbers" :
                                               "rotation needs 7 numbers (a, b, angle)"));
                  if (i == 0)
                    for (unsigned int d = 0; d < 3; ++d)
                      in.translation[d] = number(t[d], kw.data[i]);
                  else
                    {
                      for (unsigned int d = 0; d < 3; ++d)
                        {
                          in.a[d] = number(t[d], kw.data[i]);
                          in.b[d] = number(t[3 + d], kw.data[i]);
                        }
                      in.angle   = number(t[6], kw.data[i]);
                      in.rotated = in.angle != 0;
                      if (in.rotated && (in.b - in.a).norm() == 0)
                        throw InputError(kw.data[i].where() +
                                         "*Instance rotation axis has a = b");
                    }
                }
              instances.push_back(in);
              scope = Scope::instance;
            }
          else if (k == "END INSTANCE")
            scope = Scope::assembly;
          else if (k == "STEP")
            {
              ++skipped["*" + kw.written];
              scope = Scope::step;
            }
          else if (k == "NODE" && scope != Scope::assembly && scope != Scope::instance)
            {
              Part *p = part ? part : flat_part();
              for (const auto &line : kw.data)
                {
                  const auto t = split_commas(line.text);
                  if (t.size() < 3 || t.size() > 4)
                    throw InputError(line.where() + "a node needs 'label, x, y[, z]'");
                  dealii::Point<3> x;
                  for (unsigned int d = 0; d + 1 < t.size(); ++d)
                    x[d] = number(t[d + 1], line);
                  p->nodes[label(t[0], line)] = x;
                }
            }
          else if (k == "ELEMENT" && scope != Scope::assembly && scope != Scope::instance)
            {
              const std::string type = key(kw.required("TYPE"));
              if (type != "C3D8" && type != "C3D8R")
                throw InputError(kw.line.where() + "element type '" + printable_excerpt(type) +
                                 "' is not supported (allowed: C3D8, C3D8R)");
              Part *p = part ? part : flat_part();
              // An element's labels may continue on the next line.
              std::vector<std::string> tokens;
              SetEntry                 set;
              for (const auto &line : kw.data)
                {
                  for (const auto &t : split_commas(line.text))
                    tokens.push_back(t);
                  if (tokens.size() < 9)
                    continue;
                  if (tokens.size() > 9)
                    throw InputError(line.where() + "a " + type +
                                     " element needs 'label' and 8 node labels");
                  std::array<long, 8> nodes;
                  for (unsigned int v = 0; v < 8; ++v)
                    nodes[v] = label(tokens[v + 1], line);
                  p->elements.emplace_back(label(tokens[0], line), nodes);
                  set.labels.push_back(p->elements.back().first);
                  tokens.clear();
                }
              if (!tokens.empty())
                throw InputError(kw.data.back().where() + "a " + type +
                                 " element needs 'label' and 8 node labels");
              if (kw.has("ELSET"))
                p->elsets[key(kw.get("ELSET"))].push_back(set);
            }
          else if (k == "NSET" || k == "ELSET")
            {
              const std::string name = key(kw.required(k));
              auto &sets = scope == Scope::assembly ?
                             (k == "NSET" ? assembly_nsets : assembly_elsets) :
                             (k == "NSET" ? (part ? part : flat_part())->nsets :
                                            (part ? part : flat_part())->elsets);
              if (scope == Scope::instance)
                throw InputError(kw.line.where() + "*" + kw.name +
                                 " inside *Instance is not supported (define it in "
                                 "the part or the assembly)");
              sets[name].push_back(set_entry(kw));
            }
          else if (k == "SURFACE")
            {
              const std::string type = key(kw.get("TYPE"));
              if (!type.empty() && type != "ELEMENT")
                {
                  ++skipped["*" + kw.written + ", type=" + kw.get("TYPE")];
                  continue;
                }
              std::vector<SurfaceEntry> entries;
              for (const auto &line : kw.data)
                {
                  const auto t = split_commas(line.text);
                  const std::string face = t.size() == 2 ? key(t[1]) : "";
                  if (face.size() != 2 || face[0] != 'S' || face[1] < '1' || face[1] > '6')
                    throw InputError(line.where() + "a surface of hexahedra needs "
                                     "'element set or label, S1 ... S6'");
                  entries.push_back({key(t[0]), static_cast<unsigned int>(face[1] - '1'), line});
                }
              const std::string name = key(kw.required("NAME"));
              if (scope == Scope::assembly)
                assembly_surfaces.emplace_back(name, entries);
              else if (scope == Scope::instance)
                throw InputError(kw.line.where() + "*Surface inside *Instance is not "
                                 "supported (define it in the part or the assembly)");
              else
                (part ? part : flat_part())->surfaces.emplace_back(name, entries);
            }
          else if (k == "NODE" || k == "ELEMENT")
            ++skipped["*" + kw.written + " in the assembly"];
          else if (k != "HEADING" && k != "PREPRINT")
            ++skipped["*" + kw.written];
        }

      // Parts without instances (a deck without an assembly): each placed
      // once as it is, under its own name.
      if (instances.empty())
        for (const auto &p : parts)
          {
            Instance in;
            in.name = p.name;
            in.part = p.name;
            instances.push_back(in);
          }

      // Pass 2: the cells of every instance, and its sets resolved.
      Contents                                             out;
      std::map<std::pair<std::string, long>, unsigned int> cell_of, vertex_of;
      std::map<std::string, unsigned int>                  instances_of_part;
      for (const auto &in : instances)
        ++instances_of_part[in.part];

      auto find_part = [&](const Instance &in) -> const Part & {
        for (const auto &p : parts)
          if (p.name == in.part)
            return p;
        throw InputError(in.line.where() + "instance '" + in.name + "' names part '" +
                         in.part + "', which the file does not define");
      };

      // Labels of a set (with the sets it names, in scope 'sets') as cells
      // or vertices of instance 'in'; a name 'INSTANCE.SET' is a set of
      // that instance's part.
      using Sets = std::map<std::string, std::vector<SetEntry>>;
      std::function<void(const Sets &, const std::string &, const std::string &, bool,
                         std::vector<unsigned int> &, unsigned int)>
        resolve_name;
      std::function<void(const Sets &, const std::string &, const std::string &, bool,
                         std::vector<unsigned int> &, unsigned int)>
        resolve = [&](const Sets &sets,
                      const std::string &name, const std::string &instance, const bool cells,
                      std::vector<unsigned int> &result, const unsigned int depth) {
          const auto it = sets.find(name);
          if (it == sets.end() || depth > 20)
            throw InputError("mesh file '" + file_name + "': set '" + name +
                             "' is not defined (or nests more than 20 deep)");
          for (const auto &entry : it->second)
            {
              const std::string inst = entry.instance.empty() ? instance : entry.instance;
              for (const long l : entry.labels)
                {
                  const auto &map = cells ? cell_of : vertex_of;
                  const auto  at  = map.find({inst, l});
                  if (at == map.end())
                    throw InputError("mesh file '" + file_name + "': set '" + name +
                                     "' names " + (cells ? "element " : "node ") +
                                     std::to_string(l) +
                                     (inst.empty() ? std::string() : " of instance '" + inst + "'") +
                                     ", which does not exist");
                  result.push_back(at->second);
                }
              for (const auto &n : entry.names)
                resolve_name(sets, n, inst, cells, result, depth + 1);
            }
        };

      resolve_name = [&](const Sets &sets, const std::string &n, const std::string &inst,
                         const bool cells, std::vector<unsigned int> &result,
                         const unsigned int depth) {
        const auto dot = n.find('.');
        if (dot == std::string::npos)
          return resolve(sets, n, inst, cells, result, depth);
        const std::string other = n.substr(0, dot);
        for (const auto &in : instances)
          if (in.name == other)
            {
              const Part &p = find_part(in);
              return resolve(cells ? p.elsets : p.nsets, n.substr(dot + 1), other, cells, result,
                             depth);
            }
        throw InputError("mesh file '" + file_name + "': '" + n +
                         "' names a set of instance '" + other + "', which does not exist");
      };

      // Boundary ids: a surface named by a number keeps it; the others
      // get 1, 2, ... in order of definition, skipping those.
      std::set<unsigned int> numbered;
      auto                   collect_numbers = [&](const auto &surfaces) {
        for (const auto &s : surfaces)
          if (is_label(s.first) && s.first.size() <= 3)
            numbered.insert(std::stoul(s.first));
      };
      for (const auto &p : parts)
        collect_numbers(p.surfaces);
      collect_numbers(assembly_surfaces);
      unsigned int next_id   = 1;
      auto         id_for    = [&](const std::string &name) {
        const auto it = out.surfaces.find(name);
        if (it != out.surfaces.end())
          return it->second;
        unsigned int id;
        if (is_label(name) && name.size() <= 3)
          id = std::stoul(name);
        else
          {
            while (numbered.count(next_id))
              ++next_id;
            id = next_id++;
          }
        if (id > 255)
          throw InputError("mesh file '" + file_name + "': surface '" + name +
                           "' would get boundary id " + std::to_string(id) +
                           " (at most 255 surfaces; boundary ids are 0 ... 255)");
        out.surfaces[name] = id;
        return id;
      };
      auto add_surface = [&](const std::string &name, const std::vector<SurfaceEntry> &entries,
                             const std::map<std::string, std::vector<SetEntry>> &sets,
                             const std::string                                  &instance) {
        const unsigned int id = id_for(name);
        for (const auto &e : entries)
          {
            std::vector<unsigned int> cells;
            if (is_label(e.set_or_label))
              {
                const auto at = cell_of.find({instance, label(e.set_or_label, e.line)});
                if (at == cell_of.end())
                  throw InputError(e.line.where() + "surface '" + name + "' names element " +
                                   e.set_or_label + ", which does not exist");
                cells.push_back(at->second);
              }
            else
              resolve_name(sets, e.set_or_label, instance, true, cells, 0);
            for (const unsigned int c : cells)
              {
                Contents::Face face;
                face.cell        = c;
                face.boundary_id = id;
                // The cell's vertices in ABAQUS order (deal.II's order
                // swaps 2 <-> 3 and 6 <-> 7).
                static constexpr unsigned int from_abaqus[8] = {0, 1, 3, 2, 4, 5, 7, 6};
                for (unsigned int v = 0; v < 4; ++v)
                  face.vertices[v] = out.cells[c][from_abaqus[abaqus_face[e.face][v]]];
                out.faces.push_back(face);
              }
          }
      };

      for (const auto &in : instances)
        {
          const Part &p = find_part(in);
          for (const auto &node : p.nodes)
            {
              vertex_of[{in.name, node.first}] = out.vertices.size();
              out.vertices.push_back(in.place(node.second));
            }
          out.regions.push_back(in.name);
          auto &own = out.cell_sets[in.name];
          for (const auto &element : p.elements)
            {
              std::array<unsigned int, 8> v;
              for (unsigned int i = 0; i < 8; ++i)
                {
                  const auto at = vertex_of.find({in.name, element.second[i]});
                  if (at == vertex_of.end())
                    throw InputError("mesh file '" + file_name + "': element " +
                                     std::to_string(element.first) +
                                     (p.name.empty() ? std::string() : " of part '" + p.name + "'") +
                                     " names node " + std::to_string(element.second[i]) +
                                     ", which does not exist");
                  v[i] = at->second;
                }
              if (!cell_of.emplace(std::make_pair(in.name, element.first), out.cells.size())
                     .second)
                throw InputError("mesh file '" + file_name + "': element label " +
                                 std::to_string(element.first) + " appears twice" +
                                 (p.name.empty() ? std::string() : " in part '" + p.name + "'"));
              own.push_back(out.cells.size());
              out.cells.push_back({{v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]}});
              out.labels.push_back(element.first);
            }
          if (in.name != p.name && !p.name.empty())
            {
              auto &all = out.cell_sets[p.name];
              all.insert(all.end(), own.begin(), own.end());
            }
          // The part's sets, as 'INSTANCE.SET', and as 'SET' when the part
          // has one instance.
          const bool single = instances_of_part[p.name] == 1;
          for (const bool cells : {true, false})
            for (const auto &s : (cells ? p.elsets : p.nsets))
              {
                std::vector<unsigned int> members;
                resolve(cells ? p.elsets : p.nsets, s.first, in.name, cells, members, 0);
                auto &target = cells ? out.cell_sets : out.node_sets;
                if (!in.name.empty())
                  target[in.name + "." + s.first] = members;
                if (single)
                  target[s.first] = members;
              }
          for (const auto &s : p.surfaces)
            {
              const std::string name =
                (single || in.name.empty()) ? s.first : in.name + "." + s.first;
              add_surface(name, s.second, p.elsets, in.name);
            }
        }
      if (out.cells.empty())
        throw InputError("mesh file '" + file_name + "' has no C3D8 or C3D8R elements");
      for (const bool cells : {true, false})
        for (const auto &s : (cells ? assembly_elsets : assembly_nsets))
          {
            std::vector<unsigned int> members;
            resolve(cells ? assembly_elsets : assembly_nsets, s.first, "", cells, members, 0);
            (cells ? out.cell_sets : out.node_sets)[s.first] = members;
          }
      for (const auto &s : assembly_surfaces)
        add_surface(s.first, s.second, assembly_elsets, "");

      out.cell_sets.erase("");
      for (const auto &s : skipped)
        out.skipped += (out.skipped.empty() ? "" : ", ") + s.first +
                       (s.second > 1 ? " (" + std::to_string(s.second) + ")" : "");
      return out;
    }


    // @sect3{Gmsh files}
    //
    // ASCII formats 2.2 and 4.1, read and checked here (deal.II's reader
    // trusts its input: a damaged file corrupted memory). Hexahedra (type
    // 5) become cells, grouped by physical volume; quadrangles (type 3) of
    // physical surfaces label the cell faces they cover; other elements of
    // lower dimension are ignored, other volume elements refused.
    class GmshReader
    {
    public:
      explicit GmshReader(const std::string &file_name)
        : file(file_name)
        , in(file_name)
      {
        if (!in)
          throw InputError("mesh file '" + file + "' cannot be opened");
        in.seekg(0, std::ios::end);
        bytes = static_cast<double>(in.tellg());
        in.seekg(0);
      }

      Contents read()
      {
        std::string line;
        while (next_line(line))
          {
            if (line == "$MeshFormat")
              read_format();
            else if (line == "$PhysicalNames")
              read_names();
            else if (line == "$Entities")
              read_entities();
            else if (line == "$Nodes")
              read_nodes();
            else if (line == "$Elements")
              read_elements();
            else if (!line.empty() && line[0] == '$' && line.rfind("$End", 0) != 0)
              skip_section(line);
          }
        if (version == 0)
          fail("no $MeshFormat section: not a Gmsh file");
        return finish();
      }

    private:
      std::string                 file;
      std::ifstream               in;
      double                      bytes  = 0;
      unsigned int                number = 0;
      double                      version = 0;
      std::map<std::pair<int, int>, std::string> physical_names; // (dim, tag)
      std::map<std::pair<int, int>, std::vector<int>> entity_physicals; // (dim, entity)
      std::map<long, unsigned int> vertex_of;                           // node tag
      std::vector<dealii::Point<3>> vertices;
      std::vector<std::array<long, 8>> hexes;
      std::vector<std::vector<int>>    hex_physicals;
      std::vector<long>                hex_tags;
      std::vector<std::array<long, 4>> quads;
      std::vector<std::vector<int>>    quad_physicals;

      [[noreturn]] void fail(const std::string &what) const
      {
        throw InputError("mesh file '" + file + "', line " + std::to_string(number) + ": " + what);
      }

      bool next_line(std::string &line)
      {
        if (!std::getline(in, line))
          return false;
        ++number;
        line = trim(line);
        return true;
      }

      std::istringstream data_line(const char *what)
      {
        std::string line;
        if (!next_line(line))
          fail(std::string("the file ends inside ") + what);
        return std::istringstream(line);
      }

      template <typename T>
      T get(std::istringstream &s, const char *what)
      {
        T value;
        if (!(s >> value))
          fail(std::string("expected ") + what);
        if constexpr (std::is_floating_point_v<T>)
          if (!std::isfinite(value))
            fail(std::string(what) + " is not a finite number");
        return value;
      }

      // A count read from the file: at most what the file's size allows.
      long count(std::istringstream &s, const char *what)
      {
        const long n = get<long>(s, what);
        if (n < 0 || double(n) > bytes)
          fail(std::string(what) + " = " + std::to_string(n) +
               " cannot be right for a file of this size");
        return n;
      }

      void end_of(const std::string &section)
      {
        std::string line;
        if (!next_line(line) || line != "$End" + section)
          fail("expected $End" + section);
      }

      void skip_section(const std::string &start)
      {
        std::string line;
        const std::string end = "$End" + start.substr(1);
        while (next_line(line))
          if (line == end)
            return;
        fail("the file ends inside " + start);
      }

      void read_format()
      {
        auto s      = data_line("$MeshFormat");
        version     = get<double>(s, "a format version");
        const int t = get<int>(s, "the file type");
        if (t == 1)
          fail("a binary Gmsh file: Anvil reads ASCII .msh (format 2.2 or 4.1; Gmsh: "
               "-format msh41 without -bin, or Mesh.Binary = 0)");
        if (t != 0 || !(version == 2.2 || version == 4.1))
          fail("format " + std::to_string(version).substr(0, 3) + ", type " + std::to_string(t) +
               " (allowed: ASCII 2.2 or 4.1)");
        end_of("MeshFormat");
      }

      void read_names()
      {
        auto       s = data_line("$PhysicalNames");
        const long n = count(s, "the number of names");
        for (long i = 0; i < n; ++i)
          {
            std::string line;
            if (!next_line(line))
              fail("the file ends inside $PhysicalNames");
            std::istringstream entry(line);
            const int          dim = get<int>(entry, "a dimension");
            const int          tag = get<int>(entry, "a physical tag");
            const auto q1 = line.find('"'), q2 = line.rfind('"');
            if (dim < 0 || dim > 3 || q1 == std::string::npos || q2 <= q1)
              fail("'" + printable_excerpt(line) + "' is not 'dimension tag \"name\"'");
            physical_names[{dim, tag}] = key(line.substr(q1 + 1, q2 - q1 - 1));
          }
        end_of("PhysicalNames");
      }

      void read_entities()
      {
        if (version < 4)
          fail("$Entities in a format 2.2 file");
        auto       s = data_line("$Entities");
        long       n[4];
        for (auto &k : n)
          k = count(s, "an entity count");
        for (int dim = 0; dim < 4; ++dim)
          for (long i = 0; i < n[dim]; ++i)
            {
              auto      e   = data_line("$Entities");
              const int tag = get<int>(e, "an entity tag");
              for (int k = 0; k < (dim == 0 ? 3 : 6); ++k)
                get<double>(e, "a coordinate of the entity's box");
              const long np = count(e, "the number of physical tags");
              auto      &physicals = entity_physicals[{dim, tag}];
              for (long k = 0; k < np; ++k)
                physicals.push_back(get<int>(e, "a physical tag"));
            }
        end_of("Entities");
      }

      void add_node(const long tag, const dealii::Point<3> &x)
      {
        if (!vertex_of.emplace(tag, vertices.size()).second)
          fail("node " + std::to_string(tag) + " appears twice");
        vertices.push_back(x);
      }

      void read_nodes()
      {
        auto s = data_line("$Nodes");
        if (version < 4)
          {
            const long n = count(s, "the number of nodes");
            for (long i = 0; i < n; ++i)
              {
                auto       line = data_line("$Nodes");
                const long tag  = get<long>(line, "a node tag");
                dealii::Point<3> x;
                for (unsigned int d = 0; d < 3; ++d)
                  x[d] = get<double>(line, "a coordinate");
                add_node(tag, x);
              }
          }
        else
          {
            const long blocks = count(s, "the number of node blocks");
            count(s, "the number of nodes");
            for (long b = 0; b < blocks; ++b)
              {
                auto       head = data_line("$Nodes");
                get<int>(head, "an entity dimension");
                get<int>(head, "an entity tag");
                const int  parametric = get<int>(head, "the parametric flag");
                const long n          = count(head, "the number of nodes in a block");
                if (parametric != 0)
                  fail("parametric nodes (Anvil reads Gmsh's default, without)");
                std::vector<long> tags(n);
                for (long i = 0; i < n; ++i)
                  {
                    auto line = data_line("$Nodes");
                    tags[i]   = get<long>(line, "a node tag");
                  }
                for (long i = 0; i < n; ++i)
                  {
                    auto             line = data_line("$Nodes");
                    dealii::Point<3> x;
                    for (unsigned int d = 0; d < 3; ++d)
                      x[d] = get<double>(line, "a coordinate");
                    add_node(tags[i], x);
                  }
              }
          }
        end_of("Nodes");
      }

      void add_element(const int type, std::istringstream &line, const long tag,
                       const std::vector<int> &physicals)
      {
        if (type == 5)
          {
            std::array<long, 8> v;
            for (auto &x : v)
              x = get<long>(line, "a node tag of a hexahedron");
            hexes.push_back(v);
            hex_physicals.push_back(physicals);
            hex_tags.push_back(tag);
          }
        else if (type == 3)
          {
            std::array<long, 4> v;
            for (auto &x : v)
              x = get<long>(line, "a node tag of a quadrangle");
            quads.push_back(v);
            quad_physicals.push_back(physicals);
          }
        else if (type == 4 || type == 6 || type == 7 || (type >= 11 && type <= 14) ||
                 (type >= 17 && type <= 19) || type == 29 || type == 30)
          fail("element " + std::to_string(tag) + " of type " + std::to_string(type) +
               " is a volume element other than the 8-node hexahedron (Anvil meshes "
               "hexahedra only: Gmsh: Recombine and Mesh.SubdivisionAlgorithm = 2, or "
               "transfinite volumes)");
      }

      void read_elements()
      {
        auto s = data_line("$Elements");
        if (version < 4)
          {
            const long n = count(s, "the number of elements");
            for (long i = 0; i < n; ++i)
              {
                auto       line  = data_line("$Elements");
                const long tag   = get<long>(line, "an element tag");
                const int  type  = get<int>(line, "an element type");
                const long ntags = count(line, "the number of tags");
                std::vector<int> physicals;
                for (long k = 0; k < ntags; ++k)
                  {
                    const int t = get<int>(line, "a tag");
                    if (k == 0 && t != 0)
                      physicals.push_back(t);
                  }
                add_element(type, line, tag, physicals);
              }
          }
        else
          {
            const long blocks = count(s, "the number of element blocks");
            count(s, "the number of elements");
            for (long b = 0; b < blocks; ++b)
              {
                auto       head   = data_line("$Elements");
                const int  dim    = get<int>(head, "an entity dimension");
                const int  entity = get<int>(head, "an entity tag");
                const int  type   = get<int>(head, "an element type");
                const long n      = count(head, "the number of elements in a block");
                const auto it     = entity_physicals.find({dim, entity});
                const std::vector<int> physicals =
                  it == entity_physicals.end() ? std::vector<int>() : it->second;
                for (long i = 0; i < n; ++i)
                  {
                    auto       line = data_line("$Elements");
                    const long tag  = get<long>(line, "an element tag");
                    add_element(type, line, tag, physicals);
                  }
              }
          }
        end_of("Elements");
      }

      unsigned int vertex(const long tag, const long element) const
      {
        const auto it = vertex_of.find(tag);
        if (it == vertex_of.end())
          throw InputError("mesh file '" + file + "': element " + std::to_string(element) +
                           " names node " + std::to_string(tag) + ", which $Nodes does not define");
        return it->second;
      }

      Contents finish()
      {
        Contents out;
        out.vertices = vertices;
        if (hexes.empty())
          throw InputError("mesh file '" + file + "' has no hexahedra (element type 5)");
        std::map<std::array<unsigned int, 4>, std::pair<unsigned int, std::array<unsigned int, 4>>>
          face_of;
        for (unsigned int c = 0; c < hexes.size(); ++c)
          {
            std::array<unsigned int, 8> g;
            for (unsigned int i = 0; i < 8; ++i)
              g[i] = vertex(hexes[c][i], hex_tags[c]);
            // Gmsh's order is ABAQUS's: deal.II's swaps 2 <-> 3, 6 <-> 7.
            out.cells.push_back({{g[0], g[1], g[3], g[2], g[4], g[5], g[7], g[6]}});
            out.labels.push_back(hex_tags[c]);
            std::vector<int> tags = hex_physicals[c];
            if (tags.empty())
              tags.push_back(0);
            for (const int tag : tags)
              {
                const auto        name = physical_names.find({3, tag});
                const std::string region =
                  name != physical_names.end() ? name->second : std::to_string(tag);
                if (out.cell_sets.count(region) == 0)
                  out.regions.push_back(region);
                out.cell_sets[std::to_string(tag)].push_back(c);
                if (name != physical_names.end())
                  out.cell_sets[name->second].push_back(c);
              }
            for (const auto &f : abaqus_face)
              {
                std::array<unsigned int, 4> v = {{g[f[0]], g[f[1]], g[f[2]], g[f[3]]}}, k = v;
                std::sort(k.begin(), k.end());
                face_of[k] = {c, v};
              }
          }
        std::map<unsigned int, std::set<unsigned int>> surface_nodes;
        for (unsigned int q = 0; q < quads.size(); ++q)
          {
            std::array<unsigned int, 4> k;
            for (unsigned int i = 0; i < 4; ++i)
              k[i] = vertex(quads[q][i], -1);
            std::sort(k.begin(), k.end());
            const auto face = face_of.find(k);
            for (const int tag : quad_physicals[q])
              {
                if (tag <= 0 || tag > 255)
                  throw InputError("mesh file '" + file + "': physical surface " +
                                   std::to_string(tag) +
                                   " is not a boundary id Anvil can use (allowed: 1 ... 255)");
                surface_nodes[tag].insert(k.begin(), k.end());
                if (face != face_of.end())
                  out.faces.push_back({face->second.first, face->second.second,
                                       static_cast<unsigned int>(tag)});
              }
          }
        for (const auto &s : surface_nodes)
          {
            std::vector<std::string> names = {std::to_string(s.first)};
            const auto name = physical_names.find({2, static_cast<int>(s.first)});
            if (name != physical_names.end())
              names.push_back(name->second);
            for (const auto &n : names)
              {
                out.surfaces[n] = s.first;
                out.node_sets[n].assign(s.second.begin(), s.second.end());
              }
          }
        return out;
      }
    };
  } // namespace


  bool is_keyword_deck(const std::string &file_name)
  {
    const auto dot = file_name.find_last_of('.');
    const auto ext = dot == std::string::npos ? std::string() : key(file_name.substr(dot + 1));
    return ext == "K" || ext == "KEY" || ext == "DYN";
  }


  namespace Abaqus
  {
    std::string Keyword::required(const std::string &p) const
    {
      const std::string value = get(p);
      if (value.empty())
        throw InputError(line.where() + "*" + name + " needs '" + key(p) + "=...'");
      return value;
    }


    std::vector<Keyword> read_keywords(const std::string &file_name)
    {
      std::vector<Line> lines;
      read_lines(file_name, lines, 0);
      return keywords_of(lines);
    }


    std::vector<std::string> fields(const std::string &text)
    {
      std::vector<std::string> out;
      std::string::size_type   start = 0;
      while (true)
        {
          const auto comma = text.find(',', start);
          out.push_back(trim(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
          if (comma == std::string::npos)
            break;
          start = comma + 1;
        }
      if (!out.empty() && out.back().empty())
        out.pop_back();
      return out;
    }
  } // namespace Abaqus


  Contents read(const std::string &file_name)
  {
    const auto dot = file_name.find_last_of('.');
    const auto ext = dot == std::string::npos ? std::string() : key(file_name.substr(dot + 1));
    if (!std::filesystem::is_regular_file(file_name))
      throw InputError("mesh file '" + file_name + "' does not exist or is not a file");
    if (ext == "INP")
      return read_abaqus(file_name);
    if (is_keyword_deck(file_name))
      return read_keyword_deck(file_name);
    if (ext == "MSH")
      return GmshReader(file_name).read();
    throw InputError("mesh file '" + file_name + "': unknown extension (allowed: .msh, .inp, .k, .key, .dyn)");
  }
} // namespace anvil::MeshFile
