/**
 * @file
 * reactions.csv: the force each boundary condition's support exerts on its
 * body, summed per condition; the peaks summary.csv reports (and the axial
 * capacity of a capacity stage).
 */
#include <anvil/boundary_conditions/boundary_condition.h>
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
      std::vector<double> reactions(get_bc_reaction());
      if (reactions.empty())
        return;
      dealii::Utilities::MPI::sum(reactions, get_mpi_communicator(), reactions);
      if (!is_root())
        return;
      const auto &conditions = get_boundary_conditions();
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
      auto magnitude = [&](const unsigned int b) {
        return std::sqrt(reactions[3 * b] * reactions[3 * b] + reactions[3 * b + 1] * reactions[3 * b + 1] +
                         reactions[3 * b + 2] * reactions[3 * b + 2]);
      };
      auto &peak = get_peak_bc_reaction();
      peak.resize(conditions.size(), 0.);
      for (unsigned int b = 0; b < conditions.size(); ++b)
        peak[b] = std::max(peak[b], magnitude(b));
      auto &summary = get_summary();
      for (unsigned int b = 0; b < conditions.size(); ++b)
        summary.peak_reaction = std::max(summary.peak_reaction, magnitude(b));
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
