/**
 * @file
 * The contact pairs of a scene as one family: their surfaces (every boundary
 * face of the two bodies), the positions of the pair's nodes (the rank's
 * own and ghost cells', or gathered for a pair that is not distributed), the
 * evaluation by each pair's algorithm (Contact::Algorithm), the forces on
 * the owned nodes, the springs' bound on the step, contact_NAME.csv and the
 * pairs' part of a checkpoint.
 */
#pragma once

#include <anvil/contact/interface.h>
#include <anvil/rigid_body/rigid_bodies.h>
#include <anvil/simulator/force_contributor.h>

#include <array>
#include <memory>

namespace anvil::Contact
{
  class ContactPairs : public ForceContributor
  {
  public:
    /** @p inactive: per pair, whether it involves a body a stage took out
        (then skipped); @p rigid_bodies receives the reactions of analytic
        shapes. */
    ContactPairs(Simulator                               &simulator,
                 std::vector<std::unique_ptr<Algorithm>>  pairs,
                 std::vector<unsigned char>               inactive,
                 RigidBody::RigidBodies                  &rigid_bodies);

    std::string name() const override
    {
      return "contact";
    }
    bool empty() const override
    {
      return pairs.empty();
    }
    void setup() override
    {}
    /** The surfaces: each rank lists the boundary faces of its own cells,
        all ranks then hold the whole surface; the pair nodes' masses. */
    void initialize() override;
    /** Each active pair's node positions (and velocities) to it, its
        evaluation, the forces of the owned nodes. The springs bound the step
        through frequency_squared(), not through the returned value. */
    double add_forces(double dt) override;
    std::string describe() const override;
    /** The penalty pairs' approach (collective, at each history row). */
    void   prepare_history() override;
    void   write_history(double t, double dt) override;
    void   write_summary(std::ostream &out) const override;
    void serialize(StateArchive &ar) override;
    /** Per pair that touched: its deepest penetration, as a share of the
        pressed elements' thickness, and the largest energy its springs
        held, as a share of the initial energy: the penalty's own error. */
    std::string end_of_run_note() const override;

    /** The kinematic pairs' forces at time n (Algorithm::correct()), once
        the next step @p dt is known (0: the run's last call); the other
        forces of time n are complete. */
    void add_kinematic_forces(double dt_previous, double dt);
    bool has_kinematic() const
    {
      return any_kinematic;
    }

    /** The largest k/m of the springs in reach (all pairs), held against
        a quick fall: omega_c^2 of the stable step. */
    double frequency_squared() const
    {
      return contact_frequency_squared;
    }
    /** The magnitude of the last contact force of each own pair node, the
        largest over the pairs, into the x entry of the node in @p nodal
        (a vector of the nodal layout; 'Indicator = contact_pressure'). */
    void nodal_force_magnitudes(VectorType &nodal) const;
    /** Whether a pair names the body @p body. */
    bool names_body(const std::string &body) const
    {
      for (const auto &p : pairs)
        if (p->first_body == body || p->second_body == body)
          return true;
      return false;
    }

    /** The faces of the eroded elements @p ids (sorted, scene-wide) leave
        every pair. */
    void deactivate_elements(const std::vector<unsigned long> &ids);
    /** The pairs of the bodies a stage takes out: their springs' energy
        (returned) leaves with them. */
    double remove_inactive();

    unsigned int n_pairs() const
    {
      return pairs.size();
    }
    const std::string &pair_name(const unsigned int p) const
    {
      return pairs[p]->name;
    }
    const Algorithm &pair(const unsigned int p) const
    {
      return *pairs[p];
    }
    const std::vector<ContactResult> &results() const
    {
      return contact_results;
    }

  private:
    /** Place the analytic shapes of the rigid bodies of pair @p p (at n+1,
        like the positions; their velocities are the half-step ones). */
    void place_analytic_shapes(unsigned int p);
    /** After pair @p p's evaluation: the reaction on its analytic shape,
        the run's maxima. */
    void record_result(unsigned int p);

    std::vector<std::unique_ptr<Algorithm>> pairs;
    std::vector<unsigned char>              inactive;
    RigidBody::RigidBodies                 &rigid_bodies;
    /** Per pair: whether it evaluates each rank's share (distribute()),
        and (pair node, local index of its x dof) of its nodes on the
        rank's own and ghost cells (distributed pairs) and of its own
        nodes; the gather/scatter buffers. */
    std::vector<unsigned char>                                           distributed;
    std::vector<std::vector<std::pair<unsigned int, unsigned int>>> relevant_index, owned_index;
    std::vector<std::vector<double>> positions, velocities, forces;
    /** Per kinematic pair: the other forces and the inverse masses of its
        nodes (gathered). */
    std::vector<std::vector<double>> other_forces, inverse_masses;
    bool                             any_kinematic = false;
    std::vector<ContactResult>       contact_results;
    /** Per pair and surface: the body whose analytic shape the surface
        is (a rigid body's sphere, plane, ...), -1: the body's mesh faces. */
    std::vector<std::array<int, 2>>  analytic_body;
    double                           contact_frequency_squared = 0;
    /** Over the run: the springs whose state crossed a partition boundary
        (summed over the steps and the distributed pairs). */
    unsigned long springs_across_partitions = 0;
    /** Over the run, per pair: the deepest penetration, its largest ratio
        to the pressed element's thickness, the largest spring energy. */
    std::vector<std::array<double, 3>> run_maxima;
    /** Per pair: its two bodies (indices into the scene's bodies). */
    std::vector<std::array<unsigned int, 2>> pair_body;
    /** Per penalty pair, the contact's approach (prepare_history()): the
        two bodies' centre-of-mass displacements when its force began
        (0-2, 3-5), whether it acts (6), the largest approach so far (7). */
    std::vector<std::array<double, 8>> approach;
  };
} // namespace anvil::Contact
