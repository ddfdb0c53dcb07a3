/**
 * @file
 * The rigid bodies of a scene as one family: mass properties from the mesh,
 * the motion of each body from the resultant of its nodal forces and the
 * reactions of analytic contact shapes, the nodes' velocities that keep it
 * rigid, rigid_NAME.csv, and its part of a checkpoint.
 */
#pragma once

#include <anvil/rigid_body/rigid_body.h>
#include <anvil/simulator/force_contributor.h>

#include <deal.II/fe/fe_system.h>

namespace anvil::RigidBody
{
  class RigidBodies : public ForceContributor
  {
  public:
    /** @p rigid_dof: the Simulator's mask of the owned dofs of rigid bodies
        (set here, read by the nodal updates); @p inactive: per body,
        whether a stage took it out of the analysis. */
    RigidBodies(Simulator                        &simulator,
                const dealii::FESystem<3>        &fe,
                VectorType                       &velocity,
                std::vector<unsigned char>       &rigid_dof,
                const std::vector<unsigned char> &inactive);

    std::string name() const override
    {
      return "rigid bodies";
    }
    bool empty() const override
    {
      return n_rigid == 0;
    }
    /** Mass, centre of mass and inertia from the mesh, the owned nodes and
        their initial velocity V + omega x (X - c). */
    void   setup() override;
    /** Rigid bodies carry no element forces and do not limit the step. */
    bool has_forces() const override
    {
      return false;
    }
    double add_forces(double) override
    {
      return 1e300;
    }
    /** The resultant force and torque about the centre, the body's motion
        to n+1/2 and every node's velocity to its rigid placement at n+1. */
    void   update_velocity(double dt_previous, double dt, OwnMotion &motion) override;
    void   add_kinetic_energy(double &kinetic) const override;
    /** A rigid body's momentum is M V at time n (its nodal masses need not
        add up to M when the mass is given). */
    void   add_momentum(double dt, std::vector<double> &momentum) const override;
    std::string describe() const override;
    void   write_history(double t, double dt) override;
    void serialize(StateArchive &ar) override;

    /** The reactions of the analytic contact shapes on body @p b this step
        (replicated on every rank), zeroed before the contact pairs add
        theirs. */
    void clear_shape_reactions();
    void add_shape_reaction(unsigned int b, const dealii::Tensor<1, 3> &force,
                            const dealii::Tensor<1, 3> &torque);

    /** Stop the bodies a stage takes out (held where they are); returns
        their kinetic energy, printed when @p report. */
    double remove_inactive(bool report);

  private:
    const dealii::FESystem<3>        &fe;
    VectorType                       &velocity;
    std::vector<unsigned char>       &rigid_dof;
    const std::vector<unsigned char> &inactive;
    unsigned int                      n_rigid = 0;
    /** Per body: its owned nodes (local x-dof index, reference position);
        empty for deformable bodies. */
    std::vector<std::vector<std::pair<unsigned int, dealii::Point<3>>>> nodes;
    std::vector<dealii::Tensor<1, 3>> shape_force, shape_torque;
  };
} // namespace anvil::RigidBody
