/**
 * @file
 * The base of the rate-form (hypoelastic-plastic) models that build on the
 * elastic constants: their total Lagrangian form is the updated Lagrangian
 * update driven on the reference mesh (Interface::update_pk2_by_rate_form),
 * with the previous F - I (9 values) kept after the model's own history.
 */
#pragma once

#include <anvil/material_model/elastic.h>

namespace anvil::MaterialModel
{
  class RateFormElastic : public Elastic
  {
  public:
    /** History values per point of the updated Lagrangian form. */
    virtual unsigned int n_updated_lagrangian_history() const = 0;

    unsigned int n_history(const Formulation f) const override
    {
      return n_updated_lagrangian_history() + (f == Formulation::total_lagrangian ? 9 : 0);
    }

    void compute_pk2_stress(const double *F,
                            const double *,
                            double       *S,
                            double       *history) const override
    {
      update_pk2_by_rate_form(F, 0., S, history, n_updated_lagrangian_history());
    }

    void update_pk2_stress(const double *F,
                           const double *,
                           const double dt,
                           double      *S,
                           double      *history) const override
    {
      update_pk2_by_rate_form(F, dt, S, history, n_updated_lagrangian_history());
    }
  };
} // namespace anvil::MaterialModel
