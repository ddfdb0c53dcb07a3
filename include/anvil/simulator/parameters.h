/**
 * @file
 * Parameters: the settings of a scene the Simulator itself reads from
 * subsection 'Simulation' (source/simulator/parameters.cc), in one place;
 * what the families and plugins read they declare and parse themselves.
 */
#pragma once

#include <anvil/simulator/records.h>

#include <deal.II/base/function_parser.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  struct Parameters
  {
    /** The scene file, its name (OUTPUT DIRECTORY/NAME) and the result
        directory. */
    std::string scene_file;
    std::string scene_name;
    std::string output_directory;
    /** What the translation of a deck warns of (Deck::Translation). */
    std::vector<std::string> deck_notes;
    /** The run's end: 'End time', or the stage's start plus 'Duration'. */
    double end_time = 1;
    /** 'Duration' (> 0): the run ends this long after its start (a
        stage's: after the state it starts from); 0: at 'End time'. */
    double       duration         = 0;
    double       time_step_factor = 0.9;
    unsigned int max_steps        = 0;
    /** 'Maximum time step' (<= 0: no bound): a constant, or a function of
        t when the entry names t. */
    double                                     max_dt_constant = 0;
    std::unique_ptr<dealii::FunctionParser<1>> max_dt_function;
    double                                     energy_tolerance = 0;
    double                                     min_dt_ratio     = 0;
    EndCriterion                               end_criterion;
    SummarySubjects                            summary_subjects;
    // Output
    double output_interval  = 0;
    double history_interval = 0;
    bool   overwrite_output = false;
    bool   print_wall_times = false;
    /** Wall time between progress lines (0: every 10 % of the end time). */
    double progress_interval = 5;
    bool   make_plots        = false;
    bool   compress_output   = true;
    // Checkpoints
    double checkpoint_interval      = 0;
    double checkpoint_wall_interval = 0;
    bool   checkpoint_at_end        = false;
    /** 'Inactive bodies': per body, whether it is out of the analysis
        (rigid bodies only: held still, their contact pairs skipped). */
    std::vector<unsigned char> inactive_bodies;
    /** 'Partitioner': hierarchical, metis or zoltan. */
    std::string partitioner = "hierarchical";
    /** 'Rebalance interval' (s; 0: never) and 'Rebalance threshold'. */
    double rebalance_interval  = 0;
    /** 'Adapt interval': simulated time between refinements and
        coarsenings of the bodies by their 'Refinement region' (0: the
        mesh of the start throughout). */
    double adapt_interval      = 0;
    double rebalance_threshold = 1.1;
    bool   rebalance_when_it_pays = true;
  };
} // namespace anvil
