/**
 * @file
 * Contact algorithms: what a contact pair computes, behind one interface,
 * and their registry. An algorithm registers itself with
 * ANVIL_REGISTER_CONTACT_ALGORITHM at the bottom of its .cc file, as a
 * material model does; a scene picks it with 'Contact pair NAME/Algorithm'
 * (Anvil's own: 'penalty', the symmetric node-to-segment penalty method). A
 * plugin's algorithm (doc/extending.md) loads with 'Additional shared
 * libraries' and takes part like Anvil's own.
 *
 * The family that holds the pairs (Contact::ContactPairs) gathers each
 * pair's node positions (and velocities if it asks for them), calls
 * compute_forces() and scatters the forces to the nodes each rank owns; an
 * algorithm sees only the pair's nodes, in the order of node_dofs(). An
 * algorithm that can evaluate each rank's share alone says so in
 * distribute(); its pair is then not gathered (Anvil's penalty pair does,
 * but with a rigid body's mesh).
 */
#pragma once

#include <anvil/rigid_body/rigid_body.h>
#include <anvil/utilities/registry.h>
#include <anvil/utilities/state_archive.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <utility>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil::Contact
{
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
    /** Bulk modulus and reference volume of the segment's element. */
    double bulk_modulus;
    double volume;
    /** Scene-wide id of the segment's element. */
    unsigned long element = 0;
    /** The scene vertices of the four nodes (checkpoint keys). */
    std::array<std::uint64_t, 4> vertex = {{0, 0, 0, 0}};
    /** For an interior face of an eroding body, the element on its other
        side: the face joins the surface when that element erodes (and its
        own element lives), as the faces an eroded element exposes do in
        LS-DYNA's eroding contact. no_neighbour: a face of the body's
        boundary, in the surface from the start. */
    static constexpr unsigned long no_neighbour = ~0ul;
    unsigned long                  neighbour    = no_neighbour;
  };

  /** What a contact evaluation reports. */
  struct ContactResult
  {
    /** Sum of the contact forces on the first body's nodes. Units: N. */
    std::array<double, 3> force_on_first = {{0, 0, 0}};
    /** Deepest penetration found in either pass. Units: m. */
    double max_penetration = 0;
    /** Largest penetration as a fraction of the current thickness V / A of
        the element that the penalty spring stands for. Units: none. */
    double max_penetration_ratio = 0;
    /** Work done so far on the penalty springs, the sum over steps of
        1/2 (f^{n-1} + f^n) (l^n - l^{n-1}) per spring: 1/2 k l^2 while k is
        constant, and the energy balance stays closed when k follows the
        current geometry. Units: J. */
    double energy = 0;
    /** The square of the highest frequency that the springs which act, or
        may act within the next step (a slave node within the thickness of
        its partner's element), can add: a bound per node from the springs
        on it and its mass. Units: 1/s^2. */
    double frequency_squared = 0;
    /** Work done this step against the friction forces (dissipated, or
        stored in sticking tangential springs), >= 0 for sliding, and
        dissipated by the normal damping. Units: J. */
    double friction_work = 0;
    /** The springs' energy made (+) or lost (-) this step by a change of
        the surfaces rather than by motion: a spring on a face that an
        eroded element took away, or one that starts compressed on a face
        an eroded element exposed. The contact energy counts it; the
        simulator books its negative as 'removed', so the balance stays
        closed. Units: J. */
    double topology_energy = 0;
    /** Sum of the friction forces on the first body's nodes. Units: N. */
    std::array<double, 3> friction_on_first = {{0, 0, 0}};
    /** Resultant force and torque (about the body's centre) on a rigid
        body's analytic shape. Units: N, N m. */
    dealii::Tensor<1, 3> shape_force, shape_torque;
    /** Number of active slave nodes (both passes). */
    unsigned int n_active = 0;
    /** Slave nodes in contact last step that are now deeper than the
        element they pressed on (passed through the master surface), and
        the largest such depth over the element's thickness. */
    unsigned int n_passed_through     = 0;
    double       passed_through_ratio = 0;
    /** Springs of slave nodes of another rank whose gradient term acts on
        this rank's nodes (a distributed pair; their state crossed a
        partition boundary this step). */
    unsigned int n_springs_across_partitions = 0;
  };

  /**
   * One contact pair's algorithm. The names are set before
   * parse_parameters(); everything else is the algorithm's own.
   */
  class Algorithm
  {
  public:
    virtual ~Algorithm() = default;

    /** Read the algorithm's entries (in the pair's subsection; a plugin's
        in a subsection of its own name, declared by its
        declare_parameters). InputError with one line on bad input. */
    virtual void parse_parameters(dealii::ParameterHandler &prm) = 0;

    /** A line the scene's reading prints (a warning), or empty. */
    virtual std::string parse_note() const
    {
      return "";
    }

    /** Build the pair from all ranks' boundary faces of the two bodies. */
    virtual void setup(const std::vector<SegmentDescription> &first,
                       const std::vector<SegmentDescription> &second) = 0;

    /** Global x-dof indices of the pair's nodes, in the pair's order. */
    virtual const std::vector<unsigned long> &node_dofs() const = 0;

    /** Surface @p s (0: the first body) is a rigid body's. */
    virtual void set_rigid(unsigned int s, bool rigid) = 0;

    /** Surface @p s is the analytic shape @p a (placed anew each step). */
    virtual void set_analytic(unsigned int s, const AnalyticSurface &a)
    {
      (void)s, (void)a;
    }
    virtual bool has_analytic(unsigned int s) const
    {
      (void)s;
      return false;
    }

    /** Lumped masses of the pair's nodes. */
    virtual void set_node_masses(const std::vector<double> &masses)
    {
      (void)masses;
    }

    /**
     * Evaluate only this rank's share of the pair, if the algorithm can:
     * the slave nodes whose dofs are in @p owned_dofs (the rank's own,
     * a contiguous range). compute_forces() then receives the positions
     * and velocities of the pair's nodes on the rank's own and ghost cells
     * (the others are left zero), sets the forces of its own nodes, and
     * returns the whole pair's figures, the same on every rank. Returns
     * false (the default) if the algorithm evaluates the whole pair on
     * gathered positions instead. Collective.
     */
    virtual bool distribute(MPI_Comm comm, const dealii::IndexSet &owned_dofs)
    {
      (void)comm, (void)owned_dofs;
      return false;
    }

    /** Whether compute_forces() needs the nodes' velocities. */
    virtual bool needs_velocities() const
    {
      return false;
    }

    /** Add the contact forces at positions @p x (3 per pair node; @p v the
        velocities of the step @p dt that led there, if asked for) to @p f;
        @p dt = 0: an evaluation that changes no state. */
    virtual ContactResult compute_forces(const std::vector<double> &x,
                                         const std::vector<double> &v,
                                         double                     dt,
                                         std::vector<double>       &f) = 0;

    /** Whether the pair enforces contact kinematically: it adds its forces
        in correct(), once the next step is known, not in compute_forces(). */
    virtual bool kinematic() const
    {
      return false;
    }

    /**
     * A kinematic pair's forces: from the positions @p x (x^n), velocities
     * @p v (v^{n-1/2}), all other forces @p f (F^n) and inverse masses
     * @p inverse_mass (0 for a rigid body's or a constrained dof; 3 per
     * pair node each) the motion over the next step is predicted, and the
     * forces that remove its penetration are added to @p f_contact.
     * @p dt_previous, @p dt: the steps before and after time n.
     */
    virtual ContactResult correct(const std::vector<double> &x,
                                  const std::vector<double> &v,
                                  const std::vector<double> &f,
                                  const std::vector<double> &inverse_mass,
                                  double                     dt_previous,
                                  double                     dt,
                                  std::vector<double>       &f_contact)
    {
      (void)x, (void)v, (void)f, (void)inverse_mass, (void)dt_previous, (void)dt, (void)f_contact;
      return {};
    }

    /** The pair nodes that hang on a refinement interface: for each pair
        node, its masters (pair node indices) and weights, empty where it
        does not hang. A kinematic pair moves them through their masters;
        the others need nothing (their forces are condensed with the
        elements'). */
    virtual void set_hanging_nodes(const std::vector<std::vector<std::pair<unsigned int, double>>> &masters)
    {
      (void)masters;
    }

    /** The faces of the eroded elements @p ids (sorted) leave the pair. */
    virtual void deactivate_elements(const std::vector<unsigned long> &ids)
    {
      (void)ids;
    }

    /** Everything a step changes (checkpoints): what every rank holds
        alike in the stream, each node's state (by its scene vertex,
        node_keys) in keyed tables, written by the rank in own_nodes. A
        load onto a mesh refined or coarsened since
        (StateArchive::element_transfer()) starts the new nodes afresh and
        forgets the segments the nodes were last paired with. */
    virtual void serialize(StateArchive &ar) = 0;

    /** The pair's nodes (indices into node_dofs()) whose dofs this rank
        owns, set before the first step. */
    std::vector<std::uint64_t> own_nodes;
    /** Each node's key in a checkpoint (its scene vertex), by its index
        in node_dofs(). */
    std::vector<std::uint64_t> node_keys;

    /** The nodes of a keyed table of serialize() and their keys: loading,
        every node of the pair (each rank takes them all); writing, the
        rank's own. */
    void keyed_nodes(const bool loading, std::vector<std::uint64_t> &index, std::vector<std::uint64_t> &keys) const
    {
      index.clear();
      keys.clear();
      if (loading)
        for (std::uint64_t i = 0; i < node_keys.size(); ++i)
          index.push_back(i);
      else
        index = own_nodes;
      for (const auto i : index)
        keys.push_back(node_keys[i]);
    }

    std::string name;
    std::string first_body, second_body;
  };


  /**
   * The pair's nodes (x-dof indices) of the two surfaces' segments in an
   * order fixed by (surface, reference coordinates), so that an evaluation
   * in that order does not depend on the dof numbering (and so on the
   * partitioning); the surface is part of the key, as nodes of the two
   * bodies may coincide. Sets @p dofs, @p on_first (per node) and @p index
   * (x-dof to position in @p dofs).
   */
  template <typename Flag>
  void order_pair_nodes(const std::vector<SegmentDescription>  &first,
                        const std::vector<SegmentDescription>  &second,
                        std::vector<unsigned long>             &dofs,
                        std::vector<Flag>                      &on_first,
                        std::map<unsigned long, unsigned int>  &index)
  {
    std::map<std::array<double, 4>, unsigned long> by_position;
    std::map<unsigned long, bool>                  dof_on_first;
    for (unsigned int s = 0; s < 2; ++s)
      for (const auto &seg : (s == 0 ? first : second))
        for (unsigned int v = 0; v < 4; ++v)
          {
            by_position[{{double(s),
                          seg.reference_position[3 * v],
                          seg.reference_position[3 * v + 1],
                          seg.reference_position[3 * v + 2]}}] = seg.x_dof[v];
            dof_on_first[seg.x_dof[v]] = (s == 0);
          }
    dofs.clear();
    for (const auto &[p, d] : by_position)
      dofs.push_back(d);
    index.clear();
    for (unsigned int i = 0; i < dofs.size(); ++i)
      index[dofs[i]] = i;
    on_first.resize(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      on_first[i] = dof_on_first[dofs[i]];
  }


  /** Whether a segment takes part, and whether its own element has eroded,
      after the elements @p ids (sorted, scene-wide) erode: an eroded
      element's faces leave for good; an interior face of an eroding body
      (SegmentDescription::neighbour) joins once the element across has
      eroded and its own lives (eroding contact). Every algorithm's
      deactivate_elements() applies this one rule. */
  inline std::pair<bool, bool> segment_after_erosion(const unsigned long               element,
                                                     const unsigned long               neighbour,
                                                     const std::vector<unsigned long> &ids,
                                                     const bool                        active,
                                                     const bool                        dead)
  {
    if (std::binary_search(ids.begin(), ids.end(), element))
      return {false, true};
    if (!dead && std::binary_search(ids.begin(), ids.end(), neighbour))
      return {true, false};
    return {active, dead};
  }


  /**
   * The segments of @p segs as pair-node indices (@p index from
   * order_pair_nodes()), each with its position in @p segs, sorted by
   * those indices: an order that does not depend on the partitioning.
   */
  inline std::vector<std::pair<std::array<unsigned int, 4>, unsigned int>>
  order_segments(const std::vector<SegmentDescription> &segs, std::map<unsigned long, unsigned int> &index)
  {
    std::vector<std::pair<std::array<unsigned int, 4>, unsigned int>> order;
    for (unsigned int k = 0; k < segs.size(); ++k)
      {
        std::array<unsigned int, 4> n;
        for (unsigned int v = 0; v < 4; ++v)
          n[v] = index[segs[k].x_dof[v]];
        order.emplace_back(n, k);
      }
    std::sort(order.begin(), order.end());
    return order;
  }


  /** The registered algorithms, by name (ANVIL_REGISTER_CONTACT_ALGORITHM). */
  using Registry = ::anvil::Registry<Algorithm>;

  /** In a 'Contact pair NAME' subsection: 'Algorithm', 'First body',
      'Second body' and every registered algorithm's entries. */
  void declare_parameters(dealii::ParameterHandler &prm);

  /** The algorithm the pair @p pair_name selects, its names set and its
      entries read (the pair's subsection is the current one). 'automatic'
      (the default) is 'kinematic', whose passes balance themselves between
      two deformable bodies. */
  std::unique_ptr<Algorithm> create(dealii::ParameterHandler &prm, const std::string &pair_name);
} // namespace anvil::Contact

namespace anvil
{
  // The table is the executable's (source/contact/interface.cc).
  extern template class Registry<Contact::Algorithm>;
}

/**
 * Register contact algorithm @p classname under @p name. Put this at the
 * bottom of the algorithm's .cc file, in namespace anvil::Contact.
 */
#define ANVIL_REGISTER_CONTACT_ALGORITHM(classname, name, description) \
  namespace                                                             \
  {                                                                     \
    const bool anvil_registered_contact_##classname =                   \
      ::anvil::Contact::Registry::add(                                  \
        name,                                                           \
        {description,                                                   \
         &classname::declare_parameters,                                \
         []() { return std::make_unique<classname>(); }});              \
  }
