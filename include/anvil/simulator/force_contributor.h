/**
 * @file
 * ForceContributor: one family of the scene behind one small interface
 * (doc/step.md). The Simulator owns the nodal state, the clock, the energies
 * and the loop; each family owns its setup, its forces and their stable
 * step, the state it advances itself, its energy terms, its histories and
 * its part of a checkpoint. The loop calls the families in a fixed order, so
 * that sums over them, and the whole run, are bitwise the same as before the
 * families were separated.
 */
#pragma once

#include <anvil/simulator/simulator_access.h>
#include <anvil/utilities/output_files.h>
#include <anvil/utilities/state_archive.h>

#include <ostream>
#include <string>
#include <vector>

namespace anvil
{
  /** What the families that advance their own state add to the step's
      kinetic energy (at time n), external work and step-change power. */
  struct OwnMotion
  {
    double kinetic = 0;
    double work    = 0;
    double power   = 0;
  };

  class ForceContributor : public SimulatorAccess
  {
  public:
    using SimulatorAccess::SimulatorAccess;

    /** The family's TimerOutput section (e.g. "rebar and bond"). */
    virtual std::string name() const = 0;

    /** Nothing of this family in the scene: the step never calls it. */
    virtual bool empty() const = 0;

    /** After the mesh, the DoFs and the element groups exist. */
    virtual void setup() = 0;

    /** Once the lumped mass and the boundary conditions exist. */
    virtual void initialize()
    {}

    /** Add the family's lumped mass to the owned entries of @p mass. */
    virtual void add_mass(VectorType &mass)
    {
      (void)mass;
    }

    /** Whether add_forces() adds any (a family that only moves its own
        state, the rigid bodies, is then not called, nor timed). */
    virtual bool has_forces() const
    {
      return true;
    }

    /** Add the forces at time n (the current positions) to the owned
        entries of the Simulator's force vector and book their work; @p dt:
        the step that led to n (0 for the first evaluation, which changes
        no state). Returns the family's stable step (1e300: none). */
    virtual double add_forces(double dt) = 0;

    /** Advance what the family moves itself (its own nodes) to the
        velocity of n+1/2, adding to @p motion. */
    virtual void update_velocity(double dt_previous, double dt, OwnMotion &motion)
    {
      (void)dt_previous, (void)dt, (void)motion;
    }

    /** ... and to the position of n+1. */
    virtual void update_position(double dt)
    {
      (void)dt;
    }

    /** Add the kinetic energy of the family's own nodes to @p kinetic
        (the initial energy; term by term, as the sum was always formed). */
    virtual void add_kinetic_energy(double &kinetic) const
    {
      (void)kinetic;
    }

    /** Add the momentum of its own nodes at time n to @p momentum (three
        entries per body); @p dt: the coming step. */
    virtual void add_momentum(double dt, std::vector<double> &momentum) const
    {
      (void)dt, (void)momentum;
    }

    /** A part of the step's one-line description (Simulator::step_contents). */
    virtual std::string describe() const = 0;

    /** Lines for the end of the run (each ending in a newline), or empty:
        what the family's own approximation cost (e.g. the contact
        penalty's penetration). */
    virtual std::string end_of_run_note() const
    {
      return "";
    }

    /** Rows of summary.csv ('key,value\n'), rank 0. */
    virtual void write_summary(std::ostream &out) const
    {
      (void)out;
    }

    /** A new stage starts from a checkpoint: figures kept for the stage's
        summary (peaks) start afresh. */
    virtual void start_stage()
    {}

    /** Before a history row, on every process: reduce what rank 0's
        write_history() needs from the others (collective). */
    virtual void prepare_history()
    {}

    /** A history row at time @p t (rank 0 writes); @p dt: the coming step
        (the velocities at n are v^{n+1/2} - dt/2 a^n). */
    virtual void write_history(double t, double dt)
    {
      (void)t, (void)dt;
    }

    /** The family's own fields of frame @p count (rank 0 writes). */
    virtual void output_frame(double t, unsigned int count)
    {
      (void)t, (void)count;
    }

    /** Its history files (rank 0), in a fixed order: flushed together with
        the others, their lengths kept in a checkpoint. By default the
        family's 'files'. */
    virtual std::vector<HistoryFile *> history_files()
    {
      return pointers_to(files);
    }

    /** The number of history files to reopen at a restart. */
    virtual void resize_history_files(unsigned int n)
    {
      files.resize(n);
    }

    /** Everything the steps change, in one order for writing and reading. */
    virtual void serialize(StateArchive &ar) = 0;

    /** The version of serialize()'s record in a checkpoint, which is keyed
        by name(): raise it when the record changes, so that a checkpoint
        holding the old record is refused by name instead of read wrongly
        (the other families' records are unaffected). */
    virtual unsigned int state_version() const
    {
      return 1;
    }

  protected:
    /** The family's history files (rank 0; e.g. one per contact pair). */
    std::vector<HistoryFile> files;
  };
} // namespace anvil
