/**
 * @file
 * energy.csv: the energy balance of seed Eq. (21) at every history row,
 * term by term, with its total and the balance error.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/records.h>

#include <iomanip>

namespace anvil::Postprocess
{
  class Energies : public Interface
  {
  public:
    using Interface::Interface;

    void execute(const double t, double) override
    {
      if (!is_root())
        return;
      if (!file.is_open())
        {
          record_output("energy.csv");
          file.open(get_output_directory() + "/energy.csv");
          file << "time,kinetic,internal,hourglass,viscous,damping,contact,friction,eroded,removed,bond,"
                  "step_change,adaptation,external_work,total,balance_error\n";
        }
      const auto &e = get_energies();
      file << std::setprecision(12) << t << ',' << e.kinetic << ',' << e.internal << ',' << e.hourglass << ','
           << e.viscous << ',' << e.damping << ',' << e.contact << ',' << e.friction << ',' << e.eroded << ','
           << e.removed << ',' << e.bond << ',' << e.step_change << ',' << e.adaptation << ',' << e.external_work << ',' << e.total()
           << ',' << get_balance_error() << '\n';
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    HistoryFile file;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Energies, "energies", "energy.csv: the energy balance, term by term.")
} // namespace anvil::Postprocess
