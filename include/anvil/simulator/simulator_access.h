/**
 * @file
 * SimulatorAccess: what a family of the scene (solid bodies, contact,
 * reinforcement, rigid bodies) and a postprocessor may read and change of
 * the Simulator, as ASPECT's SimulatorAccess gives its plugins. The nodal
 * state, the mesh and the energies belong to the Simulator; everything else
 * a family needs it holds itself.
 */
#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <string>
#include <vector>

namespace anvil
{
  using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

  class Simulator;
  struct Energies;
  class Body;
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
    const dealii::parallel::distributed::Triangulation<3> &get_triangulation() const;
    const dealii::DoFHandler<3>                           &get_dof_handler() const;
    const std::vector<Element::ElementGroup>              &get_element_groups() const;
    const VectorType &get_reference_position() const;
    const VectorType &get_position() const;
    const VectorType &get_velocity() const;
    VectorType       &get_force() const;
    VectorType       &get_mass() const;

    // The clock and the energy balance
    double            get_time() const;
    unsigned int      get_step_number() const;
    Energies         &get_energies() const;

    /** Note the output file @p name (in the output directory) as this
        run's before writing it (rank 0). */
    void record_output(const std::string &name) const;

  private:
    Simulator &simulator;
  };
} // namespace anvil
