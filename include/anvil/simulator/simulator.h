/**
 * @file
 * The one Simulator class: reads a scene, builds the distributed mesh of
 * all bodies, and runs the explicit central-difference loop.
 */
#pragma once

#include <anvil/boundary_conditions/constraints.h>
#include <anvil/contact/contact_pairs.h>
#include <anvil/element/element_group.h>
#include <anvil/element/solid_bodies.h>
#include <anvil/mesh/body.h>
#include <anvil/mesh/hanging_nodes.h>
#include <anvil/postprocess/interface.h>
#include <anvil/rebar/rebar.h>
#include <anvil/rigid_body/rigid_bodies.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/parameters.h>
#include <anvil/simulator/records.h>
#include <anvil/simulator/simulator_access.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <anvil/utilities/output_files.h>
#include <anvil/utilities/state_archive.h>

#include <chrono>
#include <map>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace anvil
{
  /** A checkpoint's record of a family or postprocessor that this build
      reads otherwise (absent, another version, longer). */
  struct RecordMismatch : std::runtime_error
  {
    explicit RecordMismatch(const std::string &what);
  };


  /** A run that asks to be partitioned anew ('Rebalance interval'): its
      checkpoint is written, and the run goes on from it on the partition
      of these weights (per element id; run_simulator()). */
  struct RebalanceRequest
  {
    std::vector<unsigned long> weights;
  };



  /** A stage of a scene (doc/user_guide.md, "Stages"): its name and the
      entries it changes ('PATH=VALUE', as --set), applied to the scene for
      this stage and the stages after it. */
  struct Stage
  {
    std::string              name;
    std::vector<std::string> changes;
  };

  class Simulator
  {
    friend class SimulatorAccess;

  public:
    /**
     * Read the scene @p parameter_file. Throws InputError with a one-line
     * message on bad input.
     */
    Simulator(const std::string              &parameter_file,
              MPI_Comm                         comm,
              const std::vector<std::string> &overrides = {});

    /**
     * Parse the scene @p parameter_file with @p overrides ("SUBSECTION/.../
     * ENTRY=VALUE", applied after the file) against the full declaration,
     * without MPI, a mesh or any output: throws InputError with one line
     * naming the file, entry or override that is wrong.
     */
    static void validate_scene(const std::string              &parameter_file,
                               const std::vector<std::string> &overrides);

    /** Split "PATH=VALUE" overrides; InputError for a malformed one. */
    static std::vector<std::pair<std::string, std::string>>
    split_overrides(const std::vector<std::string> &overrides);

    /** The stages of the scene @p parameter_file (with @p overrides): its
        'Stages' and their 'Changes' (none may change the scene's lists);
        empty for a scene of one stage. */
    static std::vector<Stage> read_stages(const std::string              &parameter_file,
                                          const std::vector<std::string> &overrides);

    /** OUTPUT DIRECTORY/NAME of this scene. */
    const std::string &get_output_directory() const
    {
      return parameters.output_directory;
    }

    /** Print the whole parameter tree with documentation (.prm syntax). */
    static void print_parameters(std::ostream &out);

    /** Run the scene to its end time; with @p resume, continue from the
        checkpoint in its output directory (same number of processes), or
        with @p resume_from, start a new stage in this scene's (fresh)
        output directory from the checkpoint in that directory: the state
        of another run, continued under this scene's boundary conditions,
        loads and end (doc/user_guide.md, "Stages"). */
    void run(bool resume = false, const std::string &resume_from = "");

    /** A run that goes on from a rebalance's checkpoint (RebalanceRequest):
        the elements partitioned by @p weights (per element id), the wall
        clock of the run from @p wall_start. */
    void set_rebalance(std::vector<unsigned long> weights, std::chrono::steady_clock::time_point wall_start)
    {
      partition_weights = std::move(weights);
      run_wall_start    = wall_start;
    }

    /** Build everything a run needs (mesh, DoFs, boundary conditions,
        contact surfaces) without running or writing: a scene check. */
    void check();

    /** Estimate the run's steps, element-cycles and wall time (the cost per
        element-cycle measured on the initial state); writes nothing. */
    void print_cost();

    /** Largest relative difference of two energies tables (testing aid). */
    const Energies &get_energies() const
    {
      return energies;
    }

  private:
    // Parameters (source/simulator/parameters.cc)
    static void declare_parameters(dealii::ParameterHandler         &prm,
                                   const std::vector<std::string>   &bodies,
                                   const std::vector<std::string>   &bcs,
                                   const std::vector<std::string>   &pairs,
                                   const std::vector<std::string>   &probes,
                                   const std::vector<std::string>   &rebars = {},
                                   const std::vector<std::string>   &stages = {});
    /** Expand the scene and its overrides and parse them strictly into
        @p prm; returns the lists of names (bodies, boundary conditions,
        contact pairs, probes, rebars, stages). A deck of another code
        (Deck::is_deck) is translated first; its warnings go to
        @p deck_notes if given. */
    static std::vector<std::vector<std::string>>
                read_scene(const std::string              &parameter_file,
                           const std::vector<std::string> &overrides,
                           dealii::ParameterHandler       &prm,
                           std::vector<std::string>       *deck_notes = nullptr);
    void        parse_parameters(const std::string              &parameter_file,
                                 const std::vector<std::string> &overrides);

    // Setup (source/simulator/setup.cc)
    /** Mesh, DoFs, element groups, bars, lumped mass, boundary conditions,
        rigid bodies, contact and probes: the one sequence of run(),
        check() and print_cost(). */
    void setup();
    void make_grid();
    /** The owner of each cell of the scene's whole mesh @p serial, by the
        cells' cost per step (setup.cc). */
    void partition_by_cost(dealii::Triangulation<3> &serial) const;
    /** Refine each body's 'Refinement region' in @p serial. */
    void refine_regions(dealii::Triangulation<3> &serial) const;
    /** After every force of the step: the hanging nodes' forces go to
        their masters (nothing without local refinement). */
    void condense_forces();
    /** The order of a checkpoint's state (check_checkpoint()). */
    static constexpr int checkpoint_layout = 13;
    /** The weight of a fully integrated element against 1000 for a
        one-point one: the production column's fully integrated concrete
        (cracking under the hammer, eight return mappings an element)
        costs about 15 one-point elements, measured on one process with
        the region and without it ('element forces' per step, the extra
        over its 576 elements): 15.4 over the whole 150 ms, 15.9 and 13.3
        over the first 40 ms. (Two-process runs cannot measure it on these
        machines: one core of the pair runs up to 60 % slower than the
        other for minutes at a time.) */
    static constexpr unsigned int full_integration_weight = 15000;
    void setup_system();
    void assemble_lumped_mass();
    void setup_probes();
    void setup_section_probe(Probe &probe, double along, double tolerance);
    /** At the start of a run and in --check: the elements with the
        smallest stable steps and a warning for distorted ones (scaled
        Jacobian below 0.3), source/simulator/mesh_quality.cc. */
    void report_element_quality();
    /** One line of what the step evaluates (element groups and which of
        them carry bulk viscosity, rate effects and erosion; contact pairs;
        bars; mass damping; gravity): the same flags that gate the loop. */
    std::string step_contents() const;
    /** Make the output directory and remove the files of the earlier run
        there; with @p check_only, only report what would stop the run. */
    void prepare_output_directory(bool check_only = false);

    // The explicit step (source/simulator/time_integration.cc)
    void   run_scene(bool resume, const std::string &resume_from);
    /** The wall clock of a run and the time it started from. */
    struct RunClock
    {
      std::chrono::steady_clock::time_point wall_start;
      double                                time_start;
      double                                next_wall_progress;
      /** The tolerance of time comparisons, 1e-12 of the end time. */
      double eps;
    };
    /** The stages of run_scene(): setup and the starting state; the step
        from time n (returns the stable step); a progress line; from n to
        n+1; the end of the run. */
    void   start_run(bool resume, const std::string &resume_from);
    double choose_step(bool last);
    void   report_progress(RunClock &clock, bool last);
    void   advance(const RunClock &clock);
    void   finish_run(const RunClock &clock);
    /** The stable step of the current critical element step and the
        contact springs (before the safety factor). */
    double stable_time_step() const;

    // Checkpoints (source/simulator/checkpoint.cc)
    /** Every piece of state a step changes, in one order for writing and
        reading. */
    void serialize(StateArchive &ar);
    /** OUTPUT/NAME/checkpoint/: state.R.bin per process and info, written
        as checkpoint.new and renamed (the previous one stays until then). */
    void write_checkpoint();
    /** Load the checkpoint in @p directory; @p new_stage: the histories,
        frames and summary start afresh (a stage of its own). */
    void load_checkpoint(const std::string &directory, bool new_stage);
    /** The checkpoint in @p directory exists and is of this build's
        layout; InputError otherwise. */
    void check_checkpoint(const std::string &directory) const;
    /** For --resume: the output directory must hold a checkpoint; nothing
        is deleted, the run's file list is read back. */
    void resume_output_directory();
    /** The loop's own schedule (what the step, outputs and end criterion
        have reached). */
    struct LoopState
    {
      double dt_previous   = 0;
      double next_output   = 0;
      double next_history  = 0;
      double next_progress = 0;
      bool   quiet_end     = false;
      /** The step the stable step allows, held against small rises (see
          run_scene). */
      double held_dt       = 0;
      /** The time the run (or its stage) started from. */
      double stage_start = 0;
      /** The next check of the processes' balance ('Rebalance interval'). */
      double next_rebalance = 0;
      /** The next refinement and coarsening ('Adapt interval'). */
      double next_adapt = 0;
    };
    LoopState loop;
    void   zero_forces();
    double compute_internal_forces(double dt_previous);
    void reduce_element_balance();
    void print_element_balance();
    void   apply_contact(double dt_previous);
    /** The kinematic contact pairs' forces of time n, the next step @p dt known;
        false if the scene has none. */
    bool   apply_kinematic_contact(double dt_previous, double dt);
    void   update_velocity(double dt_previous, double dt);
    void   update_position(double dt);
    void   check_health(double time, unsigned int step, double dt_next);

    // Output (source/simulator/output.cc)
    /** Histories at time @p time, between the velocity and the position
        update; @p dt is the coming step (velocities are reported at time
        n as v^{n+1/2} - dt/2 a^n). */
    void write_history(double time, double dt);
    /** A frame of the fields (@p basename 'solution': the next of the
        time series; 'last_good') by the postprocessors, and the families'
        own. */
    void output_results(double time, const std::string &basename);
    /** The 'status' file of the output directory (rank 0; written whole,
        then renamed over the last one): @p state ('running', 'finished',
        'stopped') and the run's progress, for a user to follow. */
    void write_status(const std::string &state, double time, double wall_seconds,
                      double eta_seconds, const std::string &message = "") const;

    /** Figures of the run that summary.csv reports (RunSummary). */
    RunSummary summary;
    /** Per step: the summary figures and the end criterion; true when the
        criterion says the run ends now. */
    bool update_summary(double time);
    void record_probe_summary(const std::vector<double> &probe_values);

    MPI_Comm                   mpi_communicator;
    dealii::ConditionalOStream pcout;
    std::unique_ptr<dealii::TimerOutput> timer;

    /** The settings the driver reads ('Simulation'). */
    Parameters parameters;
    /** Take the inactive bodies out: their motion stops; with
        @p book_energy their kinetic energy and that of their pairs'
        springs is booked as removed (a stage's start). */
    void        remove_inactive_bodies(bool book_energy);

    std::vector<Body>                     bodies;
    std::vector<Probe>                    probes;
    /** The families that add forces beside the element groups and the
        contact pairs, in the order the step calls them (the rigid bodies,
        the reinforcement; ForceContributor). */
    std::vector<std::unique_ptr<ForceContributor>> families;

    // Discretisation
    dealii::parallel::fullydistributed::Triangulation<3> triangulation;
    /** The scene's index of each vertex the process holds (make_grid). */
    std::vector<unsigned int> scene_vertex;
    /** Each active cell's element id (by its local active cell index),
        the same on any number of processes. */
    std::vector<unsigned int> element_id;
    /** By element id: how many times the element's cell was halved during
        the run ('Adapt interval'), beyond the mesh the run started from
        (empty: none was). */
    std::vector<unsigned char> halvings_during_run;
    /** The hanging nodes of local refinement (empty without). */
    HangingNodes        hanging;
    std::vector<double> hanging_position;
    /** The hanging nodes' own lumped masses, before condensation (their
        contact springs' frequency and damping). */
    std::vector<double> hanging_mass;
    /** The owned dofs the central difference leaves to others: the rigid
        bodies' and the hanging ones (empty: none). */
    std::vector<unsigned char> moved_dof;
    dealii::FESystem<3>                             fe;
    dealii::DoFHandler<3>                           dof_handler;
    /** The solid bodies: the element groups (a family, evaluated first). */
    std::unique_ptr<Element::SolidBodies>           solids;

    // Nodal state: reference and current positions, half-step velocity,
    // force and lumped mass, all with ghost entries.
    VectorType reference_position;
    VectorType position;
    VectorType velocity;
    VectorType force;
    VectorType mass;
    /** Body index of each locally owned dof, for momentum output. */
    std::vector<unsigned char> dof_body, dof_component;
    /** Each locally owned dof's key in a checkpoint, 3 (its node's scene
        vertex) + component: the same for any partition. */
    std::vector<std::uint64_t> dof_key;

    /** A mask of the owned dofs that belong to rigid bodies (empty: no
        rigid bodies), set by the rigid-body family. */
    std::vector<unsigned char> rigid_dof;
    /** The rigid-body family (one of 'families'): the contact pairs hand
        it the reactions of analytic shapes. */
    RigidBody::RigidBodies *rigid_bodies = nullptr;

    /** The kinematic constraints and loads (one of 'families', the last:
        boundary conditions, mass damping, gravity), called at three
        points of the velocity update. */
    ConstraintsAndLoads *constraints = nullptr;

    /** The contact pairs: a family of their own, evaluated after the
        element forces and erosion (apply_contact). */
    std::unique_ptr<Contact::ContactPairs> contact;
    /** Every family for the hooks that are not the forces (setup, mass,
        energy and momentum terms, histories, fields, summary, checkpoint):
        the solid bodies, the families in their order, then the contact
        pairs. */
    const std::vector<ForceContributor *> &contributors() const
    {
      return all_families;
    }
    std::vector<ForceContributor *> all_families;

    // Energy bookkeeping
    Energies     energies;
    double       critical_dt    = 0;
    double       current_dt     = 0;
    unsigned int step_number    = 0;
    double       time           = 0;


    /** What the run writes besides the families' histories, in their
        order (source/postprocess/, Postprocess::Interface). */
    std::vector<std::unique_ptr<Postprocess::Interface>> postprocessors;
    /** Every history file (rank 0) in a fixed order: the postprocessors',
        then the families'. */
    std::vector<HistoryFile *> history_files() const;
    /** Write the rows every history holds, all together (rank 0); a write
        error is kept in output_failure, shared with the other ranks at the
        next health check. */
    void                         flush_histories();
    /** Note @p name (in the output directory) in anvil_files.txt before it
        is written: the next run in that directory deletes just these
        (rank 0). */
    void                         record_output(const std::string &name);
    /** The energy balance and the health checks on it (check_health). */
    struct Balance
    {
      double initial_energy = 0;
      double balance_error  = 0;
      /** Running maximum of E_kin, E_int, E_0, |W_ext|: the balance scale. */
      double energy_scale = 0;
      /** The step-change energy of time n, booked at n+1 (the identity at
          time n holds with the terms of the earlier steps). */
      double pending_step_change = 0;
      /** Consecutive steps with the step-change energy creating more than
          the tolerance, with the energy above it, and with the internal
          energy below minus it. */
      unsigned int step_change_steps = 0;
      unsigned int growth_steps      = 0;
      unsigned int negative_steps    = 0;
      /** The first step's stable step (for 'Minimum time step ratio'). */
      double first_dt = 0;
      /** The last state that passed the health checks. */
      VectorType good_position, good_velocity;
      double     good_time = 0;
    } balance;

    /** What the run has written and when it writes next: histories
        flushed together, the files noted in anvil_files.txt, the frames,
        checkpoints. */
    struct OutputState
    {
      /** Whether this run's output directory exists (a status file can go
          there). */
      bool                                  directory_ready = false;
      std::chrono::steady_clock::time_point last_flush;
      unsigned int                          rows_since_flush = 0;
      /** A failed write of the histories (rank 0), shared with the other
          ranks at the next health check. */
      std::string           failure;
      std::set<std::string> recorded_outputs;
      /** The frames of the time series so far. */
      unsigned int                          output_count    = 0;
      double                                next_checkpoint = 1e300;
      std::chrono::steady_clock::time_point last_checkpoint_wall;
      bool                                  checkpoint_due = false;
      bool                                  stop_requested = false;
    } output;

    /** With 'Print wall times' on several processes: the wall time of each
        step's element loop on this process, reduced over the processes
        every 4096 steps into the sums (this run's steps), and what the
        ranks lose waiting for the slowest one, printed at the end
        (print_element_balance()). */
    struct ElementBalance
    {
      std::vector<float> seconds;
      bool               record = false;
      unsigned long      steps  = 0;
      double             own = 0, slowest_by_step = 0, mean = 0;
    } element_balance;

    /** 'Rebalance interval': the processes' element times since the last
        check; past the threshold, each element's weight (its group's time
        per element on its process), a checkpoint and a RebalanceRequest. */
    void check_balance();
    /** The weights of a rebalance (per element id; empty: by element kind,
        partition_by_cost()) and the wall clock's start of the whole run. */
    std::vector<unsigned long>                   partition_weights;
    /** The step from which the elements' times count: the first steps
        after a start or a new partition run slower (pages touched for the
        first time, cold caches) wherever their elements are. */
    unsigned int timing_from_step = 0;
    /** The wall time this run's start took (setup, checkpoint, first
        forces), the slowest process's: a new partition costs about as
        much ('Rebalance when it pays'). Units: s. */
    double startup_seconds = 0;
    std::optional<std::chrono::steady_clock::time_point> run_wall_start;

    // Refinement and coarsening during the run (source/simulator/adaptivity.cc)

    /** 'Adapt interval': each element's wish (finer, coarser) from its
        body's 'Refinement region' in the current state; where any element
        changes, the round is recorded, a checkpoint written and a
        RebalanceRequest thrown: the run goes on on the new mesh. */
    void check_adaptivity();
    /** The rounds of refinement and coarsening of this run so far, each
        the element ids (of the mesh before it) to refine (id + 1) and to
        coarsen (-(id + 1)), and how many of them the state of the
        checkpoint to resume from was computed on (read_adaptation()). */
    std::vector<std::vector<std::int64_t>> adapt_rounds;
    unsigned int                           state_rounds = 0;
    /** The rounds of the checkpoint in @p directory ('adaptation'), for
        the mesh of a run that resumes from it. */
    void read_adaptation(const std::string &directory);
    /** The rounds into @p directory (a checkpoint's), the state's count
        @p state_count. */
    void write_adaptation(const std::string &directory, unsigned int state_count) const;
    /** The rounds applied to the scene's serial mesh (after the regions);
        where the state to load is of the mesh before the last round, the
        sources of the new nodes and elements are kept (below). */
    void replay_adaptation(dealii::Triangulation<3> &serial);
    /** A resume onto the mesh of one more round: each new node's (by
        scene vertex) motion from the old nodes around it; each new
        element's sources. */
    bool                                                                   transferring = false;
    std::map<unsigned int, std::vector<std::pair<unsigned int, double>>> motion_sources;
    std::shared_ptr<ElementTransfer>                                       element_sources;
    /** Loading: the nodes' table of the mesh before onto this one. */
    void load_transferred_nodes(StateArchive &ar);
    /** After a transferred load (@p old_nodes: the checkpoint's table of
        the nodes of the mesh before): the contact surfaces' erosion, the
        forces of the new mesh, the energy the transfer changed. */
    void finish_transfer(const KeyedTable &old_nodes);
    /** The rounds the current mesh was built with, and the coarsenings of
        the last round that deal.II refused (the level difference of
        neighbours), by element id: not asked for again on this mesh. */
    unsigned int            mesh_rounds = 0;
    std::set<unsigned long> coarsening_refused;
    /** The serial mesh the run's elements were cut from (after the
        regions and the rounds), kept where the run adapts: a round of
        joins alone is first asked of its flags. */
    std::unique_ptr<dealii::Triangulation<3>> serial_mesh;
  };

  /**
   * A run of @p file (Simulator::run()), partitioned anew from its
   * checkpoint wherever it asks (RebalanceRequest), until it ends.
   */
  void run_simulator(const std::string              &file,
                     MPI_Comm                        comm,
                     const std::vector<std::string> &overrides,
                     bool                            resume,
                     const std::string              &resume_from = "");

  /**
   * `anvil SCENE.prm` (and --check, --resume): the scene's own run, then
   * each of its 'Stages' on the state the one before left
   * (source/simulator/stages.cc); a scene without stages is one run.
   */
  void run_scene_with_stages(const std::string              &file,
                             const std::vector<std::string> &overrides,
                             MPI_Comm                        comm,
                             bool                            resume,
                             bool                            check_only);
} // namespace anvil
