/**
 * @file
 * Hexahedral meshes from files as ABAQUS/CAE and Gmsh write them: cells,
 * labelled faces and the names the file gives to groups of cells, faces
 * and nodes, read before any of them becomes (part of) a body.
 */
#pragma once

#include <deal.II/base/point.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace anvil::MeshFile
{
  /**
   * What a mesh file holds. Names of groups are kept upper-case (ABAQUS
   * names are case-insensitive; a scene matches them without regard to
   * case).
   */
  struct Contents
  {
    std::vector<dealii::Point<3>> vertices;
    /** Hexahedra, their vertices in deal.II's (lexicographic) order. */
    std::vector<std::array<unsigned int, 8>> cells;
    /** The file's label of each cell (ABAQUS element label, Gmsh element
        tag), for messages. */
    std::vector<long> labels;

    /** A face with a boundary id: its cell and its four vertices. */
    struct Face
    {
      unsigned int                cell;
      std::array<unsigned int, 4> vertices;
      unsigned int                boundary_id;
    };
    std::vector<Face> faces;

    /** Named groups of cells (ABAQUS: instances, parts, element sets;
        Gmsh: physical volumes, by name and by number). */
    std::map<std::string, std::vector<unsigned int>> cell_sets;
    /** Named groups of vertices (ABAQUS: node sets; Gmsh: the nodes of
        physical surfaces). */
    std::map<std::string, std::vector<unsigned int>> node_sets;
    /** Named faces (ABAQUS: element-based surfaces; Gmsh: physical
        surfaces): the boundary id each became. */
    std::map<std::string, unsigned int> surfaces;

    /** The file's top-level groups of cells (ABAQUS instances, Gmsh
        physical volumes by name or else number): a body that takes all of
        several is told so. */
    std::vector<std::string> regions;

    /** What the reader took no notice of, for one warning line. */
    std::string skipped;
  };

  /** Read @p file_name (.inp, .msh, or an LS-DYNA keyword deck .k, .key,
      .dyn, by its extension). Throws InputError with the file, the line
      and what is wrong. */
  Contents read(const std::string &file_name);

  /** The mesh of an LS-DYNA keyword deck: cell groups 'PART<pid>', node
      sets 'SET<sid>', surfaces 'SEGMENTSET<sid>', and the nodes that
      *NODE's TC codes and *BOUNDARY_SPC_NODE constrain as node sets
      'NODE_TC<code>' and 'SPC_NODE_<dofs>' (dofs: e.g. 'XZ'). */
  Contents read_keyword_deck(const std::string &file_name);

  /** 'X', 'XZ', 'XYZ', ...: the constrained directions of @p dofs. */
  std::string keyword_dofs_name(const std::array<bool, 3> &dofs);

  /** Whether @p file_name is an LS-DYNA keyword deck by its extension. */
  bool is_keyword_deck(const std::string &file_name);

  /** The keywords of an ABAQUS deck, for the mesh reader and the deck
      translator. */
  namespace Abaqus
  {
    /** A line of the deck and where it came from (for messages). */
    struct Line
    {
      std::string  text;
      std::string  file;
      unsigned int number = 0;

      std::string where() const
      {
        return "mesh file '" + file + "', line " + std::to_string(number) + ": ";
      }
    };

    /** A keyword with its parameters (upper-case names; values as
        written) and its data lines. */
    struct Keyword
    {
      std::string                        name, written;
      std::map<std::string, std::string> parameters;
      std::vector<Line>                  data;
      Line                               line;

      bool has(const std::string &p) const
      {
        return parameters.count(p) > 0;
      }
      std::string get(const std::string &p) const
      {
        const auto it = parameters.find(p);
        return it == parameters.end() ? std::string() : it->second;
      }
      /** The parameter's value; an InputError naming it if it has none. */
      std::string required(const std::string &p) const;
    };

    /** The keywords of @p file_name, *Include files in place, '**'
        comments dropped. */
    std::vector<Keyword> read_keywords(const std::string &file_name);

    /** The comma-separated fields of a data line, trimmed (empty ones
        kept). */
    std::vector<std::string> fields(const std::string &text);
  } // namespace Abaqus

  /** Upper-case copy of @p name (the key of the maps above). */
  std::string key(const std::string &name);

  /** The keys of @p map joined by ", " (for messages), at most @p max;
      not ABAQUS's internal names (those starting with '_'). */
  template <typename Map>
  std::string names_of(const Map &map, const unsigned int max = 12)
  {
    std::string  s;
    unsigned int n = 0;
    for (const auto &entry : map)
      {
        if (!entry.first.empty() && entry.first[0] == '_')
          continue;
        if (n++ == max)
          return s + ", ...";
        s += (s.empty() ? "" : ", ") + entry.first;
      }
    return s.empty() ? std::string("none") : s;
  }
} // namespace anvil::MeshFile
