/**
 * Patch test across a 2:1 refinement interface (hanging nodes).
 *
 * A 3 x 3 x 3 block whose centre element is refined once: the centre's
 * six faces carry hanging nodes (face centres and edge midpoints of the
 * coarse neighbours), all inside the block. For an affine deformation
 * x = (I + A) X the stress is constant, so the internal forces of every
 * interior node cancel. They do so only after the hanging nodes' forces
 * are condensed onto their masters (f_j += w_ij f_i, HangingNodes): before,
 * the coarse neighbours' corner nodes are out of balance by the order of
 * stress x face area, which the test prints. Checked, for one-point and
 * full integration, on a skewed (parallelepiped) block:
 * - every interior node's condensed force below 1e-12 of stress x face
 *   area, and the hanging nodes' zero;
 * - the sum of the forces and of the lumped masses unchanged by the
 *   condensation (momentum and mass: the weights sum to one);
 * - the hanging nodes' velocities, from their masters', those of the
 *   linear field to 1e-14; and the positions after a step (advance()).
 */
#include "unit_test.h"

#include <anvil/mesh/hanging_nodes.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

using namespace anvil;
using test::check;
using test::check_below;

int main()
{
  using namespace dealii;
  const double A[3][3] = {{0.02, 0.05, -0.01}, {0.03, -0.04, 0.02}, {-0.02, 0.01, 0.06}};
  const double L[3][3] = {{0.3, -0.1, 0.2}, {0.1, -0.2, 0.05}, {0.4, 0.05, 0.1}};

  Triangulation<3> tria(Triangulation<3>::limit_level_difference_at_vertices);
  GridGenerator::subdivided_hyper_cube(tria, 3);
  // A skew of the whole block: the elements stay parallelepipeds.
  GridTools::transform(
    [](const Point<3> &p) { return Point<3>(p[0] + 0.3 * p[1] + 0.1 * p[2], 0.9 * p[1] + 0.2 * p[2], p[2] + 0.15 * p[0]); },
    tria);
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->index() == 13) // the centre of 27
      cell->set_refine_flag();
  tria.execute_coarsening_and_refinement();

  FESystem<3>   fe(FE_Q<3>(1), 3);
  DoFHandler<3> dof_handler(tria);
  dof_handler.distribute_dofs(fe);
  const unsigned int        n_dofs = dof_handler.n_dofs();
  AffineConstraints<double> constraints;
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  constraints.close();
  const Utilities::MPI::Partitioner partitioner(n_dofs);
  std::vector<unsigned long>        key(n_dofs);
  for (unsigned int i = 0; i < n_dofs; ++i)
    key[i] = i;
  HangingNodes hanging;
  hanging.reinit(constraints, partitioner, key);
  std::printf("%u elements, %u nodes, %u of them hanging\n", tria.n_active_cells(), n_dofs / 3,
              hanging.size() / 3);
  check("hanging nodes: 6 face centres and 12 edge midpoints of the refined centre", hanging.size() / 3, 18, 0);

  // Reference positions and the interior nodes (off the block's boundary).
  std::vector<double> X(n_dofs);
  std::vector<bool>   interior(n_dofs / 3, true);
  for (const auto &cell : dof_handler.active_cell_iterators())
    for (unsigned int v = 0; v < 8; ++v)
      {
        const unsigned int n = cell->vertex_dof_index(v, 0) / 3;
        for (unsigned int d = 0; d < 3; ++d)
          X[3 * n + d] = cell->vertex(v)[d];
      }
  for (const auto &cell : dof_handler.active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        for (unsigned int v = 0; v < 4; ++v)
          interior[cell->face(f)->vertex_dof_index(v, 0) / 3] = false;

  MaterialModel::Elastic material;
  material.set(7850., 2e11, 0.3);
  for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
    {
      std::printf("== %s integration\n", Element::to_string(integration).c_str());
      Element::ElementGroup group(material, Formulation::total_lagrangian, integration,
                                  Element::HourglassType::viscous, 0.1);
      std::vector<double> m(n_dofs, 0.);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          std::array<unsigned int, 8> node;
          double                      Xe[8][3], me[8];
          for (unsigned int v = 0; v < 8; ++v)
            {
              node[v] = cell->vertex_dof_index(v, 0);
              for (unsigned int d = 0; d < 3; ++d)
                Xe[v][d] = cell->vertex(v)[d];
            }
          group.add_element(node, Xe, group.n_elements());
          Element::lumped_mass(Xe, material.density(), me);
          for (unsigned int v = 0; v < 8; ++v)
            for (unsigned int d = 0; d < 3; ++d)
              m[node[v] + d] += me[v];
        }
      group.finalize();

      std::vector<double> x(X), v(n_dofs, 0.), f(n_dofs, 0.);
      for (unsigned int n = 0; n < n_dofs / 3; ++n)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            x[3 * n + i] += A[i][j] * X[3 * n + j];
      group.compute_internal_forces(x.data(), v.data(), 0., f.data());

      // The scale: a stress component times an element face area.
      double s_scale = 0;
      for (unsigned int k = 0; k < 3; ++k)
        s_scale = std::max(s_scale, std::abs(group.stress(0, 0)[k]));
      const double f_scale = s_scale / 9.;
      auto         worst_interior = [&](const std::vector<double> &g) {
        double worst = 0;
        for (unsigned int n = 0; n < n_dofs / 3; ++n)
          if (interior[n] && !hanging.is_hanging(3 * n))
            worst = std::max(worst, std::sqrt(g[3 * n] * g[3 * n] + g[3 * n + 1] * g[3 * n + 1] +
                                              g[3 * n + 2] * g[3 * n + 2]));
        return worst / f_scale;
      };
      double sum_before[3] = {0, 0, 0}, mass_before = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          sum_before[i % 3] += f[i];
          mass_before += m[i];
        }
      std::printf("  largest interior force before condensation / (stress x face area): %.3g\n",
                  worst_interior(f));
      hanging.condense(f.data());
      hanging.condense(m.data());
      check_below("largest interior force after condensation / (stress x face area)", worst_interior(f), 1e-12);
      double hanging_force = 0, sum_after[3] = {0, 0, 0}, mass_after = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          if (hanging.is_hanging(i))
            hanging_force = std::max(hanging_force, std::abs(f[i]) + std::abs(m[i]));
          sum_after[i % 3] += f[i];
          mass_after += m[i];
        }
      check("hanging nodes' force and mass after condensation", hanging_force, 0., 0.);
      for (unsigned int d = 0; d < 3; ++d)
        check("sum of the forces, component " + std::to_string(d) + ", after - before (/ stress x area)",
              (sum_after[d] - sum_before[d]) / f_scale, 0., 1e-12);
      check("total lumped mass, after / before - 1", mass_after / mass_before - 1., 0., 1e-14);
    }

  // The hanging nodes follow their masters: a linear velocity field, and
  // the positions after a step.
  std::vector<double> v(n_dofs), x(X), out;
  for (unsigned int n = 0; n < n_dofs / 3; ++n)
    for (unsigned int i = 0; i < 3; ++i)
      v[3 * n + i] = L[i][0] * X[3 * n] + L[i][1] * X[3 * n + 1] + L[i][2] * X[3 * n + 2];
  std::vector<double> exact(v);
  for (unsigned int i = 0; i < n_dofs; ++i)
    if (hanging.is_hanging(i))
      v[i] = 1e3; // overwritten
  hanging.distribute(v.data(), n_dofs);
  double worst = 0;
  for (unsigned int i = 0; i < n_dofs; ++i)
    worst = std::max(worst, std::abs(v[i] - exact[i]));
  check_below("hanging nodes' velocity from their masters against the linear field", worst, 1e-14);
  const double dt = 0.01;
  hanging.advance(x.data(), v.data(), dt, n_dofs, out);
  for (unsigned int i = 0; i < n_dofs; ++i)
    x[i] += dt * v[i];
  worst = 0;
  unsigned int k = 0;
  for (unsigned int i = 0; i < n_dofs; ++i)
    if (hanging.is_hanging(i))
      worst = std::max(worst, std::abs(out[k++] - x[i]));
  check_below("hanging nodes' positions after a step (advance) against x + dt v", worst, 1e-14);
  return test::finish();
}
