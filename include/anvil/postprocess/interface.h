/**
 * @file
 * Postprocessors: what a run writes besides the families' own histories
 * (energy.csv, momentum.csv, probes, reactions, erosion, the VTU frames,
 * bodies.csv, summary.csv, the plots), each in its own file, registered with
 * ANVIL_REGISTER_POSTPROCESSOR as material models and contact algorithms
 * are (ASPECT's include/aspect/postprocess/interface.h is the model). Every
 * registered postprocessor runs in every scene, Anvil's own and a plugin's
 * loaded with 'Additional shared libraries' alike (doc/extending.md).
 *
 * Each hook is called on every process (a postprocessor sums over the
 * processes what it needs; rank 0 writes); a file is noted with
 * record_output() before it is written, and a history goes through a
 * HistoryFile, so that its rows reach the disk whole and together with the
 * others, and a checkpoint records its length.
 */
#pragma once

#include <anvil/simulator/simulator_access.h>
#include <anvil/utilities/output_files.h>
#include <anvil/utilities/state_archive.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil::Postprocess
{
  class Interface : public SimulatorAccess
  {
  public:
    using SimulatorAccess::SimulatorAccess;

    /** Postprocessors run in the order of this key, then of their names;
        the end of a run needs it (the last frame, then bodies.csv, then
        summary.csv, then the plots, which read them). */
    virtual int order() const
    {
      return 0;
    }

    /** A history row at time @p t, between the velocity and the position
        update; @p dt: the coming step (velocities at n are v^{n+1/2} -
        dt/2 a^n). */
    virtual void execute(double t, double dt)
    {
      (void)t, (void)dt;
    }

    /** A frame of the fields at time @p t: @p basename 'solution' (frame
        @p frame of the time series) or 'last_good' (the state a numerical
        failure leaves). */
    virtual void write_frame(double t, const std::string &basename, unsigned int frame)
    {
      (void)t, (void)basename, (void)frame;
    }

    /** The end of a run (not of a stopped one); @p wall_time in s. */
    virtual void end_of_run(double wall_time)
    {
      (void)wall_time;
    }

    /** A new stage starts from a checkpoint: its histories, frames and
        figures start afresh. */
    virtual void start_stage()
    {}

    /** Its history files (rank 0), in a fixed order; by default its
        'files'. */
    virtual std::vector<HistoryFile *> history_files()
    {
      return pointers_to(files);
    }
    /** The number of history files to reopen at a restart. */
    virtual void resize_history_files(unsigned int n)
    {
      files.resize(n);
    }

    /** What a checkpoint keeps of it. */
    virtual void serialize(StateArchive &ar)
    {
      (void)ar;
    }

    /** The version of serialize()'s record in a checkpoint: raise it when
        the record changes, so that a checkpoint holding the old record is
        refused by name instead of read wrongly. */
    virtual unsigned int state_version() const
    {
      return 1;
    }

    /** The name it is registered under (its checkpoint record's key). */
    std::string plugin_name;

  protected:
    /** Its history files (rank 0; e.g. one per probe). */
    std::vector<HistoryFile> files;
  };


  struct RegistryEntry
  {
    std::string                                              description;
    std::function<std::unique_ptr<Interface>(Simulator &)> create;
  };

  /** All registered postprocessors, by name. */
  std::map<std::string, RegistryEntry> &registry();

  /** Called by ANVIL_REGISTER_POSTPROCESSOR. */
  bool register_postprocessor(const std::string &name, RegistryEntry entry);

  /** One of each registered postprocessor for @p simulator, in their order. */
  std::vector<std::unique_ptr<Interface>> create_all(Simulator &simulator);
} // namespace anvil::Postprocess

/**
 * Register postprocessor @p classname (constructed from a Simulator &) under
 * @p name. Put this at the bottom of its .cc file, in namespace
 * anvil::Postprocess.
 */
#define ANVIL_REGISTER_POSTPROCESSOR(classname, name, description)             \
  namespace                                                                      \
  {                                                                              \
    const bool anvil_registered_postprocessor_##classname =                      \
      ::anvil::Postprocess::register_postprocessor(                              \
        name, {description, [](::anvil::Simulator &simulator) {                 \
                 return std::unique_ptr<::anvil::Postprocess::Interface>(       \
                   std::make_unique<classname>(simulator));                     \
               }});                                                              \
  }
