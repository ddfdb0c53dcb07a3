/**
 * @file
 * ConstraintsAndLoads: the scene's kinematic constraints and loads as one
 * family (ForceContributor): the boundary conditions (the nodes they hold,
 * the velocities their plugins prescribe, the reactions that hold them and
 * the work those do), mass-proportional damping and gravity. The Simulator
 * calls it at three points of the central-difference update
 * (source/simulator/time_integration.cc); the reactions postprocessor and
 * summary.csv read what it keeps.
 */
#pragma once

#include <anvil/boundary_conditions/boundary_condition.h>
#include <anvil/simulator/force_contributor.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <string>
#include <vector>

namespace anvil
{
  class ConstraintsAndLoads : public ForceContributor
  {
  public:
    /** @p velocity: the Simulator's nodal velocity (a held dof starts at
        its prescribed velocity). */
    ConstraintsAndLoads(Simulator &simulator, VectorType &velocity);

    /** The entries of 'Simulation' (Mass damping, Gravity, Capacity
        support, Intact axial capacity) and each 'Boundary condition NAME'
        of @p bc_names; @p bodies: the scene's bodies (a condition names a
        deformable one). InputError for bad input. */
    void parse_parameters(dealii::ParameterHandler       &prm,
                          const std::vector<std::string> &bc_names,
                          const std::vector<Body>        &bodies);

    /** Turn the condition's surface and node-set names into what body
        @p body's mesh file names (before setup). */
    void resolve_names(const std::string &body, const MeshNames &names);

    std::string name() const override
    {
      return "constraints and loads";
    }
    bool empty() const override
    {
      return conditions.empty() && mass_damping == 0 && gravity.norm() == 0;
    }
    bool has_forces() const override
    {
      return false;
    }
    double add_forces(double) override
    {
      return 1e300;
    }
    /** Which owned dofs each condition holds; they start at the prescribed
        velocity of t = 0. InputError for a condition that holds none. */
    void setup() override;
    /** The work of gravity over the step just made. */
    void update_position(double dt) override;
    std::string describe() const override;
    /** The conditions' reactions summed over the processes, and their
        peaks (collective). */
    void prepare_history() override;
    void start_stage() override;
    void serialize(StateArchive &ar) override;

    // The three points of the velocity update (Simulator::update_velocity).
    /** The body force of gravity, m g, on the owned dofs that are not a
        rigid body's: the force vector's first entries of a step. */
    void set_body_forces(VectorType &force) const;
    /** Before the update: the held dofs' v^{n-1/2}; the prescribed
        velocities of a time-dependent condition at t^{n+1/2} = @p t +
        @p dt / 2. */
    void begin_velocity_update(const double *v, double t, double dt);
    /** Whether the scene damps (then damped_velocity_update() is the
        update of the free dofs). */
    bool damps() const
    {
      return mass_damping > 0;
    }
    /** The update of the deformable dofs under mass-proportional damping
        (a dof of @p moved_dof is another's), adding the step's kinetic and
        step-change terms to @p kinetic and @p power; books the damping's
        work. */
    void damped_velocity_update(double dt_previous, double dt_avg, const double *f, const double *m,
                                double *v, const std::vector<unsigned char> &moved_dof, double &kinetic,
                                double &power);
    /** After the free update: each held dof back to its prescribed
        velocity, the reaction that does it, its work and its terms of the
        energy identity. */
    void impose(double dt_previous, double dt_avg, const double *f, const double *m, double *v,
                double &kinetic, double &work, double &power);

    // What the others read.
    const std::vector<BoundaryCondition> &get_conditions() const
    {
      return conditions;
    }
    const dealii::Tensor<1, 3> &get_gravity() const
    {
      return gravity;
    }
    /** Whether the owned dof @p i is held. */
    bool is_held(const unsigned int i) const
    {
      return i < held_index.size() && held_index[i] > 0;
    }
    /** The velocity held dof @p i is held at over the step (v^{n+1/2}). */
    double prescribed_velocity(const unsigned int i) const
    {
      return constrained_velocity[held_index[i] - 1];
    }
    /** The velocity of held dof @p i at time n (between the velocity
        and the position update: the prescribed velocity of t^n). */
    double held_velocity(const unsigned int i) const
    {
      return velocity_n[held_index[i] - 1];
    }
    /** The damping force on owned dof @p i this step (0 without). */
    double damping_force(const unsigned int i) const
    {
      return mass_damping > 0 && i < damping_force_old.size() ? damping_force_old[i] : 0.;
    }
    /** Each condition's reaction (3 per condition, summed over the
        processes at the last history row), the largest magnitude of each
        so far, 'Capacity support' and 'Intact axial capacity'. */
    const std::vector<double> &reactions() const
    {
      return reaction_sums;
    }
    const std::vector<double> &peak_reactions() const
    {
      return peak_reaction;
    }
    const std::string &capacity_support() const
    {
      return capacity;
    }
    double intact_capacity() const
    {
      return intact;
    }

  private:
    VectorType                    &velocity;
    std::vector<BoundaryCondition> conditions;
    /** Mass-proportional damping alpha (1/s; 0: none), each owned dof's
        damping force of the last step and whether it is damped (0: held,
        1: free, 2: another family's). */
    double                     mass_damping = 0;
    std::vector<double>        damping_force_old;
    std::vector<unsigned char> damped_dof;
    dealii::Tensor<1, 3>       gravity;
    std::string                capacity;
    double                     intact = 0;

    std::vector<unsigned int> constrained_dofs;
    std::vector<double>       constrained_velocity;
    std::vector<unsigned int> held_index;
    /** Per held dof: 3 condition + component; the reaction of the last
        step (its trapezoidal work) and v^{n-1/2} during the update. */
    std::vector<unsigned int> constrained_bc;
    std::vector<double>       constrained_reaction, constrained_velocity_old;
    /** This process's part of each condition's reaction this step, the
        sums at the last history row, and the peaks of their magnitudes. */
    std::vector<double> bc_reaction, reaction_sums, peak_reaction;
    bool                time_dependent = false;
    /** Each held dof's prescribed velocity of t^n (the probes' velocity
        at n), and each condition's velocity at t^n and t^{n+1/2} (the
        time-dependent ones', evaluated once a step). */
    std::vector<double>               velocity_n;
    std::vector<dealii::Tensor<1, 3>> condition_velocity_n, condition_velocity_half;
  };


  // (In the header: the step's update compiles it with the free dofs'
  // loop, as one piece of arithmetic.)
  // Reaction R^n = M (v_prescribed - v_free) / dt_avg: it joins f in K^n,
  // and does the work (R^{n-1} + R^n)/2 v^{n-1/2} dt^{n-1/2}.
  inline void ConstraintsAndLoads::impose(const double dt_previous, const double dt_avg, const double *f,
                                   const double *m, double *v, double &kinetic, double &work, double &power)
  {
    std::fill(bc_reaction.begin(), bc_reaction.end(), 0.);
    for (unsigned int k = 0; k < constrained_dofs.size(); ++k)
      {
        const unsigned int i        = constrained_dofs[k];
        const double       v_old    = constrained_velocity_old[k];
        const double       reaction = dt_avg > 0 ? m[i] * (constrained_velocity[k] - v[i]) / dt_avg : 0.;
        kinetic += v_old * dt_previous * reaction;
        work += 0.5 * (constrained_reaction[k] + reaction) * v_old * dt_previous;
        // F^n dv with F^n = f + R and dv = v_prescribed - v_old.
        power += (f[i] + reaction) * (constrained_velocity[k] - v_old) - f[i] * (v[i] - v_old);
        constrained_reaction[k] = reaction;
        bc_reaction[constrained_bc[k]] += reaction;
        v[i]                    = constrained_velocity[k];
      }
  }


} // namespace anvil
