/**
 * @file
 * Mesh-source plugins: where a body's mesh comes from. The 'Source' entry
 * of subsection 'Body NAME/Mesh' names one; each declares and reads its
 * own entries in that subsection and builds the body's reference mesh.
 * Anvil's own: 'box', 'cylinder', 'sphere' (deal.II's generators) and
 * 'file' (ABAQUS .inp, Gmsh .msh); a plugin library registers more with
 * ANVIL_REGISTER_MESH_SOURCE. The body adds what every source shares:
 * 'Global refinements' (passed to the source) and 'Offset' (applied after
 * it).
 */
#pragma once

#include <anvil/utilities/registry.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * What a body's mesh names (upper-case keys): the boundary id of each
   * surface, and the reference positions of each node set, so that
   * boundary conditions can select them.
   */
  struct MeshNames
  {
    std::map<std::string, unsigned int>                  surfaces;
    std::map<std::string, std::vector<dealii::Point<3>>> node_sets;
    /** A warning for the log (what the file held that the body ignores),
        or empty. */
    std::string note;
    /** A line for the log about the mesh (a cylinder's section), or
        empty. */
    std::string info;
  };
} // namespace anvil

namespace anvil::MeshSources
{
  /** What a source reads its entries with. */
  struct Context
  {
    /** "subsection 'Body NAME/Mesh'", for an InputError. */
    std::string where;
    /** The body's name. */
    std::string body;
    /** Resolves relative file names. */
    std::string scene_directory;
    /** 'Global refinements': the times every element is split into eight. */
    unsigned int refinements = 0;
  };

  class Interface
  {
  public:
    virtual ~Interface() = default;

    /** Read the entries the plugin's static declare_parameters() declared
        (the handler is in subsection 'Body NAME/Mesh'); an InputError
        naming @p context.where for a bad one. A source that knows its
        element count before building checks it here (check_size). */
    virtual void parse_parameters(dealii::ParameterHandler &prm, const Context &context)
    {
      (void)prm, (void)context;
    }

    /** Build the body's reference mesh into the empty @p tria, split
        globally @p refinements times (most sources end with
        tria.refine_global(refinements); one with a curved manifold may
        refine while it builds), and what it names into @p names, if given.
        The body then shifts it by 'Offset'. */
    virtual void create(dealii::Triangulation<3> &tria, unsigned int refinements, MeshNames *names) const = 0;
  };

  /** The registered mesh sources, by name. */
  using Registry = ::anvil::Registry<Interface>;

  /**
   * The entries another source declares that are set (differ from their
   * default) while @p chosen is the source, one sentence each: they are
   * ignored, which the log should say ('Region' on a box). A scene that
   * includes another and switches its source inherits such entries, so
   * they are not an error. @p prm is in the body's 'Mesh' subsection;
   * @p shared are entries the body reads for every source.
   */
  std::vector<std::string> foreign_entries(const dealii::ParameterHandler &prm,
                                           const std::string              &chosen,
                                           const std::vector<std::string> &shared);
} // namespace anvil::MeshSources

namespace anvil
{
  // The table is the executable's (source/mesh/source.cc).
  extern template class Registry<MeshSources::Interface>;
}

/**
 * Register mesh source @p classname (with a static
 * declare_parameters(dealii::ParameterHandler &) declaring its entries in
 * subsection 'Body NAME/Mesh') under @p name, the value of 'Source' that
 * selects it. At the bottom of its .cc file, in namespace
 * anvil::MeshSources.
 */
#define ANVIL_REGISTER_MESH_SOURCE(classname, name, description)  \
  namespace                                                        \
  {                                                                \
    const bool anvil_registered_mesh_source_##classname =          \
      ::anvil::MeshSources::Registry::add(                         \
        name,                                                      \
        {description,                                              \
         &classname::declare_parameters,                           \
         []() { return std::make_unique<classname>(); }});         \
  }
