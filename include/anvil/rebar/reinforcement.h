/**
 * @file
 * Reinforcement as a family of the scene: the bars of every 'Rebar NAME'
 * layout, their embedding in the host body, truss forces, bond-slip and the
 * bars' own nodes, their histories and fields (seed sections 5.1, 5.3, 5.4).
 */
#pragma once

#include <anvil/rebar/rebar.h>
#include <anvil/simulator/force_contributor.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <array>

namespace anvil::Rebar
{
  class Reinforcement : public ForceContributor
  {
  public:
    Reinforcement(Simulator &simulator, std::vector<Layout> layouts);

    std::string name() const override
    {
      return "rebar and bond";
    }
    bool empty() const override
    {
      return layouts.empty();
    }
    /** Embedding: each process locates the truss nodes in the host cells it
        owns; a node on a shared face goes to the cell with the smallest
        scene-wide id, so every partition embeds it the same way. */
    void   setup() override;
    /** Perfectly bonded bars: rho A l_trib to the host nodes through N_I. */
    void   add_mass(VectorType &mass) override;
    double add_forces(double dt) override;
    void   update_velocity(double dt_previous, double dt, OwnMotion &motion) override;
    void   update_position(double dt) override;
    void   add_kinetic_energy(double &kinetic) const override;
    void   add_momentum(double dt, std::vector<double> &momentum) const override;
    std::string describe() const override;
    void   write_summary(std::ostream &out) const override;
    void   write_history(double t, double dt) override;
    /** rebar_NAME_NNNN.vtu (line cells: axial force, stress, effective
        plastic strain; bond-slip: slip and bond stress at the nodes) and
        rebar_NAME.pvd. */
    void   output_frame(double t, unsigned int count) override;
    void serialize(StateArchive &ar) override
    {
      for (unsigned int r = 0; r < bars.size(); ++r)
        bars[r].serialize(ar, "layout '" + layouts[r].name + "'");
      ar &own_step &pending_step_change;
    }

    /** The history row's figures of every layout, reduced over the
        processes (rank 0 writes them in write_history()). */
    void prepare_history() override;

  private:
    std::vector<Layout>      layouts;
    std::vector<Trusses>     bars;

    /** Layout @p r's truss elements and bond on the bar positions @p xb
        (the bars' own nodes for bond-slip, the host points for perfect
        bond) and the host points T.xh: the nodal forces in T.nodal_force
        (bond-slip: on the bars' nodes, the bond forces in T.bond_force),
        the histories advanced by @p dt (0: forces only), this process's
        share of the work booked (work_done on several processes, the
        energies on one). Returns the smallest stable step of the elements
        and bond springs. */
    double evaluate(unsigned int r, double dt, const std::vector<double> &xb);
    /** The bond of layout @p r (seed Eq. (68)): adds to T.nodal_force and
        @p bond_work; returns the bond springs' smallest stable step. */
    double evaluate_bond(unsigned int r, double dt, const std::vector<double> &xb, double &bond_work);
    /** Central differences for the own nodes of bond-slip layout @p r, from
        v^{-h_previous/2} to v^{+h/2} under T.fs and gravity; adds the
        kinetic energy of the variable-step identity at the step's start,
        the work of the pull's reactions, and F dv. */
    void advance_velocity(unsigned int r, double h_previous, double h, double &kinetic, double &work,
                          double &power);
    /** Subcycled layouts: the substeps 1 ... m - 1 of the scene's step just
        made (substep 0 went with the host's update), each on the host
        points interpolated between the last evaluation's and the new ones. */
    void subcycle();
    /** Per layout: the bars' own stable step at the last evaluation
        (subcycled layouts, the smallest over the processes). */
    std::vector<double> own_step;
    /** The step-change term of the subcycled bars' energy identity, booked
        at the next step (as Simulator::update_velocity books the host's). */
    double pending_step_change = 0;

    /**
     * The bars' partition. A node belongs to the process that owns its
     * host cell. A process evaluates the elements with a node in its own
     * or ghost cells (in element order), the bond of those nodes, and
     * advances its own nodes; what the ends of those elements need from
     * other processes (positions: the bars' own for bond-slip, the host
     * points for perfect bond) comes through a ghost exchange. Elements
     * and bonds on both sides of a boundary are evaluated on both, from
     * the same numbers, so each process holds the state of one process's
     * run. One process: every node is its own, nothing is exchanged.
     */
    struct Share
    {
      /** Own nodes, nodes in own or ghost cells, every node an evaluated
          element touches, the evaluated elements, and per element whether
          it is this process's (its first node is own: its work and its
          history-row figures are booked here). */
      std::vector<unsigned int> own_nodes, relevant_nodes, nodes, elements;
      std::vector<char>         own_element;
      /** The nodes another process sends (halo), and the local index in
          the exchange of each own node and each halo node. */
      std::vector<unsigned int> halo, own_slot, halo_slot;
    };
    void setup_partition();
    bool                                               partitioned = false;
    std::vector<Share>                                 shares;
    dealii::LinearAlgebra::distributed::Vector<double> exchange;
    /** Per layout: max / min axial force, max / min stress, max
        effective plastic strain, the probe element's force and stress,
        the probe node's slip and bond stress. */
    std::vector<std::array<double, 9>> history_rows;
    /** Per layout, this process's share of the step's truss and bond work
        (summed over the processes; kept, so that a step allocates nothing). */
    std::vector<double> work_done;
  };
} // namespace anvil::Rebar
