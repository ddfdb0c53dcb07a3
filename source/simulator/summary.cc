/**
 * @file
 * summary.csv: the figures of a run that studies and tests read (peak and
 * residual displacement of the summary probe, peak force and duration of
 * the summary contact pair, energy conversion, hourglass share, balance,
 * cost), and the end criterion of an impact that is over.
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
    summary.max_balance_error = std::max(summary.max_balance_error, balance.balance_error);
    // The hourglass share once the internal energy is a measurable part of
    // the initial energy (before, a ratio of two round-off figures).
    if (energies.internal > 0.01 * std::abs(balance.initial_energy))
      summary.max_hourglass_ratio =
        std::max(summary.max_hourglass_ratio, energies.hourglass / energies.internal);

    const auto &contact_results = contact->results();
    auto        force_of        = [&](const unsigned int p) {
      const auto &f = contact_results[p].force_on_first;
      return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    };
    const std::size_t n_pairs = contact_results.size();
    summary.pair_peak_force.resize(n_pairs, 0.);
    summary.pair_contact_start.resize(n_pairs, -1.);
    summary.pair_contact_end.resize(n_pairs, -1.);
    for (unsigned int p = 0; p < n_pairs; ++p)
      if (const double force = force_of(p); force > 0)
        {
          summary.pair_peak_force[p] = std::max(summary.pair_peak_force[p], force);
          if (summary.pair_contact_start[p] < 0)
            summary.pair_contact_start[p] = t;
          summary.pair_contact_end[p] = t;
        }

    const auto &end = parameters.end_criterion;
    if (!end.asked())
      return false;
    bool in_contact = false;
    for (const unsigned int p : end.pairs)
      in_contact = in_contact || (p < contact_results.size() && force_of(p) > 0);
    double rigid_kinetic = 0;
    for (const auto &b : bodies)
      if (b.is_rigid())
        rigid_kinetic += b.rigid.kinetic_energy;
    const double deformable_kinetic = energies.kinetic - rigid_kinetic;
    // An impact that is over (against the initial energy), a member that
    // has settled (against its internal energy): each one set must hold.
    const bool quiet =
      !in_contact &&
      (end.kinetic_fraction <= 0 || deformable_kinetic < end.kinetic_fraction * std::abs(balance.initial_energy)) &&
      (end.kinetic_internal_ratio <= 0 || deformable_kinetic < end.kinetic_internal_ratio * energies.internal);
    if (!quiet)
      {
        summary.quiet_since = -1;
        summary.quiet_rows  = 0;
        std::fill(summary.probe_quiet_sum.begin(), summary.probe_quiet_sum.end(), 0.);
        return false;
      }
    if (summary.quiet_since < 0)
      summary.quiet_since = t;
    if (t - summary.quiet_since >= end.quiet_time)
      {
        summary.ended_early = true;
        return true;
      }
    return false;
  }


  // At each history row, on rank 0: every probe's displacement.
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
    if (summary.quiet_since >= 0)
      ++summary.quiet_rows;
  }


} // namespace anvil
