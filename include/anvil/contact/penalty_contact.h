/**
 * @file
 * Symmetric node-to-segment penalty contact between two deformable bodies
 * (seed section 4.3, steps (1)-(5) and (7)).
 */
#pragma once

#include <anvil/contact/interface.h>
#include <anvil/utilities/state_archive.h>

#include <anvil/rigid_body/rigid_body.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <array>
#include <tuple>
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
    /** Bulk modulus K and reference volume V of each segment's element
        (seed Eq. (59), k = f K A^2 / V, is evaluated with the segment's
        current area A). Units: Pa, m^3. */
    std::vector<double> bulk, volume;
    /** Scene-wide id of each segment's element, and whether the segment
        takes part (its element has not been eroded, and it is on the
        boundary or the element across it has been). For the interior
        faces of an eroding body: the element across (else
        SegmentDescription::no_neighbour), and whether its own element has
        eroded. */
    std::vector<unsigned long> element;
    std::vector<bool>          active;
    std::vector<unsigned long> neighbour;
    std::vector<bool>          dead;
    /** Segments whose activity the last erosion changed (until the next
        evaluation books the springs it made or took away). */
    std::vector<char>          changed;
    /** Segments around each node of the pair's node list. */
    std::vector<std::vector<unsigned int>> node_segments;
    /** The other segments of each segment's element on this surface (a
        wall one element thick: its front and back faces). */
    std::vector<std::vector<unsigned int>> same_element;
    /** The pair's nodes on this surface. */
    std::vector<unsigned int> nodes;
    /** Whether the surface belongs to a rigid body. */
    bool rigid = false;

    /** The current geometry, refreshed at every evaluation
        (update_geometry()): per segment its area; per pair node the area
        vector of its tributary patch, sum over the active segments around
        it of A n / 4, the patch's area, and the mean over those segments of
        the contact modulus K A / V and of the thickness V / A. Units: m^2,
        m^2, m^2, Pa/m, m. */
    std::vector<double> area;
    std::vector<double> area_vector, node_area, node_modulus, node_depth;
    /** Per segment: its area vector A n and its pressure modulus K A / V
        (current A). Units: m^2, Pa/m. */
    std::vector<double> segment_area_vector, modulus;
    /** The thickest element's reference thickness V / A (the reach of an
        analytic shape's search). Units: m. */
    double max_reference_depth = 0;
    /** The thinnest element's reference thickness (the search trees'
        safety distance). Units: m. */
    double min_reference_depth = 0;
    /** Work arrays of update_geometry() near an analytic shape. */
    std::vector<char>         seen;
    std::vector<unsigned int> touched;

    /** Area, area vector and pressure modulus of segment @p k at the
        positions @p x (3 per pair node). */
    void update_segment(unsigned int k, const std::vector<double> &x);
    /** The sums of node @p i over its active segments (their geometry
        made first). */
    void update_node(unsigned int i);
  };

  /**
   * A contact pair: each body's surface is master for the other's nodes
   * (the symmetric penalty method). The pair's surfaces are known on every
   * rank, in an order fixed by the reference coordinates. Each rank
   * evaluates the slave nodes it owns (distribute()): between two
   * deformable meshes against the master segments within reach, which the
   * other ranks send it (a halo, found by boxes); against a rigid body's
   * analytic shape on its own and ghost cells. A pair with a rigid body's
   * mesh is evaluated whole on every rank, on gathered positions. Either
   * way the motion does not depend on the number of processes, bit for
   * bit.
   */
  class PenaltyContact : public Algorithm
  {
  public:
    /** The entries of the pair's subsection ('Penalty scale factor',
        friction, damping, 'Symmetric'). */
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;
    /** A penalty factor above 0.4 lowers the step (seed section 4.3). */
    std::string parse_note() const override;

    /** Everything a step changes (checkpoints): surfaces (erosion),
        friction forces and the search trees as last built. */
    void serialize(StateArchive &ar) override;

    /** Build the replicated surfaces from all ranks' segments. */
    void setup(const std::vector<SegmentDescription> &first,
               const std::vector<SegmentDescription> &second) override;

    /** Take the faces of the eroded elements @p ids (sorted) out of the
        pair: an eroded element leaves contact. */
    void deactivate_elements(const std::vector<unsigned long> &ids) override;

    /** Global x-dof indices of the pair's nodes, in the pair's order. */
    const std::vector<unsigned long> &node_dofs() const override
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
                                 std::vector<double>       &f) override;

    /** Evaluate this rank's own slave nodes only: against an analytic
        shape (see analytic_pass()), or between two deformable meshes
        against the halo (setup_halo()). A rigid body's mesh: false (the
        pair is gathered). */
    bool distribute(MPI_Comm comm, const dealii::IndexSet &owned_dofs) override;

    /** Whether the pair needs velocities (friction or damping). */
    bool needs_velocities() const override
    {
      return static_friction > 0 || dynamic_friction > 0 || normal_damping > 0;
    }

    /** Mark surface @p s (0: first body) as a rigid body's. */
    void set_rigid(const unsigned int s, const bool rigid) override
    {
      surface[s].rigid = rigid;
    }

    /** Let surface @p s be the analytic shape @p a (placed anew each
        step) instead of its mesh faces. */
    void set_analytic(const unsigned int s, const AnalyticSurface &a) override
    {
      analytic[s] = a;
    }
    bool has_analytic(const unsigned int s) const override
    {
      return analytic[s].shape != nullptr;
    }

    /** Lumped masses of the pair's nodes (for the normal damping). */
    void set_node_masses(const std::vector<double> &masses) override
    {
      node_mass = masses;
    }

    double       penalty_factor = 0.1;
    /** 'Penalty stiffness = nodal mass' (LS-DYNA's SOFT = 1): k the larger
        of the element-based one and s m / dt^2 with the slave node's mass
        m and the last step dt, s = 'Mass penalty scale factor'; the
        mass-based springs do not bound the step. */
    bool   mass_penalty       = false;
    double mass_penalty_scale = 0.1;
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

    /**
     * What a pass found for one slave node within reach of a master
     * segment: the spring's terms that the nodes' forces and the stable
     * step need, applied to the nodes in the order of one process
     * (apply_touches()) by whichever rank owns them.
     */
    struct Touch
    {
      /** The order of one process: the pass (0: the second body's nodes,
          1: the first's) times the pair's nodes, plus the slave node. */
      unsigned long key;
      unsigned int  segment;
      /** 1: in contact (a force), 2: besides, the gradient term of a
          stiffness that follows the geometry (add_stiffness_gradient();
          its penetration and normal are in touch_normals). */
      unsigned int flags;
      /** The segment's shape functions at the contact point. */
      double phi[4];
      /** Normal and friction force on the slave node. Units: N. */
      double force[3];
      /** The spring's stiffness. Units: N/m. */
      double k;
    };

    /** One pass: the own nodes of surface @p s against the segments of
        the other surface; a Touch per node within reach (in @p touches),
        the pass's sums in @p result, the slave nodes' state. */
    void pass(unsigned int               s,
              SearchTree                &search,
              const std::vector<double> &x,
              const std::vector<double> &v,
              double                     dt,
              ContactResult             &result);

    /** Forces and spring loads of this rank's nodes from all touches (own
        and received), in the order of one process. */
    void apply_touches(const std::vector<double> &x, std::vector<double> &f);
    std::vector<Touch> touches;
    /** Per pass (by slave surface) and slave node, its nearest master
        node of the last evaluation (the search's first guess; ~0u:
        none). Not part of the state: the nearest node does not depend on
        it. */
    std::vector<unsigned int> nearest_guess[2];
    /** Per touch, its penetration and normal, against a rigid body's mesh
        only (its gradient term; such a pair is evaluated whole by every
        rank). */
    std::vector<std::array<double, 4>> touch_normals;

    /** Between two deformable meshes, the exchange of a distributed pair
        (distribute()): the halo of master segments, the touches. */
    struct Halo;
    std::shared_ptr<Halo> halo;
    /** Make the halo: over @p comm, this rank owning the pair nodes in
        @p owned_dofs (MPI_COMM_SELF: every node, nothing exchanged). */
    void setup_halo(MPI_Comm comm, const dealii::IndexSet *owned_dofs);
    /** This step's positions (and velocities) of the master segments
        within reach of this rank's slave nodes, from the ranks that own
        them; the geometry of the segments this rank sees. */
    void exchange_halo(const std::vector<double> &x, const std::vector<double> &v);
    /** Send the touches to the owners of their master nodes, receive
        theirs. */
    void exchange_touches();

    /** The current areas, tributary area vectors, moduli and thicknesses
        of surface @p s at positions @p x. */
    void update_geometry(unsigned int                     s,
                         const std::vector<double>       &x,
                         const std::vector<unsigned int> *near = nullptr);
    /** Work arrays of the analytic pass: the slave nodes near the shape,
        their gap and the shape's normal there. */
    std::vector<unsigned int>          near_nodes;
    std::vector<std::array<double, 4>> near_gaps;

    /** The work this step on the penalty springs of pass @p s (the slave
        surface, its own nodes) from last step's and this step's spring
        forces and penetrations. */
    double spring_work_step(unsigned int s) const;
    /** The nodes of each pass whose spring an erosion may have made or
        taken away (their own segments or their partner changed), whether
        any erosion is pending, and of such a node's work terms those of a
        spring that appeared or vanished: topology_energy. */
    std::vector<char> topology_node[2];
    bool              topology_pending = false;
    double            topology_term(unsigned int s, unsigned int i, double f0, double f1, double l0,
                                    double l1) const
    {
      return topology_pending && topology_node[s][i] && ((f0 != 0) != (f1 != 0)) ? 0.5 * (f0 + f1) * (l1 - l0) : 0.;
    }
    double topology_step(unsigned int s) const;
    /** The work this step of the gradient forces of pass @p s (against a
        rigid mesh) over the nodes' motion since @p previous_position. */
    double gradient_work_step(unsigned int s, const std::vector<double> &x) const;

    /** Add -1/2 l^2 grad kappa of slave node @p i of surface @p
        slave_index (pressed along the normal (nx, ny, nz) against a rigid
        surface, penetration l) to @p f and to geometric_force. */
    void add_stiffness_gradient(unsigned int               slave_index,
                                unsigned int               i,
                                double                     nx,
                                double                     ny,
                                double                     nz,
                                double                     l,
                                const std::vector<double> &x,
                                std::vector<double>       &f);

    /** The spring of slave node @p s: the element-based stiffness
        @p element_k, or with 'Penalty stiffness = nodal mass' the larger
        of it and s m / dt^2 (as LS-DYNA's SOFT = 1); a mass-based spring
        has no gradient term (@p floored) and does not bound the step
        (@p bounds_step false). */
    double spring_stiffness(unsigned int s, double element_k, bool &floored, bool &bounds_step) const
    {
      bounds_step = !mass_penalty;
      if (!mass_penalty)
        return element_k;
      // (Before the first step there is no step to scale by: the
      // element's spring, which the first step's mass-based one replaces.)
      if (!(penalty_dt > 0))
        return element_k;
      bounds_step = true;
      const double m  = s < node_mass.size() ? node_mass[s] : 0.;
      const double km = penalty_dt > 0 ? mass_penalty_scale * m / (penalty_dt * penalty_dt) : 0.;
      if (!(km > element_k))
        return element_k;
      floored     = true;
      bounds_step = false;
      return km;
    }
    /** The last step the pair was evaluated after (the mass-based
        stiffness). */
    double penalty_dt = 0;

    std::vector<unsigned long> dofs;
    std::vector<bool>          on_first;
    Surface                    surface[2];
    /** Per pass (by slave surface), the friction force (3 per pair node)
        of the last step; zero for nodes not in contact. */
    std::vector<double> tangential_force[2];
    /** Per pass and pair node: the master segment that held the node last
        step (-1: none; kept as a candidate, so that a node that has passed
        the middle of a thin wall keeps the face it penetrated), and the
        spring force k l and penetration l of this and the last step. */
    std::vector<int>    partner[2];
    std::vector<double> spring_force[2], spring_depth[2];
    std::vector<double> old_spring_force, old_spring_depth;
    /** Per pass, the forces -1/2 l^2 grad kappa of this and the last step
        (3 per pair node), and the positions of the last evaluation: their
        work is part of the spring work. */
    std::vector<double> geometric_force[2], old_geometric_force, previous_position;
    /** The mesh passes' spring forces, penetrations and gradient forces of
        the last step (per pass: both are booked after both are made). */
    std::vector<double> last_spring_force[2], last_spring_depth[2], last_geometric_force[2];
    /** The pair nodes whose spring load this evaluation set (cleared at
        the next), and a mark per node. */
    std::vector<unsigned int> loaded;
    std::vector<char>         load_mark;
    /** Work done on the penalty springs so far. Units: J. */
    double spring_work = 0;
    std::vector<double> node_mass;
    /** Per pair node, this evaluation's sum over the springs in reach of
        k |w_a| sum_b |w_b| (stable_frequency_squared()). Units: N/m. */
    std::vector<double> spring_load;
    /** The square of the highest frequency the springs in reach can add:
        max over nodes of spring_load / mass. Units: 1/s^2. */
    double stable_frequency_squared() const;
    /** Work arrays of a pass (kept, so that a step allocates nothing):
        the tangential forces of the previous step, and slave normals. */
    mutable std::vector<double> previous_tangential_force;
    AnalyticSurface     analytic[2];
    std::shared_ptr<SearchTree> search[2];

    /** The slave nodes of surface @p s (this rank's own) against the
        analytic shape of the other. */
    void analytic_pass(unsigned int               s,
                       const std::vector<double> &x,
                       const std::vector<double> &v,
                       double                     dt,
                       std::vector<double>       &f,
                       ContactResult             &result);

    /** The pair's sums of the analytic pass from every rank's records, in
        the order of one process. */
    void replay_records(bool slave_is_first, ContactResult &result);

    /** This rank's share (distribute()): the communicator, which pair
        nodes it owns (empty: all), and the ghost exchange of the springs'
        state of the slave nodes next to its own (none on one process). */
    MPI_Comm          communicator = MPI_COMM_SELF;
    std::vector<char> owned;
    struct Exchange;
    std::shared_ptr<Exchange> exchange;
    /** Work arrays of the analytic pass: per pair node its spring's state
        (0 / 1 in contact / 2 with the gradient term, l, n, its force), the
        nodes with a state, the own nodes whose force is summed, a node's
        candidates, and the records of the pair's sums (own, gathered). */
    std::vector<std::array<double, 8>>                     contact_state;
    std::vector<unsigned int>                              state_nodes, targets, candidates;
    std::vector<char>                                      target_mark;
    std::vector<double>                                    records, gathered;
    /** The records' layout: a header (frequency^2, max penetration, max
        ratio, active nodes, the counts of the three kinds, springs across
        partitions), then per node in contact 16 numbers, per spring-work
        term 2 (key, value). */
    static constexpr std::size_t header_size = 9, contact_record_size = 16;
    std::vector<int>                                       record_counts, record_offsets;
    std::vector<std::tuple<int, double, std::size_t>>      order;
    /** The own slave nodes; the own nodes with a spring (in contact) and
        with a gradient force in this and in the last step (their entries
        are the only ones a step changes). */
    std::vector<unsigned int> own_slave_nodes, springs_now, springs_before, gradients_now, gradients_before;
  };
} // namespace anvil::Contact
