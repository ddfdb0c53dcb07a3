/**
 * @file
 * Von Mises plasticity with isotropic hardening along a tabulated flow
 * curve: LS-DYNA's *MAT_PIECEWISE_LINEAR_PLASTICITY (MAT_024) and ABAQUS's
 * *Plastic with a table of yield stress against plastic strain, the metal
 * models most decks bring.
 */
#pragma once

#include <anvil/material_model/rate_form_elastic.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace anvil::MaterialModel
{
  /**
   * The flow curve sigma_y(eps_p): straight between the points (eps_i,
   * sigma_i), eps_0 = 0, and beyond the last one either constant (ABAQUS)
   * or continued with the last segment's slope (LS-DYNA); a falling
   * continuation ends at 0, where the curve is given a last point (the
   * flow stress is never negative). Every slope exceeds -3G, so that the
   * return has one root.
   * The rate factor is Cowper-Symonds', 1 + (eps_dot / C)^(1/p), of the
   * effective plastic strain rate of the increment (ABAQUS's *Rate
   * Dependent, type=POWER LAW, and LS-DYNA's VP = 1), or 1.
   */
  struct FlowCurve
  {
    std::vector<double> strain, stress;
    /** Beyond the last point: the last segment's slope (false: constant). */
    bool   extrapolate = true;
    double C = 0, p = 1;
    bool   rate_effects = false;

    /** sigma_y at @p eps, and its slope in @p H. */
    double flow_stress(const double eps, double &H) const
    {
      if (strain.size() < 2 || (eps >= strain.back() && !extrapolate))
        {
          H = 0.;
          return stress.back();
        }
      // The segment holding eps (the last one beyond the table).
      const auto   k = std::min<std::size_t>(std::upper_bound(strain.begin(), strain.end(), eps) - strain.begin(),
                                           strain.size() - 1) - 1;
      H = (stress[k + 1] - stress[k]) / (strain[k + 1] - strain[k]);
      return stress[k] + H * (eps - strain[k]);
    }

    /** Where the piece of the curve holding @p eps ends (the next point;
        infinity beyond the last). */
    double piece_end(const double eps) const
    {
      const auto next = std::upper_bound(strain.begin(), strain.end(), eps);
      return next == strain.end() ? std::numeric_limits<double>::infinity() : *next;
    }

    double rate_factor(const double rate) const
    {
      return rate_effects && rate > 0 ? 1. + std::pow(rate / C, 1. / p) : 1.;
    }

    /** The effective plastic strain increment of the radial return from
        the trial effective stress @p q at plastic strain @p eps_p (0 when
        elastic): q - 3G d = sigma_y(eps_p + d), exact, segment by segment;
        with rate effects q - 3G d = R(d / dt) sigma_y(eps_p + d) by
        Newton's method in [0, the rate-free increment]. */
    double increment(double q, double eps_p, double dt, double three_G) const;
  };


  /**
   * The material: the rate-form (hypoelastic-plastic) update of ABAQUS and
   * LS-DYNA, as the plastic-kinematic model's with isotropic hardening
   * along FlowCurve (no back stress), and erosion at a failure plastic
   * strain. History per point: effective plastic strain, plastic work
   * density, effective plastic strain rate.
   */
  class PiecewiseLinearPlasticity : public RateFormElastic
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    /** Set the constants directly (unit tests). */
    void set(double density, double youngs_modulus, double poissons_ratio, const FlowCurve &curve,
             double failure_strain);

    unsigned int n_updated_lagrangian_history() const override
    {
      return 3;
    }
    std::vector<std::string> history_names() const override
    {
      return {"effective_plastic_strain", "plastic_work_density", "effective_plastic_strain_rate"};
    }
    int dissipation_index() const override
    {
      return 1;
    }
    bool erodes() const override
    {
      return failure_strain > 0;
    }
    bool point_failed(const double *history) const override
    {
      return history[0] >= failure_strain;
    }
    bool rate_dependent() const override
    {
      return curve.rate_effects;
    }
    std::string rate_law() const override;

    void update_cauchy_stress(const double *D, double dt, double *stress, double *history) const override;

    /** Point by point (Interface's), not the elastic model's batch. */
    void update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                    const double (&spin)[3][batch_size],
                                    const double dt,
                                    double (&stress)[6][batch_size],
                                    const BatchHistory &history) const override
    {
      Interface::update_cauchy_stress_batch(D, spin, dt, stress, history);
    }

    const FlowCurve &get_curve() const
    {
      return curve;
    }

  private:
    FlowCurve curve;
    double    failure_strain = 0;
  };
} // namespace anvil::MaterialModel
