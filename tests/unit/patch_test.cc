/**
 * Patch test on a distorted mesh.
 *
 * A linear (affine) displacement field x = (I + A) X must give the exact
 * constant Green-Lagrange strain in every element, with one-point and with
 * 2x2x2 integration, and (full integration) zero internal force at the
 * interior node: constant stress is in equilibrium. Both a non-affinely
 * distorted patch and an affinely skewed one (parallelepipeds) are tested.
 *
 * The kernel's deformation gradient is also compared, at every Gauss point
 * and for a non-affine field, with deal.II's FEValues (the reference path).
 */
#include "unit_test.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

using namespace anvil;
using test::check;
using test::check_below;

namespace
{
  const double A[3][3] = {{0.02, 0.05, -0.01}, {0.03, -0.04, 0.02}, {-0.02, 0.01, 0.06}};

  /** St. Venant-Kirchhoff stress of F = I + A, the closed form. */
  void exact_pk2(const MaterialModel::Elastic &m, double *S)
  {
    double F[3][3];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F[i][j] = (i == j) + A[i][j];
    double E[6];
    const unsigned int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
    for (unsigned int k = 0; k < 6; ++k)
      {
        const unsigned int a = ij[k][0], b = ij[k][1];
        E[k] = 0.5 * (F[0][a] * F[0][b] + F[1][a] * F[1][b] + F[2][a] * F[2][b] - (a == b));
      }
    m.compute_pk2_stress(nullptr, E, S, nullptr);
  }

  void distort(test::Block &block, const bool affine_only)
  {
    // An affine skew of the whole patch (elements stay parallelepipeds) ...
    for (unsigned int n = 0; n < block.n_nodes(); ++n)
      {
        double *X = &block.X[3 * n];
        const double x = X[0], y = X[1], z = X[2];
        X[0] = x + 0.3 * y + 0.1 * z;
        X[1] = 0.9 * y + 0.2 * z;
        X[2] = z + 0.15 * x;
      }
    if (affine_only)
      return;
    // ... then non-affine moves of the interior node and some boundary nodes.
    const double moves[4][4] = {{13, 0.07, -0.05, 0.04}, {4, 0.05, 0.03, 0}, {10, -0.04, 0.02, 0.03}, {22, 0.03, 0.04, -0.05}};
    for (const auto &m : moves)
      for (unsigned int d = 0; d < 3; ++d)
        block.X[3 * int(m[0]) + d] += m[1 + d];
  }
} // namespace

int main()
{
  MaterialModel::Elastic material;
  material.set(7850., 2e11, 0.3);
  double S_exact[6];
  exact_pk2(material, S_exact);
  const double s_scale = std::abs(S_exact[0]) + std::abs(S_exact[1]) + std::abs(S_exact[2]);

  for (const bool affine_only : {false, true})
    for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
      {
        std::printf("== %s mesh, %s integration, total Lagrangian\n",
                    affine_only ? "parallelepiped" : "distorted",
                    Element::to_string(integration).c_str());
        test::Block block(2, 2, 2);
        distort(block, affine_only);
        Element::ElementGroup group(material, Formulation::total_lagrangian, integration,
                                    Element::HourglassType::viscous, 0.1);
        block.make_elements(group);
        std::vector<double> x(block.X), v(x.size(), 0.), f(x.size(), 0.);
        for (unsigned int n = 0; n < block.n_nodes(); ++n)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              x[3 * n + i] += A[i][j] * block.X[3 * n + j];
        group.compute_internal_forces(x.data(), v.data(), 0., f.data());

        double worst = 0;
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
            for (unsigned int k = 0; k < 6; ++k)
              worst = std::max(worst, std::abs(group.stress(e, q)[k] - S_exact[k]) / s_scale);
        check_below("largest stress deviation from C:E(exact), relative", worst, 1e-12);

        // Interior node 13: all forces of a constant stress cancel.
        const double f_scale = s_scale * 0.25; // stress times a face area
        const double f13     = std::sqrt(f[39] * f[39] + f[40] * f[40] + f[41] * f[41]) / f_scale;
        check_below("interior node force / (stress x face area)", f13, 1e-12);
      }

  // Updated Lagrangian: a velocity field linear in the current coordinates
  // gives the same deformation rate, and so the same stress, everywhere.
  for (const auto integration : {Element::Integration::one_point, Element::Integration::full})
    {
      std::printf("== distorted mesh, %s integration, updated Lagrangian\n",
                  Element::to_string(integration).c_str());
      test::Block block(2, 2, 2);
      distort(block, false);
      Element::ElementGroup group(material, Formulation::updated_lagrangian, integration,
                                  Element::HourglassType::viscous, 0.1);
      block.make_elements(group);
      const double        B[3][3] = {{0.3, 0.1, 0.0}, {0.1, -0.2, 0.05}, {0.0, 0.05, 0.1}}; // symmetric
      const double        dt      = 1e-3;
      std::vector<double> x(block.X), v(x.size()), f(x.size(), 0.);
      for (unsigned int n = 0; n < block.n_nodes(); ++n)
        for (unsigned int i = 0; i < 3; ++i)
          v[3 * n + i] = B[i][0] * x[3 * n] + B[i][1] * x[3 * n + 1] + B[i][2] * x[3 * n + 2];
      group.compute_internal_forces(x.data(), v.data(), dt, f.data());
      // Closed form: the mid-step configuration is (I - dt B / 2) x, so
      // L = B (I - dt B / 2)^{-1}, symmetric for symmetric B: D = L, W = 0.
      double M[3][3], Mi[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          M[i][j] = (i == j) - 0.5 * dt * B[i][j];
      const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                         M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                         M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          {
            const unsigned int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            Mi[i][j] = (M[i1][j1] * M[i2][j2] - M[i1][j2] * M[i2][j1]) / det;
          }
      double L[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          L[i][j] = B[i][0] * Mi[0][j] + B[i][1] * Mi[1][j] + B[i][2] * Mi[2][j];
      const double D[6] = {L[0][0], L[1][1], L[2][2], L[0][1], L[1][2], L[0][2]};
      double       sigma[6] = {};
      material.update_cauchy_stress(D, dt, sigma, nullptr);
      const double scale = std::abs(sigma[0]) + std::abs(sigma[1]) + std::abs(sigma[2]);
      double       worst = 0;
      for (unsigned int e = 0; e < group.n_elements(); ++e)
        for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
          for (unsigned int k = 0; k < 6; ++k)
            worst = std::max(worst, std::abs(group.stress(e, q)[k] - sigma[k]) / scale);
      check_below("largest Cauchy stress deviation from the closed form, relative", worst, 1e-12);
    }

  // Reference path: deal.II's FEValues on the same distorted element, for
  // a non-affine nodal displacement, at the 2x2x2 Gauss points.
  {
    std::printf("== kernel against FEValues, one distorted element, random displacement\n");
    using namespace dealii;
    test::Block block(1, 1, 1);
    const double moves[8][3] = {{0.05, 0.02, -0.03}, {-0.04, 0.03, 0.02}, {0.02, -0.05, 0.04}, {0.03, 0.04, -0.02},
                                {-0.02, 0.01, 0.05}, {0.04, -0.03, 0.01}, {-0.03, 0.02, -0.04}, {0.01, 0.05, 0.03}};
    for (unsigned int n = 0; n < 8; ++n)
      for (unsigned int d = 0; d < 3; ++d)
        block.X[3 * n + d] += moves[n][d];
    const double u[8][3] = {{0.011, -0.02, 0.03}, {0.04, 0.01, -0.02}, {-0.03, 0.02, 0.01}, {0.02, 0.05, -0.01},
                            {0.01, -0.04, 0.02}, {-0.02, 0.03, 0.04}, {0.03, -0.01, -0.03}, {0.05, 0.02, 0.01}};
    Element::ElementGroup group(material, Formulation::total_lagrangian, Element::Integration::full,
                                Element::HourglassType::none, 0.);
    block.make_elements(group);
    std::vector<double> x(block.X), v(24, 0.), f(24, 0.);
    for (unsigned int n = 0; n < 8; ++n)
      for (unsigned int d = 0; d < 3; ++d)
        x[3 * n + d] += u[n][d];
    group.compute_internal_forces(x.data(), v.data(), 0., f.data());

    Triangulation<3>         tria;
    std::vector<Point<3>>    vertices(8);
    for (unsigned int n = 0; n < 8; ++n)
      vertices[n] = Point<3>(block.X[3 * n], block.X[3 * n + 1], block.X[3 * n + 2]);
    std::vector<CellData<3>> cells(1);
    for (unsigned int n = 0; n < 8; ++n)
      cells[0].vertices[n] = n;
    tria.create_triangulation(vertices, cells, SubCellData());
    FESystem<3>   fe(FE_Q<3>(1), 3);
    DoFHandler<3> dh(tria);
    dh.distribute_dofs(fe);
    Vector<double> disp(dh.n_dofs());
    const auto     cell = dh.begin_active();
    for (unsigned int n = 0; n < 8; ++n)
      for (unsigned int d = 0; d < 3; ++d)
        disp[cell->vertex_dof_index(n, d)] = u[n][d];
    QGauss<3>   quadrature(2);
    FEValues<3> fe_values(fe, quadrature, update_gradients);
    fe_values.reinit(cell);
    std::vector<Tensor<2, 3>> grad(quadrature.size());
    fe_values[FEValuesExtractors::Vector(0)].get_function_gradients(disp, grad);
    double worst = 0, scale = 0;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad[q];
        const Tensor<2, 3> C = transpose(F) * F;
        const double       E[6] = {0.5 * (C[0][0] - 1), 0.5 * (C[1][1] - 1), 0.5 * (C[2][2] - 1),
                                   0.5 * C[0][1], 0.5 * C[1][2], 0.5 * C[0][2]};
        double S[6];
        material.compute_pk2_stress(nullptr, E, S, nullptr);
        for (unsigned int k = 0; k < 6; ++k)
          {
            worst = std::max(worst, std::abs(S[k] - group.stress(0, q)[k]));
            scale = std::max(scale, std::abs(S[k]));
          }
      }
    check_below("largest stress difference kernel - FEValues, relative", worst / scale, 1e-12);
  }
  return test::finish();
}
