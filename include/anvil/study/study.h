/**
 * @file
 * Parameter studies: one base scene run over a list or grid of values of
 * any of its entries, each run a process of its own (an MPI job when it
 * asks for more than one process), then study.csv and the plots.
 */
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * `anvil --study STUDY.prm [--jobs N]`. The study file names a base scene
   * and its variables (subsection 'Variable NAME': an entry path and a list
   * of values); the runs are the grid of all combinations or, with
   * 'Combination = zip', the values taken together. Every run is the base
   * scene with the study's overrides (the same mechanism as `anvil SCENE.prm
   * --set PATH=VALUE`), in its own directory OUTPUT/NAME/run_NN, with its
   * screen output in run.log there; a run that finished (exit 0, the same
   * overrides, its summary.csv in place) is not run again, so a study that
   * was interrupted continues where it stopped.
   */
  class Study
  {
  public:
    /** Entry point from main() (before MPI is initialised); returns the
        exit status: 0 every run succeeded, 2 bad input (before any run), 1
        some runs failed (study.csv says which). */
    static int main(const std::vector<std::string> &args);

    /** Every entry of a study file, with default, pattern and
        documentation (.prm syntax). */
    static void print_parameters(std::ostream &out);

    struct Variable
    {
      std::string              name;
      std::string              entry;
      std::vector<std::string> values;
      /** One number per value, the abscissa of the plots. */
      std::vector<double> plot_values;
      std::string         label;
    };

    struct Run
    {
      std::string              name;
      /** Index into each variable's values. */
      std::vector<unsigned int> choice;
      std::vector<std::string> overrides;
      int                      status    = -1;
      double                   wall_time = 0;
    };

  private:
    explicit Study(const std::string &file);
    int run(unsigned int jobs_from_command_line);

    void make_runs();
    void validate() const;
    bool finished_earlier(const Run &run) const;
    int  launch(const Run &run) const;
    void write_table() const;
    void write_plots() const;
    std::string describe(const Run &run) const;

    std::string file;
    std::string base_scene;
    std::string name;
    std::string directory;
    std::string combination;
    unsigned int processes = 1;
    unsigned int jobs      = 1;
    std::string  launcher;
    std::string  history_file, history_column;
    double       history_scale = 1;
    std::string  history_label;
    bool         plots = true;
    std::vector<std::string> fixed;
    std::vector<Variable>    variables;
    std::vector<Run>         runs;
  };
} // namespace anvil
