/**
 * @file
 * The run's outputs: at each history row and frame, the postprocessors
 * (source/postprocess/) and the families' own; all histories flushed
 * together; the list of the files this run wrote (anvil_files.txt).
 */
#include <anvil/simulator/simulator.h>

#include <chrono>
#include <fstream>

namespace anvil
{
  using namespace dealii;

  // @sect3{Histories}
  //
  // The families reduce what their rows need (the reactions' sums among
  // them, which reactions.csv reads); every postprocessor's row (energy.csv,
  // momentum.csv, probes, reactions, erosion: source/postprocess/), then the
  // families' own (contact_NAME.csv, rigid_NAME.csv, rebar_NAME.csv). Rank 0
  // writes.
  void Simulator::write_history(const double t, const double dt)
  {
    for (auto *family : contributors())
      if (!family->empty())
        family->prepare_history();
    for (auto &postprocessor : postprocessors)
      postprocessor->execute(t, dt);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    for (auto *family : contributors())
      if (!family->empty())
        family->write_history(t, dt);
    // All histories reach the disk together, at most a second or 1,000 rows
    // apart.
    if (++output.rows_since_flush >= 1000 ||
        std::chrono::steady_clock::now() - output.last_flush > std::chrono::seconds(1))
      flush_histories();
  }


  // @sect3{Fields}
  void Simulator::output_results(const double t, const std::string &basename)
  {
    TimerOutput::Scope timer_scope(*timer, "output");
    for (auto &postprocessor : postprocessors)
      postprocessor->write_frame(t, basename, output.output_count);
    if (basename == "solution")
      {
        for (auto *family : contributors())
          if (!family->empty())
            family->output_frame(t, output.output_count);
        ++output.output_count;
      }
  }


  std::vector<HistoryFile *> Simulator::history_files() const
  {
    std::vector<HistoryFile *> files;
    for (const auto &postprocessor : postprocessors)
      for (auto *f : postprocessor->history_files())
        files.push_back(f);
    for (auto *family : contributors())
      for (auto *f : family->history_files())
        files.push_back(f);
    return files;
  }


  void Simulator::flush_histories()
  {
    output.last_flush       = std::chrono::steady_clock::now();
    output.rows_since_flush = 0;
    auto flush = [&](HistoryFile &f) {
      const std::string failure = f.flush();
      if (!failure.empty() && output.failure.empty())
        output.failure = failure;
    };
    for (auto *f : history_files())
      flush(*f);
  }


  void Simulator::record_output(const std::string &name)
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0 || !output.recorded_outputs.insert(name).second)
      return;
    std::ofstream list(parameters.output_directory + "/anvil_files.txt", std::ios::app);
    list << name << '\n';
    list.flush();
    if (!list)
      throw OutputError("cannot write " + parameters.output_directory + "/anvil_files.txt (the list of this run's files)");
  }
} // namespace anvil
