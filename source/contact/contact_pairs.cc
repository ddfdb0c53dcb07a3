/**
 * @file
 * The contact pairs of a scene as one family (contact/contact_pairs.h).
 */
#include <anvil/boundary_conditions/constraints.h>
#include <anvil/contact/contact_pairs.h>
#include <anvil/mesh/body.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/mpi.h>

#include <iomanip>
#include <map>

namespace anvil::Contact
{
  using namespace dealii;

  ContactPairs::ContactPairs(Simulator                               &simulator,
                             std::vector<std::unique_ptr<Algorithm>>  pairs,
                             std::vector<unsigned char>               inactive,
                             RigidBody::RigidBodies                  &rigid_bodies)
    : ForceContributor(simulator)
    , pairs(std::move(pairs))
    , inactive(std::move(inactive))
    , rigid_bodies(rigid_bodies)
  {}


  // @sect3{Contact surfaces}
  //
  // Every boundary face of a body in a pair is a segment. Each rank lists
  // the segments of its own cells; all ranks then hold the whole surface.
  void ContactPairs::initialize()
  {
    const auto        &bodies           = get_bodies();
    const auto        &dof_handler      = get_dof_handler();
    const VectorType  &position         = get_position();
    const MPI_Comm     mpi_communicator = get_mpi_communicator();
    const std::string &scene_file       = get_scene_file();
    const unsigned int n_pairs          = pairs.size();
    relevant_index.assign(n_pairs, {});
    owned_index.assign(n_pairs, {});
    distributed.assign(n_pairs, 0);
    positions.assign(n_pairs, {});
    velocities.assign(n_pairs, {});
    forces.assign(n_pairs, {});
    other_forces.assign(n_pairs, {});
    inverse_masses.assign(n_pairs, {});
    any_kinematic = false;
    contact_results.assign(n_pairs, {});
    analytic_body.assign(n_pairs, {{-1, -1}});
    pair_body.clear();
    contact_frequency_squared = 0;
    for (unsigned int p = 0; p < n_pairs; ++p)
      {
        std::vector<Contact::SegmentDescription> segments[2];
        const unsigned int body[2] = {body_index(pairs[p]->first_body),
                                      body_index(pairs[p]->second_body)};
        pair_body.push_back({{body[0], body[1]}});
        for (unsigned int s = 0; s < 2; ++s)
          {
            // The body's boundary faces; and of an eroding body, its
            // interior faces too, each from both sides, in the surface once
            // the element across has eroded (eroding contact: the faces
            // an eroded element exposes; not across a refinement
            // interface, whose faces do not match).
            const bool          eroding = bodies[body[s]].material->erodes();
            std::vector<double> local;
            auto                across  = [&](const auto &cell, const unsigned int f) -> double {
              if (cell->face(f)->at_boundary())
                return -1.;
              if (!eroding || cell->face(f)->has_children() || cell->neighbor_is_coarser(f) ||
                  cell->neighbor(f)->material_id() != body[s])
                return -2.;
              return double(element_id(cell->neighbor(f)->active_cell_index()));
            };
            for (const auto &cell : dof_handler.active_cell_iterators())
              if (cell->is_locally_owned() && cell->material_id() == body[s])
                for (const unsigned int f : cell->face_indices())
                  if (const double neighbour = across(cell, f); neighbour != -2.)
                    {
                      const auto   face     = cell->face(f);
                      const double V        = cell->measure();
                      // (An element halved during the run keeps the
                      // penalty's pressure stiffness f K / h of the
                      // element the run started with: K / 2 per halving,
                      // so that a round at a pressed face leaves the
                      // contact force as it was; doc/adaptivity.md.)
                      const double K = bodies[body[s]].material->bulk_modulus() /
                                       double(1u << halvings_during_run(element_id(cell->active_cell_index())));
                      constexpr unsigned int cyclic[4] = {0, 1, 3, 2};
                      Point<3>               p[4];
                      for (unsigned int k = 0; k < 4; ++k)
                        p[k] = face->vertex(cyclic[k]);
                      const Tensor<1, 3> n = cross_product_3d(p[1] - p[0], p[3] - p[0]);
                      const bool flip = n * (face->center() - cell->center()) < 0;
                      for (unsigned int k = 0; k < 4; ++k)
                        {
                          const unsigned int kk = flip ? cyclic[3 - k] : cyclic[k];
                          local.push_back(face->vertex_dof_index(kk, 0));
                        }
                      for (unsigned int k = 0; k < 4; ++k)
                        {
                          const unsigned int kk = flip ? cyclic[3 - k] : cyclic[k];
                          for (unsigned int d = 0; d < 3; ++d)
                            local.push_back(face->vertex(kk)[d]);
                        }
                      local.push_back(K);
                      local.push_back(V);
                      local.push_back(element_id(cell->active_cell_index()));
                      for (unsigned int k = 0; k < 4; ++k)
                        local.push_back(scene_vertex_index(face->vertex_index(flip ? cyclic[3 - k] : cyclic[k])));
                      local.push_back(neighbour);
                    }
            for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, local))
              for (std::size_t i = 0; i < part.size(); i += 24)
                {
                  Contact::SegmentDescription d;
                  for (unsigned int k = 0; k < 4; ++k)
                    d.x_dof[k] = static_cast<unsigned long>(part[i + k]);
                  for (unsigned int k = 0; k < 12; ++k)
                    d.reference_position[k] = part[i + 4 + k];
                  d.bulk_modulus = part[i + 16];
                  d.volume       = part[i + 17];
                  d.element   = static_cast<unsigned long>(part[i + 18]);
                  for (unsigned int k = 0; k < 4; ++k)
                    d.vertex[k] = static_cast<std::uint64_t>(part[i + 19 + k]);
                  if (part[i + 23] >= 0)
                    d.neighbour = static_cast<unsigned long>(part[i + 23]);
                  segments[s].push_back(d);
                }
          }
        pairs[p]->setup(segments[0], segments[1]);
        {
          std::map<unsigned long, std::uint64_t> vertex_of;
          for (unsigned int s = 0; s < 2; ++s)
            for (const auto &d : segments[s])
              for (unsigned int k = 0; k < 4; ++k)
                vertex_of[d.x_dof[k]] = d.vertex[k];
          pairs[p]->node_keys.clear();
          for (const auto dof : pairs[p]->node_dofs())
            pairs[p]->node_keys.push_back(vertex_of.at(dof));
        }
        for (unsigned int s = 0; s < 2; ++s)
          {
            pairs[p]->set_rigid(s, bodies[body[s]].is_rigid());
            analytic_body[p][s] = bodies[body[s]].is_rigid() &&
                                      bodies[body[s]].rigid.shape.type != RigidBody::Shape::Type::mesh ?
                                    int(body[s]) :
                                    -1;
          }
        if (bodies[body[0]].is_rigid() && bodies[body[1]].is_rigid())
          throw InputError(scene_file + ": subsection 'Contact pair " + pairs[p]->name +
                           "': both bodies are rigid");
        // A pair that evaluates each rank's share reads the nodes of the
        // rank's own and ghost cells, and is not gathered.
        const auto &dofs        = pairs[p]->node_dofs();
        const auto &partitioner = *position.get_partitioner();
        place_analytic_shapes(p);
        distributed[p] = pairs[p]->distribute(mpi_communicator, dof_handler.locally_owned_dofs());
        pairs[p]->own_nodes.clear();
        for (unsigned int i = 0; i < dofs.size(); ++i)
          {
            if (partitioner.in_local_range(dofs[i]))
              {
                owned_index[p].emplace_back(i, partitioner.global_to_local(dofs[i]));
                pairs[p]->own_nodes.push_back(i);
              }
            if (distributed[p] && (partitioner.in_local_range(dofs[i]) || partitioner.is_ghost_entry(dofs[i])))
              relevant_index[p].emplace_back(i, partitioner.global_to_local(dofs[i]));
          }
        // The pair's node masses (normal damping, the springs' frequency in
        // the stable step, which each evaluation updates).
        std::vector<double> m(dofs.size(), 0.);
        int                 hanging = 0;
        for (const auto &[i, local] : owned_index[p])
          {
            m[i] = node_mass(local);
            hanging |= is_hanging(local) ? 1 : 0;
          }
        Utilities::MPI::sum(m, mpi_communicator, m);
        // A kinematic pair corrects the motion of its nodes; a hanging
        // node's motion is its masters', which the pair must hold too (they
        // lie on the coarse face or edge the node hangs on, the surface).
        if (pairs[p]->kinematic() && Utilities::MPI::max(hanging, mpi_communicator) != 0)
          {
            // Each owner's hanging pair nodes: pair index, number of
            // masters, then each master's global x dof and weight.
            std::vector<double> local;
            for (const auto &[i, l] : owned_index[p])
              if (is_hanging(l))
                {
                  const auto masters = hanging_masters(l);
                  local.push_back(i);
                  local.push_back(masters.size());
                  for (const auto &[j, w] : masters)
                    {
                      local.push_back(static_cast<double>(partitioner.local_to_global(j)));
                      local.push_back(w);
                    }
                }
            std::map<unsigned long, unsigned int> pair_index;
            for (unsigned int i = 0; i < dofs.size(); ++i)
              pair_index[dofs[i]] = i;
            std::vector<std::vector<std::pair<unsigned int, double>>> masters(dofs.size());
            for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, local))
              for (std::size_t k = 0; k < part.size();)
                {
                  const auto i = static_cast<unsigned int>(part[k]);
                  const auto n = static_cast<unsigned int>(part[k + 1]);
                  k += 2;
                  for (unsigned int e = 0; e < n; ++e, k += 2)
                    {
                      const auto at = pair_index.find(static_cast<unsigned long>(part[k]));
                      if (at == pair_index.end())
                        throw InputError(scene_file + ": subsection 'Contact pair " + pairs[p]->name +
                                         "': a hanging node of the contact surface (a 'Refinement region' "
                                         "meeting it) follows a node that is not on the surface, which "
                                         "kinematic contact cannot move: set 'Algorithm = penalty' there, "
                                         "or keep the region's boundary off the contact surface");
                      masters[i].emplace_back(at->second, part[k + 1]);
                    }
                }
            pairs[p]->set_hanging_nodes(masters);
          }
        else
          pairs[p]->set_hanging_nodes({});
        pairs[p]->set_node_masses(m);
        positions[p].resize(3 * dofs.size());
        if (pairs[p]->needs_velocities())
          velocities[p].resize(3 * dofs.size());
        forces[p].resize(3 * dofs.size());
        if (pairs[p]->kinematic())
          {
            any_kinematic = true;
            other_forces[p].resize(3 * dofs.size());
            inverse_masses[p].resize(3 * dofs.size());
          }
      }
  }


  // @sect3{Contact}
  //
  // A distributed pair (two deformable meshes, or against an analytic
  // shape) reads the positions of the rank's own and ghost cells and sets
  // the forces of its own nodes; it returns the whole pair's figures on
  // every rank. Any other pair (a rigid body's mesh) has its nodes'
  // positions gathered to every rank, every rank evaluates it whole, and
  // each keeps the forces on the nodes it owns.
  double ContactPairs::add_forces(const double dt_previous)
  {
    const VectorType &position         = get_position();
    const VectorType &velocity         = get_velocity();
    VectorType       &force            = get_force();
    Energies         &energies         = get_energies();
    const MPI_Comm    mpi_communicator = get_mpi_communicator();
    rigid_bodies.clear_shape_reactions();
    // The springs in reach bound the step at once; once they leave, the
    // bound relaxes over some hundred steps (omega^2 by 1 % a step, the step
    // by 0.5 %). A step that jumps back and forth as nodes enter and leave
    // the reach of their partners resonates with the mesh (the energy
    // error of the variable-step scheme, energies.step_change).
    const double held_frequency_squared = 0.99 * contact_frequency_squared;
    contact_frequency_squared           = 0;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        if (inactive[p] || pairs[p]->kinematic())
          continue;
        auto &xs = positions[p];
        auto &vs = velocities[p];
        auto &fs = forces[p];
        if (distributed[p])
          {
            // Only the entries of the own and ghost nodes are ever set;
            // the algorithm sets forces on own nodes only.
            for (const auto &[i, local] : relevant_index[p])
              for (unsigned int d = 0; d < 3; ++d)
                {
                  xs[3 * i + d] = position.local_element(local + d);
                  if (!vs.empty())
                    vs[3 * i + d] = velocity.local_element(local + d);
                }
            for (const auto &[i, local] : owned_index[p])
              for (unsigned int d = 0; d < 3; ++d)
                fs[3 * i + d] = 0;
          }
        else
          {
            std::fill(xs.begin(), xs.end(), 0.);
            std::fill(vs.begin(), vs.end(), 0.);
            std::fill(fs.begin(), fs.end(), 0.);
            for (const auto &[i, local] : owned_index[p])
              for (unsigned int d = 0; d < 3; ++d)
                {
                  xs[3 * i + d] = position.local_element(local + d);
                  if (!vs.empty())
                    vs[3 * i + d] = velocity.local_element(local + d);
                }
            Utilities::MPI::sum(xs, mpi_communicator, xs);
            if (!vs.empty())
              Utilities::MPI::sum(vs, mpi_communicator, vs);
          }
        place_analytic_shapes(p);
        contact_results[p] = pairs[p]->compute_forces(xs, vs, dt_previous, fs);
        // The springs in contact, or within reach by the next step, bound
        // the next step (replicated: the same on every rank).
        contact_frequency_squared =
          std::max(contact_frequency_squared, contact_results[p].frequency_squared);
        record_result(p);
        springs_across_partitions += contact_results[p].n_springs_across_partitions;
        // Every rank has the whole pair's friction work, and the energy of
        // the springs an erosion made or took away (booked as removed: not
        // work of the motion).
        energies.friction += contact_results[p].friction_work;
        energies.removed -= contact_results[p].topology_energy;
        for (const auto &[i, local] : owned_index[p])
          for (unsigned int d = 0; d < 3; ++d)
            force.local_element(local + d) += fs[3 * i + d];
      }
    contact_frequency_squared = std::max(contact_frequency_squared, held_frequency_squared);
    return 1e300;
  }


  // @sect3{Kinematic contact}
  //
  // A kinematic pair is evaluated whole on every rank: the positions,
  // velocities, forces and inverse masses of its nodes are gathered (a
  // rigid body's and a constrained dof's inverse mass is 0, a constrained
  // dof moves at its prescribed velocity), and each rank adds the forces
  // of the nodes it owns.
  void ContactPairs::add_kinematic_forces(const double dt_previous, const double dt)
  {
    if (!any_kinematic)
      return;
    const VectorType &position         = get_position();
    const VectorType &velocity         = get_velocity();
    VectorType       &force            = get_force();
    const VectorType &mass             = get_mass();
    const auto       &rigid_dof        = get_rigid_dof();
    const auto       &constraints      = get_constraints();
    const MPI_Comm    mpi_communicator = get_mpi_communicator();
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        if (inactive[p] || !pairs[p]->kinematic())
          continue;
        auto &xs = positions[p];
        auto &vs = velocities[p];
        auto &fs = other_forces[p];
        auto &ws = inverse_masses[p];
        std::fill(xs.begin(), xs.end(), 0.);
        std::fill(vs.begin(), vs.end(), 0.);
        std::fill(fs.begin(), fs.end(), 0.);
        std::fill(ws.begin(), ws.end(), 0.);
        for (const auto &[i, local] : owned_index[p])
          for (unsigned int d = 0; d < 3; ++d)
            {
              const unsigned int l = local + d;
              xs[3 * i + d]        = position.local_element(l);
              fs[3 * i + d]        = force.local_element(l);
              const bool rigid     = !rigid_dof.empty() && rigid_dof[l];
              const bool held      = constraints.is_held(l);
              vs[3 * i + d]        = held ? constraints.prescribed_velocity(l) : velocity.local_element(l);
              // (A hanging node moves with its masters: no mass of its own.)
              ws[3 * i + d] = rigid || held || is_hanging(l) ? 0. : 1. / mass.local_element(l);
            }
        Utilities::MPI::sum(xs, mpi_communicator, xs);
        Utilities::MPI::sum(vs, mpi_communicator, vs);
        Utilities::MPI::sum(fs, mpi_communicator, fs);
        Utilities::MPI::sum(ws, mpi_communicator, ws);
        place_analytic_shapes(p);
        auto &out = forces[p];
        std::fill(out.begin(), out.end(), 0.);
        contact_results[p] = pairs[p]->correct(xs, vs, fs, ws, dt_previous, dt, out);
        record_result(p);
        for (const auto &[i, local] : owned_index[p])
          for (unsigned int d = 0; d < 3; ++d)
            force.local_element(local + d) += out[3 * i + d];
      }
  }


  void ContactPairs::nodal_force_magnitudes(VectorType &nodal) const
  {
    for (unsigned int p = 0; p < pairs.size(); ++p)
      if (!inactive[p] && forces[p].size() == 3 * pairs[p]->node_dofs().size())
        for (const auto &[i, local] : owned_index[p])
          {
            const double *f = &forces[p][3 * i];
            nodal.local_element(local) =
              std::max(nodal.local_element(local), std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
          }
  }


  // A pair's result: the reaction on a rigid body's analytic shape (at
  // most one surface of a pair is a rigid body's), the run's maxima.
  void ContactPairs::record_result(const unsigned int p)
  {
    const int shape_body = analytic_body[p][0] >= 0 ? analytic_body[p][0] : analytic_body[p][1];
    if (shape_body >= 0)
      rigid_bodies.add_shape_reaction(shape_body, contact_results[p].shape_force, contact_results[p].shape_torque);
    if (run_maxima.size() != pairs.size())
      run_maxima.assign(pairs.size(), {{0., 0., 0.}});
    auto &m = run_maxima[p];
    m[0]    = std::max(m[0], contact_results[p].max_penetration);
    m[1]    = std::max(m[1], contact_results[p].max_penetration_ratio);
    m[2]    = std::max(m[2], contact_results[p].energy);
  }


  void ContactPairs::place_analytic_shapes(const unsigned int p)
  {
    for (unsigned int s = 0; s < 2; ++s)
      if (analytic_body[p][s] >= 0)
        {
          const auto              &m = get_bodies()[analytic_body[p][s]].rigid;
          Contact::AnalyticSurface a;
          a.shape            = &m.shape;
          a.centre           = m.centre;
          a.reference_centre = m.reference_centre;
          a.rotation         = m.rotation;
          a.velocity         = m.velocity;
          a.angular_velocity = m.angular_velocity;
          pairs[p]->set_analytic(s, a);
        }
  }


  void ContactPairs::deactivate_elements(const std::vector<unsigned long> &ids)
  {
    for (auto &pair : pairs)
      pair->deactivate_elements(ids);
  }


  double ContactPairs::remove_inactive()
  {
    double energy = 0;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      if (inactive[p])
        {
          energy += contact_results[p].energy;
          contact_results[p] = ContactResult();
        }
    return energy;
  }


  std::string ContactPairs::describe() const
  {
    unsigned int active = 0;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      active += inactive[p] ? 0 : 1;
    return active == 0 ? "no contact" :
                         "contact in " + std::to_string(active) + " pair" + (active == 1 ? "" : "s");
  }


  // The contact's approach, for the penalty's note at the end: how far the
  // two bodies' centres of mass moved towards each other along the pair's
  // force since it began to act (the rigid sphere's delta in Hertz's
  // problem; v L / 2c at the middle of two equal rods' contact). The
  // springs' penetration over it is the share of the deformation at
  // contact that is the penalty's own compliance. Only at history rows,
  // only with penalty pairs.
  void ContactPairs::prepare_history()
  {
    bool any_penalty = false;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      any_penalty |= !pairs[p]->kinematic() && !inactive[p];
    if (!any_penalty)
      return;
    const auto       &bodies = get_bodies();
    const VectorType &x = get_position(), &X = get_reference_position(), &m = get_mass();
    const auto       &dof_body = get_dof_body(), &dof_component = get_dof_component();
    const auto       &rigid_dof = get_rigid_dof();
    // Per body: sum m u (three components) and sum m.
    std::vector<double> moments(4 * bodies.size(), 0.);
    for (unsigned int i = 0; i < x.locally_owned_size(); ++i)
      if (rigid_dof.empty() || !rigid_dof[i])
        {
          const unsigned int b = dof_body[i];
          moments[4 * b + dof_component[i]] += m.local_element(i) * (x.local_element(i) - X.local_element(i));
          if (dof_component[i] == 0)
            moments[4 * b + 3] += m.local_element(i);
        }
    Utilities::MPI::sum(moments, get_mpi_communicator(), moments);
    auto displacement = [&](const unsigned int b) {
      Tensor<1, 3> d;
      if (bodies[b].is_rigid())
        return Tensor<1, 3>(bodies[b].rigid.centre - bodies[b].rigid.reference_centre);
      if (moments[4 * b + 3] > 0)
        for (unsigned int k = 0; k < 3; ++k)
          d[k] = moments[4 * b + k] / moments[4 * b + 3];
      return d;
    };
    if (approach.size() != pairs.size())
      approach.assign(pairs.size(), {{0, 0, 0, 0, 0, 0, 0, 0}});
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        if (pairs[p]->kinematic() || inactive[p])
          continue;
        auto              &a = approach[p];
        const Tensor<1, 3> f({contact_results[p].force_on_first[0], contact_results[p].force_on_first[1],
                              contact_results[p].force_on_first[2]});
        if (!(f.norm() > 0))
          {
            a[6] = 0;
            continue;
          }
        const Tensor<1, 3> d[2] = {displacement(pair_body[p][0]), displacement(pair_body[p][1])};
        if (a[6] == 0)
          for (unsigned int k = 0; k < 3; ++k)
            a[k] = d[0][k], a[3 + k] = d[1][k], a[6] = 1;
        // The force on the first body pushes it away from the second.
        Tensor<1, 3> moved;
        for (unsigned int k = 0; k < 3; ++k)
          moved[k] = (d[1][k] - a[3 + k]) - (d[0][k] - a[k]);
        a[7] = std::max(a[7], moved * f / f.norm());
      }
  }


  void ContactPairs::write_history(const double t, double)
  {
    if (files.empty())
      for (const auto &c : pairs)
        {
          record_output("contact_" + c->name + ".csv");
          files.emplace_back(get_output_directory() + "/contact_" + c->name + ".csv");
          files.back() << "time,normal_force_x,normal_force_y,normal_force_z,max_penetration,"
                          "friction_force_x,friction_force_y,friction_force_z,max_penetration_ratio,"
                          "active_nodes\n";
        }
    for (unsigned int c = 0; c < pairs.size(); ++c)
      {
        const auto &r = contact_results[c];
        files[c] << std::setprecision(12) << t << ',' << r.force_on_first[0] << ',' << r.force_on_first[1]
                 << ',' << r.force_on_first[2] << ',' << r.max_penetration << ',' << r.friction_on_first[0]
                 << ',' << r.friction_on_first[1] << ',' << r.friction_on_first[2] << ','
                 << r.max_penetration_ratio << ',' << r.n_active << '\n';
      }
  }



  // How often a spring's state crossed a partition boundary (distributed
  // pairs; zero on one process).
  void ContactPairs::write_summary(std::ostream &out) const
  {
    for (unsigned int p = 0; p < pairs.size(); ++p)
      if (distributed[p])
        {
          out << "contact_springs_across_partitions," << springs_across_partitions << '\n';
          break;
        }
    // (A kinematic pair's energy is what it took from the bodies so far.)
    for (unsigned int p = 0; p < run_maxima.size(); ++p)
      {
        out << "contact_" << pairs[p]->name << "_max_penetration," << run_maxima[p][0] << '\n'
            << "contact_" << pairs[p]->name << "_max_penetration_ratio," << run_maxima[p][1] << '\n'
            << "contact_" << pairs[p]->name
            << (pairs[p]->kinematic() ? "_energy_taken," : "_max_spring_energy,")
            << (pairs[p]->kinematic() ? contact_results[p].energy : run_maxima[p][2]) << '\n';
        if (p < approach.size() && approach[p][7] > 0)
          out << "contact_" << pairs[p]->name << "_max_approach," << approach[p][7] << '\n'
              << "contact_" << pairs[p]->name << "_penetration_over_approach,"
              << run_maxima[p][0] / approach[p][7] << '\n';
      }
  }


  std::string ContactPairs::end_of_run_note() const
  {
    std::ostringstream s;
    const double       E0 = get_initial_energy();
    for (unsigned int p = 0; p < run_maxima.size(); ++p)
      if (pairs[p]->kinematic() && (run_maxima[p][0] > 0 || contact_results[p].energy != 0))
        {
          s << "  contact pair '" << pairs[p]->name << "' (kinematic): deepest penetration left at a step's end "
            << std::setprecision(3) << run_maxima[p][0] << " (" << 100 * run_maxima[p][1]
            << " % of the thinnest element's thickness), energy the contact took " << contact_results[p].energy;
          if (E0 > 0)
            s << " (" << 100 * contact_results[p].energy / E0 << " % of the initial energy)";
          s << '\n';
        }
      else if (run_maxima[p][0] > 0)
        {
          s << "  contact pair '" << pairs[p]->name << "': deepest penetration " << std::setprecision(3)
            << run_maxima[p][0] << " (" << 100 * run_maxima[p][1]
            << " % of the pressed element's thickness), largest energy in its penalty springs "
            << run_maxima[p][2];
          if (E0 > 0)
            s << " (" << 100 * run_maxima[p][2] / E0 << " % of the initial energy)";
          s << '\n';
          // The springs' compliance against the bodies' own deformation at
          // contact; from 1 % on it is a measurable share of the answer.
          if (p < approach.size() && approach[p][7] > 0)
            {
              const double share = run_maxima[p][0] / approach[p][7];
              s << "  contact pair '" << pairs[p]->name << "': the deepest penetration is "
                << std::setprecision(3) << 100 * share << " % of the contact's approach ("
                << approach[p][7] << ", the bodies' centres of mass towards each other)";
              if (share > 0.01)
                s << ": the penalty springs' compliance is a measurable share of the deformation at "
                     "contact ('Algorithm = kinematic' has none; a larger 'Penalty scale factor' "
                     "shrinks it)";
              s << '\n';
            }
        }
    return s.str();
  }


  // The pairs' figures are every rank's alike; the positions, velocities
  // and forces of a pair's nodes (the last evaluation's) are each node's
  // owner's, by the node's index in the pair; then each pair's algorithm,
  // its tables under the pair's name.
  void ContactPairs::serialize(StateArchive &ar)
  {
    ar &contact_frequency_squared &contact_results &springs_across_partitions &run_maxima &approach;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        const unsigned int n_nodes = pairs[p]->node_dofs().size();
        std::vector<std::vector<double> *> arrays;
        for (auto *a : {&positions[p], &velocities[p], &forces[p]})
          if (a->size() == 3 * n_nodes && n_nodes > 0)
            arrays.push_back(a);
        const unsigned int         record = 3 * arrays.size();
        std::vector<std::uint64_t> index, keys;
        if (ar.is_loading())
          for (unsigned int i = 0; i < n_nodes; ++i)
            index.push_back(i);
        else
          index = pairs[p]->own_nodes;
        for (const auto i : index)
          keys.push_back(pairs[p]->node_keys[i]);
        const std::string table = "pair '" + pairs[p]->name + "'";
        // (Onto a refined mesh, the new nodes start from what the next
        // evaluation finds.)
        ar.keyed_items(
          table,
          keys,
          record,
          [&](const std::size_t k, RecordCursor &io) {
            for (auto *a : arrays)
              io(*a, 3 * index[k], 3);
          },
          ar.element_transfer() != nullptr);
        std::string stream;
        if (!ar.is_loading())
          {
            StateArchive own = ar.nested(table);
            pairs[p]->serialize(own);
            stream = own.data();
          }
        ar &stream;
        if (ar.is_loading())
          {
            StateArchive own = ar.nested(table, stream);
            pairs[p]->serialize(own);
            if (!own.exhausted())
              throw std::runtime_error("the state of contact pair '" + pairs[p]->name +
                                       "' is longer than this build's");
          }
      }
  }
} // namespace anvil::Contact
