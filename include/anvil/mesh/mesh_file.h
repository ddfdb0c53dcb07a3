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

  /** Read @p file_name (.inp or .msh, by its extension). Throws
      InputError with the file, the line and what is wrong. */
  Contents read(const std::string &file_name);

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
