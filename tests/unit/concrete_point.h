/**
 * @file
 * One material point of the seed's column concrete for the unit tests:
 * f'c = 45.4 MPa with the fib Model Code 2010 curves, every other entry at
 * its default (rate effects off), and a fresh point's history.
 */
#pragma once

#include <anvil/material_model/concrete_damaged_plasticity.h>

#include <vector>

namespace anvil::test
{
  /** The column concrete's parameters. */
  inline MaterialModel::ConcreteDamagedPlasticity::Parameters column_concrete()
  {
    MaterialModel::ConcreteDamagedPlasticity::Parameters p;
    p.curves = MaterialModel::ConcreteCurves::model_code_2010(45.4e6);
    return p;
  }

  /** The updated Lagrangian history of a fresh point of @p model in an
      element of characteristic length @p h (m). */
  inline std::vector<double> fresh_history(const MaterialModel::ConcreteDamagedPlasticity &model,
                                           const double                                   h)
  {
    std::vector<double> history(model.n_history(Formulation::updated_lagrangian), 0.);
    MaterialModel::PointData data;
    data.characteristic_length = h;
    model.initialize_history(history.data(), data);
    return history;
  }
} // namespace anvil::test
