/**
 * @file
 * Setting up a scene: one distributed triangulation for all bodies, the
 * DoFs and ghosted nodal vectors, the element groups of the fast loop, the
 * lumped mass, boundary conditions, contact surfaces and probes.
 */
#include <anvil/mesh/mesh_file.h>
#include <anvil/deck/deck.h>
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/step_section.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <metis.h>

#include <filesystem>
#include <unistd.h>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  Simulator::Simulator(const std::string              &parameter_file,
                       MPI_Comm                         comm,
                       const std::vector<std::string> &overrides)
    : mpi_communicator(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , triangulation(comm)
    , fe(FE_Q<3>(1), 3)
    , dof_handler(triangulation)
  {
    // Reading the scene only converts text: a deal.II exception here (a
    // number that is not one, in an entry whose pattern lets any text
    // through) is bad input, and arises on every rank alike.
    try
      {
        parse_parameters(parameter_file, overrides);
      }
    catch (const ExceptionBase &e)
      {
        throw InputError(parameter_file + ": " + one_line_message(e) +
                         " (an entry that needs numbers holds something else; "
                         "'anvil --print-parameters' shows what each entry takes)");
      }
  }


  // @sect3{The mesh}
  //
  // Each body builds its own serial mesh (generators may refine along
  // curved manifolds); its active cells become cells of the scene's one
  // mesh, with the body index as material id, in the order of the bodies
  // and of each body's cells: a cell's index in this mesh is the element's
  // id, the same on any number of processes. Bodies never share vertices,
  // even where they touch: contact, not the mesh, couples them.
  //
  // The triangulation is fully distributed (deal.II's
  // parallel::fullydistributed::Triangulation): a process holds its own
  // cells and the layer of ghost cells that share a vertex with them,
  // nothing of the rest. (A p4est-distributed triangulation holds every
  // cell of its coarse mesh on every process, and a forest tree for each:
  // 837 bytes an element on the production column, against 391 now; Anvil
  // refines nothing, so the forest brought nothing else.)
  void Simulator::make_grid()
  {
    std::vector<Point<3>>    vertices;
    std::vector<CellData<3>> cells;
    SubCellData              boundary;
    for (const auto &note : parameters.deck_notes)
      pcout << "Warning: " << parameters.scene_file << ": " << note << std::endl;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        Triangulation<3> tria;
        MeshNames        names;
        bodies[b].create_mesh(tria, &names);
        // A deck's translation has accounted for every keyword the mesh
        // reader passes over.
        if (!names.note.empty() && !Deck::is_deck(parameters.scene_file))
          pcout << "Warning: body '" << bodies[b].name << "': " << names.note << std::endl;
        if (!names.info.empty())
          pcout << "Body '" << bodies[b].name << "': " << names.info << std::endl;
        constraints->resolve_names(bodies[b].name, names);
        for (auto &probe : probes)
          if (probe.body == bodies[b].name && !probe.node_set.empty())
            {
              const auto set = names.node_sets.find(probe.node_set);
              const std::string where = "subsection 'Probe " + probe.name + "': 'Node set' ";
              if (set == names.node_sets.end())
                throw InputError(where + "names '" + printable_excerpt(probe.node_set) +
                                 "', which body '" + bodies[b].name +
                                 "' does not have (its node sets: " +
                                 MeshFile::names_of(names.node_sets) + ")");
              if (set->second.size() != 1)
                throw InputError(where + "'" + probe.node_set + "' has " +
                                 std::to_string(set->second.size()) +
                                 " nodes (a probe follows one: make a set of one node)");
              probe.point = set->second[0];
            }
        const unsigned int offset = vertices.size();
        std::vector<int>   new_index(tria.n_vertices(), -1);
        const auto        &used = tria.get_used_vertices();
        for (unsigned int v = 0; v < tria.n_vertices(); ++v)
          if (used[v])
            {
              new_index[v] = vertices.size() - offset;
              vertices.push_back(tria.get_vertices()[v]);
            }
        for (const auto &cell : tria.active_cell_iterators())
          {
            CellData<3> c(8);
            for (unsigned int v = 0; v < 8; ++v)
              c.vertices[v] = offset + new_index[cell->vertex_index(v)];
            c.material_id = b;
            cells.push_back(c);
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() != 0)
                {
                  CellData<2> q(4);
                  for (unsigned int v = 0; v < 4; ++v)
                    q.vertices[v] = offset + new_index[cell->face(f)->vertex_index(v)];
                  q.boundary_id = cell->face(f)->boundary_id();
                  boundary.boundary_quads.push_back(q);
                }
          }
      }
    // The whole mesh, serial, for as long as the partition and the
    // description of each process's cells take; then each process keeps its
    // own cells and the ghost layer around them, nothing else.
    {
      // (Neighbours across a face, an edge or a vertex differ by one
      // level at most: each hanging node then has masters that are not
      // hanging themselves, all in the ghost layer of the process that
      // owns it.)
      Triangulation<3> serial(Triangulation<3>::limit_level_difference_at_vertices);
      try
        {
          serial.create_triangulation(vertices, cells, boundary);
        }
      catch (const ExceptionBase &e)
        {
          throw InputError("the scene's mesh is not valid: " + one_line_message(e));
        }
      std::vector<Point<3>>().swap(vertices);
      std::vector<CellData<3>>().swap(cells);
      boundary = SubCellData();
      refine_regions(serial);
      // The cells the run starts from, so that each element knows how
      // often it was halved during the run (halvings_during_run: the
      // penalty keeps the stiffness of the start's element).
      std::set<CellId> start_cells;
      if (!adapt_rounds.empty())
        for (const auto &cell : serial.active_cell_iterators())
          start_cells.insert(cell->id());
      replay_adaptation(serial);
      halvings_during_run.clear();
      if (!start_cells.empty())
        {
          halvings_during_run.assign(serial.n_active_cells(), 0);
          for (const auto &cell : serial.active_cell_iterators())
            {
              unsigned int n = 0;
              auto         c = cell;
              while (start_cells.count(c->id()) == 0 && c->level() > 0)
                c = c->parent(), ++n;
              halvings_during_run[cell->active_cell_index()] = start_cells.count(c->id()) > 0 ? n : 0;
            }
        }
      partition_by_cost(serial);
      if (parameters.adapt_interval > 0)
        {
          serial_mesh = std::make_unique<Triangulation<3>>(Triangulation<3>::limit_level_difference_at_vertices);
          serial_mesh->copy_triangulation(serial);
        }
      const auto description =
        TriangulationDescription::Utilities::create_description_from_triangulation(serial, mpi_communicator);
      triangulation.create_triangulation(description);
      // The process numbers the vertices it holds from 0; each keeps the
      // scene's index, found through its cell's (output's node ids). An
      // element's id is its index among the scene's active cells (its
      // coarse cell's where nothing is refined).
      scene_vertex.assign(triangulation.n_vertices(), numbers::invalid_unsigned_int);
      element_id.assign(triangulation.n_active_cells(), numbers::invalid_unsigned_int);
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          const auto whole = serial.create_cell_iterator(cell->id());
          if (!cell->is_artificial())
            element_id[cell->active_cell_index()] = whole->active_cell_index();
          for (const unsigned int v : cell->vertex_indices())
            {
              AssertThrow(cell->vertex(v) == whole->vertex(v), ExcInternalError());
              scene_vertex[cell->vertex_index(v)] = whole->vertex_index(v);
            }
        }
    }
  }


  // @sect3{Local refinement}
  //
  // Each body's 'Refinement region': its elements are halved once per
  // level, by their reference centroid, the scene's mesh being the coarse
  // mesh of a forest (deal.II's refinement, with one level at most between
  // neighbours). The refined mesh is then distributed as any other: each
  // process holds its cells and their ghost layer, with the hanging nodes'
  // constraints (setup_system).
  void Simulator::refine_regions(Triangulation<3> &serial) const
  {
    unsigned int levels = 0;
    for (const auto &body : bodies)
      levels = std::max(levels, body.local_refinement_levels());
    if (levels == 0)
      return;
    // Each body's box in the reference configuration (for 'Near body').
    std::vector<Point<3>> lower(bodies.size(), Point<3>(1e300, 1e300, 1e300)),
      upper(bodies.size(), Point<3>(-1e300, -1e300, -1e300));
    for (const auto &cell : serial.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int d = 0; d < 3; ++d)
          {
            lower[cell->material_id()][d] = std::min(lower[cell->material_id()][d], cell->vertex(v)[d]);
            upper[cell->material_id()][d] = std::max(upper[cell->material_id()][d], cell->vertex(v)[d]);
          }
    const auto near = Body::near_boxes(bodies, lower, upper);
    for (unsigned int level = 0; level < levels; ++level)
      {
        bool any = false;
        for (const auto &cell : serial.active_cell_iterators())
          {
            const unsigned int b = cell->material_id();
            if (level < bodies[b].wanted_levels(cell->center(), cell->center(), near[b], 0., false))
              {
                cell->set_refine_flag();
                any = true;
              }
          }
        if (!any)
          break;
        serial.execute_coarsening_and_refinement();
      }
  }


  // @sect3{The partition}
  //
  // By default ('metis per kind') METIS cuts the cells' face graph with
  // each kind of element balanced by itself (partition_kinds_by_metis()).
  // 'hierarchical': the cells are put in a hierarchical order of their vertex connectivity
  // (SparsityTools::reorder_hierarchical: neighbours grouped together, in
  // groups of groups, the order p4est's forest would give the same cells),
  // and the order is cut into pieces of equal weight, one per process. A
  // fully integrated element costs several one-point elements (8 points), a
  // rigid body's element almost nothing, and a process that held the
  // column's fully integrated region under the hammer with an equal count
  // of cells would hold the slowest share of the step. Weights per cell:
  // 1000 for a one-point element, full_integration_weight (15000, measured)
  // for a fully integrated one, 100 for a rigid body's. The partition is a
  // function of the mesh and the scene only, so a resumed run finds the
  // same one; the results do not depend on it.
  //
  // A run partitioned anew during its course ('Rebalance interval') weighs
  // each cell by what its element measured instead (check_balance()).
  namespace
  {
    // 'Partitioner = metis per kind': METIS's multi-constraint partition
    // of the cells' face graph, each kind of element (the cells of kind k
    // weigh weight[c] in constraint k and nothing in the others) balanced
    // by itself within 1 %. Where the work of one kind changes during the
    // run (the fully integrated concrete under a hammer, as it cracks),
    // each process holds its share of that kind, and of the change. The
    // same graph, weights and seed on every process give every process the
    // same partition.
    constexpr unsigned int n_kinds = 2; // one-point (and rigid), fully integrated

    void partition_kinds_by_metis(Triangulation<3>                 &serial,
                                  const std::vector<unsigned long> &weight,
                                  const std::vector<unsigned int>  &kind,
                                  const unsigned int                n_ranks)
    {
      idx_t n = serial.n_active_cells();
      // The kinds present, numbered 0, 1, ... as constraints.
      std::vector<int> constraint(n_kinds, -1);
      idx_t            n_constraints = 0;
      for (idx_t c = 0; c < n; ++c)
        if (constraint[kind[c]] < 0)
          constraint[kind[c]] = n_constraints++;
      DynamicSparsityPattern graph;
      GridTools::get_face_connectivity_of_cells(serial, graph);
      std::vector<idx_t> xadj(1, 0), adjacent, vertex_weight(n * n_constraints, 0);
      for (idx_t c = 0; c < n; ++c)
        {
          for (auto entry = graph.begin(c); entry != graph.end(c); ++entry)
            if (static_cast<idx_t>(entry->column()) != c)
              adjacent.push_back(entry->column());
          xadj.push_back(adjacent.size());
          // (METIS's weights are 32-bit: the measured ones are scaled so
          // that the mean element weighs 1000.)
          vertex_weight[n_constraints * c + constraint[kind[c]]] =
            static_cast<idx_t>(std::min<unsigned long>(weight[c], 1u << 30));
        }
      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_SEED] = 1;
      std::vector<real_t> tolerance(n_constraints, 1.01);
      idx_t               n_parts = n_ranks, cut = 0;
      std::vector<idx_t>  part(n);
      // (Recursive bisection for a few parts, k-way beyond, as deal.II's
      // own call of METIS chooses.)
      const int status =
        (n_ranks <= 8 ? METIS_PartGraphRecursive : METIS_PartGraphKway)(&n,
                                                                          &n_constraints,
                                                                          xadj.data(),
                                                                          adjacent.data(),
                                                                          vertex_weight.data(),
                                                                          nullptr,
                                                                          nullptr,
                                                                          &n_parts,
                                                                          nullptr,
                                                                          tolerance.data(),
                                                                          options,
                                                                          &cut,
                                                                          part.data());
      AssertThrow(status == METIS_OK,
                  ExcMessage("METIS's partition by kind of element failed (status " + std::to_string(status) + ")"));
      for (const auto &cell : serial.active_cell_iterators())
        cell->set_subdomain_id(part[cell->active_cell_index()]);
    }
  } // namespace


  void Simulator::partition_by_cost(Triangulation<3> &serial) const
  {
    const unsigned long n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    // (A process with no element of its own has nothing to compute and no
    // cell to hold its share of the nodes.)
    if (serial.n_active_cells() < n_ranks)
      throw InputError(parameters.scene_file + ": the scene has " + std::to_string(serial.n_active_cells()) +
                       " element(s), fewer than the " + std::to_string(n_ranks) +
                       " MPI processes: run it on at most as many processes as elements");
    // Each cell's weight and kind (1: fully integrated, 0: the others).
    std::vector<unsigned long> weight(serial.n_active_cells());
    std::vector<unsigned int>  kind(serial.n_active_cells());
    for (const auto &cell : serial.active_cell_iterators())
      {
        const Body &body = bodies[cell->material_id()];
        const bool  full = !body.is_rigid() && body.integration_of(cell) == Element::Integration::full;
        weight[cell->active_cell_index()] = body.is_rigid() ? 100 : full ? full_integration_weight : 1000;
        kind[cell->active_cell_index()]   = full ? 1 : 0;
      }
    if (partition_weights.size() == weight.size())
      weight = partition_weights;
    if (n_ranks > 1 && parameters.partitioner == "metis per kind")
      {
        partition_kinds_by_metis(serial, weight, kind, n_ranks);
        return;
      }
    // A graph partitioner (METIS, Trilinos' Zoltan) on the cells' face
    // graph with the same weights.
    if (n_ranks > 1 && parameters.partitioner != "hierarchical")
      {
        const std::vector<unsigned int> cell_weight(weight.begin(), weight.end());
        GridTools::partition_triangulation(n_ranks,
                                           cell_weight,
                                           serial,
                                           parameters.partitioner == "metis" ? SparsityTools::Partitioner::metis :
                                                                    SparsityTools::Partitioner::zoltan);
        return;
      }
    std::vector<DynamicSparsityPattern::size_type> position_of(serial.n_active_cells());
    std::iota(position_of.begin(), position_of.end(), 0);
    if (n_ranks > 1)
      {
        DynamicSparsityPattern connectivity;
        GridTools::get_vertex_connectivity_of_cells(serial, connectivity);
        SparsityTools::reorder_hierarchical(connectivity, position_of);
      }
    std::vector<unsigned int> in_order(serial.n_active_cells());
    for (unsigned int c = 0; c < in_order.size(); ++c)
      in_order[position_of[c]] = c;
    const unsigned long total = std::accumulate(weight.begin(), weight.end(), 0ul);
    std::vector<types::subdomain_id> owner(serial.n_active_cells());
    unsigned long before = 0;
    for (const unsigned int c : in_order)
      {
        owner[c] = static_cast<types::subdomain_id>(std::min(n_ranks - 1, n_ranks * before / total));
        before += weight[c];
      }
    for (const auto &cell : serial.active_cell_iterators())
      cell->set_subdomain_id(owner[cell->active_cell_index()]);
  }


  void Simulator::setup_system()
  {
    dof_handler.distribute_dofs(fe);
    const IndexSet owned = dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    for (VectorType *v : {&reference_position, &position, &velocity, &force, &mass})
      v->reinit(owned, relevant, mpi_communicator);

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (unsigned int v = 0; v < 8; ++v)
          for (unsigned int c = 0; c < 3; ++c)
            {
              const auto dof          = cell->vertex_dof_index(v, c);
              reference_position(dof) = cell->vertex(v)[c];
              velocity(dof) = bodies[cell->material_id()].initial_velocity[c];
            }
    position = reference_position;

    // The hanging nodes of local refinement: deal.II's constraints of the
    // dofs this process holds, summed onto the masters in the order of the
    // nodes' scene index.
    hanging = HangingNodes();
    if (triangulation.n_global_levels() > 1)
      {
        AffineConstraints<double> constraints(relevant);
        DoFTools::make_hanging_node_constraints(dof_handler, constraints);
        constraints.close();
        const auto               &partitioner = *position.get_partitioner();
        std::vector<unsigned long> key(partitioner.locally_owned_size() + partitioner.n_ghost_indices(),
                                       std::numeric_limits<unsigned long>::max());
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            for (unsigned int v = 0; v < 8; ++v)
              for (unsigned int c = 0; c < 3; ++c)
                key[partitioner.global_to_local(cell->vertex_dof_index(v, c))] =
                  3ul * scene_vertex[cell->vertex_index(v)] + c;
        hanging.reinit(constraints, partitioner, key);
      }

    dof_body.assign(position.locally_owned_size(), 0);
    dof_component.assign(position.locally_owned_size(), 0);
    dof_key.assign(position.locally_owned_size(), 0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (unsigned int v = 0; v < 8; ++v)
          for (unsigned int c = 0; c < 3; ++c)
            {
              const auto dof = cell->vertex_dof_index(v, c);
              if (owned.is_element(dof))
                {
                  dof_body[owned.index_within_set(dof)]      = cell->material_id();
                  dof_component[owned.index_within_set(dof)] = c;
                  dof_key[owned.index_within_set(dof)]       = 3ul * scene_vertex[cell->vertex_index(v)] + c;
                }
            }
  }


  // Everything a run, a check and a cost estimate build, in one sequence.
  void Simulator::setup()
  {
    make_grid();
    setup_system();
    for (auto *family : contributors())
      family->setup();
    assemble_lumped_mass();
    for (auto *family : contributors())
      family->initialize();
    setup_probes();
  }


  void Simulator::check()
  {
    setup();
    report_element_quality();
    prepare_output_directory(true);
    pcout << parameters.scene_file << ": scene '" << parameters.scene_name << "' is valid: "
          << bodies.size() << " bodies, " << triangulation.n_global_active_cells()
          << " elements, " << contact->n_pairs() << " contact pairs"
          << std::endl;
  }


  // @sect3{Lumped mass}
  //
  // Each family adds its own (the solid bodies' elements first, then the
  // perfectly bonded bars); every node ends with a positive mass.
  void Simulator::assemble_lumped_mass()
  {
    mass = 0;
    for (auto *family : contributors())
      family->add_mass(mass);
    // A hanging node's mass goes to its masters (HangingNodes): the
    // owners' complete masses first.
    if (!hanging.empty())
      {
        mass.update_ghost_values();
        hanging_mass.assign(mass.begin(), mass.begin() + mass.locally_owned_size());
        hanging.condense(mass.begin());
        mass.update_ghost_values();
      }
    // (Every element has a positive volume and every material a density,
    // so a massless node is a mesh whose elements have no volume: refused
    // by every process together, with one line.)
    unsigned int massless = 0;
    for (unsigned int i = 0; i < mass.locally_owned_size(); ++i)
      massless += !(mass.local_element(i) > 0) && !hanging.is_hanging(i);
    if (Utilities::MPI::sum(massless, mpi_communicator) > 0)
      throw InputError(parameters.scene_file + ": " + std::to_string(Utilities::MPI::sum(massless, mpi_communicator) / 3) +
                       " node(s) have no mass: their elements have no volume (a mesh degenerate in places)");
    // The dofs the central difference leaves alone: the rigid bodies'
    // (the family moves them) and the hanging ones (they follow).
    moved_dof = rigid_dof;
    if (!hanging.empty())
      {
        moved_dof.resize(mass.locally_owned_size(), 0);
        for (unsigned int i = 0; i < mass.locally_owned_size(); ++i)
          if (hanging.is_hanging(i))
            moved_dof[i] = 1;
      }
  }


  void Simulator::condense_forces()
  {
    if (hanging.empty())
      return;
    StepSection t(*timer, parameters.print_wall_times, "time integration");
    // Each hanging node's force is complete on its owner alone.
    force.update_ghost_values();
    hanging.condense(force.begin());
  }


  // @sect3{Boundary conditions}
  // @sect3{Probes}
  void Simulator::setup_probes()
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    const IndexSet    &owned = dof_handler.locally_owned_dofs();
    for (auto &probe : probes)
      {
        // The nearest node, its coordinate along a section's normal and
        // the shortest edge of the cell it was found in.
        double best = 1e300, dof = 0, along = 0, edge = 0;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() &&
              (probe.body.empty() || bodies[cell->material_id()].name == probe.body))
            for (unsigned int v = 0; v < 8; ++v)
              {
                const auto d = cell->vertex_dof_index(v, 0);
                if (!owned.is_element(d))
                  continue;
                // (A hanging node's motion is its neighbours': the probe
                // follows the nearest node that is not hanging.)
                if (hanging.is_hanging(position.get_partitioner()->global_to_local(d)))
                  continue;
                // Ties broken by position so that every partition picks
                // the same node.
                const double dist = cell->vertex(v).distance(probe.point);
                if (dist < best - 1e-12 * (1 + best))
                  {
                    best  = dist;
                    dof   = d;
                    along = probe.section_normal >= 0 ? cell->vertex(v)[probe.section_normal] : 0.;
                    edge  = cell->minimum_vertex_distance();
                  }
              }
        const auto all = Utilities::MPI::all_gather(mpi_communicator,
                                                    std::array<double, 5>{{best, dof, double(rank), along, edge}});
        std::array<double, 5> chosen = all[0];
        for (const auto &a : all)
          if (a[0] < chosen[0] - 1e-12 * (1 + chosen[0]))
            chosen = a;
        probe.x_dof = static_cast<unsigned long>(chosen[1]);
        probe.owner = static_cast<int>(chosen[2]);
        if (probe.owner == int(rank))
          {
            const auto    local = position.get_partitioner()->global_to_local(probe.x_dof);
            unsigned long best_id = static_cast<unsigned long>(-1);
            for (unsigned int g = 0; g < solids->groups().size(); ++g)
              for (unsigned int e = 0; e < solids->groups()[g].n_elements(); ++e)
                for (const unsigned int n : solids->groups()[g].element_nodes(e))
                  if (n == local && solids->groups()[g].element_global_id(e) < best_id)
                    {
                      best_id       = solids->groups()[g].element_global_id(e);
                      probe.group   = g;
                      probe.element = e;
                    }
          }
        if (probe.section_normal >= 0)
          setup_section_probe(probe, chosen[3], 1e-3 * chosen[4]);
      }
  }


  // A section probe's nodes: those of the body (not hanging) within a
  // thousandth of the chosen node's shortest edge of its plane, ordered
  // by scene index, so that every partition sums them in one order.
  void Simulator::setup_section_probe(Probe &probe, const double along, const double tolerance)
  {
    const IndexSet          &owned = dof_handler.locally_owned_dofs();
    std::set<types::global_dof_index> seen;
    std::vector<std::array<double, 4>> mine; // scene key, rank, dof, mass
    const double                      rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && (probe.body.empty() || bodies[cell->material_id()].name == probe.body))
        for (unsigned int v = 0; v < 8; ++v)
          {
            const auto d = cell->vertex_dof_index(v, 0);
            if (!owned.is_element(d) || std::abs(cell->vertex(v)[probe.section_normal] - along) > tolerance ||
                hanging.is_hanging(position.get_partitioner()->global_to_local(d)) || !seen.insert(d).second)
              continue;
            mine.push_back({{double(dof_key[owned.index_within_set(d)]), rank, double(d), mass(d)}});
          }
    std::vector<std::array<double, 4>> section;
    for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, mine))
      section.insert(section.end(), part.begin(), part.end());
    std::sort(section.begin(), section.end());
    probe.section_mass.clear();
    probe.owned_section_dofs.clear();
    for (unsigned int i = 0; i < section.size(); ++i)
      {
        probe.section_mass.push_back(section[i][3]);
        if (section[i][1] == rank)
          probe.owned_section_dofs.emplace_back(i, static_cast<unsigned long>(section[i][2]));
      }
  }


  // A run deletes only files a run wrote: those listed in anvil_files.txt
  // of the earlier run in this directory (a user's own files stay). Earlier
  // results (that list, or an energy.csv) stop the run unless 'Overwrite
  // existing output' is set.
  void Simulator::prepare_output_directory(const bool check_only)
  {
    int         status = 0;
    std::string detail;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        namespace fs = std::filesystem;
        const fs::path  dir  = parameters.output_directory;
        const fs::path  list = dir / "anvil_files.txt";
        std::error_code ec;
        if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
          status = 3;
        else if ((fs::exists(list) || fs::exists(dir / "energy.csv")) && !parameters.overwrite_output)
          status = 1;
        else if (check_only)
          {
            // Nothing made or removed: only whether the run could write.
            fs::path existing = fs::absolute(dir);
            while (!existing.empty() && !fs::exists(existing, ec) && existing != existing.parent_path())
              existing = existing.parent_path();
            if (!fs::is_directory(existing, ec) || access(existing.c_str(), W_OK) != 0)
              {
                status = 2;
                detail = "no write permission in " + existing.string();
              }
          }
        else
          {
            fs::create_directories(dir, ec);
            if (ec)
              {
                status = 2;
                detail = ec.message();
              }
            else if (access(dir.c_str(), W_OK) != 0)
              {
                status = 2;
                detail = "no write permission";
              }
            else if (fs::exists(list))
              {
                std::ifstream in(list);
                std::string   name;
                while (std::getline(in, name))
                  if (!name.empty() && name.find('/') == std::string::npos && name != "..")
                    fs::remove(dir / name, ec);
                in.close();
                fs::remove(list, ec);
              }
          }
      }
    status = Utilities::MPI::max(status, mpi_communicator);
    if (status == 1)
      throw InputError(parameters.scene_file + ": results of an earlier run exist in '" +
                       parameters.output_directory +
                       "'; set 'Overwrite existing output = true' in "
                       "subsection 'Simulation' or choose another 'Output "
                       "directory'");
    if (status == 2)
      throw InputError(parameters.scene_file + ": cannot create or write the output directory '" +
                       parameters.output_directory + "'" + (detail.empty() ? "" : ": " + detail));
    if (status == 3)
      throw InputError(parameters.scene_file + ": the output directory '" + parameters.output_directory +
                       "' is a file; choose another 'Output directory' or 'Name'");
  }


  // What the step will evaluate, read from the flags the loop itself
  // tests: a physics the scene does not contain is not computed.
  std::string Simulator::step_contents() const
  {
    std::ostringstream s;
    s << solids->describe() << "; " << contact->describe();
    for (const auto &family : families)
      s << "; " << family->describe();
    return s.str();
  }
} // namespace anvil
