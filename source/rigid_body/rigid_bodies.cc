/**
 * @file
 * The rigid bodies of a scene as one family (rigid_body/rigid_bodies.h).
 */
#include <anvil/rigid_body/rigid_bodies.h>
#include <anvil/mesh/body.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <array>
#include <iomanip>

namespace anvil::RigidBody
{
  using namespace dealii;

  // @sect3{Rigid bodies}
  //
  // Mass, centre of mass and inertia from the mesh by 2x2x2 Gauss
  // quadrature of rho, rho x and rho (|r|^2 I - r r) over the owned cells
  // (exact for the trilinear map and constant density), summed over the
  // ranks. The centre equals the lumped-mass centroid sum m_I X_I / M,
  // since sum N_I X_I = x; so gravity exerts no torque about it.
  RigidBodies::RigidBodies(Simulator                        &simulator,
                           const FESystem<3>                &fe,
                           VectorType                       &velocity,
                           std::vector<unsigned char>       &rigid_dof,
                           const std::vector<unsigned char> &inactive)
    : ForceContributor(simulator)
    , fe(fe)
    , velocity(velocity)
    , rigid_dof(rigid_dof)
    , inactive(inactive)
  {}


  void RigidBodies::setup()
  {
    auto              &bodies           = get_bodies_for_update();
    const auto        &dof_handler      = get_dof_handler();
    const VectorType  &position         = get_position();
    const MPI_Comm     mpi_communicator = get_mpi_communicator();
    const auto        &pcout            = get_pcout();
    const unsigned int nb               = bodies.size();
    nodes.assign(nb, {});
    rigid_dof.assign(position.locally_owned_size(), 0);
    shape_force.assign(nb, Tensor<1, 3>());
    shape_torque.assign(nb, Tensor<1, 3>());
    n_rigid = 0;
    for (const auto &b : bodies)
      n_rigid += b.is_rigid() ? 1 : 0;
    if (n_rigid == 0)
      {
        rigid_dof.clear();
        return;
      }
    // Moments of order 0, 1, 2 about the origin: m, m x (3), m x x (6).
    std::vector<double> moments(10 * nb, 0.);
    const QGauss<3>     quadrature(2);
    FEValues<3>         fe_values(fe, quadrature, update_quadrature_points | update_JxW_values);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() && bodies[cell->material_id()].is_rigid())
        {
          const unsigned int b   = cell->material_id();
          const double       rho = bodies[b].material->density();
          fe_values.reinit(cell);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Point<3> x  = fe_values.quadrature_point(q);
              const double   dm = rho * fe_values.JxW(q);
              double        *m  = &moments[10 * b];
              m[0] += dm;
              for (unsigned int d = 0; d < 3; ++d)
                m[1 + d] += dm * x[d];
              m[4] += dm * x[0] * x[0];
              m[5] += dm * x[1] * x[1];
              m[6] += dm * x[2] * x[2];
              m[7] += dm * x[0] * x[1];
              m[8] += dm * x[1] * x[2];
              m[9] += dm * x[0] * x[2];
            }
        }
    Utilities::MPI::sum(moments, mpi_communicator, moments);
    for (unsigned int b = 0; b < nb; ++b)
      if (bodies[b].is_rigid())
        {
          const double *m = &moments[10 * b];
          const double  M = m[0];
          Point<3>      c(m[1] / M, m[2] / M, m[3] / M);
          // Second moments about the centre, then I = tr(S) 1 - S.
          Tensor<2, 3> S;
          S[0][0] = m[4] - M * c[0] * c[0];
          S[1][1] = m[5] - M * c[1] * c[1];
          S[2][2] = m[6] - M * c[2] * c[2];
          S[0][1] = S[1][0] = m[7] - M * c[0] * c[1];
          S[1][2] = S[2][1] = m[8] - M * c[1] * c[2];
          S[0][2] = S[2][0] = m[9] - M * c[0] * c[2];
          Tensor<2, 3> I = trace(S) * unit_symmetric_tensor<3>() - S;
          auto        &motion = bodies[b].rigid;
          double       mass   = M;
          if (motion.given_mass > 0)
            {
              I *= motion.given_mass / M;
              mass = motion.given_mass;
            }
          if (!motion.given_inertia.empty())
            {
              const auto &g = motion.given_inertia;
              I[0][0]       = g[0];
              I[1][1]       = g[1];
              I[2][2]       = g[2];
              I[0][1] = I[1][0] = g[3];
              I[1][2] = I[2][1] = g[4];
              I[0][2] = I[2][0] = g[5];
            }
          motion.initialize(mass, c, I, bodies[b].initial_velocity);
          pcout << "  rigid body '" << bodies[b].name << "': " << (motion.free ? "free" : "prescribed")
                << " motion, mass " << mass << " kg, centre (" << c << ")" << std::endl;
        }

    // The owned nodes of each rigid body, and their initial velocity
    // V + omega x (X - c).
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    std::vector<bool> seen(position.locally_owned_size(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial() && bodies[cell->material_id()].is_rigid())
        for (unsigned int v = 0; v < 8; ++v)
          {
            const auto dof = cell->vertex_dof_index(v, 0);
            if (!owned.is_element(dof))
              continue;
            const unsigned int i = owned.index_within_set(dof);
            if (seen[i])
              continue;
            seen[i]            = true;
            const auto &motion = bodies[cell->material_id()].rigid;
            nodes[cell->material_id()].emplace_back(
              position.get_partitioner()->global_to_local(dof), cell->vertex(v));
            const Tensor<1, 3> vel = motion.velocity_at(cell->vertex(v), motion.centre);
            for (unsigned int d = 0; d < 3; ++d)
              {
                rigid_dof[i + d] = 1;
                velocity.local_element(position.get_partitioner()->global_to_local(dof) + d) = vel[d];
              }
          }
    velocity.update_ghost_values();
  }


  // @sect3{Rigid bodies}
  //
  // Resultant force and torque about the centre from the nodal forces
  // (contact, gravity) of the owned nodes, plus the reactions of analytic
  // contact shapes; the body advances (RigidBody::Motion::advance), and each
  // node gets the velocity that carries it exactly to its rigid placement at
  // n+1, so the common position update keeps the body rigid. A body of
  // prescribed motion is held by a reaction equal and opposite to the
  // resultant, whose work is external work (Motion::advance).
  void RigidBodies::update_velocity(const double dt_previous, const double dt, OwnMotion &own)
  {
    auto             &bodies           = get_bodies_for_update();
    const VectorType &position         = get_position();
    const VectorType &force            = get_force();
    const auto       &gravity          = get_gravity();
    const MPI_Comm    mpi_communicator = get_mpi_communicator();
    double           &kinetic          = own.kinetic;
    double           &work             = own.work;
    double           &power            = own.power;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].is_rigid() && inactive[b])
        {
          // Out of the analysis: held where it was removed.
          for (const auto &node : nodes[b])
            for (unsigned int d = 0; d < 3; ++d)
              velocity.local_element(node.first + d) = 0;
        }
      else if (bodies[b].is_rigid())
        {
          auto               &motion = bodies[b].rigid;
          std::array<double, 6> ft{};
          for (const auto &[i, X] : nodes[b])
            {
              Tensor<1, 3> fi, r;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  fi[d] = force.local_element(i + d);
                  r[d]  = position.local_element(i + d) - motion.centre[d];
                }
              const Tensor<1, 3> t = cross_product_3d(r, fi);
              for (unsigned int d = 0; d < 3; ++d)
                {
                  ft[d] += fi[d];
                  ft[3 + d] += t[d];
                }
            }
          Utilities::MPI::sum(ArrayView<const double>(ft.data(), ft.size()), mpi_communicator,
                              ArrayView<double>(ft.data(), ft.size()));
          Tensor<1, 3> F({ft[0], ft[1], ft[2]}), T({ft[3], ft[4], ft[5]});
          F += shape_force[b];
          T += shape_torque[b];
          // Gravity: M g at the centre of mass.
          F += motion.mass * gravity;
          // Work of gravity over the last step: the centre moved by exactly
          // V^{n-1/2} dt^{n-1/2}.
          work += motion.mass * (gravity * motion.velocity) * dt_previous;
          const Tensor<1, 3> V_old = motion.velocity, w_old = motion.angular_velocity;
          kinetic += motion.advance(F, T, dt_previous, dt);
          work += motion.last_reaction_work;
          // F_tot . dV + T_tot . d omega, with the totals (reactions
          // included) that moved the body.
          power += (F + motion.reaction_force) * (motion.velocity - V_old) +
                   (T + motion.reaction_torque) * (motion.angular_velocity - w_old);
          for (const auto &[i, X] : nodes[b])
            {
              Point<3> x;
              for (unsigned int d = 0; d < 3; ++d)
                x[d] = position.local_element(i + d);
              const Tensor<1, 3> vel = dt > 0 ? (motion.placement(X) - x) / dt :
                                                motion.velocity_at(x, motion.centre);
              for (unsigned int d = 0; d < 3; ++d)
                velocity.local_element(i + d) = vel[d];
            }
        }
  }



  void RigidBodies::add_kinetic_energy(double &kinetic) const
  {
    // 1/2 M V.V + 1/2 omega . I omega.
    for (const auto &b : get_bodies())
      if (b.is_rigid())
        kinetic += b.rigid.velocity_kinetic_energy();
  }


  void RigidBodies::add_momentum(const double dt, std::vector<double> &momentum) const
  {
    const auto &bodies = get_bodies();
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (bodies[b].is_rigid())
        {
          const auto &m = bodies[b].rigid;
          for (unsigned int d = 0; d < 3; ++d)
            momentum[3 * b + d] = m.mass * m.velocity[d] - (m.free ? 0.5 * dt * m.last_force[d] : 0.);
        }
  }


  std::string RigidBodies::describe() const
  {
    return n_rigid == 0 ? "no rigid bodies" :
                          std::to_string(n_rigid) + " rigid bod" + (n_rigid == 1 ? "y" : "ies");
  }


  // Rigid bodies have advanced to n+1 already: the row reports the centre
  // of time n and the velocity at n, V^{n+1/2} - dt/2 F/M in the
  // directions it is free to move in.
  void RigidBodies::write_history(const double t, const double dt)
  {
    const auto &bodies = get_bodies();
    if (files.empty())
      for (const auto &b : bodies)
        if (b.is_rigid())
          {
            record_output("rigid_" + b.name + ".csv");
            files.emplace_back(get_output_directory() + "/rigid_" + b.name + ".csv");
            files.back() << "time,x,y,z,vx,vy,vz,fx,fy,fz,kinetic\n";
          }
    unsigned int r = 0;
    for (const auto &b : bodies)
      if (b.is_rigid())
        {
          const auto        &m = b.rigid;
          // (A constrained direction keeps its given velocity: the force
          // there is held by the constraint's reaction.)
          Tensor<1, 3> v = m.velocity;
          if (m.free)
            for (unsigned int d = 0; d < 3; ++d)
              if (!m.constrained[d])
                v[d] -= 0.5 * dt / m.mass * m.last_force[d];
          files[r] << std::setprecision(12) << t << ',' << m.previous_centre[0] << ','
                   << m.previous_centre[1] << ',' << m.previous_centre[2] << ',' << v[0] << ',' << v[1]
                   << ',' << v[2] << ',' << m.last_force[0] << ',' << m.last_force[1] << ','
                   << m.last_force[2] << ',' << m.kinetic_energy << '\n';
          ++r;
        }
  }



  void RigidBodies::serialize(StateArchive &ar)
  {
    ar &shape_force &shape_torque;
    for (auto &b : get_bodies_for_update())
      b.rigid.serialize(ar);
  }


  void RigidBodies::clear_shape_reactions()
  {
    for (auto &t : shape_force)
      t = 0;
    for (auto &t : shape_torque)
      t = 0;
  }


  void RigidBodies::add_shape_reaction(const unsigned int b, const Tensor<1, 3> &force, const Tensor<1, 3> &torque)
  {
    shape_force[b] += force;
    shape_torque[b] += torque;
  }


  // A stage that takes bodies out (the hammer once the impact is over):
  // they stop where they are.
  double RigidBodies::remove_inactive(const bool report)
  {
    auto  &bodies  = get_bodies_for_update();
    double removed = 0;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (inactive[b])
        {
          auto        &m       = bodies[b].rigid;
          const double kinetic = m.velocity_kinetic_energy();
          removed += kinetic;
          m.velocity         = 0;
          m.angular_velocity = 0;
          m.angular_momentum = 0;
          m.kinetic_energy   = 0;
          for (const auto &node : nodes[b])
            for (unsigned int d = 0; d < 3; ++d)
              velocity.local_element(node.first + d) = 0;
          if (report && kinetic > 0)
            get_pcout() << "  body '" << bodies[b].name << "' taken out of the analysis with " << kinetic
                        << " J of kinetic energy" << std::endl;
        }
    return removed;
  }
} // namespace anvil::RigidBody
