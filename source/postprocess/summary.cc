/**
 * @file
 * summary.csv: the figures of a run that studies and tests read (peak and
 * residual displacement of the first probe, peak force and duration of the
 * first contact pair, support reactions and the damage index, energy
 * conversion, hourglass share, balance, cost), two columns
 * 'quantity,value' with the units in the names; written under a temporary
 * name and renamed, so a reader never sees half a file.
 */
#include <anvil/boundary_conditions/constraints.h>
#include <anvil/postprocess/interface.h>
#include <anvil/element/element_group.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/mpi.h>

#include <iomanip>
#include <sstream>

namespace anvil::Postprocess
{
  using namespace dealii;

  class Summary : public Interface
  {
  public:
    using Interface::Interface;

    /** The figures the probes keep in the run's summary. */
    std::vector<std::string> run_after() const override
    {
      return {"probes"};
    }

    void end_of_run(const double wall_time) override
    {
      // The memory the mesh and the solver's state hold on all processes
      // (deal.II's own accounting for the triangulation, the DoF handler
      // and the nodal vectors; the element groups' arrays): what an element
      // costs beyond the executable.
      // And the ghost layer all processes hold: its cells (each computed
      // twice or more) and its nodal entries (exchanged every step).
      unsigned long ghost_cells = 0;
      for (const auto &cell : get_triangulation().active_cell_iterators())
        ghost_cells += cell->is_ghost() ? 1 : 0;
      const unsigned long ghosts[2] = {ghost_cells, get_position().get_partitioner()->n_ghost_indices()};
      unsigned long       ghost_sums[2];
      Utilities::MPI::sum(ArrayView<const unsigned long>(ghosts, 2), get_mpi_communicator(),
                          ArrayView<unsigned long>(ghost_sums, 2));
      double memory[4] = {double(get_triangulation().memory_consumption()),
                          double(get_dof_handler().memory_consumption()),
                          double(get_reference_position().memory_consumption() +
                                 get_position().memory_consumption() + get_velocity().memory_consumption() +
                                 get_force().memory_consumption() + get_mass().memory_consumption()),
                          0.};
      for (const auto &group : get_element_groups())
        memory[3] += group.memory_per_element() * group.n_elements();
      Utilities::MPI::sum(ArrayView<const double>(memory, 4), get_mpi_communicator(), ArrayView<double>(memory, 4));
      if (!is_root())
        return;
      const auto &summary             = get_summary();
      const auto &energies            = get_energies();
      const auto &constraints         = get_constraints();
      const auto &boundary_conditions = constraints.get_conditions();
      const auto &peak_bc_reaction    = constraints.peak_reactions();
      record_output("summary.csv");
      std::ostringstream out;
      {
        out << std::setprecision(10) << "quantity,value\n";
        out << "end_time_s," << get_time() << '\n';
        out << "ended_by_criterion," << (summary.ended_early || summary.capacity_end_reaction >= 0 ? 1 : 0) << '\n';
        // The summary probe's and pair's figures first, then every probe's
        // and pair's by name (a run without a history row yet: zeros).
        const auto &subjects = get_summary_subjects();
        const auto  probe_residual = [&](const unsigned int p) {
          // When the end criterion ended the run, the mean over its quiet
          // period (the member still rings about its residual shape); else
          // the last value.
          return summary.ended_early && summary.quiet_rows > 0 ? summary.probe_quiet_sum[p] / summary.quiet_rows :
                                                                  summary.probe_last[p];
        };
        const auto pair_duration = [&](const unsigned int p) {
          return summary.pair_contact_start[p] < 0 ? 0. : summary.pair_contact_end[p] - summary.pair_contact_start[p];
        };
        if (!get_probes().empty())
          {
            const bool known = subjects.probe < summary.probe_peak.size();
            out << "peak_displacement_m," << (known ? summary.probe_peak[subjects.probe] : 0.) << '\n'
                << "residual_displacement_m," << (known ? probe_residual(subjects.probe) : 0.) << '\n';
            const auto &probes = get_probes();
            for (unsigned int p = 0; p < probes.size() && p < summary.probe_peak.size(); ++p)
              out << "peak_displacement_" << probes[p].name << "_m," << summary.probe_peak[p] << '\n'
                  << "residual_displacement_" << probes[p].name << "_m," << probe_residual(p) << '\n';
          }
        if (has_contact())
          {
            const bool known = subjects.pair < summary.pair_peak_force.size();
            out << "peak_contact_force_N," << (known ? summary.pair_peak_force[subjects.pair] : 0.) << '\n'
                << "contact_duration_s," << (known ? pair_duration(subjects.pair) : 0.) << '\n';
            for (unsigned int p = 0; p < summary.pair_peak_force.size(); ++p)
              out << "peak_contact_force_" << contact_pair_name(p) << "_N," << summary.pair_peak_force[p] << '\n'
                  << "contact_duration_" << contact_pair_name(p) << "_s," << pair_duration(p) << '\n';
          }
        if (!boundary_conditions.empty())
          out << "peak_support_reaction_N," << summary.peak_reaction << '\n';
        for (unsigned int b = 0; b < boundary_conditions.size() && b < peak_bc_reaction.size(); ++b)
          out << "peak_reaction_" << boundary_conditions[b].name << "_N," << peak_bc_reaction[b] << '\n';
        for (unsigned int b = 0; b < boundary_conditions.size() && b < peak_bc_reaction.size(); ++b)
          if (boundary_conditions[b].name == constraints.capacity_support())
            {
              out << "axial_capacity_N," << peak_bc_reaction[b] << '\n';
              if (constraints.intact_capacity() > 0)
                out << "damage_index," << 1. - peak_bc_reaction[b] / constraints.intact_capacity() << '\n';
            }
        out << "initial_energy_J," << get_initial_energy() << '\n';
        out << "final_kinetic_energy_J," << energies.kinetic << '\n';
        out << "kinetic_energy_converted,"
            << (summary.initial_kinetic > 0 ? 1. - energies.kinetic / summary.initial_kinetic : 0.)
            << '\n';
        out << "internal_energy_J," << energies.internal << '\n';
        out << "hourglass_energy_J," << energies.hourglass << '\n';
        out << "viscous_energy_J," << energies.viscous << '\n';
        if (constraints.damps() || energies.damping != 0)
          out << "damping_energy_J," << energies.damping << '\n';
        if (energies.removed != 0)
          out << "removed_energy_J," << energies.removed << '\n';
        out << "max_hourglass_to_internal," << summary.max_hourglass_ratio << '\n';
        out << "max_balance_error," << summary.max_balance_error << '\n';
        out << "wall_time_s," << wall_time << '\n';
        out << "steps," << get_step_number() << '\n';
        // What the contact springs cost: the steps the elements alone would
        // have needed, and how many steps the springs made smaller.
        out << "steps_elements_only," << summary.element_steps << '\n';
        out << "contact_limited_steps," << summary.contact_limited_steps << '\n';
        for (const auto *family : get_families())
          family->write_summary(out);
        out << "elements," << get_triangulation().n_global_active_cells() << '\n';
        out << "memory_triangulation_bytes," << memory[0] << '\n';
        out << "memory_dof_handler_bytes," << memory[1] << '\n';
        out << "memory_nodal_vectors_bytes," << memory[2] << '\n';
        out << "memory_element_state_bytes," << memory[3] << '\n';
        out << "processes," << Utilities::MPI::n_mpi_processes(get_mpi_communicator()) << '\n';
        out << "ghost_elements," << ghost_sums[0] << '\n';
        out << "ghost_dofs," << ghost_sums[1] << '\n';
      }
      write_atomically(get_output_directory() + "/summary.csv", out.str());
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Summary, "summary", "summary.csv: the run's figures at its end.")
} // namespace anvil::Postprocess
