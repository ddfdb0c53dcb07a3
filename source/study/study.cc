/**
 * @file
 * Parameter studies (`anvil --study STUDY.prm`): the study file, its runs
 * as child processes, study.csv and the plots.
 */
#include <anvil/simulator/simulator.h>
#include <anvil/study/study.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/output_files.h>
#include <anvil/utilities/python_script.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <csignal>
#include <cerrno>
#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

extern char **environ;

namespace anvil
{
  namespace
  {
    namespace fs = std::filesystem;

    std::string trim(std::string s)
    {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t") + 1);
      return s;
    }

    // Values are separated by ';' (a value may itself be a list: '-2, 0, 0').
    std::vector<std::string> split_values(const std::string &text)
    {
      std::vector<std::string> result;
      std::stringstream        in(text);
      std::string              item;
      while (std::getline(in, item, ';'))
        if (!trim(item).empty())
          result.push_back(trim(item));
      return result;
    }

    // The number a plot puts on its axis for a value: the value itself, or
    // the first number in it ('-2, 0, 0' -> -2); NaN when it has none.
    double first_number(const std::string &value)
    {
      const char *begin = value.c_str();
      while (*begin != '\0')
        {
          char        *end = nullptr;
          const double x   = std::strtod(begin, &end);
          if (end != begin)
            return x;
          ++begin;
        }
      return std::nan("");
    }

    std::string csv_field(const std::string &s)
    {
      if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
      std::string quoted = "\"";
      for (const char c : s)
        quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
      return quoted + "\"";
    }

    std::string read_file(const fs::path &path)
    {
      std::ifstream      in(path);
      std::ostringstream s;
      s << in.rdbuf();
      return s.str();
    }

    void declare_lists(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Variables",
                        "",
                        dealii::Patterns::List(dealii::Patterns::Anything()),
                        "Names of the varied entries; each has a subsection "
                        "'Variable NAME'.");
    }

    void declare_parameters(dealii::ParameterHandler &prm, const std::vector<std::string> &variables)
    {
      using namespace dealii;
      declare_lists(prm);
      prm.declare_entry("Base scene",
                        "",
                        Patterns::Anything(),
                        "The scene every run starts from, relative to the study file.");
      prm.declare_entry("Name",
                        "",
                        Patterns::Anything(),
                        "Study name; results go to OUTPUT DIRECTORY/NAME. Empty: "
                        "the study file's name without .prm.");
      prm.declare_entry("Output directory",
                        "output",
                        Patterns::Anything(),
                        "Directory under which the study's directory is made, "
                        "relative to the working directory.");
      prm.declare_entry("Combination",
                        "grid",
                        Patterns::Selection("grid|zip"),
                        "grid: every combination of the variables' values; zip: "
                        "the i-th values of all variables together (equal "
                        "numbers of values).");
      prm.declare_entry("Fixed entries",
                        "",
                        Patterns::Anything(),
                        "Entries every run sets, 'PATH=VALUE' separated by ';' "
                        "(for example 'Simulation/Plots=false').");
      prm.declare_entry("Processes per run",
                        "1",
                        Patterns::Integer(1),
                        "MPI processes of each run; more than 1 starts it with "
                        "'MPI launcher'. Units: none.");
      prm.declare_entry("Jobs",
                        "1",
                        Patterns::Integer(1),
                        "Runs at a time ('--jobs N' on the command line wins). Units: none.");
      prm.declare_entry("MPI launcher",
                        "mpirun -np",
                        Patterns::Anything(),
                        "Command that starts a run on several processes, "
                        "followed by the number of processes.");
      prm.declare_entry("History plot",
                        "",
                        Patterns::Anything(),
                        "The history overlaid for all runs in history.png, "
                        "'FILE.csv:COLUMN' of each run's output (for example "
                        "'probe_impact_point.csv:ux'); empty: none.");
      prm.declare_entry("History scale",
                        "1",
                        Patterns::Double(),
                        "Factor on the plotted history (1e3: m to mm). Units: none.");
      prm.declare_entry("History label",
                        "",
                        Patterns::Anything(),
                        "Axis label of the plotted history.");
      prm.declare_entry("Plots",
                        "true",
                        Patterns::Bool(),
                        "Write history.png and summary.png (Python's matplotlib).");
      for (const auto &v : variables)
        {
          prm.enter_subsection("Variable " + v);
          prm.declare_entry("Entry",
                            "",
                            Patterns::Anything(),
                            "Path of the varied entry in the base scene, "
                            "subsections and entry name separated by '/' (for "
                            "example 'Body hammer/Rigid body/Mass').");
          prm.declare_entry("Values",
                            "",
                            Patterns::Anything(),
                            "The values, separated by ';' (a value may be a list: "
                            "'-1, 0, 0; -2, 0, 0').");
          prm.declare_entry("Plot values",
                            "",
                            Patterns::Anything(),
                            "One number per value for the plots' axis, separated "
                            "by ';'; empty: the first number in each value.");
          prm.declare_entry("Label",
                            "",
                            Patterns::Anything(),
                            "Axis label (empty: the variable's name).");
          prm.leave_subsection();
        }
    }
  } // namespace


  void Study::print_parameters(std::ostream &out)
  {
    dealii::ParameterHandler prm;
    declare_parameters(prm, {"NAME"});
    prm.print_parameters(out,
                         dealii::ParameterHandler::OutputStyle::PRM |
                           dealii::ParameterHandler::OutputStyle::KeepDeclarationOrder);
  }


  Study::Study(const std::string &study_file)
    : file(study_file)
  {
    if (!fs::exists(file))
      throw InputError(file + ": the study file does not exist");
    auto parse = [&](dealii::ParameterHandler &prm, const bool skip) {
      try
        {
          std::ifstream in(file);
          prm.parse_input(in, file, "", skip);
        }
      catch (const dealii::ExceptionBase &e)
        {
          throw InputError(file + ": " + one_line_message(e) +
                           " ('anvil --study' entries: doc/studies.md)");
        }
    };
    dealii::ParameterHandler lists;
    declare_lists(lists);
    parse(lists, true);
    const auto names = dealii::Utilities::split_string_list(lists.get("Variables"), ',');
    if (names.empty())
      throw InputError(file + ": entry 'Variables' names no variable");
    if (std::set<std::string>(names.begin(), names.end()).size() != names.size())
      throw InputError(file + ": a name appears twice in 'Variables'");

    dealii::ParameterHandler prm;
    declare_parameters(prm, names);
    parse(prm, false);

    const fs::path here = fs::path(file).parent_path();
    base_scene          = prm.get("Base scene");
    if (base_scene.empty())
      throw InputError(file + ": entry 'Base scene' is empty; name the scene the runs start from");
    if (fs::path(base_scene).is_relative())
      base_scene = (here / base_scene).lexically_normal().string();
    if (!fs::exists(base_scene))
      throw InputError(file + ": entry 'Base scene': '" + base_scene +
                       "' does not exist (relative to the study file)");
    name = prm.get("Name");
    if (name.empty())
      name = fs::path(file).stem().string();
    directory     = fs::absolute(fs::path(prm.get("Output directory")) / name).lexically_normal().string();
    combination   = prm.get("Combination");
    processes     = prm.get_integer("Processes per run");
    jobs          = prm.get_integer("Jobs");
    launcher      = prm.get("MPI launcher");
    plots         = prm.get_bool("Plots");
    history_scale = prm.get_double("History scale");
    history_label = prm.get("History label");
    {
      const std::string h = prm.get("History plot");
      if (!h.empty())
        {
          const auto colon = h.rfind(':');
          if (colon == std::string::npos || colon == 0 || colon + 1 == h.size())
            throw InputError(file + ": entry 'History plot': '" + h +
                             "' is not FILE.csv:COLUMN (for example probe_impact_point.csv:ux)");
          history_file   = trim(h.substr(0, colon));
          history_column = trim(h.substr(colon + 1));
        }
    }
    for (const auto &f : split_values(prm.get("Fixed entries")))
      fixed.push_back(f);

    for (const auto &n : names)
      {
        prm.enter_subsection("Variable " + n);
        Variable v;
        v.name   = n;
        v.entry  = trim(prm.get("Entry"));
        v.values = split_values(prm.get("Values"));
        v.label  = prm.get("Label").empty() ? n : prm.get("Label");
        const auto plot_values = split_values(prm.get("Plot values"));
        prm.leave_subsection();
        const std::string where = file + ": subsection 'Variable " + n + "': ";
        if (v.entry.empty())
          throw InputError(where + "entry 'Entry' is empty; give the path of an entry of the base scene");
        if (v.values.empty())
          throw InputError(where + "entry 'Values' gives no value (values are separated by ';')");
        if (!plot_values.empty() && plot_values.size() != v.values.size())
          throw InputError(where + "entry 'Plot values' has " + std::to_string(plot_values.size()) +
                           " numbers for " + std::to_string(v.values.size()) + " values");
        for (unsigned int i = 0; i < v.values.size(); ++i)
          {
            const double x = plot_values.empty() ? first_number(v.values[i]) :
                                                   first_number(plot_values[i]);
            v.plot_values.push_back(x);
          }
        variables.push_back(v);
      }
    if (combination == "zip")
      for (const auto &v : variables)
        if (v.values.size() != variables[0].values.size())
          throw InputError(file + ": 'Combination = zip' needs as many values in every variable ('" +
                           variables[0].name + "' has " + std::to_string(variables[0].values.size()) +
                           ", '" + v.name + "' " + std::to_string(v.values.size()) + ")");
    make_runs();
  }


  // The runs: the grid of all combinations (the last variable fastest) or
  // the zipped lists.
  void Study::make_runs()
  {
    std::vector<std::vector<unsigned int>> choices;
    if (combination == "zip")
      for (unsigned int i = 0; i < variables[0].values.size(); ++i)
        choices.emplace_back(variables.size(), i);
    else
      {
        std::vector<unsigned int> c(variables.size(), 0);
        while (true)
          {
            choices.push_back(c);
            int k = int(variables.size()) - 1;
            while (k >= 0 && ++c[k] == variables[k].values.size())
              c[k--] = 0;
            if (k < 0)
              break;
          }
      }
    const unsigned int width = std::max<std::size_t>(2, std::to_string(choices.size()).size());
    for (unsigned int r = 0; r < choices.size(); ++r)
      {
        Run run;
        std::ostringstream n;
        n << "run_" << std::setw(width) << std::setfill('0') << r + 1;
        run.name   = n.str();
        run.choice = choices[r];
        run.overrides = fixed;
        for (unsigned int v = 0; v < variables.size(); ++v)
          run.overrides.push_back(variables[v].entry + "=" + variables[v].values[run.choice[v]]);
        run.overrides.push_back("Simulation/Output directory=" + directory);
        run.overrides.push_back("Simulation/Name=" + run.name);
        run.overrides.push_back("Simulation/Overwrite existing output=true");
        runs.push_back(run);
      }
  }


  // Before any run: every fixed entry and every value of every variable
  // parses against the base scene's declaration (an unknown entry path, a
  // value its pattern refuses: one line naming the variable).
  void Study::validate() const
  {
    for (const auto &f : fixed)
      try
        {
          Simulator::validate_scene(base_scene, {f});
        }
      catch (const InputError &e)
        {
          throw InputError(file + ": entry 'Fixed entries', '" + f + "': " + e.what());
        }
    for (const auto &v : variables)
      for (const auto &value : v.values)
        try
          {
            Simulator::validate_scene(base_scene, {v.entry + "=" + value});
          }
        catch (const InputError &e)
          {
            throw InputError(file + ": subsection 'Variable " + v.name + "', entry '" + v.entry +
                             "', value '" + value + "': " + e.what());
          }
    for (const auto &r : runs)
      Simulator::validate_scene(base_scene, r.overrides);
  }


  std::string Study::describe(const Run &run) const
  {
    std::string s;
    for (unsigned int v = 0; v < variables.size(); ++v)
      s += (v ? ", " : "") + variables[v].name + " = " + variables[v].values[run.choice[v]];
    return s;
  }


  namespace
  {
    std::string joined(const std::vector<std::string> &lines)
    {
      std::string s;
      for (const auto &l : lines)
        s += l + '\n';
      return s;
    }
  } // namespace


  bool Study::finished_earlier(const Run &run) const
  {
    const fs::path dir = fs::path(directory) / run.name;
    return fs::exists(dir / "summary.csv") && fs::exists(dir / "run.status") &&
           read_file(dir / "run.status").rfind("exit 0\n", 0) == 0 &&
           read_file(dir / "run.args") == joined(run.overrides);
  }


  // One run as a child process: the anvil executable itself (or the MPI
  // launcher with it), stdout and stderr to run.log in its directory.
  int Study::launch(const Run &run) const
  {
    const fs::path dir = fs::path(directory) / run.name;
    fs::create_directories(dir);
    std::error_code ec;
    fs::remove(dir / "run.status", ec);
    // A run the study was stopped in (its checkpoint there, the same
    // overrides) continues from its checkpoint.
    const bool resume = fs::exists(dir / "checkpoint" / "info") && fs::exists(dir / "run.args") &&
                        read_file(dir / "run.args") == joined(run.overrides);
    write_atomically((dir / "run.args").string(), joined(run.overrides));

    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    std::vector<std::string> argv;
    if (processes > 1)
      {
        std::istringstream words(launcher);
        std::string        w;
        while (words >> w)
          argv.push_back(w);
        argv.push_back(std::to_string(processes));
      }
    argv.push_back(exe);
    if (resume)
      argv.push_back("--resume");
    argv.push_back(base_scene);
    for (const auto &o : run.overrides)
      {
        argv.push_back("--set");
        argv.push_back(o);
      }
    std::vector<char *> c_argv;
    for (auto &a : argv)
      c_argv.push_back(a.data());
    c_argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log = (dir / "run.log").string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t      pid    = 0;
    const int  status = posix_spawnp(&pid, c_argv[0], &actions, nullptr, c_argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (status != 0)
      throw std::runtime_error("cannot start '" + argv[0] + "' for " + run.name + ": " +
                               std::strerror(status));
    return pid;
  }


  int Study::run(const unsigned int jobs_from_command_line)
  {
    if (jobs_from_command_line > 0)
      jobs = jobs_from_command_line;
    validate();
    // Without SA_RESTART, so that waitpid returns when a signal arrives.
    struct sigaction action = {};
    action.sa_handler       = [](int) { raise_stop_flag(); };
    sigaction(SIGTERM, &action, nullptr);
    sigaction(SIGINT, &action, nullptr);
    fs::create_directories(directory);
    std::cout << "study " << name << ": " << runs.size() << " runs of " << base_scene << ", "
              << jobs << " at a time, " << processes << " process(es) each, in " << directory
              << std::endl;

    using clock = std::chrono::steady_clock;
    std::map<int, std::pair<unsigned int, clock::time_point>> running;
    unsigned int next = 0, done = 0;
    double       wall_sum = 0;
    unsigned int wall_runs = 0;
    auto report = [&](const unsigned int r, const std::string &what) {
      std::cout << "study " << name << ": run " << r + 1 << " of " << runs.size() << " ("
                << describe(runs[r]) << ") " << what;
      const unsigned int left = runs.size() - done;
      if (wall_runs > 0 && left > 0)
        std::cout << "; about " << std::fixed << std::setprecision(0)
                  << wall_sum / wall_runs * std::ceil(double(left) / jobs) << " s left";
      std::cout << std::defaultfloat << std::setprecision(6) << std::endl;
    };

    while (done < runs.size())
      {
        while (next < runs.size() && running.size() < jobs)
          {
            const unsigned int r = next++;
            if (finished_earlier(runs[r]))
              {
                // It keeps the wall time of the invocation that ran it.
                std::istringstream status(read_file(fs::path(directory) / runs[r].name / "run.status"));
                std::string        word;
                while (status >> word)
                  if (word == "wall")
                    status >> runs[r].wall_time;
                runs[r].status  = 0;
                ++done;
                report(r, "finished earlier: skipped");
                continue;
              }
            running[launch(runs[r])] = {r, clock::now()};
            std::cout << "study " << name << ": run " << r + 1 << " of " << runs.size() << " ("
                      << describe(runs[r]) << ") started" << std::endl;
          }
        if (running.empty())
          continue;
        int         wstatus = 0;
        const pid_t pid     = waitpid(-1, &wstatus, 0);
        if (pid < 0 && errno == EINTR && stop_signal_received())
          {
            // SIGTERM / SIGINT: the running runs checkpoint and stop; the
            // study started again resumes them.
            for (const auto &[child, what] : running)
              kill(child, SIGTERM);
            for (std::size_t k = 0; k < running.size(); ++k)
              waitpid(-1, &wstatus, 0);
            std::cout << "study " << name << ": stopped; " << done << " of " << runs.size()
                      << " runs finished; the runs under way wrote checkpoints: 'anvil --study " << file
                      << "' continues" << std::endl;
            return 5;
          }
        if (pid < 0)
          throw std::runtime_error("waitpid failed");
        const auto it = running.find(pid);
        if (it == running.end())
          continue;
        const unsigned int r    = it->second.first;
        const double       wall = std::chrono::duration<double>(clock::now() - it->second.second).count();
        running.erase(it);
        Run &run     = runs[r];
        run.status   = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : 128 + WTERMSIG(wstatus);
        run.wall_time = wall;
        ++done;
        wall_sum += wall;
        ++wall_runs;
        std::ostringstream status;
        status << "exit " << run.status << "\nwall " << wall << "\n";
        write_atomically((fs::path(directory) / run.name / "run.status").string(), status.str());
        std::ostringstream what;
        what << "finished in " << std::fixed << std::setprecision(1) << wall << " s";
        if (run.status != 0)
          what << ", FAILED with exit " << run.status << " (see " << run.name << "/run.log)";
        report(r, what.str());
      }

    write_table();
    if (plots)
      write_plots();
    unsigned int failed = 0;
    for (const auto &r : runs)
      failed += (r.status != 0);
    if (failed > 0)
      {
        std::cout << "study " << name << ": " << failed << " of " << runs.size()
                  << " runs failed; study.csv lists their exit status" << std::endl;
        return 1;
      }
    return 0;
  }


  // study.csv: a row per run, the varied values (as given and as plotted)
  // and every quantity of that run's summary.csv (the union over the runs,
  // in the order they first appear; empty where a run has none).
  void Study::write_table() const
  {
    std::vector<std::string>                          quantities;
    std::vector<std::map<std::string, std::string>>   values(runs.size());
    for (unsigned int r = 0; r < runs.size(); ++r)
      {
        std::ifstream in(fs::path(directory) / runs[r].name / "summary.csv");
        std::string   line;
        std::getline(in, line); // header
        while (std::getline(in, line))
          {
            const auto comma = line.find(',');
            if (comma == std::string::npos)
              continue;
            const std::string q = line.substr(0, comma);
            if (std::find(quantities.begin(), quantities.end(), q) == quantities.end())
              quantities.push_back(q);
            values[r][q] = line.substr(comma + 1);
          }
      }
    std::ostringstream out;
    out << std::setprecision(10) << "run,exit_status,run_wall_time_s";
    for (const auto &v : variables)
      out << ',' << csv_field(v.name) << ',' << csv_field(v.name + "_plot_value");
    for (const auto &q : quantities)
      out << ',' << q;
    out << '\n';
    for (unsigned int r = 0; r < runs.size(); ++r)
      {
        const Run &run = runs[r];
        out << run.name << ',' << run.status << ','
            << run.wall_time;
        for (unsigned int v = 0; v < variables.size(); ++v)
          out << ',' << csv_field(variables[v].values[run.choice[v]]) << ','
              << variables[v].plot_values[run.choice[v]];
        for (const auto &q : quantities)
          {
            const auto it = values[r].find(q);
            out << ',' << (it == values[r].end() ? "" : it->second);
          }
        out << '\n';
      }
    write_atomically((fs::path(directory) / "study.csv").string(), out.str());
    std::cout << "study " << name << ": " << (fs::path(directory) / "study.csv").string() << std::endl;
  }


  // history.png and summary.png by scripts/anvil_study_plot.py (beside the
  // executable, like the runs' own anvil_plot.py).
  void Study::write_plots() const
  {
    std::string arguments = shell_quote(directory);
    for (const auto &v : variables)
      arguments += " --label " + shell_quote(v.name + "=" + v.label);
    if (!history_file.empty())
      {
        std::ostringstream scale;
        scale << std::setprecision(17) << history_scale;
        arguments += " --history " + shell_quote(history_file + ":" + history_column) + " --scale " +
                     scale.str() + " --history-label " + shell_quote(history_label);
      }
    std::string message;
    const bool  ok = run_python_script("anvil_study_plot.py", arguments, directory + "/plots.log", message);
    std::cout << "study " << name << ": " << (ok ? "" : "plots skipped: ") << message << std::endl;
  }


  int Study::main(const std::vector<std::string> &args)
  {
    std::string  study_file;
    unsigned int jobs       = 0;
    bool         check_only = false;
    for (unsigned int i = 1; i < args.size(); ++i)
      {
        if (args[i] == "--check")
          check_only = true;
        else if (args[i] == "--jobs" && i + 1 < args.size())
          {
            const std::string n = args[++i];
            if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos || std::stoul(n) == 0 ||
                n.size() > 4)
              {
                std::cerr << "anvil: error: --jobs '" << n << "': expected a positive integer" << std::endl;
                return 2;
              }
            jobs = std::stoul(n);
          }
        else if (study_file.empty() && !args[i].empty() && args[i][0] != '-')
          study_file = args[i];
        else
          {
            std::cerr << "anvil: error: --study: unexpected argument '" << args[i]
                      << "' (usage: anvil --study STUDY.prm [--jobs N] [--check])" << std::endl;
            return 2;
          }
      }
    if (study_file.empty())
      {
        std::cerr << "anvil: error: --study needs a study file (usage: anvil --study STUDY.prm [--jobs N])"
                  << std::endl;
        return 2;
      }
    if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_RANK") != nullptr)
      {
        std::cerr << "anvil: error: --study starts its runs itself: run it without mpirun and set "
                     "'Processes per run' in the study file"
                  << std::endl;
        return 2;
      }
    try
      {
        Study study(study_file);
        if (check_only)
          {
            study.validate();
            std::cout << "study " << study.name << ": " << study.runs.size() << " runs of "
                      << study.base_scene << " parse" << std::endl;
            return 0;
          }
        return study.run(jobs);
      }
    catch (const InputError &e)
      {
        std::cerr << "anvil: error: " << e.what() << std::endl;
        return 2;
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::cerr << "anvil: error: " << one_line_message(e) << std::endl;
        return 1;
      }
    catch (const std::exception &e)
      {
        std::cerr << "anvil: error: " << e.what() << std::endl;
        return 1;
      }
  }
} // namespace anvil
