/**
 * @file
 * Reinforcement: two-node truss elements (like ABAQUS T3D2) embedded in a
 * hexahedral host body (seed sections 5.1, 5.3, 5.4).
 */
#pragma once

#include <anvil/utilities/state_archive.h>

#include <anvil/material_model/interface.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace anvil::Rebar
{
  /**
   * One reinforcement layout of a scene ("Rebar NAME"): where the bars are,
   * their section and steel, and how they are coupled to the host body.
   *
   * Layouts: longitudinal bars of a prismatic member along an axis (bars
   * per face, corners included, at 'Cover' from the member's faces to the
   * bar surface), closed stirrups at a spacing, or polylines from a file.
   * Every polyline is cut into truss elements no longer than 'Element
   * length'.
   *
   * Coupling 'perfect bond' (the seed's common-node model): every truss
   * node follows the host material point it sits in, x_r = sum_I N_I(xi_r)
   * x_I; the truss forces and the rebar mass go to the host nodes through
   * the same N_I, which conserves momentum. Where the host mesh has nodes on
   * the bar, xi_r is a vertex and the coupling is the shared node.
   */
  class Layout
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &name,
                                 const std::string        &scene_directory);

    /** The bars as polylines in the reference configuration. */
    std::vector<std::vector<dealii::Point<3>>> polylines() const;

    /** Longitudinal and transverse reinforcement ratios of the member
        (steel area over concrete area; A_sv / (b s) per direction for
        stirrups), for the screen. */
    std::string ratio_summary() const;

    std::string                                name;
    std::string                                host;
    std::string                                layout;
    double                                     diameter       = 0;
    double                                     element_length = 0;
    /** Bond-slip (seed Eq. (68)) instead of perfect bond, and its law:
        tau = G_s S up to S_max, then tau_max exp(-h D) with D the
        accumulated slip beyond the elastic range; elastic unloading with
        G_s. */
    bool   bond_slip     = false;
    double bond_modulus  = 5e10;
    double slip_at_peak  = 3.6e-4;
    double damage_rate   = 200.;
    /** Bond-slip: the smallest step the bar elements may set; elements
        below it get nonstructural mass (selective mass scaling); 0: off. */
    double mass_scaling_step = 0;
    /** Bond-slip: the bars advance in substeps of their own stable step
        inside the scene's step (Reinforcement::subcycle()). */
    bool subcycling = false;
    /** Velocity imposed on the last node of every bar (pull-out tests). */
    dealii::Tensor<1, 3> pull_velocity;
    bool                 pulled = false;
    /** Optional point whose nearest truss element rebar_NAME.csv reports. */
    bool             has_probe = false;
    dealii::Point<3> probe;
    std::unique_ptr<MaterialModel::Interface> material;

    double area() const
    {
      return 0.25 * 3.14159265358979323846 * diameter * diameter;
    }

  private:
    unsigned int     axis = 0;
    dealii::Point<3> lower, upper;
    double           cover   = 0;
    unsigned int     per_face = 2;
    double           spacing = 0;
    std::string      file_name;
  };


  /**
   * The truss elements of one layout with their state. Every process holds
   * the arrays whole but keeps current only its share (the elements and
   * nodes of its own and ghost cells, Reinforcement::Share); it evaluates
   * them in element order on the same positions as one process would, so
   * the result does not depend on the partition.
   */
  struct Trusses
  {
    /** Reference positions of the nodes, and the two nodes of each element. */
    std::vector<dealii::Point<3>>            X;
    std::vector<std::array<unsigned int, 2>> elements;
    std::vector<double>                      reference_length, length;
    /** Half the reference length of the elements at each node. */
    std::vector<double> tributary;
    /** The element rebar_NAME.csv reports (nearest to 'Probe point'). */
    unsigned int probe_element = 0;
    /** Axial Cauchy stress, axial force, internal energy per element. */
    std::vector<double> stress, force, energy;
    std::vector<double> history;
    unsigned int        n_history = 0;
    /** Current node positions (3 per node), as last evaluated. */
    std::vector<double> x;
    /** Bond-slip: the bars' own nodes (positions, half-step velocities,
        forces, lumped masses), the host material points they sit in, and
        per node the plastic slip, accumulated slip beyond the elastic
        range, bond stress, slip, bond force; the pulled nodes. */
    std::vector<double>       xs, vs, fs, ms, xh;
    /** Per element: sqrt of its mass factor (1, or more where the bars'
        mass is scaled), the factor on its stable step L / c. */
    std::vector<double> step_factor;
    /** Subcycling: the substeps of the scene's last step and their size
        h (s), and the host points of the last evaluation (work array). */
    unsigned int        substeps = 1;
    double              substep  = 0;
    std::vector<double> xh_start;
    /** The nonstructural mass added by mass scaling. Units: kg. */
    double added_mass = 0;
    std::vector<double>       plastic_slip, damage, bond_stress, slip, bond_force;
    std::vector<bool> pulled;
    /** Reaction at the pulled nodes' dofs in the last step (3 per node). */
    std::vector<double> pull_reaction;
    /** Work arrays of the step (no allocation per step): nodal forces and
        bar tangents. */
    std::vector<double>               nodal_force;
    std::vector<dealii::Tensor<1, 3>> tangent;
    /** Relative displacement bar - host at the last evaluation (3 per node). */
    std::vector<double> x_bond_old;
    /** Output records (time, file) of rebar_NAME.pvd. */
    std::vector<std::pair<double, std::string>> pvd_records;

    /** Embedding: host cell (scene-wide coarse id) and natural coordinates
        in [-1,1]^3 of each node. */
    std::vector<unsigned long>          host_cell;
    std::vector<std::array<double, 3>>  xi;
    /** The host cell's shape functions at xi, per node (the step's gather
        of host points and scatter of forces). */
    std::vector<std::array<double, 8>> shape;
    /** On this process: for each node, the local x-dof indices of the host
        cell's 8 vertices if the cell is owned or ghost here (-1 if not), and
        whether the host cell is owned here. */
    std::vector<std::array<long, 8>> host_dofs;
    std::vector<bool>                host_owned;

    /** Trilinear shape functions at xi (lexicographic vertices). */
    static std::array<double, 8> shape_values(const std::array<double, 3> &xi);

    /** Everything a step changes (checkpoints): the substeps and frames
        in the stream, the elements' and nodes' state in the keyed tables
        @p table (each node's by the process that owns its host cell, each
        element's by its first node's). */
    void serialize(StateArchive &ar, const std::string &table);
  };
} // namespace anvil::Rebar
