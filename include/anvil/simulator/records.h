/**
 * @file
 * The records a run keeps beside its nodal state: the energy balance, the
 * probes and the figures of summary.csv. The families and postprocessors
 * that book and read them include this header, not the Simulator's.
 */
#pragma once

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace anvil
{
  /** Energies of the whole scene (seed Eq. (21)). Units: J. */
  struct Energies
  {
    double kinetic       = 0;
    double internal      = 0;
    double hourglass     = 0;
    double contact       = 0;
    double friction      = 0;
    /** Energy held by eroded elements when they were removed. */
    double eroded        = 0;
    /** Work done on the bond of bond-slip reinforcement (elastic and
        dissipated). */
    double bond          = 0;
    /** The energy the central difference scheme itself removes when the
        step changes, sum over steps of 1/4 (dt^{n+1/2} - dt^{n-1/2})
        F^n . (v^{n+1/2} - v^{n-1/2}) (doc/theory.md, "Energy balance with
        variable steps"); negative: energy created. */
    double step_change   = 0;
    /** Work of the bulk viscosity (dissipated). */
    double viscous       = 0;
    /** Work of the mass-proportional damping ('Mass damping'; dissipated). */
    double damping       = 0;
    /** Energy taken out of the analysis with the bodies a stage removes
        ('Inactive bodies': their kinetic energy, and the energy of their
        contact springs, when they were removed), and the energy of the
        contact springs an erosion took away (+) or made (-), which no
        motion did work on (Contact::ContactResult::topology_energy). */
    double removed       = 0;
    /** The energy that refinement and coarsening during the run took out
        of the motion and the stress they moved onto the new elements
        ('Adapt interval', doc/adaptivity.md): the kinetic energy of the
        interpolated velocities and the elastic energy of the averaged
        stresses against the old mesh's; negative: energy created. */
    double adaptation    = 0;
    double external_work = 0;
    double total() const
    {
      return kinetic + internal + hourglass + viscous + damping + contact + friction + eroded +
             removed + bond + step_change + adaptation;
    }
  };

  /** A named output point: the node of a body nearest to a given point,
      or the centre of mass of the body's cross-section through it. */
  struct Probe
  {
    std::string      name;
    std::string      body;
    dealii::Point<3> point;
    /** A one-node set of the body's mesh file that gives 'point' (upper
        case), or empty. */
    std::string      node_set;
    /** 'Average = section': the normal of the section (0, 1, 2), or -1
        for the node alone. */
    int section_normal = -1;
    /** Global x-dof index of the chosen node, and its owner. */
    unsigned long x_dof = 0;
    int           owner = 0;
    /** A section probe: the section's nodes in the order of their scene
        index (the same on every partition), their lumped masses, and the
        slot of each of this process's owned ones in that order. */
    std::vector<double>                                 section_mass;
    std::vector<std::pair<unsigned int, unsigned long>> owned_section_dofs;
    /** On the owner: the element group and element whose stress the probe
        reports (of the elements around the node, the one with the smallest
        scene-wide id, so that every partition reports the same). */
    int          group   = -1;
    unsigned int element = 0;
  };

  /** When a run ends before its end time ('Simulation/End ...' entries):
      once the pairs named carry no force and the deformable bodies'
      kinetic energy has stayed below the bounds set for quiet_time. */
  struct EndCriterion
  {
    /** Kinetic energy below this fraction of the initial energy (an
        impact that is over); 0: not asked. */
    double kinetic_fraction = 0;
    /** Kinetic energy below this fraction of the internal energy (a member
        that has settled); 0: not asked. */
    double kinetic_internal_ratio = 0;
    double quiet_time             = 0.01;
    /** The contact pairs that must carry no force, by index ('End contact
        pairs'; every pair when the entry is empty). */
    std::vector<unsigned int> pairs;
    /** The push ends once the capacity support's reaction has fallen by
        this fraction of its peak ('End capacity drop'); 0: not asked. */
    double                    capacity_drop = 0;
    bool                      asked() const
    {
      return kinetic_fraction > 0 || kinetic_internal_ratio > 0;
    }
  };

  /** The probe and the contact pair whose figures are summary.csv's
      peak_displacement_m, residual_displacement_m, peak_contact_force_N and
      contact_duration_s ('Simulation/Summary probe', 'Summary contact
      pair'; the first of each by default). */
  struct SummarySubjects
  {
    unsigned int probe = 0;
    unsigned int pair  = 0;
  };

  /** Figures of the run that summary.csv reports (source/simulator/
      summary.cc); updated every step from replicated data, the probe on
      rank 0 at each history row. */
  struct RunSummary
  {
    double initial_kinetic       = 0;
    double max_hourglass_ratio   = 0;
    double max_balance_error     = 0;
    double peak_reaction         = 0;
    /** The steps the elements alone would have needed (the sum over steps
        of dt / dt_elements) and the steps whose size the contact springs
        set. */
    double       element_steps         = 0;
    unsigned int contact_limited_steps = 0;
    /** Start of the current quiet period (end criterion), -1: none, and
        the history rows in it. */
    double       quiet_since = -1;
    unsigned int quiet_rows = 0;
    bool   ended_early = false;
    /** Since when the capacity support's reaction has been below the
        'End capacity drop' bound (-1: it is not), and the reaction at the
        row that ended the push (-1: the push did not end so). */
    double capacity_below_since  = -1;
    double capacity_end_reaction = -1;
    /** Every probe's peak and last displacement magnitude and its sum over
        the quiet period's rows, in the order of 'Probes' (summary.csv's
        peak_displacement_NAME_m, residual_displacement_NAME_m). */
    std::vector<double> probe_peak, probe_last, probe_quiet_sum;
    /** Every contact pair's peak force and the first and last time it
        carried force (-1: never), in the order of 'Contact pairs'
        (summary.csv's peak_contact_force_NAME_N, contact_duration_NAME_s). */
    std::vector<double> pair_peak_force, pair_contact_start, pair_contact_end;

    template <class Archive>
    void serialize(Archive &ar)
    {
      ar &initial_kinetic &max_hourglass_ratio &max_balance_error &peak_reaction &element_steps
        &contact_limited_steps &quiet_since &quiet_rows &ended_early &capacity_below_since &capacity_end_reaction &probe_peak &probe_last &probe_quiet_sum
          &pair_peak_force &pair_contact_start &pair_contact_end;
    }
  };
} // namespace anvil
