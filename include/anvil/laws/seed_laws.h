/**
 * @file
 * Constitutive laws of the seed's interfaces as named functions, called by
 * the contact and the bars and tested against their closed forms on their
 * own (tests/unit/seed_laws.cc).
 */
#pragma once

#include <cmath>

namespace anvil::Laws
{
  /**
   * Seed Eq. (62): the Coulomb coefficient at slip rate @p slip_rate,
   * mu = mu_d + (mu_s - mu_d) exp(-C |v|), decaying from the static
   * coefficient @p mu_s at rest to the dynamic one @p mu_d; @p decay is C
   * (s/m).
   */
  inline double friction_coefficient(const double mu_s, const double mu_d, const double decay,
                                     const double slip_rate)
  {
    return mu_d + (mu_s - mu_d) * std::exp(-decay * slip_rate);
  }

  /**
   * Seed Eq. (68), the bond between a bar and the concrete at one node:
   * elastic with modulus @p G (stress per unit slip) from the plastic slip
   * @p plastic_slip, within a strength tau_max exp(-h D) that softens
   * with the accumulated plastic slip @p damage (D); beyond it the slip
   * becomes plastic and D grows by it. Updates @p plastic_slip and
   * @p damage for the total slip @p slip; returns the bond stress.
   */
  inline double bond_stress(const double G, const double tau_max, const double h, const double slip,
                            double &plastic_slip, double &damage)
  {
    const double trial = G * (slip - plastic_slip);
    const double limit = tau_max * std::exp(-h * damage);
    double       tau   = trial;
    if (std::abs(trial) > limit)
      {
        tau              = trial > 0 ? limit : -limit;
        const double dsp = slip - plastic_slip - tau / G;
        plastic_slip += dsp;
        damage += std::abs(dsp);
      }
    return tau;
  }
} // namespace anvil::Laws
