/**
 * @file
 * erosion.csv: one row per eroded element (time, scene-wide element id,
 * body, position, effective plastic strain, energy it held, reference
 * volume), written once the first element erodes.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/records.h>

namespace anvil::Postprocess
{
  class Erosion : public Interface
  {
  public:
    using Interface::Interface;

    // The step gathers the rows of the elements it erodes to rank 0
    // (Simulator::compute_internal_forces); they are written here.
    void execute(double, double) override
    {
      auto &rows = get_erosion_rows();
      if (!is_root() || rows.empty())
        return;
      if (!file.is_open())
        {
          record_output("erosion.csv");
          file.open(get_output_directory() + "/erosion.csv");
          file << "time,element,body,x,y,z,effective_plastic_strain,energy,reference_volume\n";
        }
      for (const auto &row : rows)
        file << row << '\n';
      rows.clear();
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    HistoryFile file;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Erosion, "erosion", "erosion.csv: the elements eroded, one row each.")
} // namespace anvil::Postprocess
