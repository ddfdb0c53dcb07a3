/**
 * @file
 * A scene of several stages (doc/user_guide.md, "Stages"): the scene's own
 * run, then each stage of 'Stages' on the state the one before left, with
 * its 'Changes' applied to the scene. Each stage is a run of its own in
 * OUTPUT/NAME/STAGE/ (histories, frames, summary.csv, status), started from
 * the checkpoint the stage before wrote at its end; the energies and the
 * balance go on through all of them. At the end the scene's summary.csv
 * gains every stage's figures ('STAGE.quantity'), and the capacity figures
 * of the stage that has them (axial_capacity_N, damage_index).
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/output_files.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace anvil
{
  namespace fs = std::filesystem;

  namespace
  {
    // The 'status' file of a run's output directory says 'state: finished'.
    bool finished(const std::string &directory)
    {
      std::ifstream in(directory + "/status");
      std::string   line;
      std::getline(in, line);
      return line == "state: finished";
    }

    std::vector<std::pair<std::string, std::string>> read_summary(const std::string &file)
    {
      std::vector<std::pair<std::string, std::string>> rows;
      std::ifstream                                    in(file);
      std::string                                      line;
      std::getline(in, line); // quantity,value
      while (std::getline(in, line))
        {
          const auto comma = line.find(',');
          if (comma != std::string::npos)
            rows.emplace_back(line.substr(0, comma), line.substr(comma + 1));
        }
      return rows;
    }
  } // namespace


  void run_scene_with_stages(const std::string              &file,
                             const std::vector<std::string> &overrides,
                             MPI_Comm                        comm,
                             const bool                      resume,
                             const bool                      check_only)
  {
    const std::vector<Stage> stages = Simulator::read_stages(file, overrides);
    if (stages.empty())
      {
        if (check_only)
          Simulator(file, comm, overrides).check();
        else
          run_simulator(file, comm, overrides, resume);
        return;
      }

    const bool          root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
    dealii::ConditionalOStream pcout(std::cout, root);

    // Every stage's scene is read (and so checked) before anything runs.
    std::vector<std::vector<std::string>> stage_overrides;
    std::string                           directory;
    {
      std::vector<std::string> first = overrides;
      first.push_back("Simulation/Checkpoint at end=true");
      Simulator simulator(file, comm, first);
      directory = simulator.get_output_directory();
      stage_overrides.push_back(first);
      std::vector<std::string> accumulated = overrides;
      for (unsigned int s = 0; s < stages.size(); ++s)
        {
          accumulated.insert(accumulated.end(), stages[s].changes.begin(), stages[s].changes.end());
          std::vector<std::string> o = accumulated;
          o.push_back("Simulation/Output directory=" + directory);
          o.push_back("Simulation/Name=" + stages[s].name);
          o.push_back(std::string("Simulation/Checkpoint at end=") +
                      (s + 1 < stages.size() ? "true" : "false"));
          try
            {
              Simulator stage(file, comm, o);
            }
          catch (const InputError &e)
            {
              throw InputError(file + ": subsection 'Stage " + stages[s].name + "': " + e.what());
            }
          stage_overrides.push_back(o);
        }
      if (check_only)
        {
          simulator.check();
          pcout << file << ": " << stages.size() << " stage(s) after the scene's own run:";
          for (const auto &s : stages)
            pcout << " '" << s.name << "'";
          pcout << ", each in " << directory << "/NAME/" << std::endl;
          return;
        }
    }

    // The scene's own run, then the stages; with --resume, finished ones
    // are skipped and the interrupted one continues from its checkpoint.
    std::string previous = directory;
    for (unsigned int s = 0; s <= stages.size(); ++s)
      {
        const std::string here = s == 0 ? directory : directory + "/" + stages[s - 1].name;
        if (resume && finished(here))
          {
            pcout << "Anvil: " << (s == 0 ? "the scene's own run" : "stage '" + stages[s - 1].name + "'")
                  << " finished earlier (" << here << ")" << std::endl;
            previous = here;
            continue;
          }
        if (s > 0)
          pcout << "Anvil: stage " << s << " of " << stages.size() << ", '" << stages[s - 1].name << "'"
                << std::endl;
        if (resume && fs::exists(here + "/checkpoint/info"))
          run_simulator(file, comm, stage_overrides[s], true);
        else if (s == 0)
          {
            if (resume)
              throw InputError(file + ": --resume: no checkpoint in '" + here +
                               "/checkpoint' (set 'Checkpoint interval' or stop a run with SIGTERM to "
                               "write one)");
            run_simulator(file, comm, stage_overrides[s], false);
          }
        else
          run_simulator(file, comm, stage_overrides[s], false, previous + "/checkpoint");
        previous = here;
      }

    // The scene's summary.csv gains the stages' figures.
    if (root)
      {
        auto              rows = read_summary(directory + "/summary.csv");
        double            wall = 0;
        std::ostringstream out;
        out << "quantity,value\n";
        for (const auto &[q, v] : rows)
          if (q.find('.') == std::string::npos && q != "total_wall_time_s")
            {
              out << q << ',' << v << '\n';
              if (q == "wall_time_s")
                wall += std::atof(v.c_str());
            }
        std::vector<std::pair<std::string, std::string>> capacity;
        for (const auto &stage : stages)
          for (const auto &[q, v] : read_summary(directory + "/" + stage.name + "/summary.csv"))
            {
              out << stage.name << '.' << q << ',' << v << '\n';
              if (q == "wall_time_s")
                wall += std::atof(v.c_str());
              if (q == "axial_capacity_N" || q == "damage_index")
                capacity.emplace_back(q, v);
            }
        for (const auto &[q, v] : capacity)
          if (std::none_of(rows.begin(), rows.end(), [&](const auto &r) { return r.first == q; }))
            out << q << ',' << v << '\n';
        out << "total_wall_time_s," << wall << '\n';
        write_atomically(directory + "/summary.csv", out.str());
      }
    pcout << "Anvil: the scene's run and its " << stages.size()
          << " stage(s) done; the figures of all of them in " << directory << "/summary.csv" << std::endl;
  }
} // namespace anvil
