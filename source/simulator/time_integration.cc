/**
 * @file
 * The explicit central-difference loop (seed section 3.6):
 *
 *   a^n       = M^{-1} (f_ext^n - f_int^n + f_contact^n)            (Eq. 35)
 *   v^{n+1/2} = v^{n-1/2} + (dt^{n-1/2} + dt^{n+1/2}) / 2 a^n
 *   x^{n+1}   = x^n + dt^{n+1/2} v^{n+1/2}
 *
 * with the lumped mass M, and dt^{n+1/2} = factor * min_e L_e / c_e from
 * the configuration x^n.
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/step_section.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * 'End capacity drop' at a history row: whether the reaction of the
     * capacity support (summed over the processes, the same on each) has
     * stayed below its peak less the drop for 'End quiet time' (not the
     * dips of the wave the push's start sends through the member, rho c v
     * A, which fall below half their first peak for a fraction of a ms).
     * Records since when it is below, and the reaction that ends the run.
     */
    bool capacity_past_peak(const ConstraintsAndLoads &constraints,
                            const EndCriterion        &end,
                            const double               time,
                            const double               eps,
                            RunSummary                &summary)
    {
      if (end.capacity_drop <= 0)
        return false;
      const auto &conditions = constraints.get_conditions();
      for (unsigned int b = 0; b < conditions.size() && b < constraints.peak_reactions().size(); ++b)
        if (conditions[b].name == constraints.capacity_support())
          {
            const double *r    = &constraints.reactions()[3 * b];
            const double  now  = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
            const double  peak = constraints.peak_reactions()[b];
            if (!(peak > 0 && now <= (1. - end.capacity_drop) * peak))
              summary.capacity_below_since = -1;
            else if (summary.capacity_below_since < 0)
              summary.capacity_below_since = time;
            if (summary.capacity_below_since >= 0 && time - summary.capacity_below_since >= end.quiet_time - eps)
              {
                summary.capacity_end_reaction = now;
                return true;
              }
          }
      return false;
    }
  } // namespace

  void Simulator::zero_forces()
  {
    std::fill(force.begin(),
              force.begin() + force.locally_owned_size() +
                force.get_partitioner()->n_ghost_indices(),
              0.);
    // The body forces of the loads (gravity) start the sum.
    constraints->set_body_forces(force);
  }


  // @sect3{Internal forces}
  //
  // The solid bodies' elements (Element::SolidBodies; no communication in
  // their section), then the families
  // with forces of their own (the bars: each process its share, their
  // energy counted once), each timed in its own section, then the elements'
  // energy increments (summed over the processes and booked after the
  // families' work, as they always were: the same sums, bit for bit) and
  // erosion: the eroded elements' faces leave every family that holds them
  // (the contact pairs).
  double Simulator::compute_internal_forces(const double dt_previous)
  {
    StepSection t(*timer, parameters.print_wall_times, "element forces");
    // (The clock only where the balance is recorded.)
    const auto start =
      element_balance.record ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();
    double dt_crit = solids->add_forces(dt_previous);
    if (element_balance.record)
      {
        element_balance.seconds.push_back(
          std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count());
        if (element_balance.seconds.size() == 4096)
          reduce_element_balance();
      }
    t.stop();
    for (auto &family : families)
      if (!family->empty() && family->has_forces())
        {
          StepSection section(*timer, parameters.print_wall_times, family->name());
          dt_crit = std::min(dt_crit, family->add_forces(dt_previous));
        }
    // The step's first collective: a process that finished its elements
    // early waits here (or at the bars' exchange), not in 'element forces',
    // whose minimum and maximum over the processes show the imbalance.
    StepSection r(*timer, parameters.print_wall_times, "reductions");
    const std::vector<unsigned long> eroded = solids->finish_forces();
    if (!eroded.empty())
      contact->deactivate_elements(eroded);
    return Utilities::MPI::min(dt_crit, mpi_communicator);
  }


  // @sect3{Central difference update}
  //
  // The velocity update also gives the kinetic energy at the integer time
  // n and the work of the reaction forces at constrained dofs, in the forms
  // that make the discrete energy identity of the scheme hold for variable
  // steps (doc/theory.md, "Energy balance with variable steps"):
  //
  //   K^n = 1/2 v^{n-1/2} . (M v^{n-1/2} + dt^{n-1/2} F^n),
  //
  // the kinetic energy of the last half-step velocity plus the work of the
  // force F^n = M a^n over the second half of the last step, and the
  // reaction work by the trapezoidal rule over the step just made,
  // (R^{n-1} + R^n)/2 . (x^n - x^{n-1}), the rule the elements use for
  // the internal energy. (The form 1/2 v^{n-1/2} M v^{n+1/2} agrees with
  // K^n only when dt^{n+1/2} = dt^{n-1/2}: a step cut short by the end
  // time or a change of the stable step made it jump.)
  // Histories are written between the velocity and the position update,
  // when positions are those of time n.
  // @sect3{Contact}
  //
  // The contact pairs, after the element forces and erosion (an eroded
  // element's faces have left the pairs): Contact::ContactPairs.
  void Simulator::apply_contact(const double dt_previous)
  {
    if (contact->empty())
      return;
    StepSection t(*timer, parameters.print_wall_times, "contact");
    contact->add_forces(dt_previous);
  }


  // Kinematic pairs correct the motion predicted over the step dt from all
  // other forces of time n (Contact::KinematicContact); false without such
  // pairs.
  bool Simulator::apply_kinematic_contact(const double dt_previous, const double dt)
  {
    if (contact->empty() || !contact->has_kinematic())
      return false;
    StepSection t(*timer, parameters.print_wall_times, "contact");
    contact->add_kinematic_forces(dt_previous, dt);
    return true;
  }


  void Simulator::update_velocity(const double dt_previous, const double dt)
  {
    StepSection t(*timer, parameters.print_wall_times, "time integration");
    const double       dt_avg = 0.5 * (dt_previous + dt);
    const unsigned int n      = position.locally_owned_size();
    double            *v      = velocity.begin();
    const double      *f      = force.begin();
    const double      *m      = mass.begin();
    // sum_i v^{n-1/2} (m v^{n-1/2} + dt^{n-1/2} F^n) and sum_i F^n dv.
    double kinetic = 0, power = 0;
    // The held dofs' v^{n-1/2} (and their prescribed velocities of
    // t^{n+1/2}); the free dofs' update, damped or not; the held ones back
    // to their prescribed velocities by their reactions.
    constraints->begin_velocity_update(v, time, dt);
    if (constraints->damps())
      constraints->damped_velocity_update(dt_previous, dt_avg, f, m, v, moved_dof, kinetic, power);
    else
      {
        // (The sums in locals: 'kinetic' and 'power' go to the constraints
        // by reference, so that GCC kept them in memory, a store and a
        // load in every dof's chain of additions. The same additions in
        // the same order: the same bits.)
        double k = 0, w = 0;
        if (moved_dof.empty())
          for (unsigned int i = 0; i < n; ++i)
            {
              const double v_old = v[i];
              const double dv    = dt_avg * f[i] / m[i];
              v[i] += dv;
              k += v_old * (m[i] * v_old + dt_previous * f[i]);
              w += f[i] * dv;
            }
        else
          for (unsigned int i = 0; i < n; ++i)
            if (!moved_dof[i])
              {
                const double v_old = v[i];
                const double dv    = dt_avg * f[i] / m[i];
                v[i] += dv;
                k += v_old * (m[i] * v_old + dt_previous * f[i]);
                w += f[i] * dv;
              }
        kinetic = k;
        power   = w;
      }
    double work = 0;
    constraints->impose(dt_previous, dt_avg, f, m, v, kinetic, work, power);
    std::vector<double> sums = {kinetic, work, power};
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    OwnMotion own;
    for (auto &family : families)
      if (!family->empty())
        family->update_velocity(dt_previous, dt, own);
    // The hanging nodes follow their masters' new velocities.
    if (!hanging.empty())
      {
        velocity.update_ghost_values();
        hanging.distribute(v, n);
      }
    energies.kinetic = 0.5 * sums[0] + own.kinetic;
    energies.external_work += sums[1] + own.work;
    // The identity at time n holds with the step-change terms of the steps
    // before n; this step's is booked at n+1. The last call (dt = 0, the
    // synchronisation of the velocities) needs none: K^n is exact there.
    energies.step_change += balance.pending_step_change;
    balance.pending_step_change = dt > 0 ? 0.25 * (dt - dt_previous) * (sums[2] + own.power) : 0.;
  }


  void Simulator::update_position(const double dt)
  {
    StepSection t(*timer, parameters.print_wall_times, "time integration");
    const unsigned int n = position.locally_owned_size();
    double            *x = position.begin();
    const double      *v = velocity.begin();
    // (A hanging node's position: its masters' new ones, weighed.)
    if (!hanging.empty())
      hanging.advance(x, v, dt, n, hanging_position);
    for (unsigned int i = 0; i < n; ++i)
      x[i] += dt * v[i];
    if (!hanging.empty())
      hanging.assign(x, n, hanging_position);
    // (The families' own nodes; the loads book the work of gravity, m g .
    // (x^{n+1} - x^n).)
    for (auto &family : families)
      if (!family->empty())
        family->update_position(dt);
  }


  // @sect3{Health checks}
  //
  // The balance error is |E_total - E_0 - W_ext| / max(E_kin, E_int, E_0,
  // |W_ext|), each maximum taken over the run so far: the external work
  // belongs in the scale for scenes that start at rest and are loaded by
  // gravity or boundary motion, where E_0 = 0.
  //
  // A numerical failure stops the run with a message naming the time, the
  // step, the element and its position, after writing the last good state.
  //
  // Also a stop: the internal energy below minus the tolerance for ten
  // steps (stored plus dissipated energy of passive materials is >= 0: a
  // material that returns more work than it took drives the motion), and
  // the stable step below 'Minimum time step ratio' of the first one.
  void Simulator::check_health(const double t, const unsigned int step, const double dt_next)
  {
    // One reduction for the inverted elements and a failed write of the
    // histories (rank 0's files).
    // ... and, from rank 0's clock and every rank's signal handler, whether
    // a checkpoint is due and whether the run was asked to stop.
    const bool wall_due = parameters.checkpoint_wall_interval > 0 &&
                          std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                        output.last_checkpoint_wall)
                              .count() >= parameters.checkpoint_wall_interval &&
                          Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    std::array<double, 4> flags{{double(solids->inverted_cell()),
                                 output.failure.empty() ? 0. : 1.,
                                 wall_due ? 1. : 0.,
                                 stop_signal_received() ? 1. : 0.}};
    Utilities::MPI::max(ArrayView<const double>(flags.data(), flags.size()),
                        mpi_communicator,
                        ArrayView<double>(flags.data(), flags.size()));
    if (flags[2] != 0)
      output.checkpoint_due = true;
    if (flags[3] != 0)
      output.stop_requested = true;
    if (flags[1] != 0)
      throw OutputError(output.failure.empty() ? "a history file could not be written (see rank 0)" :
                                                 output.failure);
    const long int inverted = std::lround(flags[0]);
    std::string    problem;
    if (inverted >= 0)
      problem = "element " + std::to_string(inverted) + " is inverted (Jacobian <= 0)";
    // Springs so stiff that the step they allow is below the ratio of the
    // elements' own: a penalty factor out of all proportion (or an
    // overflow to infinity), which would otherwise take the step to zero
    // at once and the run nowhere.
    const double dt_stable = dt_next / parameters.time_step_factor;
    // Contact lost by pass-through (replicated results: no reduction).
    const auto &contact_results = contact->results();
    for (unsigned int p = 0; p < contact_results.size() && problem.empty(); ++p)
      if (contact_results[p].n_passed_through > 0)
        {
          std::ostringstream s;
          s << "contact pair '" << contact->pair(p).name << "': " << contact_results[p].n_passed_through
            << " node(s) in contact last step passed through the surface they pressed on (now "
            << contact_results[p].passed_through_ratio
            << " of its element's thickness deep): the springs cannot stop this impact within a step; "
               "raise the pair's 'Penalty scale factor' or lower 'Time step safety factor'";
          problem = s.str();
        }
    if (problem.empty() && parameters.min_dt_ratio > 0 && !(dt_stable >= parameters.min_dt_ratio * critical_dt))
      {
        std::ostringstream s;
        s << "the contact springs allow a stable time step of " << dt_stable << " s, "
          << dt_stable / critical_dt << " of the elements' " << critical_dt << " s (limit "
          << parameters.min_dt_ratio
          << ", 'Minimum time step ratio'): lower the contact pairs' 'Penalty scale factor'";
        problem = s.str();
      }
    if (balance.first_dt == 0)
      balance.first_dt = dt_next;
    if (problem.empty() && parameters.min_dt_ratio > 0 && dt_next < parameters.min_dt_ratio * balance.first_dt)
      {
        std::ostringstream s;
        s << "the stable time step fell to " << dt_next << " s, " << dt_next / balance.first_dt
          << " of the first step's (limit " << parameters.min_dt_ratio
          << ", 'Minimum time step ratio'): an element is collapsing";
        problem = s.str();
      }
    const double e_total = energies.total();
    // The largest energy level the run has reached: once energy has
    // flowed through the model, an absolute error small against it is no
    // growth even when the energies return near zero (a bar that rings).
    balance.energy_scale = std::max({balance.energy_scale, std::abs(energies.kinetic), std::abs(energies.internal),
                             std::abs(balance.initial_energy), std::abs(energies.external_work), 1e-300});
    const double scale = balance.energy_scale;
    balance.balance_error = std::abs(e_total - balance.initial_energy - energies.external_work) / scale;
    if (problem.empty() && !std::isfinite(e_total))
      problem = "the energies are not finite (NaN or infinity)";
    // Energy growth must persist: a single step's excess can be the
    // O(omega dt) error with which the leapfrog measures the energy of the
    // highest modes after a sudden start; an instability grows without
    // bound.
    if ((e_total - balance.initial_energy - energies.external_work) > parameters.energy_tolerance * scale)
      ++balance.growth_steps;
    else
      balance.growth_steps = 0;
    if (energies.internal < -parameters.energy_tolerance * scale)
      ++balance.negative_steps;
    else
      balance.negative_steps = 0;
    if (problem.empty() && balance.negative_steps >= 10)
      {
        std::ostringstream s;
        s << "the internal energy is negative, " << energies.internal << " J ("
          << 100. * energies.internal / scale
          << " % of the largest of E_kin, E_int, E_0, |W_ext| so far; limit "
          << 100. * parameters.energy_tolerance
          << " %, 'Energy balance tolerance'): a material returns more work than it took";
        problem = s.str();
      }
    // Energy created by changes of the step: the variable-step scheme is
    // not unconditionally stable even below the stable step of every single
    // step (a step that switches back and forth resonates with the mesh's
    // modes); the balance closes with this term, so it is checked itself.
    if (-energies.step_change > parameters.energy_tolerance * scale)
      ++balance.step_change_steps;
    else
      balance.step_change_steps = 0;
    if (problem.empty() && balance.step_change_steps >= 10)
      {
        std::ostringstream s;
        s << "the changes of the time step created " << -energies.step_change << " J ("
          << -100. * energies.step_change / scale
          << " % of the largest of E_kin, E_int, E_0, |W_ext| so far; limit "
          << 100. * parameters.energy_tolerance
          << " %, 'Energy balance tolerance'): the explicit step is unstable, or a step that "
             "varies back and forth resonates with the mesh; lower 'Time step safety factor' (now "
          << parameters.time_step_factor << ")";
        if (balance.first_dt > 0 && dt_next < 0.5 * balance.first_dt)
          s << "; the stable step has fallen to " << dt_next / balance.first_dt
            << " of the first step's: an element is collapsing";
        problem = s.str();
      }
    const bool other_problem = !problem.empty();
    if (problem.empty() && balance.growth_steps >= 10)
      {
        std::ostringstream s;
        s << "the total energy grew by " << 100. * balance.balance_error
          << " % of the largest of E_kin, E_int, E_0, |W_ext| so far beyond the external work (limit "
          << 100. * parameters.energy_tolerance
          << " %, 'Energy balance tolerance'); the explicit step is unstable "
             "(time step safety factor "
          << parameters.time_step_factor << ")";
        problem = s.str();
      }
    if (other_problem && balance.growth_steps > 0)
      {
        std::ostringstream s;
        s << "; the explicit step is unstable: the total energy had grown for " << balance.growth_steps
          << " steps to " << 100. * balance.balance_error
          << " % of the largest of E_kin, E_int, E_0, |W_ext| so far beyond the external work (time step safety factor "
          << parameters.time_step_factor << ")";
        problem += s.str();
      }
    if (problem.empty())
      {
        if (step % 50 == 0)
          {
            balance.good_position = position;
            balance.good_velocity = velocity;
            balance.good_time     = t;
          }
        return;
      }

    // Where: the element of the fastest node (or the inverted one).
    double vmax = -1;
    long   cell = -1, element_id = -1;
    for (const auto &group : solids->groups())
      for (unsigned int e = 0; e < group.n_elements(); ++e)
        {
          if (inverted >= 0 && long(group.element_cell_index(e)) != inverted)
            continue;
          for (const unsigned int node : group.element_nodes(e))
            {
              double s = 0;
              for (unsigned int d = 0; d < 3; ++d)
                s += velocity.local_element(node + d) * velocity.local_element(node + d);
              if (!std::isfinite(s))
                s = 1e308;
              if (s > vmax)
                {
                  vmax       = s;
                  cell       = group.element_cell_index(e);
                  element_id = group.element_global_id(e);
                }
            }
        }
    const double global_max = Utilities::MPI::max(vmax, mpi_communicator);
    Point<3>     where;
    unsigned int body  = 0;
    int          mine  = (vmax == global_max && cell >= 0) ?
                           int(Utilities::MPI::this_mpi_process(mpi_communicator)) :
                           -1;
    const int    owner = Utilities::MPI::max(mine, mpi_communicator);
    if (owner >= 0 && mine == owner)
      for (const auto &c : triangulation.active_cell_iterators())
        if (c->is_locally_owned() && long(c->active_cell_index()) == cell)
          {
            where = c->center();
            body  = c->material_id();
          }
    // The element by its scene-wide id (element_id in the VTU output).
    std::array<double, 5> info{{where[0], where[1], where[2], double(body), double(element_id)}};
    if (owner >= 0)
      info = Utilities::MPI::broadcast(mpi_communicator, info, owner);

    // Leave the last good state on disk, and the histories' rows so far
    // (whole rows: they wait in memory for up to a second otherwise).
    flush_histories();
    position = balance.good_position;
    velocity = balance.good_velocity;
    position.update_ghost_values();
    velocity.update_ghost_values();
    output_results(balance.good_time, "last_good");

    std::ostringstream msg;
    msg << "numerical failure at t = " << t << " s, step " << step << ": "
        << problem << "; at element " << long(info[4]) << " of body '"
        << bodies[int(info[3])].name << "' near (" << info[0] << ", " << info[1]
        << ", " << info[2] << "); last good state (t = " << balance.good_time
        << " s) written to " << parameters.output_directory << "/last_good.pvtu";
    throw NumericalFailure(msg.str());
  }


  // The stable step (seed section 3.6) of the elements' critical step: with
  // contact springs of frequency omega_c on top of the elements' omega_e =
  // 2 / dt_e it is 2 / sqrt(omega_e^2 + omega_c^2) (seed section 4.3: large
  // penalty factors need smaller steps).
  double Simulator::stable_time_step() const
  {
    const double contact_frequency_squared = contact->frequency_squared();
    return contact_frequency_squared > 0 ?
             1. / std::sqrt(1. / (critical_dt * critical_dt) + 0.25 * contact_frequency_squared) :
             critical_dt;
  }


  // @sect3{What a run will cost}
  //
  // Before a long run: the number of steps from the stable step of the
  // initial mesh, the element-cycles, and the wall time from the cost per
  // element-cycle measured here on the first 20 steps (elements, bars,
  // contact, time integration). Nothing is written.
  void Simulator::print_cost()
  {
    timer = std::make_unique<TimerOutput>(pcout, TimerOutput::never, TimerOutput::wall_times);
    const auto setup_start = std::chrono::steady_clock::now();
    setup();
    const double setup_seconds = Utilities::MPI::max(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count(), mpi_communicator);
    position.update_ghost_values();
    velocity.update_ghost_values();
    zero_forces();
    critical_dt = compute_internal_forces(0.);
    apply_contact(0.);
    condense_forces();
    const double dt_stable = stable_time_step();
    double       dt        = parameters.time_step_factor * dt_stable;
    if (parameters.max_dt_constant > 0)
      dt = std::min(dt, parameters.max_dt_constant);
    const double       steps    = std::ceil(parameters.end_time / dt);
    const double       elements = triangulation.n_global_active_cells();
    const unsigned int samples  = 20;
    MPI_Barrier(mpi_communicator);
    const auto start = std::chrono::steady_clock::now();
    // Whole steps (forces, velocity and position updates, the ghost
    // exchange) from the initial state; only histories, checks and output
    // are left out. The state they leave is never written.
    for (unsigned int k = 0; k < samples; ++k)
      {
        apply_kinematic_contact(k == 0 ? 0. : dt, dt);
        update_velocity(k == 0 ? 0. : dt, dt);
        update_position(dt);
        position.update_ghost_values();
        velocity.update_ghost_values();
        zero_forces();
        compute_internal_forces(dt);
        apply_contact(dt);
        condense_forces();
      }
    const double wall = Utilities::MPI::max(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), mpi_communicator);
    const double ns = 1e9 * wall / (samples * elements);
    const double estimate = ns * 1e-9 * steps * elements;
    pcout << std::setprecision(3) << "cost of '" << parameters.scene_name << "': " << (unsigned long)elements
          << " elements, stable step " << dt_stable << " s (safety factor " << parameters.time_step_factor
          << ") -> " << (unsigned long)steps << " steps to 'End time' " << parameters.end_time << " s = "
          << steps * elements << " element-cycles\n"
          << "  measured here: " << ns << " ns per element-cycle (the first " << samples << " steps, "
          << Utilities::MPI::n_mpi_processes(mpi_communicator) << " process(es)) -> about " << estimate
          << " s (" << estimate / 60. << " min) of wall time\n"
          << "  (the step shrinks as elements deform, materials that soften or yield cost more than "
             "in their elastic range, and 'End kinetic energy fraction' may end the run earlier)"
          << std::endl;
    // Refinement during the run: the mesh lies between the start's and
    // every element of the refined bodies at its finest level.
    if (parameters.adapt_interval > 0)
      {
        double finest = 0;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              const unsigned int levels = bodies[cell->material_id()].local_refinement_levels();
              finest += std::pow(8., std::max(0, int(levels) - cell->level()));
            }
        finest = Utilities::MPI::sum(finest, mpi_communicator);
        pcout << "  'Adapt interval' " << parameters.adapt_interval << " s: between " << (unsigned long)elements
              << " elements (the start) and " << (unsigned long)finest
              << " (every element of the refined bodies at its finest level, the step that of their "
                 "smallest elements); each round that changes the mesh costs about a start of the run (" << setup_seconds
              << " s here: the scene built anew, the checkpoint written and read), at most "
              << (unsigned long)std::max(0., std::ceil(parameters.end_time / parameters.adapt_interval) - 1.) << " rounds"
              << std::endl;
      }
  }


  // @sect3{The run}
  void Simulator::run(const bool resume, const std::string &resume_from)
  {
    try
      {
        run_scene(resume, resume_from);
      }
    catch (const RebalanceRequest &)
      {
        // (The run goes on from its checkpoint: no summary of its part.)
        if (timer)
          {
            timer->disable_output();
            timer.reset();
          }
        throw;
      }
    catch (...)
      {
        // Every rank arrives here together (input errors and numerical
        // failures follow from replicated data or global reductions); the
        // timing summary of a failed run is of no use.
        if (output.directory_ready)
          {
            std::string message = "unknown error";
            try
              {
                throw;
              }
            catch (const std::exception &e)
              {
                message = e.what();
              }
            catch (...)
              {}
            try
              {
                write_status("stopped", time, -1., -1., message);
              }
            catch (...)
              {}
          }
        if (timer)
          {
            timer->disable_output();
            timer.reset();
          }
        throw;
      }
  }


  // @sect3{The run}
  //
  // Setup and the initial state (or a checkpoint's), then per step: the
  // step size, the velocity update with the forces of time n, the health
  // checks, histories and progress at time n, then the positions of n+1
  // and their forces; the end of the run writes the summaries.
  void Simulator::run_scene(const bool resume, const std::string &resume_from)
  {
    start_run(resume, resume_from);
    RunClock clock{run_wall_start.value_or(std::chrono::steady_clock::now()), time, 0., 1e-12 * parameters.end_time};
    output.next_checkpoint      = parameters.checkpoint_interval > 0 ? time + parameters.checkpoint_interval : 1e300;
    output.last_checkpoint_wall = clock.wall_start;
    double      &dt_previous  = loop.dt_previous;
    double      &next_history = loop.next_history;
    bool        &quiet_end    = loop.quiet_end;
    const double eps          = clock.eps;
    while (true)
      {
        const bool   last      = time >= parameters.end_time - eps || quiet_end;
        const double dt_stable = choose_step(last);
        // Contact energy of the configuration x^n.
        energies.contact = 0;
        for (const auto &r : contact->results())
          energies.contact += r.energy;

        // The state a next stage starts from: x^n, v^{n-1/2} and F^n, before
        // the last step synchronises the velocities, so that the stage goes
        // on with the step this run would have made (bitwise the same as
        // one run through the stage change).
        if (last && parameters.checkpoint_at_end)
          write_checkpoint();
        // Kinematic contact pairs, now that the step is known (after the
        // checkpoint: a run resumed from it makes their forces anew).
        if (apply_kinematic_contact(dt_previous, last ? 0. : current_dt))
          {
            energies.contact = 0;
            for (const auto &r : contact->results())
              energies.contact += r.energy;
          }
        update_velocity(dt_previous, last ? 0. : current_dt);
        check_health(time, step_number, parameters.time_step_factor * dt_stable);
        // The end criterion, met at time n, makes n+1 the last time (the
        // velocities are at n+1/2 already).
        if (update_summary(time) && !last)
          quiet_end = true;
        if (time >= next_history - eps || last)
          {
            write_history(time, last ? 0. : current_dt);
            next_history += parameters.history_interval;
            if (!last && capacity_past_peak(*constraints, parameters.end_criterion, time, eps, summary))
              quiet_end = true;
          }
        report_progress(clock, last);
        if (last)
          break;
        if (step_number >= parameters.max_steps)
          {
            flush_histories();
            throw NumericalFailure("the run reached 'Maximum number of steps' = " +
                                   std::to_string(parameters.max_steps) + " at t = " +
                                   std::to_string(time) + " s");
          }

        advance(clock);
      }
    finish_run(clock);
  }


  // Build the scene, prepare the output directory, and set up the state
  // the loop starts from: the initial one (its forces, energy and first
  // frame) or a checkpoint's.
  void Simulator::start_run(const bool resume, const std::string &resume_from)
  {
    const auto start = std::chrono::steady_clock::now();
    // Each rank times its own sections: a TimerOutput over the communicator
    // would put a barrier before and after every section of every step
    // (about a dozen a step), which turns each section's imbalance into
    // waiting. The summary is rank 0's; on more processes the minimum,
    // average and maximum over the ranks follow it.
    timer = std::make_unique<TimerOutput>(pcout,
                                          parameters.print_wall_times ? TimerOutput::summary :
                                                             TimerOutput::never,
                                          TimerOutput::wall_times);
    {
      TimerOutput::Scope t(*timer, "setup");
      // (The mesh of a run that goes on from a checkpoint has its rounds
      // of refinement and coarsening.)
      if (resume)
        read_adaptation(parameters.output_directory + "/checkpoint");
      else if (!resume_from.empty())
        read_adaptation(resume_from);
      else
        adapt_rounds.clear(), state_rounds = 0;
      setup();
      if (resume)
        resume_output_directory();
      else
        {
          if (!resume_from.empty())
            check_checkpoint(resume_from);
          prepare_output_directory();
        }
      output.directory_ready = true;
      record_output("status");
      position.update_ghost_values();
      velocity.update_ghost_values();
      balance.good_position = position;
      balance.good_velocity = velocity;
    }

    // (A run that goes on after a rebalance has said all this.)
    if (!run_wall_start)
      {
        pcout << "Anvil: scene '" << parameters.scene_name << "' from " << parameters.scene_file << "\n"
              << "  " << Utilities::MPI::n_mpi_processes(mpi_communicator)
              << " MPI process(es), " << triangulation.n_global_active_cells()
              << " elements, " << dof_handler.n_dofs() << " degrees of freedom\n";
        // (The elements of a 'Full integration region': those of a
        // one-point body's group of eight-point elements.)
        // On several processes, each one's share too (the partition's
        // balance of the expensive kind).
        std::vector<unsigned long> own_full(bodies.size(), 0);
        for (unsigned int g = 0; g < solids->groups().size(); ++g)
          {
            const auto        &group = solids->groups()[g];
            const unsigned int b     = solids->group_body()[g];
            if (group.n_quadrature_points() == 8 && bodies[b].integration == Element::Integration::one_point)
              for (unsigned int e = 0; e < group.n_elements(); ++e)
                own_full[b] += group.element_is_owned(e) ? 1 : 0;
          }
        const auto full_per_process = Utilities::MPI::gather(mpi_communicator, own_full);
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            pcout << "  body '" << bodies[b].name << "': " << to_string(bodies[b].formulation) << ", "
                  << Element::to_string(bodies[b].integration) << " integration"
                  << (bodies[b].integration == Element::Integration::one_point ?
                        ", " + Element::to_string(bodies[b].hourglass) + " hourglass control" :
                        std::string());
            if (bodies[b].has_full_integration_region())
              {
                unsigned long full = 0;
                std::string   shares;
                for (const auto &process : full_per_process)
                  {
                    full += process[b];
                    shares += (shares.empty() ? "" : ", ") + std::to_string(process[b]);
                  }
                pcout << "; " << full << " element(s) fully integrated ('Full integration region')"
                      << (full_per_process.size() > 1 ? " (per process: " + shares + ")" : std::string());
              }
            pcout << "\n";
          }
        if (parameters.adapt_interval > 0 &&
            std::none_of(bodies.begin(), bodies.end(), [](const Body &b) { return b.local_refinement_levels() > 0; }))
          pcout << "Warning: " << parameters.scene_file
                << ": 'Simulation/Adapt interval' is set, but no body has a 'Refinement region' with criteria and "
                   "'Levels' > 0: the mesh stays that of the start\n";
        pcout << "  the step computes: " << step_contents() << "\n";
        pcout << "  results in " << parameters.output_directory << "/" << std::endl;
      }
    if (resume)
      load_checkpoint(parameters.output_directory + "/checkpoint", false);
    else if (!resume_from.empty())
      load_checkpoint(resume_from, true);
    else
      {
        report_element_quality();
        // Bodies out of the analysis from the start take no part in it
        // (nothing to book: the initial energy follows).
        remove_inactive_bodies(false);
        if (parameters.duration > 0)
          parameters.end_time = parameters.duration;
        // Step 0: forces of the initial state (stress free), energy E_0.
        zero_forces();
        critical_dt = compute_internal_forces(0.);
        apply_contact(0.);
        condense_forces();
        const double contact_frequency_squared = contact->frequency_squared();
        if (contact_frequency_squared > 0)
          {
            const double reduction =
              1. - 1. / std::sqrt(1. + 0.25 * contact_frequency_squared * critical_dt * critical_dt);
            if (reduction > 0.01)
              pcout << "  contact penalty springs lower the stable time step by " << std::setprecision(3)
                    << 100. * reduction << " % at the start" << std::endl;
          }

        double kinetic0 = 0;
        for (unsigned int i = 0; i < velocity.locally_owned_size(); ++i)
          if (rigid_dof.empty() || !rigid_dof[i])
            kinetic0 += mass.local_element(i) * velocity.local_element(i) * velocity.local_element(i);
        energies.kinetic = 0.5 * Utilities::MPI::sum(kinetic0, mpi_communicator);
        for (const auto *family : contributors())
          family->add_kinetic_energy(energies.kinetic);
        balance.initial_energy   = energies.total();
        summary.initial_kinetic = energies.kinetic;
        output_results(0., "solution");
        loop = LoopState();
        loop.next_output = parameters.output_interval;
      }
    // (The element loop's balance: this run's steps only.)
    element_balance        = {};
    element_balance.record = parameters.print_wall_times && Utilities::MPI::n_mpi_processes(mpi_communicator) > 1;
    // The balance checks ('Rebalance interval'): timed groups, the first
    // check an interval after the start (a fresh run or stage; a resumed
    // run keeps the checkpoint's schedule).
    const bool rebalancing =
      parameters.rebalance_interval > 0 && Utilities::MPI::n_mpi_processes(mpi_communicator) > 1;
    solids->time_elements(rebalancing);
    timing_from_step = step_number + 16;
    // (What a new partition costs: about what this start did.)
    startup_seconds = Utilities::MPI::max(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), mpi_communicator);
    if (rebalancing && (!resume || !(loop.next_rebalance > time)))
      loop.next_rebalance = time + parameters.rebalance_interval;
    if (parameters.adapt_interval > 0 && (!resume || !(loop.next_adapt > time)))
      loop.next_adapt = time + parameters.adapt_interval;
  }


  // The step from time n: the stable step, held against small changes,
  // cut to the end time and to 'Maximum time step'; the last step (dt = 0)
  // only synchronises the velocities. Returns the stable step.
  double Simulator::choose_step(const bool last)
  {
    const double &dt_previous = loop.dt_previous;
    // The stable step from the current configuration; the last step
    // only synchronises the velocity.
    const double dt_stable = stable_time_step();
    // The stable step follows the mesh: where it oscillates with the
    // motion (an elastic body ringing), a step that follows it pumps
    // energy into that motion (the variable-step scheme's error,
    // energies.step_change: 5 % of the energy in 700 steps of a ringing
    // block), and every fall of the step creates some. So the step is
    // held while the safety factor it amounts to stays within 1 % of
    // the one asked for: it falls once it would exceed it by 1 % (to
    // the factor asked for), and rises once the stable step allows 1 %
    // more, by 0.1 % a step. A ringing body then keeps one step and the
    // bounded energy error of a fixed step.
    {
      const double target = parameters.time_step_factor * dt_stable;
      double      &held   = loop.held_dt;
      if (held == 0 || target < 0.99 * held)
        held = target;
      else if (target > 1.01 * held)
        held = std::min(target, 1.001 * held);
    }
    current_dt = last ? dt_previous : std::min(loop.held_dt, parameters.end_time - time);
    if (!last)
      {
        const double dt_max =
          parameters.max_dt_function ? parameters.max_dt_function->value(Point<1>(time)) : parameters.max_dt_constant;
        if (dt_max > 0 && dt_max < current_dt)
          current_dt = dt_max;
      }
    if (!(current_dt > 0))
      current_dt = dt_previous;
    if (!last)
      {
        summary.element_steps += current_dt / (parameters.time_step_factor * critical_dt);
        // (The step is held within 1 % of the stable one, see above.)
        if (dt_stable < 0.999999 * critical_dt && current_dt >= 0.98 * parameters.time_step_factor * dt_stable)
          ++summary.contact_limited_steps;
      }

    return dt_stable;
  }


  // A progress line (and the status file) at time n.
  void Simulator::report_progress(RunClock &clock, const bool last)
  {
    double &next_progress = loop.next_progress;
    // Progress: every 'Progress interval' of wall time (rank 0 alone
    // decides: printing involves no other rank), or every 10 % of the
    // end time where screen output must compare between runs.
    const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock.wall_start).count();
    const bool by_wall = parameters.print_wall_times && parameters.progress_interval > 0;
    if ((by_wall ? (wall >= clock.next_wall_progress || step_number == 0) :
                   time >= next_progress - clock.eps) ||
        last)
      {
        const double eta =
          time > clock.time_start ? wall / (time - clock.time_start) * (parameters.end_time - time) : -1.;
        if (!last)
          write_status("running", time, wall, eta);
        clock.next_wall_progress = wall + parameters.progress_interval;
        pcout << "  step " << std::setw(7) << step_number << "  t = " << std::setw(11)
              << std::setprecision(5) << time << " s  dt = " << std::setw(10)
              << current_dt << " s  E_kin = " << std::setw(10) << energies.kinetic
              << "  E_int = " << std::setw(10) << energies.internal
              << "  balance = " << std::setw(9) << balance.balance_error;
        if (parameters.print_wall_times && eta >= 0)
          pcout << "  left ~" << std::setprecision(3) << eta << " s";
        pcout << std::endl;
        while (next_progress <= time + clock.eps)
          next_progress += 0.1 * parameters.end_time;
      }
  }


  // From time n to n+1: positions, forces, frames and checkpoints.
  void Simulator::advance(const RunClock &clock)
  {
    double &dt_previous = loop.dt_previous;
    double &next_output = loop.next_output;
    update_position(current_dt);
    position.update_ghost_values();
    velocity.update_ghost_values();
    time += current_dt;
    ++step_number;
    dt_previous = current_dt;

    zero_forces();
    critical_dt = compute_internal_forces(dt_previous);
    apply_contact(dt_previous);
    condense_forces();

    if (parameters.output_interval > 0 && time >= next_output - clock.eps && time < parameters.end_time - clock.eps)
      {
        output_results(time, "solution");
        next_output += parameters.output_interval;
      }

    // A checkpoint by simulated time, by wall time (rank 0's clock,
    // shared at the health check) or on SIGTERM / SIGINT, which then
    // stops the run.
    if (time >= output.next_checkpoint - clock.eps && time < parameters.end_time - clock.eps)
      {
        output.checkpoint_due = true;
        while (output.next_checkpoint <= time + clock.eps)
          output.next_checkpoint += parameters.checkpoint_interval;
      }
    if (parameters.rebalance_interval > 0 && step_number == timing_from_step)
      solids->reset_timing();
    if (parameters.rebalance_interval > 0 && Utilities::MPI::n_mpi_processes(mpi_communicator) > 1 &&
        time >= loop.next_rebalance - clock.eps && time < parameters.end_time - clock.eps && !output.stop_requested)
      {
        while (loop.next_rebalance <= time + clock.eps)
          loop.next_rebalance += parameters.rebalance_interval;
        check_balance();
      }
    if (parameters.adapt_interval > 0 && time >= loop.next_adapt - clock.eps &&
        time < parameters.end_time - clock.eps && !output.stop_requested)
      {
        while (loop.next_adapt <= time + clock.eps)
          loop.next_adapt += parameters.adapt_interval;
        check_adaptivity();
      }
    if (output.checkpoint_due || output.stop_requested)
      {
        write_checkpoint();
        output.checkpoint_due = false;
        if (output.stop_requested)
          {
            std::ostringstream msg;
            msg << "interrupted at t = " << time << " s, step " << step_number
                << ": checkpoint and frame index written; continue with 'anvil --resume "
                << parameters.scene_file << "' (on any number of processes)";
            throw Interrupted(msg.str());
          }
      }
  }


  // The last frame, the postprocessors' end (bodies.csv, summary.csv, the
  // plots) and the run's closing lines.
  void Simulator::finish_run(const RunClock &clock)
  {
    position.update_ghost_values();
    velocity.update_ghost_values();
    output_results(time, "solution");
    flush_histories();
    if (Utilities::MPI::max(output.failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw OutputError(output.failure.empty() ? "a history file could not be written (see rank 0)" :
                                                 output.failure);
    const double wall_total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock.wall_start).count();
    // The last frame, bodies.csv, summary.csv, the plots (in the
    // postprocessors' order).
    for (auto &postprocessor : postprocessors)
      postprocessor->end_of_run(wall_total);
    write_status("finished", time, wall_total, 0.);
    if (summary.ended_early)
      {
        const auto &end = parameters.end_criterion;
        pcout << "  " << (end.kinetic_fraction > 0 ? "the impact is over" : "the bodies have settled") << " (no "
              << (end.pairs.size() == contact->n_pairs() ? "contact force" : "force in the pairs it follows")
              << ", kinetic energy of the deformable bodies below ";
        if (end.kinetic_fraction > 0)
          pcout << end.kinetic_fraction << " E_0";
        if (end.kinetic_fraction > 0 && end.kinetic_internal_ratio > 0)
          pcout << " and ";
        if (end.kinetic_internal_ratio > 0)
          pcout << end.kinetic_internal_ratio << " E_int";
        pcout << " for " << end.quiet_time << " s): the run ends before its end time" << std::endl;
      }
    if (summary.capacity_end_reaction >= 0)
      pcout << "  the push is past its capacity (the reaction of '" << constraints->capacity_support() << "' fell to "
            << summary.capacity_end_reaction << " N, below " << 1. - parameters.end_criterion.capacity_drop
            << " of its peak for " << parameters.end_criterion.quiet_time
            << " s): the run ends before its end time" << std::endl;
    pcout << "  done: " << step_number << " steps to t = " << time
          << " s, energy balance error " << balance.balance_error;
    if (solids->n_eroded() > 0)
      pcout << ", " << solids->n_eroded() << " elements eroded (" << parameters.output_directory << "/erosion.csv)";
    if (summary.contact_limited_steps > 0)
      pcout << "\n  contact penalty springs set the size of " << summary.contact_limited_steps
            << " steps; the elements alone would have needed "
            << static_cast<unsigned long>(std::lround(summary.element_steps)) << " steps";
    pcout << "\n";
    for (auto *family : contributors())
      if (!family->empty())
        pcout << family->end_of_run_note();
    pcout << "  results: " << parameters.output_directory << "/energy.csv, "
          << parameters.output_directory << "/solution.pvd" << std::endl;
    if (parameters.print_wall_times && Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      {
        timer->print_wall_time_statistics(mpi_communicator);
        print_element_balance();
      }
  }


  // @sect3{Balance of the element loop}
  //
  // A step waits for its slowest process. The element loop of step s took
  // t_rs on process r; the run's element time is sum_s max_r t_rs, against
  // the mean sum_s mean_r t_rs that a perfect balance would give. The gap
  // has two parts: the partition's, max_r sum_s t_rs (one process holding
  // more work all along), and what is left, the work moving between the
  // processes step by step (the cracking concrete under a hammer, a host
  // core slowed for a while). Both are printed with the wall-time
  // statistics. The step-by-step times are reduced over the processes
  // every 4096 steps (two reductions then, none in the other steps).
  void Simulator::reduce_element_balance()
  {
    const unsigned int  n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const unsigned int  steps   = Utilities::MPI::min(static_cast<unsigned int>(element_balance.seconds.size()),
                                                    mpi_communicator);
    std::vector<double> mine(element_balance.seconds.begin(), element_balance.seconds.begin() + steps);
    std::vector<double> slowest(steps), total(steps);
    Utilities::MPI::max(ArrayView<const double>(mine), mpi_communicator, ArrayView<double>(slowest));
    Utilities::MPI::sum(ArrayView<const double>(mine), mpi_communicator, ArrayView<double>(total));
    for (unsigned int s = 0; s < steps; ++s)
      {
        element_balance.own += mine[s];
        element_balance.slowest_by_step += slowest[s];
        element_balance.mean += total[s] / n_ranks;
      }
    element_balance.steps += steps;
    element_balance.seconds.clear();
  }


  void Simulator::print_element_balance()
  {
    reduce_element_balance();
    const double whole_run = Utilities::MPI::max(element_balance.own, mpi_communicator);
    const double by_step   = element_balance.slowest_by_step;
    const double mean      = element_balance.mean;
    const auto   steps     = element_balance.steps;
    if (steps == 0 || !(mean > 0))
      return;
    pcout << std::fixed << std::setprecision(3) << "  element loop over " << steps
          << " steps, wall time: the processes' mean " << mean << " s; the slowest process over the run "
          << whole_run << " s (+" << std::setprecision(1) << 100. * (whole_run / mean - 1.)
          << " %: the partition); the slowest process of each step, summed, " << std::setprecision(3)
          << by_step << " s (+" << std::setprecision(1) << 100. * (by_step / mean - 1.)
          << " %: the partition and the work moving between processes)" << std::defaultfloat
          << std::setprecision(6) << std::endl;
  }


  void Simulator::write_status(const std::string &state, const double t, const double wall_seconds,
                               const double eta_seconds, const std::string &message) const
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0 || !output.directory_ready)
      return;
    const std::string file = parameters.output_directory + "/status";
    {
      std::ofstream out(file + ".tmp");
      out << std::setprecision(8) << "state: " << state << "\nstep: " << step_number
          << "\ntime_s: " << t << "\nend_time_s: " << parameters.end_time
          << "\nfraction_done: " << std::setprecision(4) << t / parameters.end_time << std::setprecision(8)
          << "\ntime_step_s: " << current_dt << "\nkinetic_energy_J: " << energies.kinetic
          << "\ninternal_energy_J: " << energies.internal << "\nbalance_error: " << balance.balance_error;
      if (wall_seconds >= 0)
        out << "\nwall_time_s: " << std::setprecision(4) << wall_seconds;
      if (eta_seconds >= 0)
        out << "\nwall_time_left_s: " << std::setprecision(4) << eta_seconds;
      if (!message.empty())
        out << "\nmessage: " << printable_excerpt(message);
      out << '\n';
      out.flush();
      if (!out)
        throw OutputError("cannot write " + file + ".tmp (the run's status)");
    }
    if (std::rename((file + ".tmp").c_str(), file.c_str()) != 0)
      throw OutputError("cannot rename " + file + ".tmp to " + file);
  }
} // namespace anvil
