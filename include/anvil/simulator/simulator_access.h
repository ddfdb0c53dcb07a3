/**
 * @file
 * SimulatorAccess: what a family of the scene (solid bodies, contact,
 * reinforcement, rigid bodies) and a postprocessor may read and change of
 * the Simulator, as ASPECT's SimulatorAccess gives its plugins. The nodal
 * state, the mesh and the energies belong to the Simulator; everything else
 * a family needs it holds itself.
 */
#pragma once

#include <cstdint>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <string>
#include <vector>

namespace anvil
{
  using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

  class Simulator;
  struct Energies;
  struct RunSummary;
  struct SummarySubjects;
  struct Probe;
  class Body;
  class BoundaryCondition;
  class ConstraintsAndLoads;
  class ForceContributor;
  namespace Element
  {
    class ElementGroup;
  }

  class SimulatorAccess
  {
  public:
    explicit SimulatorAccess(Simulator &simulator);
    virtual ~SimulatorAccess() = default;

  protected:
    // The scene
    const std::string &get_scene_file() const;
    const std::string &get_output_directory() const;
    MPI_Comm           get_mpi_communicator() const;
    bool               is_root() const;
    const dealii::ConditionalOStream &get_pcout() const;
    dealii::TimerOutput              &get_timer() const;
    const std::vector<Body>          &get_bodies() const;
    std::vector<Body>                &get_bodies_for_update() const;
    /** Index of the body named @p name (which the scene's parsing made
        sure exists). */
    unsigned int                      body_index(const std::string &name) const;
    const dealii::Tensor<1, 3>       &get_gravity() const;

    // The discretisation and the nodal state (ghost entries included)
    const dealii::parallel::fullydistributed::Triangulation<3> &get_triangulation() const;
    const dealii::DoFHandler<3>                                &get_dof_handler() const;
    const std::vector<Element::ElementGroup>              &get_element_groups() const;
    /** The scene's index of this process's vertex @p v (the triangulation
        numbers the vertices a process holds from 0): the same node on any
        number of processes. */
    unsigned int scene_vertex_index(unsigned int v) const;
    /** The element id of the process's (owned or ghost) cell with local
        active cell index @p c: the same element on any number of
        processes. */
    unsigned int element_id(unsigned int c) const;
    /** How many times the element with id @p e was halved during the run,
        beyond the mesh the run started from (0 where it was not, or is
        coarser). */
    unsigned int halvings_during_run(unsigned int e) const;
    /** Whether the owned or ghost dof with local index @p i hangs (follows
        the coarse face or edge of a refinement interface). */
    bool         is_hanging(unsigned int i) const;
    /** The masters (local indices) and weights of the hanging dof @p i. */
    std::vector<std::pair<unsigned int, double>> hanging_masters(unsigned int i) const;
    /** Whether the mesh is refined and coarsened during the run ('Adapt
        interval'). */
    bool         adapts_during_run() const;
    /** The lumped mass of the owned dof @p i as a contact spring sees it:
        the node's own, also where it hangs (the update gives a hanging
        node's mass to its masters). */
    double       node_mass(unsigned int i) const;
    const VectorType &get_reference_position() const;
    const VectorType &get_position() const;
    const VectorType &get_velocity() const;
    VectorType       &get_force() const;
    VectorType       &get_mass() const;

    // The clock and the energy balance
    double            get_time() const;
    unsigned int      get_step_number() const;
    /** 'Time step safety factor': the step taken over the stable one. */
    double            get_time_step_factor() const;
    Energies         &get_energies() const;

    double            get_initial_energy() const;
    /** The balance error of the last history row: |E_total - E_0 - W_ext|
        over the balance scale. */
    double            get_balance_error() const;

    // The run's figures, outputs and the families
    const std::string &get_scene_name() const;
    RunSummary        &get_summary() const;
    /** The probe and the contact pair summary.csv reports first. */
    const SummarySubjects &get_summary_subjects() const;
    const std::vector<Probe> &get_probes() const;
    /** On rank 0, at each history row: the first probe's displacement for
        the summary and the end criterion. */
    void               record_probe_summary(const std::vector<double> &probe_values) const;
    /** The kinematic constraints and loads: the boundary conditions,
        their held dofs and reactions, mass damping, gravity. */
    const ConstraintsAndLoads &get_constraints() const;
    /** Per owned dof: its body and component, and whether a rigid body's
        (empty: no rigid bodies). */
    const std::vector<unsigned char> &get_dof_body() const;
    const std::vector<unsigned char> &get_dof_component() const;
    const std::vector<unsigned char> &get_rigid_dof() const;
    /** Per owned dof, its key in a checkpoint's tables (the same for any
        partition: 3 scene vertex + component). */
    const std::vector<std::uint64_t> &get_dof_keys() const;
    /** The velocity of the owned dof @p i at the integer time n, the last
        step @p dt after the half step: v^{n+1/2} - dt/2 a^n with the mass
        damping's force part of a^n; a constrained dof's prescribed
        velocity (its reaction is part of a^n), a hanging dof's half-step
        velocity (it has no mass of its own). */
    double velocity_at_n(unsigned int i, double dt) const;
    /** Whether the owned dof @p i is held by a boundary condition. */
    bool   is_held(unsigned int i) const;
    /** The body of each element group. */
    const std::vector<unsigned int> &get_group_body() const;
    const dealii::FESystem<3>        &get_fe() const;
    /** Eroded elements so far (scene-wide), and the rows of erosion.csv
        the step made and no one has written yet. */
    unsigned long                     n_eroded_elements() const;
    std::vector<std::string>         &get_erosion_rows() const;
    /** The families (rigid bodies, reinforcement, contact pairs). */
    const std::vector<ForceContributor *> &get_families() const;
    bool                              has_contact() const;
    /** The name of contact pair @p p (in the order of 'Contact pairs'). */
    const std::string                &contact_pair_name(unsigned int p) const;
    bool                              plots_requested() const;
    /** Whether the VTU fields compress their arrays ('Output compression'). */
    bool                              output_compressed() const;

    /** Note the output file @p name (in the output directory) as this
        run's before writing it (rank 0). */
    void record_output(const std::string &name) const;

  private:
    Simulator &simulator;
  };
} // namespace anvil
