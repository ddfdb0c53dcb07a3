/**
 * @file
 * Refinement and coarsening during the run ('Adapt interval';
 * doc/adaptivity.md, "Refinement during the run"). At each check every
 * element of a body with a 'Refinement region' asks to be halved (its
 * criteria hold and it is below the region's levels) or joined with its
 * siblings (they hold for their parent for none of them). A round of such
 * wishes is recorded with the checkpoint; the run goes on from it on the
 * scene's mesh with every round applied (the regions of the start, then
 * the rounds, deal.II's refinement of the serial mesh), and the state of
 * the mesh before the last round moves onto the new one:
 *
 * - a node the round kept keeps its motion; a new node takes the motion
 *   of the element it was made in, interpolated (trilinear) at its place;
 * - an element the round kept keeps its record; a child takes its parent's
 *   stresses and history (at the parent's point in its octant), a joined
 *   parent the mean of its children; energies split and add by volume,
 *   hourglass state starts anew, what the geometry set stays the new
 *   element's own (ElementGroup::serialize);
 * - the forces of time n are made on the new mesh from that state (an
 *   evaluation at dt = 0 that leaves the state as it was);
 * - the kinetic energy the round changed, the elastic energy the averaging
 *   took out and the springs the new contact nodes found are booked as
 *   'adaptation' in energy.csv.
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/output_files.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/affine_constraints.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /** Which child of its parent a cell is (0-7, x fastest). */
    unsigned int last_child_index(const CellId &id)
    {
      const auto children = id.get_child_indices();
      return children[children.size() - 1];
    }
  } // namespace

  // @sect3{The check}
  void Simulator::check_adaptivity()
  {
    // (Nothing to check where no body asks for finer elements.)
    if (std::none_of(bodies.begin(), bodies.end(), [](const Body &b) { return b.local_refinement_levels() > 0; }))
      return;
    const unsigned int n_bodies = bodies.size();
    // Each body's current box (for 'Near body').
    std::vector<double> lower(3 * n_bodies, 1e300), upper(3 * n_bodies, 1e300);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int d = 0; d < 3; ++d)
            {
              const double x = position(cell->vertex_dof_index(v, d));
              const unsigned int b = cell->material_id();
              lower[3 * b + d] = std::min(lower[3 * b + d], x);
              upper[3 * b + d] = std::min(upper[3 * b + d], -x);
            }
    for (auto *v : {&lower, &upper})
      MPI_Allreduce(MPI_IN_PLACE, v->data(), v->size(), MPI_DOUBLE, MPI_MIN, mpi_communicator);
    std::vector<Point<3>> near_lower(n_bodies), near_upper(n_bodies);
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        for (unsigned int d = 0; d < 3; ++d)
          near_lower[b][d] = lower[3 * b + d], near_upper[b][d] = -upper[3 * b + d];
      }
    // (The current boxes: 'Near body' follows the impactor.)
    const auto near = Body::near_boxes(bodies, near_lower, near_upper);

    // Each own element's largest indicator value and whether it is intact.
    std::vector<double> indicator(triangulation.n_active_cells(), 0.);
    std::vector<char>   intact(triangulation.n_active_cells(), 1);
    const auto         &groups = solids->groups();
    for (unsigned int g = 0; g < groups.size(); ++g)
      {
        const int k = bodies[solids->group_body()[g]].refinement_indicator();
        for (unsigned int e = 0; e < groups[g].n_elements(); ++e)
          if (groups[g].element_is_owned(e))
            {
              const unsigned int c = groups[g].element_cell_index(e);
              intact[c]            = !groups[g].element_is_eroded(e);
              if (k >= 0)
                for (unsigned int q = 0; q < groups[g].n_quadrature_points(); ++q)
                  indicator[c] = std::max(indicator[c], groups[g].history_output(e, q, k));
            }
      }

    // 'Indicator = contact_pressure': the largest contact force at an
    // element's nodes over its face area V^(2/3).
    if (std::any_of(bodies.begin(), bodies.end(), [](const Body &b) {
          return b.refinement_indicator() == Body::contact_pressure_indicator;
        }))
      {
        VectorType nodal(force);
        nodal = 0;
        if (!contact->empty())
          contact->nodal_force_magnitudes(nodal);
        nodal.update_ghost_values();
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() &&
              bodies[cell->material_id()].refinement_indicator() == Body::contact_pressure_indicator)
            {
              double largest = 0;
              for (const unsigned int v : cell->vertex_indices())
                largest = std::max(largest, nodal(cell->vertex_dof_index(v, 0)));
              indicator[cell->active_cell_index()] = largest / std::pow(cell->measure(), 2. / 3.);
            }
      }

    // The wishes: + (id + 1) finer, - (id + 1) coarser. A child asks to be
    // joined where its parent would not be refined: the parent's centroid
    // (reference, and moved by the child's motion) fails the criteria and
    // the child's own indicator is below the threshold. A join counts only
    // where all eight siblings ask for it: each asks under its parent's
    // cell id, which the siblings know from the distributed mesh's
    // hierarchy, whichever process owns them.
    std::vector<std::int64_t>                         finer_ids;
    std::vector<std::pair<std::string, std::int64_t>> joins;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Body &body = bodies[cell->material_id()];
          if (body.local_refinement_levels() == 0 || !intact[cell->active_cell_index()])
            continue;
          Point<3> current;
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int d = 0; d < 3; ++d)
              current[d] += 0.125 * position(cell->vertex_dof_index(v, d));
          const auto &boxes = near[cell->material_id()];
          const auto  id    = static_cast<std::int64_t>(element_id[cell->active_cell_index()]) + 1;
          const auto  value = indicator[cell->active_cell_index()];
          const auto  level = static_cast<unsigned int>(cell->level());
          if (level < body.wanted_levels(cell->center(), current, boxes, value, true))
            finer_ids.push_back(id);
          else if (level > 0 && !coarsening_refused.count(static_cast<unsigned long>(id - 1)))
            {
              // (Joined where the parent's level is all the regions want
              // for the parent.)
              const Point<3> parent_reference = cell->parent()->center();
              const Point<3> parent_current   = parent_reference + (current - cell->center());
              if (body.wanted_levels(parent_reference, parent_current, boxes, value, true) <= level - 1)
                joins.emplace_back(cell->parent()->id().to_string(), -id);
            }
        }
    std::vector<std::int64_t> wishes;
    for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, finer_ids))
      wishes.insert(wishes.end(), part.begin(), part.end());
    {
      std::map<std::string, std::vector<std::int64_t>> by_parent;
      for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, joins))
        for (const auto &[parent, wish] : part)
          by_parent[parent].push_back(wish);
      for (const auto &[parent, children] : by_parent)
        if (children.size() == GeometryInfo<3>::max_children_per_cell)
          wishes.insert(wishes.end(), children.begin(), children.end());
    }
    std::sort(wishes.begin(), wishes.end());
    if (wishes.empty())
      return;

    unsigned long finer = 0;
    for (const auto w : wishes)
      finer += w > 0;
    // A round of joins alone may be all refused (a join whose neighbours
    // the one-level rule holds finer): asked first of the serial mesh
    // (deal.II's flags only, cleared again), it then costs no checkpoint
    // and no new mesh, and the refused ones are not asked for again on
    // this mesh.
    if (finer == 0 && serial_mesh)
      {
        std::vector<Triangulation<3>::active_cell_iterator> cells;
        for (const auto &cell : serial_mesh->active_cell_iterators())
          cells.push_back(cell);
        for (const auto w : wishes)
          cells[-w - 1]->set_coarsen_flag();
        serial_mesh->prepare_coarsening_and_refinement();
        const bool any_kept =
          std::any_of(wishes.begin(), wishes.end(), [&](const auto w) { return cells[-w - 1]->coarsen_flag_set(); });
        for (const auto &cell : cells)
          {
            cell->clear_coarsen_flag();
            cell->clear_refine_flag();
          }
        if (!any_kept)
          {
            pcout << "  adapt at t = " << time << " s, step " << step_number << ": the " << wishes.size() / 8
                  << " group(s) of eight asked to be joined stay (the one-level rule keeps their neighbours "
                     "finer); the mesh stays"
                  << std::endl;
            for (const auto w : wishes)
              coarsening_refused.insert(static_cast<unsigned long>(-w - 1));
            return;
          }
      }
    pcout << "  adapt at t = " << time << " s, step " << step_number << ": " << finer << " element(s) halved, "
          << (wishes.size() - finer) / 8 << " group(s) of eight joined; the run goes on on the new mesh"
          << std::endl;
    adapt_rounds.push_back(std::move(wishes));
    write_checkpoint();
    output.checkpoint_due = false;
    throw RebalanceRequest{};
  }


  // @sect3{The rounds on disk}
  //
  // A checkpoint's 'adaptation': a line 'rounds R state S' (the state is
  // of the mesh after S of the R rounds), then one line per round, its
  // wishes.
  void Simulator::write_adaptation(const std::string &directory, const unsigned int state_count) const
  {
    std::ostringstream out;
    out << "rounds " << adapt_rounds.size() << " state " << state_count << "\n";
    for (const auto &round : adapt_rounds)
      {
        out << round.size();
        for (const auto w : round)
          out << ' ' << w;
        out << '\n';
      }
    write_atomically(directory + "/adaptation", out.str());
  }


  void Simulator::read_adaptation(const std::string &directory)
  {
    adapt_rounds.clear();
    state_rounds = 0;
    std::ifstream in(directory + "/adaptation");
    if (!in)
      return;
    std::string  word1, word2;
    std::size_t  n_rounds = 0;
    unsigned int state    = 0;
    in >> word1 >> n_rounds >> word2 >> state;
    bool good = in && word1 == "rounds" && word2 == "state" && state <= n_rounds && state + 1 >= n_rounds;
    for (std::size_t r = 0; good && r < n_rounds; ++r)
      {
        std::size_t n = 0;
        good          = static_cast<bool>(in >> n);
        std::vector<std::int64_t> round(good ? n : 0);
        for (auto &w : round)
          good = good && static_cast<bool>(in >> w) && w != 0;
        adapt_rounds.push_back(std::move(round));
      }
    if (!good)
      throw InputError(parameters.scene_file + ": --resume: the checkpoint's file '" + directory +
                       "/adaptation' (the rounds of refinement) is damaged: run the scene again from its start");
    state_rounds = state;
  }


  // @sect3{The rounds on the scene's mesh}
  void Simulator::replay_adaptation(Triangulation<3> &serial)
  {
    transferring = false;
    mesh_rounds  = adapt_rounds.size();
    motion_sources.clear();
    element_sources.reset();
    coarsening_refused.clear();
    if (adapt_rounds.empty())
      return;
    Triangulation<3> old(Triangulation<3>::limit_level_difference_at_vertices);
    for (unsigned int r = 0; r < adapt_rounds.size(); ++r)
      {
        const bool last = r + 1 == adapt_rounds.size();
        if (last && state_rounds == r)
          old.copy_triangulation(serial);
        std::vector<Triangulation<3>::active_cell_iterator> cells;
        for (const auto &cell : serial.active_cell_iterators())
          cells.push_back(cell);
        std::vector<CellId> refused;
        for (const auto w : adapt_rounds[r])
          {
            const auto id = static_cast<std::size_t>(std::abs(w) - 1);
            if (id >= cells.size())
              throw InputError(parameters.scene_file + ": --resume: the checkpoint's rounds of refinement " +
                               "name element " + std::to_string(id) + " of a mesh of " +
                               std::to_string(cells.size()) + " (was the scene changed since it was written?)");
            if (w > 0)
              cells[id]->set_refine_flag();
            else
              cells[id]->set_coarsen_flag();
          }
        serial.prepare_coarsening_and_refinement();
        // (deal.II keeps a coarsening only where the level difference
        // allows it: the last round's refused ones are not asked for again
        // until the mesh changes.)
        if (last)
          for (const auto w : adapt_rounds[r])
            if (w < 0 && !cells[std::abs(w) - 1]->coarsen_flag_set())
              refused.push_back(cells[-w - 1]->id());
        serial.execute_coarsening_and_refinement();
        if (last)
          {
            // The refused ones, by their id in the new mesh (the cell
            // stays as it was).
            std::map<CellId, unsigned int> new_index;
            for (const auto &cell : serial.active_cell_iterators())
              new_index[cell->id()] = cell->active_cell_index();
            for (const auto &id : refused)
              if (const auto at = new_index.find(id); at != new_index.end())
                coarsening_refused.insert(at->second);
          }
      }
    if (state_rounds + 1 != adapt_rounds.size())
      return;

    // The state to load is of the mesh before the last round: the sources
    // of each element and node of the new one.
    transferring    = true;
    element_sources = std::make_shared<ElementTransfer>();
    std::map<CellId, unsigned int> old_index, new_index;
    for (const auto &cell : old.active_cell_iterators())
      old_index[cell->id()] = cell->active_cell_index();
    for (const auto &cell : serial.active_cell_iterators())
      new_index[cell->id()] = cell->active_cell_index();
    auto &elements = *element_sources;
    for (const auto &cell : old.active_cell_iterators())
      {
        const auto same = new_index.find(cell->id());
        if (same != new_index.end())
          elements[same->second].push_back({cell->active_cell_index(), 1., 1., 0, ElementSource::same});
        else if (cell->level() > 0)
          if (const auto parent = new_index.find(cell->parent()->id()); parent != new_index.end())
            {
              const unsigned int octant = last_child_index(cell->id());
              elements[parent->second].push_back(
                {cell->active_cell_index(), cell->measure() / cell->parent()->measure(), 1., octant,
                 ElementSource::parent});
            }
      }
    // (A new cell whose parent was an old active cell is a child; the
    // other new ones are the joined parents above.)
    const auto made_by_refinement = [&](const Triangulation<3>::active_cell_iterator &cell) {
      return !old_index.count(cell->id()) && cell->level() > 0 && old_index.count(cell->parent()->id());
    };
    for (const auto &cell : serial.active_cell_iterators())
      if (made_by_refinement(cell))
        {
          const auto         parent = old_index.find(cell->parent()->id());
          const unsigned int octant = last_child_index(cell->id());
          elements[cell->active_cell_index()].push_back(
            {parent->second, 1., cell->measure() / cell->parent()->measure(), octant, ElementSource::child});
        }
    // Elements of the old mesh sorted by nothing else: each new element's
    // sources in the order of their old ids.
    for (auto &[id, list] : elements)
      std::sort(list.begin(), list.end(), [](const auto &a, const auto &b) { return a.id < b.id; });

    const auto &old_used = old.get_used_vertices();
    const auto  kept     = [&](const unsigned int v) {
      return v < old.n_vertices() && old_used[v] && old.get_vertices()[v] == serial.get_vertices()[v];
    };
    // A new vertex's motion from the old cell it was made in (the parent of
    // a new cell, the child's vertex at ((child + vertex) / 2) of the
    // parent's unit cell).
    for (const auto &cell : serial.active_cell_iterators())
      if (made_by_refinement(cell))
        {
          const auto         parent = cell->parent();
          const unsigned int octant = last_child_index(cell->id());
          for (const unsigned int v : cell->vertex_indices())
            {
              const unsigned int vertex = cell->vertex_index(v);
              if (kept(vertex) || motion_sources.count(vertex))
                continue;
              Point<3> unit;
              for (unsigned int d = 0; d < 3; ++d)
                unit[d] = 0.5 * (((octant >> d) & 1) + ((v >> d) & 1));
              auto &list = motion_sources[vertex];
              for (const unsigned int j : parent->vertex_indices())
                {
                  const double w = GeometryInfo<3>::d_linear_shape_function(unit, j);
                  if (w != 0)
                    list.emplace_back(parent->vertex_index(j), w);
                }
            }
        }
  }


  // @sect3{Loading onto the new mesh}
  //
  // The nodes' table of the mesh before: each owned dof's motion from its
  // sources (itself where the round kept it); its force is made anew
  // (finish_transfer()), its lumped mass is this mesh's.
  void Simulator::load_transferred_nodes(StateArchive &ar)
  {
    constexpr unsigned int     n_values = 6; // x, v, f, m, last good x and v
    const unsigned int         n_owned  = dof_key.size();
    const auto                 sources_of = [&](const std::uint64_t key) {
      std::vector<std::pair<std::uint64_t, double>> list;
      const auto at = motion_sources.find(static_cast<unsigned int>(key / 3));
      if (at == motion_sources.end())
        list.emplace_back(key, 1.);
      else
        for (const auto &[u, w] : at->second)
          list.emplace_back(3ul * u + key % 3, w);
      return list;
    };
    std::vector<std::uint64_t> wanted;
    for (unsigned int i = 0; i < n_owned; ++i)
      for (const auto &[key, w] : sources_of(dof_key[i]))
        wanted.push_back(key);
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    std::vector<double> values;
    ar.keyed("nodes", wanted, n_values, values);
    VectorType *const motion[] = {&position, &velocity, nullptr, nullptr, &balance.good_position,
                                  &balance.good_velocity};
    for (unsigned int i = 0; i < n_owned; ++i)
      {
        const auto sources = sources_of(dof_key[i]);
        for (unsigned int k = 0; k < n_values; ++k)
          if (motion[k] != nullptr)
            {
              double x = 0;
              for (const auto &[u, w] : sources)
                x += w * values[n_values * (std::lower_bound(wanted.begin(), wanted.end(), u) - wanted.begin()) + k];
              motion[k]->local_element(i) = x;
            }
        force.local_element(i) = 0;
      }
  }


  // After the load: the forces of time n on the new mesh, from its state
  // (an evaluation at dt = 0, as at the start, the elements' state copied
  // back after it: no increment of stress, history or friction), so that the step's energy identity holds on it;
  // the kinetic energy the interpolation changed (the scheme's K^n = 1/2 v
  // (M v + dt F), on the old mesh's whole table and on the new mesh), the
  // elastic energy the averaging took out and the springs' energy of the
  // new contact nodes, booked as 'adaptation'.
  void Simulator::finish_transfer(const KeyedTable &old_nodes)
  {
    // (A node the round left hanging follows its masters from now on.)
    if (!hanging.empty())
      for (VectorType *v : {&position, &velocity, &balance.good_position, &balance.good_velocity})
        {
          v->update_ghost_values();
          hanging.distribute(v->begin(), v->locally_owned_size());
          v->update_ghost_values();
        }
    // The eroded elements' faces leave the pairs' new segments.
    if (!contact->empty())
      {
        std::vector<unsigned long> own;
        for (const auto &g : solids->groups())
          for (unsigned int e = 0; e < g.n_elements(); ++e)
            if (g.element_is_owned(e) && g.element_is_eroded(e))
              own.push_back(g.element_global_id(e));
        std::vector<unsigned long> ids;
        for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, own))
          ids.insert(ids.end(), part.begin(), part.end());
        std::sort(ids.begin(), ids.end());
        if (!ids.empty())
          contact->deactivate_elements(ids);
      }

    const auto held = [&]() {
      double e = energies.total() - energies.adaptation - energies.contact;
      for (const auto &r : contact->results())
        e += r.energy;
      return e;
    };
    const double before_forces = held();
    std::vector<Element::ElementGroup::Snapshot> states;
    for (const auto &g : solids->groups())
      states.push_back(g.snapshot());
    zero_forces();
    critical_dt = compute_internal_forces(0.);
    for (unsigned int g = 0; g < states.size(); ++g)
      solids->groups()[g].restore(std::move(states[g]));
    apply_contact(0.);
    condense_forces();
    const double springs = held() - before_forces;

    // (The rigid bodies' nodes, whose kinetic energy their family books,
    // are left out on both sides.)
    const double               dt = loop.dt_previous;
    std::vector<std::uint64_t> rigid_keys;
    double                     k = 0;
    for (unsigned int i = 0; i < velocity.locally_owned_size(); ++i)
      if (rigid_dof.empty() || !rigid_dof[i])
        k += 0.5 * velocity.local_element(i) *
             (mass.local_element(i) * velocity.local_element(i) + dt * force.local_element(i));
      else
        rigid_keys.push_back(dof_key[i]);
    std::vector<std::uint64_t> all_rigid;
    for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, rigid_keys))
      all_rigid.insert(all_rigid.end(), part.begin(), part.end());
    std::sort(all_rigid.begin(), all_rigid.end());
    double kinetic_before = 0;
    for (std::size_t i = 0; i < old_nodes.keys.size() && 6 * i + 6 <= old_nodes.values.size(); ++i)
      if (!std::binary_search(all_rigid.begin(), all_rigid.end(), old_nodes.keys[i]))
        {
          const double *r = &old_nodes.values[6 * i];
          kinetic_before += 0.5 * r[1] * (r[3] * r[1] + dt * r[2]);
        }
    const double kinetic_change = Utilities::MPI::sum(k, mpi_communicator) - kinetic_before;
    double       elastic        = 0;
    for (const auto &g : solids->groups())
      elastic += g.transfer_energy();
    elastic = Utilities::MPI::sum(elastic, mpi_communicator);
    energies.kinetic += kinetic_change;
    energies.internal += elastic;
    energies.adaptation -= kinetic_change + elastic + springs;

    pcout << "  the state moved onto " << triangulation.n_global_active_cells()
          << " elements: kinetic energy " << std::setprecision(4) << kinetic_change << " J, elastic energy "
          << elastic << " J, contact springs " << springs << " J (booked as 'adaptation'), stable step " << critical_dt
          << " s" << std::endl;
  }
} // namespace anvil
