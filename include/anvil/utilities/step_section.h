/**
 * @file
 * A section of the step in the run's TimerOutput, timed only when the run
 * prints its wall times.
 */
#ifndef anvil_utilities_step_section_h
#define anvil_utilities_step_section_h

#include <deal.II/base/timer.h>

#include <optional>
#include <string>

namespace anvil
{
  /**
   * A TimerOutput::Scope of the step's own loop, entered only when @p on
   * (the run prints its wall times): deal.II's Timer reads the process's
   * CPU time, a system call, at every enter and leave, which on a small
   * scene costs as much as its step (8 elements: 40 % of the run).
   */
  class StepSection
  {
  public:
    StepSection(dealii::TimerOutput &timer, const bool on, const std::string &name)
    {
      if (on)
        scope.emplace(timer, name);
    }
    void stop()
    {
      if (scope)
        scope->stop();
    }

  private:
    std::optional<dealii::TimerOutput::Scope> scope;
  };
} // namespace anvil

#endif
