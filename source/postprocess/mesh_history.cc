/**
 * @file
 * mesh.csv: what refinement and coarsening during the run ('Simulation/Adapt
 * interval') made of the mesh, at every history row: the number of
 * elements, of them how many at each level of refinement, and the number
 * of nodes. Written only by a scene that adapts its mesh.
 */
#include <anvil/postprocess/interface.h>

#include <deal.II/base/mpi.h>

#include <iomanip>

namespace anvil::Postprocess
{
  class MeshHistory : public Interface
  {
  public:
    using Interface::Interface;

    void execute(const double t, double) override
    {
      if (!adapts_during_run())
        return;
      // (A round builds the scene anew, this postprocessor with it: the
      // mesh it sees does not change, so it is counted once.)
      if (count.empty())
        {
          count.assign(levels, 0.);
          for (const auto &cell : get_triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              count[std::min<unsigned int>(cell->level(), levels - 1)] += 1;
          dealii::Utilities::MPI::sum(count, get_mpi_communicator(), count);
        }
      if (!is_root())
        return;
      if (!file.is_open())
        {
          record_output("mesh.csv");
          file.open(get_output_directory() + "/mesh.csv");
          file << "time,elements";
          for (unsigned int l = 0; l < levels; ++l)
            file << ",level_" << l;
          file << ",nodes\n";
        }
      double total = 0;
      for (const double c : count)
        total += c;
      file << std::setprecision(12) << t << ',' << total;
      for (const double c : count)
        file << ',' << c;
      file << ',' << get_dof_handler().n_dofs() / 3 << '\n';
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    static constexpr unsigned int levels = 5; // 'Levels' is at most 4
    HistoryFile                   file;
    std::vector<double>           count;
  };

  ANVIL_REGISTER_POSTPROCESSOR(MeshHistory,
                               "mesh",
                               "mesh.csv: elements (by level of refinement) and nodes over time, in a scene that "
                               "refines and coarsens during the run.")
} // namespace anvil::Postprocess
