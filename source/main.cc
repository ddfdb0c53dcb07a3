/**
 * @file
 * anvil SCENE.prm [--set PATH=VALUE]... | --study STUDY.prm | --help | --print-parameters
 */
#include <anvil/deck/deck.h>
#include <anvil/material_model/material_point_driver.h>
#include <anvil/mesh/keyword_file.h>
#include <anvil/simulator/simulator.h>
#include <anvil/study/study.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/output_files.h>

#include <deal.II/base/mpi.h>

#include <boost/program_options.hpp>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <iostream>

namespace
{
  const char *usage =
    "Usage: anvil SCENE.prm            run a scene (mpirun -np N anvil SCENE.prm runs it distributed)\n"
    "       anvil SCENE.prm --set 'SUBSECTION/.../ENTRY=VALUE' ...   run a scene with entries changed\n"
    "       anvil --study STUDY.prm [--jobs N]   run a parameter study (its runs, study.csv, plots)\n"
    "       anvil --study STUDY.prm --check      check a study file and every run's entries; run nothing\n"
    "       anvil --resume SCENE.prm   continue a run from the checkpoint in its output directory\n"
    "       anvil --resume-from DIR SCENE.prm   a new stage: SCENE from the state in checkpoint DIR\n"
    "       anvil --print-cost SCENE.prm   estimate steps, element-cycles and wall time; run nothing\n"
    "       anvil --check SCENE.prm    read the scene and build its mesh, contact surfaces and boundary conditions; run nothing\n"
    "       anvil --check A.prm B.k ...   the same for each scene or deck in turn; exit status of the first that fails\n"
    "       anvil DECK.k | DECK.inp    run an LS-DYNA keyword deck or a whole ABAQUS/Explicit deck as it comes\n"
    "       anvil --translate DECK     print the scene a deck translates to (its mesh stays in the deck)\n"
    "       anvil DECK.k --case ID     run case ID of a deck with *CASE blocks\n"
    "       anvil --material-point DRIVER.prm   drive one material point through a deformation path (no mesh), write CSV\n"
    "       anvil --print-parameters   print every parameter with default, pattern, documentation and units\n"
    "       anvil --print-parameters --material-point   the same for driver files\n"
    "       anvil --print-parameters --study            the same for study files\n"
    "       anvil --help               this text\n"
    "       anvil --version            Anvil's and deal.II's versions\n"
    "The options may come in any order (anvil SCENE.prm --check).\n"
    "Exit status: 0 success, 2 bad input, 3 numerical failure, 4 results could not be written,\n"
    "             5 stopped by SIGTERM/SIGINT after writing a checkpoint, 1 other errors.\n";
}

namespace
{
  namespace po = boost::program_options;

  /** What the command line asks for. */
  struct CommandLine
  {
    std::string              file, resume_from, mode, error;
    std::vector<std::string> files, overrides; // files: --check takes several
    long                     case_id = 0;
    bool help = false, version = false, print_parameters = false, check = false, driver = false, resume = false,
         cost = false, translate = false;
  };

  /**
   * The command line by Boost.Program_options: the options in any order
   * (anvil SCENE.prm --check), '--set' as often as needed, at most one mode
   * (--check, --material-point, --resume, --resume-from, --print-cost,
   * --translate) and one file. A mistake becomes CommandLine::error (one
   * line; printed once MPI says which rank is the root).
   */
  CommandLine parse_command_line(const std::vector<std::string> &args)
  {
    CommandLine             c;
    po::options_description options;
    options.add_options()("help,h", "")("version", "")("print-parameters", "")("check", "")("material-point", "")(
      "resume", "")("resume-from", po::value<std::string>(), "")("print-cost", "")("translate", "")(
      "case", po::value<long>(), "")("set", po::value<std::vector<std::string>>(), "")(
      "file", po::value<std::vector<std::string>>(), "");
    po::positional_options_description positional;
    positional.add("file", -1);
    po::variables_map vm;
    try
      {
        // Unix style without guessing abbreviations ('--che' is a mistake,
        // not --check) and without '-' as a file name.
        const auto style = (po::command_line_style::unix_style ^ po::command_line_style::allow_guessing) &
                           ~po::command_line_style::allow_sticky;
        po::store(po::command_line_parser(args).options(options).positional(positional).style(style).run(), vm);
        po::notify(vm);
      }
    catch (const po::error &e)
      {
        c.error = e.what();
        return c;
      }
    c.help             = vm.count("help") > 0;
    c.version          = vm.count("version") > 0;
    c.print_parameters = vm.count("print-parameters") > 0;
    c.check            = vm.count("check") > 0;
    c.driver           = vm.count("material-point") > 0;
    c.resume           = vm.count("resume") > 0;
    c.cost             = vm.count("print-cost") > 0;
    c.translate        = vm.count("translate") > 0;
    if (vm.count("resume-from"))
      c.resume_from = vm["resume-from"].as<std::string>();
    if (vm.count("set"))
      c.overrides = vm["set"].as<std::vector<std::string>>();
    if (vm.count("case"))
      {
        c.case_id = vm["case"].as<long>();
        if (c.case_id <= 0)
          c.error = "option '--case' needs the positive id of a *CASE of the deck";
      }
    if (vm.count("file"))
      {
        c.files = vm["file"].as<std::vector<std::string>>();
        if (c.files.size() > 1 && !c.check)
          c.error = "expected one scene file, got '" + c.files[0] + "' and '" + c.files[1] +
                    "' (only --check takes several)";
        c.file = c.files[0];
      }
    for (const char *mode : {"check", "material-point", "resume", "resume-from", "print-cost", "translate"})
      if (vm.count(mode))
        {
          if (!c.mode.empty() && c.error.empty())
            c.error = "options '--" + c.mode + "' and '--" + mode + "' cannot be combined";
          c.mode = mode;
        }
    return c;
  }
} // namespace


namespace
{
  /**
   * Run, check, translate or cost one scene or deck as the command line
   * asks; the exit status.
   */
  int run_file(const CommandLine &cl, const std::string &file, const bool root)
  {
    const std::string               resume_from = cl.resume_from;
    const std::vector<std::string> &overrides   = cl.overrides;
    const bool driver = cl.driver, resume = cl.resume, cost = cl.cost, translate = cl.translate,
               check_only = cl.check;
    // Input errors and numerical failures arise on every rank together (they
    // follow from replicated input or global reductions), so every rank can
    // return; anything else aborts the whole job rather than leaving ranks
    // waiting in a collective.
    // (Rank 0's one error line, and the exit status.)
    const auto error = [root](const std::string &message, const int status) {
      if (root)
        std::cerr << "anvil: error: " << anvil::printable_excerpt(message) << std::endl;
      return status;
    };
    try
      {
        if (translate)
          {
            if (!anvil::Deck::is_deck(file))
              throw anvil::InputError(file + ": --translate takes a deck (.k, .key, .dyn: LS-DYNA keyword; "
                                      ".inp: ABAQUS)");
            const auto t = anvil::Deck::translate(file, file);
            if (root)
              {
                if (!t.ignored.empty())
                  std::cout << "# Not translated (output or settings Anvil answers its own way): " << t.ignored << "\n";
                if (!t.differs.empty())
                  std::cout << "# Where Anvil's model differs from the deck's code: " << t.differs << "\n";
                std::cout << t.text << std::flush;
              }
            return 0;
          }
        if (driver)
          {
            // One material point: rank 0 alone does the work.
            if (root)
              {
                anvil::MaterialModel::MaterialPointDriver d(file);
                std::cout << "anvil: material point written to " << d.run() << std::endl;
              }
            return 0;
          }
        if (cost)
          anvil::Simulator(file, MPI_COMM_WORLD, overrides).print_cost();
        else if (!resume_from.empty())
          anvil::run_simulator(file, MPI_COMM_WORLD, overrides, false, resume_from);
        else
          anvil::run_scene_with_stages(file, overrides, MPI_COMM_WORLD, resume, check_only);
      }
    catch (const anvil::InputError &e)
      {
        return error(e.what(), 2);
      }
    catch (const anvil::NumericalFailure &e)
      {
        return error(e.what(), 3);
      }
    catch (const anvil::Interrupted &e)
      {
        if (root)
          std::cerr << "anvil: " << e.what() << std::endl;
        return 5;
      }
    catch (const anvil::OutputError &e)
      {
        // Histories are rank 0's: the other ranks learn of the failure in a
        // collective and return with it; a frame or summary that failed on
        // one rank alone takes the job down.
        return error(e.what(), 4);
      }
    catch (const dealii::ExceptionBase &e)
      {
        std::cerr << "anvil: error: " << anvil::printable_excerpt(anvil::one_line_message(e)) << std::endl;
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
    catch (const std::exception &e)
      {
        std::cerr << "anvil: error: " << anvil::printable_excerpt(e.what()) << std::endl;
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
    return 0;
  }
} // namespace


int main(int argc, char **argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);

  // A study launches its runs as processes of their own (each possibly an
  // MPI job): it never initialises MPI itself, so the runs' mpirun starts
  // from a clean environment.
  if (!args.empty() && args[0] == "--study")
    return anvil::Study::main(args);
  if (args.size() == 2 && args[0] == "--print-parameters" && args[1] == "--study")
    {
      anvil::Study::print_parameters(std::cout);
      return 0;
    }
  const CommandLine cl = parse_command_line(args);

  // Past a file-size limit a write fails (and is reported) instead of the
  // signal killing the run.
  std::signal(SIGXFSZ, SIG_IGN);
  // A run takes SIGTERM and SIGINT as a request to checkpoint and stop,
  // from its very start: one that arrives while MPI starts or the scene is
  // set up is honoured at the first step (a study stops its runs whenever
  // it is stopped itself). Other modes keep the default: they just end.
  const bool running = cl.error.empty() && !(cl.check || cl.cost || cl.help || cl.version ||
                                             cl.print_parameters || cl.driver || cl.translate);
  if (running)
    anvil::install_stop_handler();
  // Started without mpirun, Open MPI's singleton would first start its
  // daemon (0.2-0.3 s of each '--check' and each small run) for what Anvil
  // never asks of it (spawning processes). A user's own setting stands.
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK"))
    setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // Open MPI's start installs handlers of its own: ours again.
  if (running)
    anvil::install_stop_handler();
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  if (cl.error.empty() && cl.print_parameters)
    {
      if (!cl.file.empty() || !cl.overrides.empty() || (!cl.mode.empty() && cl.mode != "material-point"))
        {
          if (root)
            std::cerr << "anvil: error: --print-parameters takes no scene ('--print-parameters "
                         "--material-point' or '--print-parameters --study' for those files)\n";
          return 2;
        }
      if (root)
        {
          if (cl.driver)
            {
              dealii::ParameterHandler prm;
              anvil::MaterialModel::MaterialPointDriver::declare_parameters(prm);
              prm.print_parameters(std::cout,
                                   dealii::ParameterHandler::OutputStyle::PRM |
                                     dealii::ParameterHandler::OutputStyle::KeepDeclarationOrder);
            }
          else
            anvil::Simulator::print_parameters(std::cout);
        }
      return 0;
    }
  if (cl.error.empty() && cl.version)
    {
      if (root)
        std::cout << "anvil " ANVIL_VERSION " (deal.II " DEAL_II_PACKAGE_VERSION ")\n";
      return 0;
    }
  if (cl.error.empty() && cl.help)
    {
      if (root)
        std::cout << usage;
      return 0;
    }
  if (!cl.error.empty())
    {
      if (root)
        std::cerr << "anvil: error: " << anvil::printable_excerpt(cl.error)
                  << " ('anvil --help' shows the usage)\n";
      return 2;
    }
  const std::string                file = cl.file;
  const std::vector<std::string>  &overrides = cl.overrides;
  anvil::KeywordFile::chosen_case() = cl.case_id;
  if (file.empty() || (cl.driver && !overrides.empty()))
    {
      if (root)
        std::cerr << "anvil: error: "
                  << (file.empty() ? "no scene file given" : "--set applies to scenes, not to --material-point")
                  << " ('anvil --help' shows the usage)\n";
      return 2;
    }
  // '--check' of several files checks each in turn (its own lines, its own
  // error) and exits with the status of the first that failed.
  int status = 0;
  for (const std::string &f : cl.files)
    {
      const int s = run_file(cl, f, root);
      if (status == 0)
        status = s;
    }
  return status;
}
