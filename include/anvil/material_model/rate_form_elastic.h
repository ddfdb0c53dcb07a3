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

  protected:
    /** The elastic trial of the rate-form plastic models, sigma +=
        (lambda tr(D) I + 2 mu D) dt, of one point... */
    void add_elastic_trial(const double *D, const double dt, double *s) const
    {
      const double tr = D[0] + D[1] + D[2];
      for (unsigned int k = 0; k < 3; ++k)
        s[k] += (lambda * tr + 2. * mu * D[k]) * dt;
      for (unsigned int k = 3; k < 6; ++k)
        s[k] += 2. * mu * D[k] * dt;
    }

    /** ... and of lane @p l of a batch (the same arithmetic, so that the
        scalar and batched paths agree). */
    void add_elastic_trial(const double (&D)[6][batch_size], const double dt, double (&s)[6][batch_size],
                           const unsigned int l) const
    {
      const double tr = D[0][l] + D[1][l] + D[2][l];
      for (unsigned int k = 0; k < 3; ++k)
        s[k][l] += (lambda * tr + 2. * mu * D[k][l]) * dt;
      for (unsigned int k = 3; k < 6; ++k)
        s[k][l] += 2. * mu * D[k][l] * dt;
    }
  };
} // namespace anvil::MaterialModel
