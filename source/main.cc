/**
 * @file
 * anvil SCENE.prm | --help | --print-parameters
 */
#include <anvil/material_model/material_point_driver.h>
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/mpi.h>

#include <iostream>

namespace
{
  const char *usage =
    "Usage: anvil SCENE.prm            run a scene (mpirun -np N anvil SCENE.prm runs it distributed)\n"
    "       anvil --check SCENE.prm    read the scene and build its mesh, contact surfaces and boundary conditions; run nothing\n"
    "       anvil --material-point DRIVER.prm   drive one material point through a deformation path (no mesh), write CSV\n"
    "       anvil --print-parameters   print every parameter with default, pattern, documentation and units\n"
    "       anvil --print-parameters --material-point   the same for driver files\n"
    "       anvil --help               this text\n"
    "Exit status: 0 success, 2 bad input, 3 numerical failure, 1 other errors.\n";
}

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const std::vector<std::string> args(argv + 1, argv + argc);

  const bool check_only = args.size() == 2 && args[0] == "--check";
  const bool driver     = args.size() == 2 && args[0] == "--material-point";
  if (args.size() == 2 && args[0] == "--print-parameters" && args[1] == "--material-point")
    {
      if (root)
        {
          dealii::ParameterHandler prm;
          anvil::MaterialModel::MaterialPointDriver::declare_parameters(prm);
          prm.print_parameters(std::cout,
                               dealii::ParameterHandler::OutputStyle::PRM |
                                 dealii::ParameterHandler::OutputStyle::KeepDeclarationOrder);
        }
      return 0;
    }
  if (args.size() != 1 && !check_only && !driver)
    {
      if (root)
        std::cerr << "anvil: error: expected exactly one argument\n" << usage;
      return 2;
    }
  if (args[0] == "--help" || args[0] == "-h")
    {
      if (root)
        std::cout << usage;
      return 0;
    }
  if (args[0] == "--print-parameters")
    {
      if (root)
        anvil::Simulator::print_parameters(std::cout);
      return 0;
    }
  if (!check_only && !driver && !args[0].empty() && args[0][0] == '-')
    {
      if (root)
        std::cerr << "anvil: error: unknown option '" << args[0] << "'\n" << usage;
      return 2;
    }

  // Input errors and numerical failures arise on every rank together (they
  // follow from replicated input or global reductions), so every rank can
  // return; anything else aborts the whole job rather than leaving ranks
  // waiting in a collective.
  try
    {
      if (driver)
        {
          // One material point: rank 0 alone does the work.
          if (root)
            {
              anvil::MaterialModel::MaterialPointDriver d(args.back());
              std::cout << "anvil: material point written to " << d.run() << std::endl;
            }
          return 0;
        }
      anvil::Simulator simulator(args.back(), MPI_COMM_WORLD);
      if (check_only)
        simulator.check();
      else
        simulator.run();
    }
  catch (const anvil::InputError &e)
    {
      if (root)
        std::cerr << "anvil: error: " << e.what() << std::endl;
      return 2;
    }
  catch (const anvil::NumericalFailure &e)
    {
      if (root)
        std::cerr << "anvil: error: " << e.what() << std::endl;
      return 3;
    }
  catch (const dealii::ExceptionBase &e)
    {
      std::cerr << "anvil: error: " << anvil::one_line_message(e) << std::endl;
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  catch (const std::exception &e)
    {
      std::cerr << "anvil: error: " << e.what() << std::endl;
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  return 0;
}
