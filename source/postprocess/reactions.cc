/**
 * @file
 * reactions.csv: the force each boundary condition's support exerts on its
 * body, summed per condition; the peaks summary.csv reports (and the axial
 * capacity of a capacity stage).
 */
#include <anvil/boundary_conditions/constraints.h>
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <iomanip>

namespace anvil::Postprocess
{
  class Reactions : public Interface
  {
  public:
    using Interface::Interface;

    void execute(const double t, double) override
    {
      // (The sums over the processes: the constraints' family forms them
      // before the rows, with the peaks summary.csv reports.)
      const auto &reactions = get_constraints().reactions();
      if (reactions.empty() || !is_root())
        return;
      const auto &conditions = get_constraints().get_conditions();
      if (!file.is_open())
        {
          record_output("reactions.csv");
          file.open(get_output_directory() + "/reactions.csv");
          file << "time";
          for (const auto &bc : conditions)
            file << ',' << bc.name << "_fx," << bc.name << "_fy," << bc.name << "_fz";
          file << '\n';
        }
      file << std::setprecision(12) << t;
      for (unsigned int k = 0; k < reactions.size(); ++k)
        file << ',' << reactions[k];
      file << '\n';
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    HistoryFile file;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Reactions, "reactions",
                               "reactions.csv: the support reaction of each boundary condition.")
} // namespace anvil::Postprocess
