/**
 * @file
 * Histories (CSV) and fields (VTU/PVTU with a PVD time series).
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/vtu_file.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <iomanip>

namespace anvil
{
  using namespace dealii;

  // @sect3{Histories}
  //
  // energy.csv every history interval, one probe_NAME.csv per probe and one
  // contact_NAME.csv per contact pair. Rank 0 writes; probe values come
  // from the rank that owns the probed node.
  void Simulator::write_history(const double t, const double dt)
  {
    const bool root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    // The mass damping's force of this step (part of a^n), by local index.
    auto damping_force = [&](const unsigned int i) {
      return mass_damping > 0 && i < damping_force_old.size() ? damping_force_old[i] : 0.;
    };

    // Per probe: displacement, velocity at time n, and the Cauchy stress
    // of its element (at time n: positions and stresses are those of x^n).
    constexpr unsigned int n_values = 12;
    std::vector<double>    probe_values(n_values * probes.size(), 0.);
    for (unsigned int p = 0; p < probes.size(); ++p)
      if (position.locally_owned_elements().is_element(probes[p].x_dof))
        {
          for (unsigned int d = 0; d < 3; ++d)
            {
              const auto g                       = probes[p].x_dof + d;
              probe_values[n_values * p + d]     = position(g) - reference_position(g);
              probe_values[n_values * p + 3 + d] =
                velocity(g) - 0.5 * dt * (force(g) + damping_force(velocity.get_partitioner()->global_to_local(g))) /
                                mass(g);
            }
          if (probes[p].group >= 0)
            element_groups[probes[p].group].cauchy_stress(probes[p].element,
                                                          position.begin(),
                                                          &probe_values[n_values * p + 6]);
        }
    if (!probes.empty())
      Utilities::MPI::sum(probe_values, mpi_communicator, probe_values);

    // Linear momentum of each body, sum m v over the owned dofs; a rigid
    // body's is M V at time n (its nodal masses need not add up to M when
    // the mass is given).
    std::vector<double> momentum(3 * bodies.size(), 0.);
    for (unsigned int i = 0; i < velocity.locally_owned_size(); ++i)
      if (rigid_dof.empty() || !rigid_dof[i])
        momentum[3 * dof_body[i] + dof_component[i]] +=
          mass.local_element(i) * velocity.local_element(i) -
          0.5 * dt * (force.local_element(i) + damping_force(i));
    Utilities::MPI::sum(momentum, mpi_communicator, momentum);
    for (const auto &family : families)
      family->add_momentum(dt, momentum);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].is_rigid())
        {
          const auto &m = bodies[b].rigid;
          for (unsigned int d = 0; d < 3; ++d)
            momentum[3 * b + d] =
              m.mass * m.velocity[d] - (m.free ? 0.5 * dt * m.last_force[d] : 0.);
        }
    // Support reactions, summed per boundary condition.
    std::vector<double> reactions(bc_reaction);
    if (!reactions.empty())
      Utilities::MPI::sum(reactions, mpi_communicator, reactions);
    if (!root)
      return;
    record_probe_summary(probe_values);
    if (!reactions.empty())
      {
        if (!reaction_file.is_open())
          {
            record_output("reactions.csv");
            reaction_file.open(output_directory + "/reactions.csv");
            reaction_file << "time";
            for (const auto &bc : boundary_conditions)
              reaction_file << ',' << bc.name << "_fx," << bc.name << "_fy," << bc.name << "_fz";
            reaction_file << '\n';
          }
        reaction_file << std::setprecision(12) << t;
        for (unsigned int k = 0; k < reactions.size(); ++k)
          reaction_file << ',' << reactions[k];
        reaction_file << '\n';
        peak_bc_reaction.resize(boundary_conditions.size(), 0.);
        for (unsigned int b = 0; b < boundary_conditions.size(); ++b)
          peak_bc_reaction[b] =
            std::max(peak_bc_reaction[b],
                     std::sqrt(reactions[3 * b] * reactions[3 * b] + reactions[3 * b + 1] * reactions[3 * b + 1] +
                               reactions[3 * b + 2] * reactions[3 * b + 2]));
        for (unsigned int b = 0; b < boundary_conditions.size(); ++b)
          summary.peak_reaction =
            std::max(summary.peak_reaction,
                     std::sqrt(reactions[3 * b] * reactions[3 * b] +
                               reactions[3 * b + 1] * reactions[3 * b + 1] +
                               reactions[3 * b + 2] * reactions[3 * b + 2]));
      }

    if (!energy_file.is_open())
      {
        record_output("energy.csv");
        record_output("momentum.csv");
        energy_file.open(output_directory + "/energy.csv");
        energy_file << "time,kinetic,internal,hourglass,viscous,damping,contact,friction,eroded,removed,bond,"
                       "step_change,external_work,total,balance_error\n";
        momentum_file.open(output_directory + "/momentum.csv");
        momentum_file << "time";
        for (const auto &b : bodies)
          momentum_file << ',' << b.name << "_px," << b.name << "_py," << b.name << "_pz";
        momentum_file << ",px,py,pz\n";
        for (const auto &p : probes)
          {
            record_output("probe_" + p.name + ".csv");
            probe_files.emplace_back(output_directory + "/probe_" + p.name + ".csv");
            probe_files.back()
              << "time,ux,uy,uz,vx,vy,vz,stress_xx,stress_yy,stress_zz,stress_xy,stress_yz,stress_xz\n";
          }
        for (const auto &c : contact_pairs)
          {
            record_output("contact_" + c.name + ".csv");
            contact_files.emplace_back(output_directory + "/contact_" + c.name + ".csv");
            contact_files.back()
              << "time,normal_force_x,normal_force_y,normal_force_z,max_penetration,"
                 "friction_force_x,friction_force_y,friction_force_z,max_penetration_ratio,"
                 "active_nodes\n";
          }
      }
    energy_file << std::setprecision(12) << t << ',' << energies.kinetic << ','
                << energies.internal << ',' << energies.hourglass << ',' << energies.viscous << ','
                << energies.damping << ',' << energies.contact << ',' << energies.friction << ','
                << energies.eroded << ',' << energies.removed << ',' << energies.bond << ',' << energies.step_change << ','
                << energies.external_work << ',' << energies.total() << ','
                << balance_error << '\n';
    momentum_file << std::setprecision(15) << t;
    double total[3] = {0, 0, 0};
    for (unsigned int k = 0; k < momentum.size(); ++k)
      {
        momentum_file << ',' << momentum[k];
        total[k % 3] += momentum[k];
      }
    momentum_file << ',' << total[0] << ',' << total[1] << ',' << total[2] << '\n';
    for (unsigned int p = 0; p < probes.size(); ++p)
      {
        probe_files[p] << std::setprecision(12) << t;
        for (unsigned int k = 0; k < n_values; ++k)
          probe_files[p] << ',' << probe_values[n_values * p + k];
        probe_files[p] << '\n';
      }
    if (rigid_files.empty())
      for (const auto &b : bodies)
        if (b.is_rigid())
          {
            record_output("rigid_" + b.name + ".csv");
            rigid_files.emplace_back(output_directory + "/rigid_" + b.name + ".csv");
            rigid_files.back() << "time,x,y,z,vx,vy,vz,fx,fy,fz,kinetic\n";
          }
    // Rigid bodies have advanced to n+1 already: report the centre of time
    // n and the velocity at n, V^{n+1/2} - dt/2 F/M.
    unsigned int r = 0;
    for (const auto &b : bodies)
      if (b.is_rigid())
        {
          const auto        &m = b.rigid;
          const Tensor<1, 3> v = m.free ? m.velocity - 0.5 * dt / m.mass * m.last_force : m.velocity;
          rigid_files[r] << std::setprecision(12) << t << ',' << m.previous_centre[0] << ','
                         << m.previous_centre[1] << ',' << m.previous_centre[2] << ',' << v[0]
                         << ',' << v[1] << ',' << v[2] << ',' << m.last_force[0] << ','
                         << m.last_force[1] << ',' << m.last_force[2] << ',' << m.kinetic_energy
                         << '\n';
          ++r;
        }
    for (auto &family : families)
      if (!family->empty())
        family->write_history(t);
    if (!erosion_rows.empty())
      {
        if (!erosion_file.is_open())
          {
            record_output("erosion.csv");
            erosion_file.open(output_directory + "/erosion.csv");
            erosion_file << "time,element,body,x,y,z,effective_plastic_strain,energy,"
                            "reference_volume\n";
          }
        for (const auto &row : erosion_rows)
          erosion_file << row << '\n';
        erosion_rows.clear();
      }
    for (unsigned int c = 0; c < contact_pairs.size(); ++c)
      {
        const auto &r = contact_results[c];
        contact_files[c] << std::setprecision(12) << t << ',' << r.force_on_first[0]
                         << ',' << r.force_on_first[1] << ',' << r.force_on_first[2]
                         << ',' << r.max_penetration << ',' << r.friction_on_first[0] << ','
                         << r.friction_on_first[1] << ',' << r.friction_on_first[2] << ','
                         << r.max_penetration_ratio << ',' << r.n_active << '\n';
      }
    // All histories reach the disk together, at most a second or 1,000 rows
    // apart.
    if (++rows_since_flush >= 1000 ||
        std::chrono::steady_clock::now() - last_flush > std::chrono::seconds(1))
      flush_histories();
  }


  // @sect3{Fields}
  //
  // Output is not on the hot path: strains come from FEValues at the cell
  // centre (the tutorial path), stresses from the element groups.
  void Simulator::output_results(const double t, const std::string &basename)
  {
    TimerOutput::Scope timer_scope(*timer, "output");
    VectorType         displacement(position);
    displacement -= reference_position;
    displacement.update_ghost_values();

    const unsigned int    n_cells = triangulation.n_active_cells();
    std::vector<Vector<float>> stress(6, Vector<float>(n_cells));
    std::vector<Vector<float>> strain(6, Vector<float>(n_cells));
    Vector<float> von_mises(n_cells), hourglass_density(n_cells), internal_density(n_cells);
    Vector<float> body_id(n_cells), rank(n_cells);
    const float   my_rank = Utilities::MPI::this_mpi_process(mpi_communicator);

    // Scalar history variables of the materials (effective plastic strain,
    // ...), averaged over each element's points; and the erosion flag.
    std::map<std::string, Vector<float>> history_fields;
    for (const auto &group : element_groups)
      for (const auto &name : group.get_material().history_names())
        if (!name.empty() && name.rfind("back_stress", 0) != 0)
          history_fields.emplace(name, Vector<float>(n_cells));
    Vector<float> eroded(n_cells);

    const double *x = position.begin();
    for (const auto &group : element_groups)
      {
      const auto names = group.get_material().history_names();
      for (unsigned int e = 0; e < group.n_elements(); ++e)
        if (group.element_is_owned(e))
        {
          for (unsigned int k = 0; k < names.size(); ++k)
            if (history_fields.count(names[k]))
              {
                double mean = 0;
                for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                  mean += group.get_material().history_value(group.history_variables(e, q), k) /
                          group.n_quadrature_points();
                history_fields[names[k]][group.element_cell_index(e)] = mean;
              }
          eroded[group.element_cell_index(e)] = group.element_is_eroded(e);
          const unsigned int c = group.element_cell_index(e);
          double             s[6];
          group.cauchy_stress(e, x, s);
          for (unsigned int k = 0; k < 6; ++k)
            stress[k][c] = s[k];
          const double p = (s[0] + s[1] + s[2]) / 3.;
          von_mises[c]   = std::sqrt(1.5 * ((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) +
                                          (s[2] - p) * (s[2] - p) +
                                          2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
          const double V0      = group.element_reference_volume(e);
          hourglass_density[c] = group.element_hourglass_energy(e) / V0;
          internal_density[c]  = group.element_internal_energy(e) / V0;
        }
      }

    const QMidpoint<3>                 centre;
    FEValues<3>                        fe_values(fe, centre, update_gradients);
    std::vector<Tensor<2, 3>>          grad(1);
    const FEValuesExtractors::Vector   u(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int c = cell->active_cell_index();
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(displacement, grad);
          const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad[0];
          const Tensor<2, 3> E = 0.5 * (transpose(F) * F - unit_symmetric_tensor<3>());
          const unsigned int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
          for (unsigned int k = 0; k < 6; ++k)
            strain[k][c] = E[ij[k][0]][ij[k][1]];
          body_id[c] = cell->material_id();
          rank[c]    = my_rank;
        }

    // One connected piece per process: the points of its cells (shared
    // by the cells around them), node ids from the scene's coarse vertices
    // and element ids from its coarse cells, the same on any number of
    // processes.
    Vtu::Piece                 piece;
    std::vector<std::int64_t>  point_of(triangulation.n_vertices(), -1);
    std::vector<double>        node_id, u_values, v_values, element_id;
    std::vector<unsigned int>  cells;
    static constexpr unsigned int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cells.push_back(cell->active_cell_index());
          element_id.push_back(cell->id().get_coarse_cell_id());
          for (const unsigned int v : vtk_order)
            {
              const unsigned int vertex = cell->vertex_index(v);
              if (point_of[vertex] < 0)
                {
                  point_of[vertex] = node_id.size();
                  node_id.push_back(vertex);
                  for (unsigned int d = 0; d < 3; ++d)
                    {
                      piece.points.push_back(cell->vertex(v)[d]);
                      const auto dof = cell->vertex_dof_index(v, d);
                      u_values.push_back(displacement(dof));
                      v_values.push_back(velocity(dof));
                    }
                }
              piece.hexahedra.push_back(point_of[vertex]);
            }
        }
    using Type = Vtu::Array::Type;
    piece.point_data.push_back({"displacement", 3, Type::float64, u_values});
    piece.point_data.push_back({"velocity", 3, Type::float64, v_values});
    piece.point_data.push_back({"node_id", 1, Type::int64, node_id});
    piece.cell_data.push_back({"element_id", 1, Type::int64, element_id});
    auto add = [&](const std::string &name, const Vector<float> &field, const Type type) {
      std::vector<double> values(cells.size());
      for (unsigned int i = 0; i < cells.size(); ++i)
        values[i] = field[cells[i]];
      piece.cell_data.push_back({name, 1, type, values});
    };
    add("body", body_id, Type::int64);
    const char *names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
    for (unsigned int k = 0; k < 6; ++k)
      {
        add(std::string("stress_") + names[k], stress[k], Type::float32);
        add(std::string("strain_") + names[k], strain[k], Type::float32);
      }
    add("von_mises", von_mises, Type::float32);
    add("internal_energy_density", internal_density, Type::float32);
    add("hourglass_energy_density", hourglass_density, Type::float32);
    for (const auto &[name, field] : history_fields)
      add(name, field, Type::float32);
    if (n_eroded > 0 || std::any_of(element_groups.begin(), element_groups.end(), [](const auto &g) {
          return g.get_material().erodes();
        }))
      add("eroded", eroded, Type::float32);
    add("mpi_rank", rank, Type::int64);

    // Each process its piece, rank 0 the record naming them.
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const std::string  frame =
      basename == "solution" ? basename + "_" + Utilities::int_to_string(output_count, 4) : basename;
    record_output(frame + ".pvtu");
    std::vector<std::string> files;
    for (unsigned int r = 0; r < n_ranks; ++r)
      {
        files.push_back(frame + "." + std::to_string(r) + ".vtu");
        record_output(files.back());
      }
    std::string failure;
    try
      {
        write_atomically(output_directory + "/" +
                           files[Utilities::MPI::this_mpi_process(mpi_communicator)],
                         Vtu::vtu_text(piece, t, output_count));
      }
    catch (const OutputError &e)
      {
        failure = e.what();
      }
    if (Utilities::MPI::max(failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw OutputError(failure.empty() ? "a VTU piece could not be written on another process" :
                                          failure);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      write_atomically(output_directory + "/" + frame + ".pvtu", Vtu::pvtu_text(piece, files));
    if (basename == "solution")
      {
        pvd_records.emplace_back(t, frame + ".pvtu");
        write_frame_index();
        for (auto &family : families)
          if (!family->empty())
            family->output_frame(t, output_count);
        ++output_count;
      }
  }


  void Simulator::write_body_summary()
  {
    const unsigned int  nb = bodies.size();
    std::vector<double> count(3 * nb, 0.), peak(2 * nb, 0.), lo(3 * nb, 1e300), hi(3 * nb, -1e300);
    std::vector<double> dissipated(nb, 0.), volume(nb, 0.);
    for (unsigned int g = 0; g < element_groups.size(); ++g)
      {
        const auto        &group = element_groups[g];
        const unsigned int b     = group_body[g];
        const auto  names = group.get_material().history_names();
        const auto  it    = std::find(names.begin(), names.end(), "effective_plastic_strain");
        const int   id    = group.get_material().dissipation_index();
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          if (group.element_is_owned(e))
            {
              const bool eroded = group.element_is_eroded(e);
              if (id >= 0)
                for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                  dissipated[b] += group.history_variables(e, q)[id] *
                                   group.element_reference_volume(e) /
                                   group.n_quadrature_points();
              count[3 * b] += 1;
              count[3 * b + 1] += eroded;
              volume[b] += group.element_reference_volume(e);
              if (it == names.end())
                continue;
              double eps_p = 0;
              for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                eps_p += group.history_variables(e, q)[it - names.begin()] /
                         group.n_quadrature_points();
              if (!eroded)
                peak[2 * b] = std::max(peak[2 * b], eps_p);
              peak[2 * b + 1] = std::max(peak[2 * b + 1], eps_p);
            }
      }
    for (unsigned int i = 0; i < position.locally_owned_size(); ++i)
      {
        const unsigned int b = dof_body[i], d = dof_component[i];
        lo[3 * b + d]        = std::min(lo[3 * b + d], position.local_element(i));
        hi[3 * b + d]        = std::max(hi[3 * b + d], position.local_element(i));
      }
    Utilities::MPI::sum(count, mpi_communicator, count);
    Utilities::MPI::sum(dissipated, mpi_communicator, dissipated);
    Utilities::MPI::sum(volume, mpi_communicator, volume);
    Utilities::MPI::max(peak, mpi_communicator, peak);
    Utilities::MPI::min(lo, mpi_communicator, lo);
    Utilities::MPI::max(hi, mpi_communicator, hi);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    record_output("bodies.csv");
    std::ofstream out(output_directory + "/bodies.csv");
    out << "body,elements,eroded,peak_effective_plastic_strain_intact,"
           "peak_effective_plastic_strain,xmin,ymin,zmin,xmax,ymax,zmax,"
           "dissipated_energy,reference_volume\n"
        << std::setprecision(12);
    for (unsigned int b = 0; b < nb; ++b)
      out << bodies[b].name << ',' << count[3 * b] << ',' << count[3 * b + 1] << ','
          << peak[2 * b] << ',' << peak[2 * b + 1] << ',' << lo[3 * b] << ',' << lo[3 * b + 1]
          << ',' << lo[3 * b + 2] << ',' << hi[3 * b] << ',' << hi[3 * b + 1] << ','
          << hi[3 * b + 2] << ',' << dissipated[b] << ',' << volume[b] << '\n';
  }


  void Simulator::write_frame_index()
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    record_output("solution.pvd");
    write_atomically(output_directory + "/solution.pvd", Vtu::pvd_text(pvd_records));
  }


  void Simulator::flush_histories()
  {
    last_flush       = std::chrono::steady_clock::now();
    rows_since_flush = 0;
    auto flush = [&](HistoryFile &f) {
      const std::string failure = f.flush();
      if (!failure.empty() && output_failure.empty())
        output_failure = failure;
    };
    for (auto *f : {&energy_file, &momentum_file, &reaction_file, &erosion_file})
      flush(*f);
    for (auto *files : {&probe_files, &contact_files, &rigid_files})
      for (auto &f : *files)
        flush(f);
    for (auto &family : families)
      for (auto *f : family->history_files())
        flush(*f);
  }


  void Simulator::record_output(const std::string &name)
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0 || !recorded_outputs.insert(name).second)
      return;
    std::ofstream list(output_directory + "/anvil_files.txt", std::ios::app);
    list << name << '\n';
    list.flush();
    if (!list)
      throw OutputError("cannot write " + output_directory + "/anvil_files.txt (the list of this run's files)");
  }


  void Simulator::write_pvd()
  {
    write_frame_index();
    flush_histories();
  }
} // namespace anvil
