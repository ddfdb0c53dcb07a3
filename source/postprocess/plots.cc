/**
 * @file
 * The plots of a run: PNGs of its histories by scripts/anvil_plot.py
 * (copied beside the executable), rank 0; a missing Python or matplotlib
 * skips them with a line.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/python_script.h>

#include <deal.II/base/utilities.h>

namespace anvil::Postprocess
{
  using namespace dealii;

  class Plots : public Interface
  {
  public:
    using Interface::Interface;

    /** Last: they read the histories, bodies.csv and summary.csv. */
    std::vector<std::string> run_after() const override
    {
      return {"bodies", "energies", "erosion", "momentum", "probes", "reactions", "summary"};
    }

    void end_of_run(double) override
    {
      if (!plots_requested() || !is_root())
        return;
      const std::string &output_directory = get_output_directory();
      std::string message;
      record_output("plots.log");
      const bool  ok = run_python_script("anvil_plot.py", shell_quote(output_directory),
                                        output_directory + "/plots.log", message);
      // 'plots: energy.png, probe_x.png, ...': the pictures this run made.
      if (ok && message.rfind("plots: ", 0) == 0)
        for (const auto &png : Utilities::split_string_list(message.substr(7), ','))
          record_output(png);
      get_pcout() << "  " << (ok ? "" : "plots skipped: ") << message << std::endl;
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Plots, "plots", "PNG plots of the histories ('Plots = true').")
} // namespace anvil::Postprocess
