/**
 * @file
 * Symmetric node-to-segment penalty contact between two deformable bodies
 * (seed section 4.3, steps (1)-(5) and (7)).
 */
#pragma once

#include <anvil/utilities/state_archive.h>

#include <anvil/rigid_body/rigid_body.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace anvil::Contact
{
  /**
   * A surface of quadrilateral segments (element faces on a body's
   * boundary) over a list of surface nodes.
   */
  struct Surface
  {
    /** Nodes (indices into the pair's node list) of each segment, cyclic,
        ordered so that (x1-x0) x (x3-x0) points out of the body. */
    std::vector<std::array<unsigned int, 4>> segments;
    /** K A^2 / V of each segment's element (seed Eq. (59) without f).
        Units: N/m. */
    std::vector<double> stiffness;
    /** Thickness V / A of each segment's element: the deepest penetration
        accepted as contact. Units: m. */
    std::vector<double> depth;
    /** Scene-wide id of each segment's element, and whether the segment
        still takes part (its element has not been eroded). */
    std::vector<unsigned long> element;
    std::vector<bool>          active;
    /** Segments around each node of the pair's node list. */
    std::vector<std::vector<unsigned int>> node_segments;
    /** The pair's nodes on this surface. */
    std::vector<unsigned int> nodes;
    /** Per pair node: mean stiffness and thickness of this surface's
        segments around it (the slave side's contact stiffness against a
        rigid surface). */
    std::vector<double> node_stiffness, node_depth;
    /** Whether the surface belongs to a rigid body. */
    bool rigid = false;
  };

  /** The placement of a rigid body's analytic contact shape. */
  struct AnalyticSurface
  {
    const RigidBody::Shape *shape = nullptr;
    dealii::Point<3>        centre, reference_centre;
    dealii::Tensor<2, 3>    rotation;
    dealii::Tensor<1, 3>    velocity, angular_velocity;
  };

  /** One segment as the simulator hands it over, with global dof indices. */
  struct SegmentDescription
  {
    std::array<unsigned long, 4> x_dof;
    std::array<double, 12>       reference_position;
    double                       stiffness;
    double                       depth;
    /** Scene-wide id of the segment's element. */
    unsigned long element = 0;
  };

  /** What a contact evaluation reports. */
  struct ContactResult
  {
    /** Sum of the contact forces on the first body's nodes. Units: N. */
    std::array<double, 3> force_on_first = {{0, 0, 0}};
    /** Deepest penetration found in either pass. Units: m. */
    double max_penetration = 0;
    /** Energy stored in the penalty springs, 1/2 k l^2. Units: J. */
    double energy = 0;
    /** Work done this step against the friction forces (dissipated, or
        stored in sticking tangential springs), >= 0 for sliding, and
        dissipated by the normal damping. Units: J. */
    double friction_work = 0;
    /** Sum of the friction forces on the first body's nodes. Units: N. */
    std::array<double, 3> friction_on_first = {{0, 0, 0}};
    /** Resultant force and torque (about the body's centre) on a rigid
        body's analytic shape. Units: N, N m. */
    dealii::Tensor<1, 3> shape_force, shape_torque;
    /** Number of active slave nodes (both passes). */
    unsigned int n_active = 0;
  };

  /**
   * A contact pair: each body's surface is master for the other's nodes
   * (the symmetric penalty method). The pair's data are replicated on every
   * rank: every rank evaluates the whole pair on the same gathered
   * positions, in an order fixed by the reference coordinates, and keeps
   * the forces of the nodes it owns. The result therefore does not depend
   * on the number of processes.
   */
  class PenaltyContact
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &name);

    /** Everything a step changes (checkpoints): surfaces (erosion),
        friction forces and the search trees as last built. */
    void serialize(StateArchive &ar);

    /** Build the replicated surfaces from all ranks' segments. */
    void setup(const std::vector<SegmentDescription> &first,
               const std::vector<SegmentDescription> &second);

    /** Take the faces of the eroded elements @p ids (sorted) out of the
        pair: an eroded element leaves contact. */
    void deactivate_elements(const std::vector<unsigned long> &ids);

    /** Global x-dof indices of the pair's nodes, in the pair's order. */
    const std::vector<unsigned long> &node_dofs() const
    {
      return dofs;
    }

    /**
     * Evaluate both passes at positions @p x (3 per pair node) and add the
     * contact forces to @p f (3 per pair node). With friction, @p v are the
     * velocities that brought the nodes to @p x over the step @p dt (the
     * slip of the contact point is (v_slave - v_master) dt, tangential);
     * the tangential forces are the pair's state from step to step.
     */
    ContactResult compute_forces(const std::vector<double> &x,
                                 const std::vector<double> &v,
                                 double                     dt,
                                 std::vector<double>       &f);

    /** Whether the pair needs velocities (friction or damping). */
    bool needs_velocities() const
    {
      return static_friction > 0 || dynamic_friction > 0 || normal_damping > 0;
    }

    /** Mark surface @p s (0: first body) as a rigid body's. */
    void set_rigid(const unsigned int s, const bool rigid)
    {
      surface[s].rigid = rigid;
    }

    /** Let surface @p s be the analytic shape @p a (placed anew each
        step) instead of its mesh faces. */
    void set_analytic(const unsigned int s, const AnalyticSurface &a)
    {
      analytic[s] = a;
    }
    bool has_analytic(const unsigned int s) const
    {
      return analytic[s].shape != nullptr;
    }

    /**
     * Largest k / m of the pair's penalty springs over the slave nodes of
     * both passes, with m the slave node's lumped mass: the square of the
     * highest frequency the springs add to a node. Needs the node masses.
     */
    double max_spring_frequency_squared() const;

    /** Lumped masses of the pair's nodes (for the normal damping). */
    void set_node_masses(const std::vector<double> &masses)
    {
      node_mass = masses;
    }

    std::string  name;
    std::string  first_body, second_body;
    double       penalty_factor = 0.1;
    bool         symmetric      = true;
    /** Coulomb friction, seed Eq. (62): mu = mu_d + (mu_s - mu_d)
        exp(-C |v_slip|). */
    double static_friction = 0, dynamic_friction = 0, friction_decay = 0;
    /** Viscous damping of the normal penalty spring, as a fraction of its
        critical damping 2 sqrt(k m_slave) (LS-DYNA's VDC). */
    double normal_damping = 0;

  private:
    /** The search structure over one surface's master nodes (an R-tree of
        their positions when it was built), kept from step to step. */
    struct SearchTree;

    /** One pass: nodes of @p slave against segments of @p master. */
    void pass(const Surface             &slave,
              const Surface             &master,
              SearchTree                &search,
              const std::vector<double> &x,
              const std::vector<double> &v,
              double                     dt,
              std::vector<double>       &f,
              bool                       slave_is_first,
              std::vector<double>       &tangential_force,
              ContactResult             &result) const;

    std::vector<unsigned long> dofs;
    std::vector<bool>          on_first;
    Surface                    surface[2];
    /** Per pass, the friction force (3 per pair node) of the last step;
        zero for nodes not in contact. */
    std::vector<double> tangential_force[2];
    std::vector<double> node_mass;
    /** Work arrays of a pass (kept, so that a step allocates nothing):
        the tangential forces of the previous step, and slave normals. */
    mutable std::vector<double> previous_tangential_force;
    AnalyticSurface     analytic[2];
    std::shared_ptr<SearchTree> search[2];

    /** The slave nodes of @p slave against the analytic shape @p a. */
    void analytic_pass(const Surface             &slave,
                       const AnalyticSurface     &a,
                       const std::vector<double> &x,
                       const std::vector<double> &v,
                       double                     dt,
                       std::vector<double>       &f,
                       bool                       slave_is_first,
                       std::vector<double>       &tangential_force,
                       ContactResult             &result) const;
  };
} // namespace anvil::Contact
