/**
 * @file
 * The scene's kinematic constraints and loads (ConstraintsAndLoads).
 */
#include <anvil/boundary_conditions/constraints.h>
#include <anvil/mesh/body.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/text.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace anvil
{
  using namespace dealii;

  ConstraintsAndLoads::ConstraintsAndLoads(Simulator &simulator, VectorType &velocity)
    : ForceContributor(simulator)
    , velocity(velocity)
  {}


  void ConstraintsAndLoads::parse_parameters(ParameterHandler               &prm,
                                             const std::vector<std::string> &bc_names,
                                             const std::vector<Body>        &bodies)
  {
    prm.enter_subsection("Simulation");
    mass_damping = prm.get_double("Mass damping");
    {
      const auto g = Utilities::split_string_list(prm.get("Gravity"));
      for (unsigned int d = 0; d < 3; ++d)
        gravity[d] = Utilities::string_to_double(g[d]);
    }
    capacity = prm.get("Capacity support");
    intact   = prm.get_double("Intact axial capacity");
    prm.leave_subsection();
    if (!capacity.empty() && std::find(bc_names.begin(), bc_names.end(), capacity) == bc_names.end())
      throw InputError("entry 'Simulation/Capacity support': '" + capacity + "' is not in 'Boundary conditions' (" +
                       join(bc_names) + ")");

    conditions.resize(bc_names.size());
    time_dependent = false;
    for (unsigned int i = 0; i < bc_names.size(); ++i)
      {
        prm.enter_subsection("Boundary condition " + bc_names[i]);
        conditions[i].parse_parameters(prm, bc_names[i]);
        prm.leave_subsection();
        const auto body = std::find_if(bodies.begin(), bodies.end(),
                                       [&](const Body &b) { return b.name == conditions[i].body; });
        if (body == bodies.end())
          {
            std::vector<std::string> names;
            for (const auto &b : bodies)
              names.push_back(b.name);
            throw InputError("subsection 'Boundary condition " + bc_names[i] + "': body '" + conditions[i].body +
                             "' is not in 'Bodies' (" + join(names) + ")");
          }
        if (body->is_rigid())
          throw InputError("subsection 'Boundary condition " + bc_names[i] + "': body '" + body->name +
                           "' is rigid; hold it with 'Rigid body/Motion' and "
                           "'Rigid body/Constraints' instead");
        time_dependent = time_dependent || conditions[i].time_dependent();
      }
  }


  void ConstraintsAndLoads::resolve_names(const std::string &body, const MeshNames &names)
  {
    for (auto &bc : conditions)
      if (bc.body == body)
        bc.resolve_names(names);
  }


  // @sect3{The held dofs}
  //
  // A node's boundary ids are those of the boundary faces it lies on; a
  // dof held by two conditions takes the later one's velocity.
  void ConstraintsAndLoads::setup()
  {
    const auto &dof_handler      = get_dof_handler();
    const auto &bodies           = get_bodies();
    const auto &dof_component    = get_dof_component();
    const auto &owned            = dof_handler.locally_owned_dofs();
    const auto  mpi_communicator = get_mpi_communicator();

    std::map<types::global_dof_index, double>       prescribed;
    std::map<types::global_dof_index, unsigned int> prescribed_by;
    std::vector<unsigned int>                       matched(conditions.size(), 0);
    std::vector<Tensor<1, 3>>                       start(conditions.size());
    for (unsigned int k = 0; k < conditions.size(); ++k)
      start[k] = conditions[k].velocity(0.);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (unsigned int v = 0; v < 8; ++v)
          {
            std::vector<unsigned int> ids;
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                for (unsigned int fv = 0; fv < 4; ++fv)
                  if (GeometryInfo<3>::face_to_cell_vertices(f, fv) == v)
                    ids.push_back(cell->face(f)->boundary_id());
            for (unsigned int k = 0; k < conditions.size(); ++k)
              {
                const auto &bc = conditions[k];
                if (!bc.selects(bodies[cell->material_id()].name, cell->vertex(v), ids))
                  continue;
                for (unsigned int c = 0; c < 3; ++c)
                  if (bc.components[c])
                    {
                      const auto dof = cell->vertex_dof_index(v, c);
                      if (owned.is_element(dof))
                        {
                          prescribed[dof]    = start[k][c];
                          prescribed_by[dof] = k;
                          ++matched[k];
                        }
                    }
              }
          }
    for (unsigned int k = 0; k < conditions.size(); ++k)
      if (Utilities::MPI::sum(matched[k], mpi_communicator) == 0)
        throw InputError(get_scene_file() + ": subsection 'Boundary condition " + conditions[k].name +
                         "' selects no node of body '" + conditions[k].body + "'");
    constrained_dofs.clear();
    constrained_velocity.clear();
    constrained_bc.clear();
    for (const auto &[dof, value] : prescribed)
      {
        constrained_dofs.push_back(velocity.get_partitioner()->global_to_local(dof));
        constrained_velocity.push_back(value);
        constrained_bc.push_back(3 * prescribed_by[dof] + dof_component[constrained_dofs.back()]);
        velocity(dof) = value;
      }
    held_index.assign(velocity.locally_owned_size(), 0);
    for (unsigned int k = 0; k < constrained_dofs.size(); ++k)
      held_index[constrained_dofs[k]] = k + 1;
    constrained_reaction.assign(constrained_dofs.size(), 0.);
    bc_reaction.assign(3 * conditions.size(), 0.);
    constrained_velocity_old.assign(constrained_dofs.size(), 0.);
    velocity_n = constrained_velocity;
    damped_dof.clear();
  }


  // Gravity: the lumped body force m_I g on every owned dof (rigid bodies
  // take M g at their centre: RigidBodies::update_velocity).
  void ConstraintsAndLoads::set_body_forces(VectorType &force) const
  {
    if (gravity.norm() == 0)
      return;
    const auto &mass          = get_mass();
    const auto &rigid_dof     = get_rigid_dof();
    const auto &dof_component = get_dof_component();
    for (unsigned int i = 0; i < force.locally_owned_size(); ++i)
      if (rigid_dof.empty() || !rigid_dof[i])
        force.local_element(i) = mass.local_element(i) * gravity[dof_component[i]];
  }


  void ConstraintsAndLoads::begin_velocity_update(const double *v, const double t, const double dt)
  {
    for (unsigned int k = 0; k < constrained_dofs.size(); ++k)
      constrained_velocity_old[k] = v[constrained_dofs[k]];
    if (time_dependent)
      {
        auto &at_n = condition_velocity_n, &half = condition_velocity_half;
        at_n.resize(conditions.size());
        half.resize(conditions.size());
        for (unsigned int b = 0; b < conditions.size(); ++b)
          if (conditions[b].time_dependent())
            {
              at_n[b] = conditions[b].velocity(t);
              half[b] = conditions[b].velocity(t + 0.5 * dt);
            }
        for (unsigned int k = 0; k < constrained_dofs.size(); ++k)
          if (conditions[constrained_bc[k] / 3].time_dependent())
            {
              velocity_n[k]           = at_n[constrained_bc[k] / 3][constrained_bc[k] % 3];
              constrained_velocity[k] = half[constrained_bc[k] / 3][constrained_bc[k] % 3];
            }
      }
  }


  // Mass-proportional damping, centred: F_d^n = -alpha m (v^{n-1/2} +
  // v^{n+1/2}) / 2 joins F^n, so v^{n+1/2} solves (1 + a) v^{n+1/2} =
  // (1 - a) v^{n-1/2} + dt_avg f / m with a = alpha dt_avg / 2
  // (unconditionally stable in the damping); its work over the step just
  // made is booked by the trapezoid, -(F_d^{n-1} + F_d^n)/2 . v^{n-1/2}
  // dt^{n-1/2}, as the elements book theirs. Held dofs are not damped (a
  // held dof's damping would be part of its reaction); rigid dofs are the
  // bodies' own.
  void ConstraintsAndLoads::damped_velocity_update(const double dt_previous, const double dt_avg,
                                                   const double *f, const double *m, double *v,
                                                   const std::vector<unsigned char> &moved_dof,
                                                   double &kinetic, double &power)
  {
    const unsigned int n = velocity.locally_owned_size();
    if (damping_force_old.size() != n)
      damping_force_old.assign(n, 0.);
    if (damped_dof.size() != n)
      {
        damped_dof.assign(n, 1);
        for (const unsigned int i : constrained_dofs)
          damped_dof[i] = 0;
        for (unsigned int i = 0; i < n; ++i)
          if (!moved_dof.empty() && moved_dof[i])
            damped_dof[i] = 2;
      }
    // (The sums in locals, added in the same order: the references would
    // keep them in memory through the loop.)
    double absorbed = 0, k = kinetic, w = power;
    for (unsigned int i = 0; i < n; ++i)
      if (damped_dof[i] != 2)
        {
          // (alpha = 0: the undamped update, to the bit.)
          const double alpha = damped_dof[i] ? mass_damping : 0.;
          const double a     = 0.5 * alpha * dt_avg;
          const double v_old = v[i];
          const double v_new = ((1. - a) * v_old + dt_avg * f[i] / m[i]) / (1. + a);
          const double fd    = -0.5 * alpha * m[i] * (v_old + v_new);
          const double ft    = f[i] + fd;
          absorbed -= 0.5 * (damping_force_old[i] + fd) * v_old * dt_previous;
          damping_force_old[i] = fd;
          v[i]                 = v_new;
          k += v_old * (m[i] * v_old + dt_previous * ft);
          w += ft * (v_new - v_old);
        }
    kinetic = k;
    power   = w;
    get_energies().damping += Utilities::MPI::sum(absorbed, get_mpi_communicator());
  }


  // Work of gravity over the step, m g . (x^{n+1} - x^n): exact for a
  // constant force.
  void ConstraintsAndLoads::update_position(const double dt)
  {
    if (gravity.norm() == 0)
      return;
    const auto        &mass          = get_mass();
    const auto        &rigid_dof     = get_rigid_dof();
    const auto        &dof_component = get_dof_component();
    const double      *v             = velocity.begin();
    double             work          = 0;
    for (unsigned int i = 0; i < velocity.locally_owned_size(); ++i)
      if (rigid_dof.empty() || !rigid_dof[i])
        work += mass.local_element(i) * gravity[dof_component[i]] * dt * v[i];
    get_energies().external_work += Utilities::MPI::sum(work, get_mpi_communicator());
  }


  std::string ConstraintsAndLoads::describe() const
  {
    return std::string(mass_damping > 0 ? "mass damping" : "no mass damping") + "; " +
           (gravity.norm() > 0 ? "gravity" : "no gravity");
  }


  void ConstraintsAndLoads::prepare_history()
  {
    if (bc_reaction.empty())
      return;
    reaction_sums = bc_reaction;
    Utilities::MPI::sum(reaction_sums, get_mpi_communicator(), reaction_sums);
    peak_reaction.resize(conditions.size(), 0.);
    auto &summary = get_summary();
    for (unsigned int b = 0; b < conditions.size(); ++b)
      {
        const double magnitude =
          std::sqrt(reaction_sums[3 * b] * reaction_sums[3 * b] + reaction_sums[3 * b + 1] * reaction_sums[3 * b + 1] +
                    reaction_sums[3 * b + 2] * reaction_sums[3 * b + 2]);
        peak_reaction[b]      = std::max(peak_reaction[b], magnitude);
        summary.peak_reaction = std::max(summary.peak_reaction, magnitude);
      }
  }


  void ConstraintsAndLoads::start_stage()
  {
    std::fill(peak_reaction.begin(), peak_reaction.end(), 0.);
  }


  void ConstraintsAndLoads::serialize(StateArchive &ar)
  {
    // (The prescribed velocities are the scene's, not state: a new stage
    // may change them.)
    ar &peak_reaction &bc_reaction;
    // By dof key: each held dof's reaction and velocity of the last step,
    // and with mass damping each owned dof's damping force.
    const auto &key = get_dof_keys();
    std::vector<std::uint64_t> held_keys;
    for (const unsigned int i : constrained_dofs)
      held_keys.push_back(key[i]);
    // (A stage may hold dofs the run before it did not: they start
    // without a reaction, as at setup.)
    ar.keyed_items(
      "held dofs",
      held_keys,
      2,
      [&](const std::size_t k, RecordCursor &io) {
        io(constrained_reaction[k]);
        io(constrained_velocity_old[k]);
      },
      true);
    if (mass_damping > 0)
      {
        if (damping_force_old.size() != key.size())
          damping_force_old.assign(key.size(), 0.);
        ar.keyed("damping", key, 1, damping_force_old, true);
      }
  }
} // namespace anvil
