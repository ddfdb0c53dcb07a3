/**
 * @file
 * Postprocessors: what a run writes besides the families' own histories
 * (energy.csv, momentum.csv, probes, reactions, erosion, the VTU frames,
 * bodies.csv, summary.csv, the plots), each in its own file, registered with
 * ANVIL_REGISTER_POSTPROCESSOR as material models and contact algorithms
 * are (ASPECT's include/aspect/postprocess/interface.h is the model). A
 * scene runs those its 'Postprocess/List' names, by default every one,
 * Anvil's own and a plugin's loaded with 'Additional shared libraries'
 * alike (doc/extending.md); each may declare entries of its own in
 * 'Postprocess/NAME', and names the postprocessors it runs after.
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
#include <anvil/utilities/registry.h>
#include <anvil/utilities/state_archive.h>

#include <deal.II/base/parameter_handler.h>

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

    /** The postprocessors this one runs after where the scene has them
        (their histories, frames or figures are what it reads): every hook
        is called in an order that honours these, ties by name. */
    virtual std::vector<std::string> run_after() const
    {
      return {};
    }

    /** Read its entries (declared by the static declare_parameters() its
        registration names) from its subsection 'Postprocess/NAME', the
        current one. */
    virtual void parse_parameters(dealii::ParameterHandler &prm)
    {
      (void)prm;
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


  /** The registered postprocessors, by name (ANVIL_REGISTER_POSTPROCESSOR). */
  using Registry = ::anvil::Registry<Interface, Simulator &>;

  /** 'Postprocess': 'List' and each registered postprocessor's own
      subsection. */
  void declare_parameters(dealii::ParameterHandler &prm);

  /** The postprocessors the scene lists (the current subsection of @p prm
      is 'Postprocess'), each with its entries read, in the order their
      run_after() asks for (ties by name). InputError for an unknown name. */
  std::vector<std::unique_ptr<Interface>> create_all(Simulator &simulator, dealii::ParameterHandler &prm);
} // namespace anvil::Postprocess

namespace anvil
{
  // The table is the executable's (source/postprocess/interface.cc).
  extern template class Registry<Postprocess::Interface, Simulator &>;
}

/**
 * Register postprocessor @p classname (constructed from a Simulator &) under
 * @p name. Put this at the bottom of its .cc file, in namespace
 * anvil::Postprocess.
 */
#define ANVIL_REGISTER_POSTPROCESSOR(classname, name, description)             \
  namespace                                                                      \
  {                                                                              \
    const bool anvil_registered_postprocessor_##classname =                      \
      ::anvil::Postprocess::Registry::add(                                       \
        name, {description, nullptr, [](::anvil::Simulator &simulator) {         \
                 return std::unique_ptr<::anvil::Postprocess::Interface>(       \
                   std::make_unique<classname>(simulator));                     \
               }});                                                              \
  }

/**
 * The same for a postprocessor with entries of its own: @p classname has a
 * static declare_parameters(dealii::ParameterHandler &), called in
 * 'Postprocess/NAME', and reads them in parse_parameters().
 */
#define ANVIL_REGISTER_POSTPROCESSOR_WITH_PARAMETERS(classname, name, description) \
  namespace                                                                          \
  {                                                                                  \
    const bool anvil_registered_postprocessor_##classname =                          \
      ::anvil::Postprocess::Registry::add(                                           \
        name, {description, &classname::declare_parameters,                          \
               [](::anvil::Simulator &simulator) {                                   \
                 return std::unique_ptr<::anvil::Postprocess::Interface>(           \
                   std::make_unique<classname>(simulator));                         \
               }});                                                                  \
  }
