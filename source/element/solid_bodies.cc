/**
 * @file
 * The solid bodies of a scene as one family (element/solid_bodies.h).
 */
#include <anvil/element/solid_bodies.h>
#include <anvil/mesh/body.h>
#include <anvil/element/element_group.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/text.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <iomanip>
#include <set>
#include <sstream>

namespace anvil::Element
{
  using namespace dealii;

  // @sect3{Element groups}
  //
  // One group per body with its locally owned and ghost cells, in the
  // order of their coarse-cell index (the same on every process). A node
  // is addressed by the local index of its x dof in the nodal vectors; y
  // and z follow.
  //
  // Why ghost cells: every process computes the forces of all elements
  // around the nodes it owns and adds them in global element order. The
  // nodal forces, and so the whole trajectory, are then bitwise the same on
  // any number of processes, and no force exchange (compress) is needed;
  // the price is the duplicated work on one layer of ghost cells.
  void SolidBodies::setup()
  {
    const auto       &bodies      = get_bodies();
    const auto       &dof_handler = get_dof_handler();
    const VectorType &position    = get_position();
    // A body's elements in its 'Full integration region' form a second
    // group of fully integrated elements: body_of_group maps a group to its
    // body, group_of_body a body to its groups (one point, full).
    element_groups.clear();
    body_of_group.clear();
    group_of_body.assign(bodies.size(), {{-1, -1}});
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const auto &body = bodies[b];
        for (unsigned int slot = 0; slot < (body.has_full_integration_region() ? 2 : 1); ++slot)
          {
            const auto integration = (slot == 0 ? body.integration : Integration::full);
            group_of_body[b][slot] = element_groups.size();
            body_of_group.push_back(b);
            element_groups.emplace_back(*body.material,
                                        body.formulation,
                                        integration,
                                        body.hourglass,
                                        body.hourglass_coefficient);
            if (!body.is_rigid())
              element_groups.back().set_bulk_viscosity(body.bulk_linear, body.bulk_quadratic);
          }
      }
    const auto &partitioner = position.get_partitioner();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          std::array<unsigned int, 8> node;
          double                      X[8][3];
          for (unsigned int v = 0; v < 8; ++v)
            {
              node[v] = partitioner->global_to_local(cell->vertex_dof_index(v, 0));
              for (unsigned int c = 1; c < 3; ++c)
                AssertThrow(partitioner->global_to_local(
                              cell->vertex_dof_index(v, c)) == node[v] + c,
                            ExcMessage("nodal dofs are not contiguous"));
              for (unsigned int c = 0; c < 3; ++c)
                X[v][c] = cell->vertex(v)[c];
            }
          const Body        &body = bodies[cell->material_id()];
          const unsigned int slot =
            (body.integration_of(cell) == body.integration ? 0 : 1);
          element_groups[group_of_body[cell->material_id()][slot]].add_element(
            node,
            X,
            cell->active_cell_index(),
            cell->is_locally_owned(),
            element_id(cell->active_cell_index()),
            body.strength_factor(cell->center()));
        }
    for (auto &g : element_groups)
      g.finalize();
  }


  // @sect3{Lumped mass}
  //
  // Row-sum lumping of the consistent mass M = int rho_0 N^T N dV_0 (seed
  // Eq. (35)): M_II = int rho_0 N_I dV_0. Like the forces, owned and ghost
  // cells are summed in global order on every process, so the masses are
  // bitwise the same for any partition.
  void SolidBodies::add_mass(VectorType &mass)
  {
    const auto     &bodies = get_bodies();
    const auto     &dof_handler = get_dof_handler();
    const IndexSet &owned  = dof_handler.locally_owned_dofs();
    // Beside the row sums, the eighths of the elements' masses around each
    // node: their ratio lowers the stable step of elements with a light
    // node (ElementGroup::set_nodal_mass_ratio()).
    VectorType eighths(mass);
    eighths = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          double X[8][3], m[8];
          for (unsigned int v = 0; v < 8; ++v)
            for (unsigned int d = 0; d < 3; ++d)
              X[v][d] = cell->vertex(v)[d];
          lumped_mass(X, bodies[cell->material_id()].material->density(), m);
          const double eighth = (m[0] + m[1] + m[2] + m[3] + m[4] + m[5] + m[6] + m[7]) / 8.;
          for (unsigned int v = 0; v < 8; ++v)
            for (unsigned int d = 0; d < 3; ++d)
              {
                const auto dof = cell->vertex_dof_index(v, d);
                if (owned.is_element(dof))
                  {
                    mass(dof) += m[v];
                    eighths(dof) += eighth;
                  }
              }
        }
    for (unsigned int i = 0; i < eighths.locally_owned_size(); ++i)
      eighths.local_element(i) =
        eighths.local_element(i) > 0 ? std::min(1., mass.local_element(i) / eighths.local_element(i)) : 1.;
    eighths.update_ghost_values();
    for (auto &g : element_groups)
      g.set_nodal_mass_ratio(eighths.begin());
  }


  // @sect3{Forces}
  //
  // Every deformable group in turn (a rigid body's elements carry no force
  // and do not limit the step): internal, hourglass and bulk-viscosity
  // forces into F, the group's stable step, its energy increments and the
  // elements it eroded.
  double SolidBodies::add_forces(const double dt_previous)
  {
    const VectorType &position = get_position(), &velocity = get_velocity();
    VectorType       &force    = get_force();
    double             dt_crit = 1e300;
    double             d_int = 0, d_hg = 0, d_visc = 0;
    const double      *x     = position.begin();
    const double      *v     = velocity.begin();
    double            *f     = force.begin();
    double                     d_eroded = 0;
    eroded.clear();
    eroded_info.clear();
    for (unsigned int g = 0; g < element_groups.size(); ++g)
      {
        auto &group = element_groups[g];
        // A rigid body's elements carry no force and do not limit the step.
        if (group.get_material().is_rigid())
          continue;
        const auto r = group.compute_internal_forces(x, v, dt_previous, f);
        dt_crit          = std::min(dt_crit, r.critical_time_step);
        d_int += r.internal_energy_increment;
        d_hg += r.hourglass_energy_increment;
        d_visc += r.viscous_energy_increment;
        d_eroded += r.eroded_energy_increment;
        if (r.inverted_element >= 0 && first_inverted_cell < 0)
          first_inverted_cell = group.element_cell_index(r.inverted_element);
        eroded.insert(eroded.end(), r.eroded_elements.begin(), r.eroded_elements.end());
        if (!r.eroded_elements.empty())
          record_erosion(g, r.eroded_elements, eroded_info);
      }
    // (Summed over the processes in finish_forces(): the loop itself
    // communicates nothing, so its timer shows each process's own work.)
    increments = {{d_int, d_hg, d_eroded, double(eroded.size()), d_visc}};
    return dt_crit;
  }


  std::vector<unsigned long> SolidBodies::finish_forces()
  {
    Utilities::MPI::sum(ArrayView<const double>(increments.data(), increments.size()),
                        get_mpi_communicator(),
                        ArrayView<double>(increments.data(), increments.size()));
    Energies &energies = get_energies();
    energies.internal += increments[0];
    energies.hourglass += increments[1];
    energies.eroded += increments[2];
    energies.viscous += increments[4];
    // Erosion is rare: only then do the ranks exchange element ids, so that
    // every replicated contact pair drops the eroded elements' faces.
    std::vector<unsigned long> all;
    if (increments[3] > 0)
      {
        const MPI_Comm mpi_communicator = get_mpi_communicator();
        const auto    &bodies           = get_bodies();
        for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, eroded))
          all.insert(all.end(), part.begin(), part.end());
        std::sort(all.begin(), all.end());
        all.erase(std::unique(all.begin(), all.end()), all.end());
        // The rows of the step by element id, whatever the partition.
        std::vector<std::array<double, 8>> step_rows;
        for (const auto &part : Utilities::MPI::gather(mpi_communicator, eroded_info, 0))
          for (std::size_t i = 0; i + 8 <= part.size(); i += 8)
            {
              step_rows.emplace_back();
              std::copy(part.begin() + i, part.begin() + i + 8, step_rows.back().begin());
            }
        std::sort(step_rows.begin(), step_rows.end(),
                  [](const auto &a, const auto &b) { return a[0] < b[0]; });
        for (const auto &r : step_rows)
          {
            std::ostringstream row;
            row << std::setprecision(10) << get_time() << ',' << (unsigned long)r[0] << ','
                << bodies[(unsigned int)r[1]].name << ',' << r[2] << ',' << r[3] << ',' << r[4] << ','
                << r[5] << ',' << r[6] << ',' << r[7];
            rows.push_back(row.str());
            ++eroded_so_far;
          }
      }
    return all;
  }


  // What erosion.csv tells of each owned element eroded this step: global
  // id, body, centre (current), effective plastic strain (mean over the
  // points, when the model has one) and the energy it held.
  void SolidBodies::record_erosion(const unsigned int                group_index,
                                   const std::vector<unsigned long> &ids,
                                   std::vector<double>              &info) const
  {
    const VectorType &position = get_position();
    std::vector<unsigned long> sorted(ids);
    std::sort(sorted.begin(), sorted.end());
    const auto  &group = element_groups[group_index];
    const auto   names = group.get_material().history_names();
    const auto   it    = std::find(names.begin(), names.end(), "effective_plastic_strain");
    const double *x    = position.begin();
    for (unsigned int e = 0; e < group.n_elements(); ++e)
      if (group.element_is_owned(e) &&
          std::binary_search(sorted.begin(), sorted.end(), group.element_global_id(e)))
        {
          double c[3] = {0, 0, 0};
          for (const unsigned int n : group.element_nodes(e))
            for (unsigned int d = 0; d < 3; ++d)
              c[d] += 0.125 * x[n + d];
          double eps_p = 0;
          if (it != names.end())
            for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
              eps_p += group.history_variable(e, q, it - names.begin()) /
                       group.n_quadrature_points();
          info.insert(info.end(),
                      {double(group.element_global_id(e)),
                       double(body_of_group[group_index]),
                       c[0],
                       c[1],
                       c[2],
                       eps_p,
                       group.element_internal_energy(e) + group.element_hourglass_energy(e),
                       group.element_reference_volume(e)});
        }
  }


  // What the step evaluates of the solid bodies, from the flags the element
  // loop itself tests.
  std::string SolidBodies::describe() const
  {
    std::set<unsigned int> deformable, bulk, rate, erosion;
    std::set<std::string>  laws;
    for (unsigned int g = 0; g < element_groups.size(); ++g)
      {
        const auto &group = element_groups[g];
        if (group.get_material().is_rigid())
          continue;
        deformable.insert(body_of_group[g]);
        if (group.bulk_viscosity())
          bulk.insert(body_of_group[g]);
        if (group.get_material().rate_dependent())
          {
            rate.insert(body_of_group[g]);
            laws.insert(group.get_material().rate_law());
          }
        if (group.get_material().erodes())
          erosion.insert(body_of_group[g]);
      }
    auto count = [](const std::size_t n, const std::string &what, const std::string &of) {
      return n == 0 ? "no " + what :
                      what + " in " + std::to_string(n) + " " +
                        (n == 1 ? of : of == "body" ? std::string("bodies") : of + "s");
    };
    std::ostringstream s;
    s << "elements of " << deformable.size() << " bod" << (deformable.size() == 1 ? "y" : "ies") << "; "
      << count(bulk.size(), "bulk viscosity", "body") << "; " << count(rate.size(), "rate effects", "body")
      << (laws.empty() ? "" : " (" + join(laws) + ")")
      << "; " << count(erosion.size(), "erosion", "body");
    return s.str();
  }


  void SolidBodies::serialize(StateArchive &ar)
  {
    // (The erosion rows not yet written are rank 0's, whose stream a
    // resumed run reads.)
    ar &first_inverted_cell &eroded_so_far &rows;
    for (unsigned int g = 0; g < element_groups.size(); ++g)
      element_groups[g].serialize(ar, "group " + std::to_string(g));
  }
} // namespace anvil::Element
