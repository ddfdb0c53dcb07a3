/**
 * @file
 * SimulatorAccess: the Simulator's state as the families and postprocessors
 * see it.
 */
#include <anvil/simulator/simulator.h>
#include <anvil/simulator/simulator_access.h>

namespace anvil
{
  SimulatorAccess::SimulatorAccess(Simulator &simulator)
    : simulator(simulator)
  {}

  const std::string &SimulatorAccess::get_scene_file() const
  {
    return simulator.scene_file;
  }

  const std::string &SimulatorAccess::get_output_directory() const
  {
    return simulator.output_directory;
  }

  MPI_Comm SimulatorAccess::get_mpi_communicator() const
  {
    return simulator.mpi_communicator;
  }

  bool SimulatorAccess::is_root() const
  {
    return dealii::Utilities::MPI::this_mpi_process(simulator.mpi_communicator) == 0;
  }

  const dealii::ConditionalOStream &SimulatorAccess::get_pcout() const
  {
    return simulator.pcout;
  }

  dealii::TimerOutput &SimulatorAccess::get_timer() const
  {
    return *simulator.timer;
  }

  const std::vector<Body> &SimulatorAccess::get_bodies() const
  {
    return simulator.bodies;
  }

  std::vector<Body> &SimulatorAccess::get_bodies_for_update() const
  {
    return simulator.bodies;
  }

  unsigned int SimulatorAccess::body_index(const std::string &name) const
  {
    unsigned int b = 0;
    while (b + 1 < simulator.bodies.size() && simulator.bodies[b].name != name)
      ++b;
    return b;
  }

  const dealii::Tensor<1, 3> &SimulatorAccess::get_gravity() const
  {
    return simulator.gravity;
  }

  const dealii::parallel::distributed::Triangulation<3> &SimulatorAccess::get_triangulation() const
  {
    return simulator.triangulation;
  }

  const dealii::DoFHandler<3> &SimulatorAccess::get_dof_handler() const
  {
    return simulator.dof_handler;
  }

  const std::vector<Element::ElementGroup> &SimulatorAccess::get_element_groups() const
  {
    return simulator.element_groups;
  }

  const VectorType &SimulatorAccess::get_reference_position() const
  {
    return simulator.reference_position;
  }

  const VectorType &SimulatorAccess::get_position() const
  {
    return simulator.position;
  }

  const VectorType &SimulatorAccess::get_velocity() const
  {
    return simulator.velocity;
  }

  VectorType &SimulatorAccess::get_force() const
  {
    return simulator.force;
  }

  VectorType &SimulatorAccess::get_mass() const
  {
    return simulator.mass;
  }

  double SimulatorAccess::get_time() const
  {
    return simulator.time;
  }

  unsigned int SimulatorAccess::get_step_number() const
  {
    return simulator.step_number;
  }

  Energies &SimulatorAccess::get_energies() const
  {
    return simulator.energies;
  }

  void SimulatorAccess::record_output(const std::string &name) const
  {
    simulator.record_output(name);
  }
} // namespace anvil
