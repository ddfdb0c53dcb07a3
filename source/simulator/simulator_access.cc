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
    return simulator.parameters.scene_file;
  }

  const std::string &SimulatorAccess::get_output_directory() const
  {
    return simulator.parameters.output_directory;
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
    for (unsigned int b = 0; b < simulator.bodies.size(); ++b)
      if (simulator.bodies[b].name == name)
        return b;
    AssertThrow(false, dealii::ExcMessage("no body is named '" + name + "' (the scene's parsing checks names)"));
    return 0;
  }

  const dealii::Tensor<1, 3> &SimulatorAccess::get_gravity() const
  {
    return simulator.constraints->get_gravity();
  }

  const dealii::parallel::fullydistributed::Triangulation<3> &SimulatorAccess::get_triangulation() const
  {
    return simulator.triangulation;
  }

  const dealii::DoFHandler<3> &SimulatorAccess::get_dof_handler() const
  {
    return simulator.dof_handler;
  }

  unsigned int SimulatorAccess::element_id(const unsigned int c) const
  {
    return simulator.element_id[c];
  }

  unsigned int SimulatorAccess::halvings_during_run(const unsigned int e) const
  {
    return e < simulator.halvings_during_run.size() ? simulator.halvings_during_run[e] : 0;
  }

  bool SimulatorAccess::is_hanging(const unsigned int i) const
  {
    return simulator.hanging.is_hanging(i);
  }

  std::vector<std::pair<unsigned int, double>> SimulatorAccess::hanging_masters(const unsigned int i) const
  {
    return simulator.hanging.masters_of(i);
  }

  double SimulatorAccess::node_mass(const unsigned int i) const
  {
    return simulator.hanging.is_hanging(i) ? simulator.hanging_mass[i] : simulator.mass.local_element(i);
  }

  bool SimulatorAccess::adapts_during_run() const
  {
    return simulator.parameters.adapt_interval > 0;
  }


  unsigned int SimulatorAccess::scene_vertex_index(const unsigned int v) const
  {
    return simulator.scene_vertex[v];
  }

  const std::vector<Element::ElementGroup> &SimulatorAccess::get_element_groups() const
  {
    return simulator.solids->groups();
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


  double SimulatorAccess::get_time_step_factor() const
  {
    return simulator.parameters.time_step_factor;
  }

  unsigned int SimulatorAccess::get_step_number() const
  {
    return simulator.step_number;
  }

  Energies &SimulatorAccess::get_energies() const
  {
    return simulator.energies;
  }

  double SimulatorAccess::get_initial_energy() const
  {
    return simulator.balance.initial_energy;
  }

  double SimulatorAccess::get_balance_error() const
  {
    return simulator.balance.balance_error;
  }

  const std::string &SimulatorAccess::get_scene_name() const
  {
    return simulator.parameters.scene_name;
  }

  const SummarySubjects &SimulatorAccess::get_summary_subjects() const
  {
    return simulator.parameters.summary_subjects;
  }

  RunSummary &SimulatorAccess::get_summary() const
  {
    return simulator.summary;
  }

  const std::vector<Probe> &SimulatorAccess::get_probes() const
  {
    return simulator.probes;
  }

  void SimulatorAccess::record_probe_summary(const std::vector<double> &probe_values) const
  {
    simulator.record_probe_summary(probe_values);
  }

  const ConstraintsAndLoads &SimulatorAccess::get_constraints() const
  {
    return *simulator.constraints;
  }

  const std::vector<unsigned char> &SimulatorAccess::get_dof_body() const
  {
    return simulator.dof_body;
  }

  const std::vector<unsigned char> &SimulatorAccess::get_dof_component() const
  {
    return simulator.dof_component;
  }

  const std::vector<std::uint64_t> &SimulatorAccess::get_dof_keys() const
  {
    return simulator.dof_key;
  }

  const std::vector<unsigned char> &SimulatorAccess::get_rigid_dof() const
  {
    return simulator.rigid_dof;
  }


  bool SimulatorAccess::is_held(const unsigned int i) const
  {
    return simulator.constraints->is_held(i);
  }

  double SimulatorAccess::velocity_at_n(const unsigned int i, const double dt) const
  {
    const auto &constraints = *simulator.constraints;
    if (constraints.is_held(i))
      return constraints.held_velocity(i);
    const double v = simulator.velocity.local_element(i);
    if (simulator.hanging.is_hanging(i))
      return v;
    return v - 0.5 * dt * (simulator.force.local_element(i) + constraints.damping_force(i)) /
                 simulator.mass.local_element(i);
  }

  const std::vector<unsigned int> &SimulatorAccess::get_group_body() const
  {
    return simulator.solids->group_body();
  }

  const dealii::FESystem<3> &SimulatorAccess::get_fe() const
  {
    return simulator.fe;
  }

  unsigned long SimulatorAccess::n_eroded_elements() const
  {
    return simulator.solids->n_eroded();
  }

  std::vector<std::string> &SimulatorAccess::get_erosion_rows() const
  {
    return simulator.solids->erosion_rows();
  }

  const std::vector<ForceContributor *> &SimulatorAccess::get_families() const
  {
    return simulator.contributors();
  }

  const std::string &SimulatorAccess::contact_pair_name(const unsigned int p) const
  {
    return simulator.contact->pair_name(p);
  }

  bool SimulatorAccess::has_contact() const
  {
    return !simulator.contact->empty();
  }

  bool SimulatorAccess::plots_requested() const
  {
    return simulator.parameters.make_plots;
  }

  bool SimulatorAccess::output_compressed() const
  {
    return simulator.parameters.compress_output;
  }

  void SimulatorAccess::record_output(const std::string &name) const
  {
    simulator.record_output(name);
  }
} // namespace anvil
