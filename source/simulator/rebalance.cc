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
    auto              &groups  = solids->groups();
    double             own     = 0;
    for (const auto &g : groups)
      own += g.measured_seconds();
    const unsigned int n_ranks   = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const double       slowest   = Utilities::MPI::max(own, mpi_communicator);
    const double       mean      = Utilities::MPI::sum(own, mpi_communicator) / n_ranks;
    const double       imbalance = mean > 0 ? slowest / mean : 1.;
    // (A new partition costs about what the run's start did: where the
    // imbalance lost less since the last check, it would not pay back
    // within the next interval.)
    const bool pays = !parameters.rebalance_when_it_pays || slowest - mean > startup_seconds;
    if (!(imbalance > parameters.rebalance_threshold) || !pays)
      {
        solids->reset_timing();
        return;
      }

    // Each owned element's cost: its share of the time of the batch of
    // elements (one-point) or of the element (fully integrated) it was
    // computed in, or of its group (the element-by-element loops), on its
    // process; a rigid body's elements, which the loop skips, a tenth of
    // the mean element's.
    std::vector<double> own_cost; // (id, seconds) pairs
    double              sum = 0, counted = 0;
    for (const auto &g : groups)
      for (unsigned int e = 0; e < g.n_elements(); ++e)
        if (g.element_is_owned(e))
          {
            const double t = g.get_material().is_rigid() ? -1. : g.element_seconds(e);
            own_cost.insert(own_cost.end(), {double(g.element_global_id(e)), t});
            if (t >= 0)
              sum += t, counted += 1;
          }
    const double mean_cost = Utilities::MPI::sum(sum, mpi_communicator) /
                             std::max(1., Utilities::MPI::sum(counted, mpi_communicator));
    // Every process the whole table, scaled so that the mean element
    // weighs 1000 (the one-point element of the partition by kind: the
    // graph partitioners take 32-bit weights).
    const auto                 all = Utilities::MPI::all_gather(mpi_communicator, own_cost);
    std::vector<unsigned long> weights(triangulation.n_global_active_cells(), 1000);
    for (const auto &part : all)
      for (std::size_t i = 0; i + 1 < part.size(); i += 2)
        weights[static_cast<std::size_t>(part[i])] =
          part[i + 1] < 0 ? 100 :
          mean_cost > 0  ? std::max<long>(1, std::lround(1000. * part[i + 1] / mean_cost)) :
                           1000;

    pcout << "  rebalance at t = " << time << " s, step " << step_number << ": the slowest process spent "
          << std::setprecision(3) << imbalance << " times the mean in the element loop since the last check ("
          << slowest - mean << " s lost; a new partition costs about " << startup_seconds
          << " s); the elements are partitioned anew by their measured cost" << std::endl;
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
