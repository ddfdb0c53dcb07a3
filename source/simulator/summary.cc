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
    const auto &contact_results = contact->results();
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
        std::fill(summary.probe_quiet_sum.begin(), summary.probe_quiet_sum.end(), 0.);
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
    const unsigned int n_values = probe_values.size() / probes.size();
    summary.probe_peak.resize(probes.size(), 0.);
    summary.probe_last.resize(probes.size(), 0.);
    summary.probe_quiet_sum.resize(probes.size(), 0.);
    for (unsigned int p = 0; p < probes.size(); ++p)
      {
        const double *u_p = &probe_values[n_values * p];
        const double  u   = std::sqrt(u_p[0] * u_p[0] + u_p[1] * u_p[1] + u_p[2] * u_p[2]);
        summary.probe_peak[p] = std::max(summary.probe_peak[p], u);
        summary.probe_last[p] = u;
        if (summary.quiet_since >= 0)
          summary.probe_quiet_sum[p] += u;
      }
    summary.peak_displacement     = summary.probe_peak[0];
    summary.residual_displacement = summary.probe_last[0];
    if (summary.quiet_since >= 0)
      {
        summary.quiet_displacement_sum = summary.probe_quiet_sum[0];
        ++summary.quiet_rows;
      }
  }


} // namespace anvil
