/**
 * @file
 * Rigid bodies: a body of material `rigid` moves as one. Its motion is either
 * prescribed (constant velocity: fixed or moving walls) or free, integrated
 * from the contact and gravity forces on it with the same central
 * differences as the nodes.
 */
#pragma once

#include <anvil/utilities/state_archive.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <string>
#include <vector>

namespace anvil::RigidBody
{
  /**
   * An analytic contact surface carried by a rigid body, in the body's
   * reference configuration: contact against it is exact (no faceting).
   * Its outward normal points into the space the other body may occupy.
   */
  struct Shape
  {
    enum class Type
    {
      mesh,
      sphere,
      cylinder,
      plane
    } type = Type::mesh;
    /** Sphere and cylinder: centre (a point on the axis); plane: a point. */
    dealii::Point<3> point;
    /** Cylinder: axis; plane: outward normal (unit). */
    dealii::Tensor<1, 3> direction;
    double               radius = 0;

    /**
     * Signed distance of @p x from the surface in the current placement
     * (centre @p c, rotation @p R of the reference shape about the
     * reference centre of mass @p c0), and the outward unit normal there.
     * Negative: penetration.
     */
    double gap(const dealii::Point<3>     &x,
               const dealii::Point<3>     &c,
               const dealii::Tensor<2, 3> &R,
               const dealii::Point<3>     &c0,
               dealii::Tensor<1, 3>       &normal) const;
  };


  /**
   * The motion of one rigid body (Goldstein, Classical Mechanics, ch. 4-5):
   *
   *   M dV/dt = F,    d(I omega)/dt = T,   I = R I_0 R^T,
   *
   * with F and T the resultant force and torque about the centre of mass.
   * Central differences as for the nodes: V and the angular momentum
   * L = I omega at half steps, the centre x_c and the rotation R at integer
   * steps; R advances by the exact rotation exp(dt [omega]) (Rodrigues), so
   * the body stays rigid to round-off. Constrained components of V and
   * omega keep their initial values.
   */
  class Motion
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm, const std::string &body);

    /** Prescribed motion (the default) or free dynamics. */
    bool free = false;
    /** Constrained translations (x, y, z) and rotations (about x, y, z). */
    std::array<bool, 6> constrained = {{false, false, false, false, false, false}};
    dealii::Tensor<1, 3> initial_angular_velocity;
    /** Given mass (0: from the mesh and density) and inertia about the
        centre of mass, [Ixx, Iyy, Izz, Ixy, Iyz, Ixz] (empty: from the
        mesh). */
    double              given_mass = 0;
    std::vector<double> given_inertia;
    Shape               shape;

    /** Set the mass properties (reference centre c0, inertia I0 about it)
        and the initial state. */
    void initialize(double                      mass,
                    const dealii::Point<3>     &centre,
                    const dealii::Tensor<2, 3> &inertia,
                    const dealii::Tensor<1, 3> &velocity);

    /**
     * Advance the half-step velocities with the force and torque of time n
     * over (dt_previous + dt) / 2, then the placement over dt. Returns the
     * kinetic energy at time n in the form of the variable-step energy
     * identity (doc/theory.md), 1/2 V^- . (M V^- + dt_previous F_tot) plus
     * its rotational counterpart, where F_tot includes the reactions of
     * prescribed motion and constraints. The work those reactions did over
     * the last step (trapezoidal rule) is left in last_reaction_work.
     */
    double advance(const dealii::Tensor<1, 3> &force,
                   const dealii::Tensor<1, 3> &torque,
                   double                      dt_previous,
                   double                      dt);

    /** Current position of the material point with reference position
        @p X (after advance(): at time n+1). */
    dealii::Point<3> placement(const dealii::Point<3> &X) const
    {
      return centre + rotation * (X - reference_centre);
    }
    /** Velocity of the body at the current point @p x (half step). */
    dealii::Tensor<1, 3> velocity_at(const dealii::Point<3> &x, const dealii::Point<3> &c) const
    {
      return velocity + cross_product_3d(angular_velocity, x - c);
    }

    /** 1/2 M V.V + 1/2 omega . I omega of the current (half-step)
        velocities, with the reference inertia. */
    double velocity_kinetic_energy() const
    {
      return 0.5 * (mass * (velocity * velocity) + angular_velocity * (reference_inertia * angular_velocity));
    }

    double                mass = 0;
    dealii::Point<3>      reference_centre, centre, previous_centre;
    dealii::Tensor<2, 3>  reference_inertia, rotation, previous_rotation;
    dealii::Tensor<1, 3>  velocity, angular_velocity, angular_momentum;
    dealii::Tensor<1, 3>  last_force;
    double                kinetic_energy = 0;
    /** Reactions of prescribed motion and constraints at time n (force and
        torque about the centre), and their work over the last step. */
    dealii::Tensor<1, 3>  reaction_force, reaction_torque;
    double                last_reaction_work = 0;

  private:
    dealii::Tensor<1, 3> initial_velocity;

  public:
    /** Everything the motion changes (checkpoints). */
    void serialize(StateArchive &ar)
    {
      ar &mass &reference_centre &centre &previous_centre &reference_inertia &rotation &previous_rotation
        &velocity &angular_velocity &angular_momentum &last_force &kinetic_energy &reaction_force
          &reaction_torque &last_reaction_work;
    }
  };
} // namespace anvil::RigidBody
