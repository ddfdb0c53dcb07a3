/**
 * @file
 * Partitioning anew during a run ('Rebalance interval'): the processes'
 * element times are compared at every check; past the threshold, each
 * element is weighed by what its group cost per element on its process,
 * a checkpoint is written, and the run goes on from it on a partition of
 * equal measured weight (doc/adaptivity.md, "Partitioning anew during the
 * run"). The checkpoint holds each process's share by scene-wide keys, so
 * the trajectory goes on bit for bit.
 */
#include <anvil/simulator/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>

namespace anvil
{
  using namespace dealii;

  void Simulator::check_balance()
  {
    auto              &seconds = solids->seconds_per_group();
    const double       own     = std::accumulate(seconds.begin(), seconds.end(), 0.);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const double       slowest = Utilities::MPI::max(own, mpi_communicator);
    const double       mean    = Utilities::MPI::sum(own, mpi_communicator) / n_ranks;
    const double       imbalance = mean > 0 ? slowest / mean : 1.;
    if (!(imbalance > parameters.rebalance_threshold))
      {
        std::fill(seconds.begin(), seconds.end(), 0.);
        return;
      }

    // Each owned element's cost: its group's time per element on this
    // process (owned and ghost elements alike: the loop computes both);
    // a rigid body's elements, which the loop skips, a tenth of the
    // cheapest group's, as the partition by kind weighs them.
    const auto        &groups = solids->groups();
    std::vector<double> per_element(groups.size(), 0.);
    double              cheapest = 1e300;
    for (unsigned int g = 0; g < groups.size(); ++g)
      if (groups[g].n_elements() > 0 && seconds[g] > 0)
        {
          per_element[g] = seconds[g] / groups[g].n_elements();
          cheapest       = std::min(cheapest, per_element[g]);
        }
    cheapest = Utilities::MPI::min(cheapest, mpi_communicator);
    std::vector<double> own_cost; // (id, cost) pairs
    for (unsigned int g = 0; g < groups.size(); ++g)
      for (unsigned int e = 0; e < groups[g].n_elements(); ++e)
        if (groups[g].element_is_owned(e))
          own_cost.insert(own_cost.end(),
                          {double(groups[g].element_global_id(e)),
                           groups[g].get_material().is_rigid() || !(per_element[g] > 0) ? 0.1 * cheapest :
                                                                                         per_element[g]});
    // Every process the whole table, scaled so that the mean element
    // weighs 1000 (the one-point element of the partition by kind: the
    // graph partitioners take 32-bit weights).
    const auto                 all = Utilities::MPI::all_gather(mpi_communicator, own_cost);
    std::vector<double>        cost(triangulation.n_global_active_cells(), 0.);
    for (const auto &part : all)
      for (std::size_t i = 0; i + 1 < part.size(); i += 2)
        cost[static_cast<std::size_t>(part[i])] = part[i + 1];
    const double mean_cost = std::accumulate(cost.begin(), cost.end(), 0.) / std::max<std::size_t>(1, cost.size());
    std::vector<unsigned long> weights(cost.size());
    for (std::size_t i = 0; i < cost.size(); ++i)
      weights[i] = std::max<unsigned long>(1, std::lround(1000. * cost[i] / mean_cost));

    pcout << "  rebalance at t = " << time << " s, step " << step_number << ": the slowest process spent "
          << std::setprecision(3) << imbalance << " times the mean in the element loop since the last check; "
          << "the elements are partitioned anew by their measured cost" << std::endl;
    write_checkpoint();
    output.checkpoint_due = false;
    throw RebalanceRequest{std::move(weights)};
  }


  void run_simulator(const std::string              &file,
                     MPI_Comm                        comm,
                     const std::vector<std::string> &overrides,
                     const bool                      resume,
                     const std::string              &resume_from)
  {
    const auto                 wall_start = std::chrono::steady_clock::now();
    std::vector<unsigned long> weights;
    for (bool rebalanced = false;; rebalanced = true)
      {
        Simulator simulator(file, comm, overrides);
        try
          {
            if (!rebalanced)
              simulator.run(resume, resume_from);
            else
              {
                simulator.set_rebalance(std::move(weights), wall_start);
                simulator.run(true);
              }
            return;
          }
        catch (RebalanceRequest &request)
          {
            weights = std::move(request.weights);
          }
      }
  }
} // namespace anvil
