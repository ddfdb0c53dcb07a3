/**
 * @file
 * summary.csv: the figures of a run that studies and tests read (peak and
 * residual displacement of the first probe, peak force and duration of the
 * first contact pair, energy conversion, hourglass share, balance, cost),
 * and the end criterion of an impact that is over.
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/python_script.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace anvil
{
  using namespace dealii;

  // Every step, after the health check, from data every rank holds (the
  // energies and the replicated contact results): no communication.
  bool Simulator::update_summary(const double t)
  {
    summary.max_balance_error = std::max(summary.max_balance_error, balance_error);
    // The hourglass share once the internal energy is a measurable part of
    // the initial energy (before, a ratio of two round-off figures).
    if (energies.internal > 0.01 * std::abs(initial_energy))
      summary.max_hourglass_ratio =
        std::max(summary.max_hourglass_ratio, energies.hourglass / energies.internal);

    bool in_contact = false;
    for (unsigned int p = 0; p < contact_results.size(); ++p)
      {
        const auto  &f     = contact_results[p].force_on_first;
        const double force = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        if (force > 0)
          in_contact = true;
        if (p == 0 && force > 0)
          {
            summary.peak_contact_force = std::max(summary.peak_contact_force, force);
            if (summary.contact_start < 0)
              summary.contact_start = t;
            summary.contact_end = t;
          }
      }

    if (end_kinetic_fraction <= 0 && end_kinetic_internal_ratio <= 0)
      return false;
    double rigid_kinetic = 0;
    for (const auto &b : bodies)
      if (b.is_rigid())
        rigid_kinetic += b.rigid.kinetic_energy;
    const double deformable_kinetic = energies.kinetic - rigid_kinetic;
    // An impact that is over (against the initial energy), a member that
    // has settled (against its internal energy): each one set must hold.
    const bool quiet =
      !in_contact &&
      (end_kinetic_fraction <= 0 || deformable_kinetic < end_kinetic_fraction * std::abs(initial_energy)) &&
      (end_kinetic_internal_ratio <= 0 || deformable_kinetic < end_kinetic_internal_ratio * energies.internal);
    if (!quiet)
      {
        summary.quiet_since            = -1;
        summary.quiet_displacement_sum = 0;
        summary.quiet_rows             = 0;
        return false;
      }
    if (summary.quiet_since < 0)
      summary.quiet_since = t;
    if (t - summary.quiet_since >= end_quiet_time)
      {
        summary.ended_early = true;
        return true;
      }
    return false;
  }


  // At each history row, on rank 0: the first probe's displacement.
  void Simulator::record_probe_summary(const std::vector<double> &probe_values)
  {
    if (probes.empty())
      return;
    const double u = std::sqrt(probe_values[0] * probe_values[0] + probe_values[1] * probe_values[1] +
                               probe_values[2] * probe_values[2]);
    summary.peak_displacement     = std::max(summary.peak_displacement, u);
    summary.residual_displacement = u;
    if (summary.quiet_since >= 0)
      {
        summary.quiet_displacement_sum += u;
        ++summary.quiet_rows;
      }
  }


  // summary.csv, two columns 'quantity,value', units in the names; written
  // under a temporary name and renamed, so a reader never sees half a file.
  void Simulator::write_summary(const double wall_time)
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    record_output("summary.csv");
    std::ostringstream out;
    {
      out << std::setprecision(10) << "quantity,value\n";
      out << "end_time_s," << time << '\n';
      out << "ended_by_criterion," << (summary.ended_early ? 1 : 0) << '\n';
      if (!probes.empty())
        {
          out << "peak_displacement_m," << summary.peak_displacement << '\n';
          // Residual: when the end criterion ended the run, the mean over
          // its quiet period (the member still rings about its residual
          // shape); else the last value.
          out << "residual_displacement_m,"
              << (summary.ended_early && summary.quiet_rows > 0 ?
                    summary.quiet_displacement_sum / summary.quiet_rows :
                    summary.residual_displacement)
              << '\n';
        }
      if (!contact_pairs.empty())
        {
          out << "peak_contact_force_N," << summary.peak_contact_force << '\n';
          out << "contact_duration_s,"
              << (summary.contact_start < 0 ? 0. : summary.contact_end - summary.contact_start)
              << '\n';
        }
      if (!boundary_conditions.empty())
        out << "peak_support_reaction_N," << summary.peak_reaction << '\n';
      for (unsigned int b = 0; b < boundary_conditions.size() && b < peak_bc_reaction.size(); ++b)
        out << "peak_reaction_" << boundary_conditions[b].name << "_N," << peak_bc_reaction[b] << '\n';
      for (unsigned int b = 0; b < boundary_conditions.size() && b < peak_bc_reaction.size(); ++b)
        if (boundary_conditions[b].name == capacity_support)
          {
            out << "axial_capacity_N," << peak_bc_reaction[b] << '\n';
            if (intact_capacity > 0)
              out << "damage_index," << 1. - peak_bc_reaction[b] / intact_capacity << '\n';
          }
      out << "initial_energy_J," << initial_energy << '\n';
      out << "final_kinetic_energy_J," << energies.kinetic << '\n';
      out << "kinetic_energy_converted,"
          << (summary.initial_kinetic > 0 ? 1. - energies.kinetic / summary.initial_kinetic : 0.)
          << '\n';
      out << "internal_energy_J," << energies.internal << '\n';
      out << "hourglass_energy_J," << energies.hourglass << '\n';
      out << "viscous_energy_J," << energies.viscous << '\n';
      if (mass_damping > 0 || energies.damping != 0)
        out << "damping_energy_J," << energies.damping << '\n';
      if (energies.removed != 0)
        out << "removed_energy_J," << energies.removed << '\n';
      out << "max_hourglass_to_internal," << summary.max_hourglass_ratio << '\n';
      out << "max_balance_error," << summary.max_balance_error << '\n';
      out << "wall_time_s," << wall_time << '\n';
      out << "steps," << step_number << '\n';
      // What the contact springs cost: the steps the elements alone would
      // have needed, and how many steps the springs made smaller.
      out << "steps_elements_only," << summary.element_steps << '\n';
      out << "contact_limited_steps," << summary.contact_limited_steps << '\n';
      for (const auto &family : families)
        family->write_summary(out);
      out << "elements," << triangulation.n_global_active_cells() << '\n';
      out << "processes," << Utilities::MPI::n_mpi_processes(mpi_communicator) << '\n';
    }
    write_atomically(output_directory + "/summary.csv", out.str());
  }


  void Simulator::write_plots()
  {
    if (!make_plots || Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::string message;
    record_output("plots.log");
    const bool  ok = run_python_script("anvil_plot.py", shell_quote(output_directory),
                                      output_directory + "/plots.log", message);
    // 'plots: energy.png, probe_x.png, ...': the pictures this run made.
    if (ok && message.rfind("plots: ", 0) == 0)
      for (const auto &png : Utilities::split_string_list(message.substr(7), ','))
        record_output(png);
    pcout << "  " << (ok ? "" : "plots skipped: ") << message << std::endl;
  }
} // namespace anvil
