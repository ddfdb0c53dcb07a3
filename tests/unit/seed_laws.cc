/**
 * The seed's interface laws as the contact and the bars call them, against
 * their closed forms.
 *
 * Eq. (62), friction: mu_s at rest, mu_d at high slip rate, and
 * mu_d + (mu_s - mu_d) / e at the slip rate 1 / C.
 *
 * Eq. (68), bond-slip at one node (G = 5e10 Pa/m, tau_max = 18 MPa,
 * h = 200 1/m):
 * - elastic below the strength: tau = G S;
 * - a monotonic slip ramp to S in small steps: the plastic slip D and the
 *   stress satisfy tau = tau_max exp(-h D) and S = D + tau / G (the
 *   fixed point, solved here by bisection), within the ramp's step;
 * - unloading from there follows G from the plastic slip (tau = G (S - D))
 *   and leaves D unchanged; reloading in the opposite sense yields at
 *   -tau_max exp(-h D).
 */
#include <anvil/laws/seed_laws.h>

#include "unit_test.h"

using namespace anvil;
using test::check;

int main()
{
  std::printf("== seed Eq. (62): friction decay\n");
  const double mu_s = 0.6, mu_d = 0.3, C = 2.5;
  check("mu at rest", Laws::friction_coefficient(mu_s, mu_d, C, 0.), mu_s, 1e-15);
  check("mu at 1e3 m/s", Laws::friction_coefficient(mu_s, mu_d, C, 1e3), mu_d, 1e-15);
  check("mu at the slip rate 1/C", Laws::friction_coefficient(mu_s, mu_d, C, 1. / C),
        mu_d + (mu_s - mu_d) / std::exp(1.), 1e-15);
  check("no decay (C = 0): mu_s at any rate", Laws::friction_coefficient(mu_s, mu_d, 0., 7.), mu_s, 1e-15);

  std::printf("== seed Eq. (68): bond-slip\n");
  const double G = 5e10, tau_max = 18e6, h = 200.;
  {
    double       sp = 0, D = 0;
    const double S  = 0.5 * tau_max / G;
    check("elastic: tau = G S [Pa]", Laws::bond_stress(G, tau_max, h, S, sp, D), G * S, 1e-6);
    check("elastic: no plastic slip", sp, 0., 0.);
  }
  {
    // A ramp to S_end in n steps.
    double       sp = 0, D = 0, tau = 0;
    const double S_end = 5e-3;
    const unsigned int n = 200000;
    for (unsigned int k = 1; k <= n; ++k)
      tau = Laws::bond_stress(G, tau_max, h, S_end * k / n, sp, D);
    // The fixed point S_end = D + tau_max exp(-h D) / G by bisection.
    double lo = 0, hi = S_end;
    for (int it = 0; it < 200; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        (mid + tau_max * std::exp(-h * mid) / G > S_end ? hi : lo) = mid;
      }
    const double D_exact = 0.5 * (lo + hi);
    check("ramp: accumulated plastic slip D [m]", D, D_exact, 2 * S_end / n);
    check("ramp: bond stress tau_max exp(-h D) [Pa]", tau, tau_max * std::exp(-h * D_exact),
          tau_max * h * 2 * S_end / n + 1e-6);
    check("ramp: plastic slip equals D (one sense)", sp, D, 1e-18);

    // Unloading by half the elastic slip: elastic from the plastic slip.
    const double D_before = D, S_un = S_end - 0.5 * tau / G;
    const double tau_un   = Laws::bond_stress(G, tau_max, h, S_un, sp, D);
    check("unloading: tau = G (S - S_p) [Pa]", tau_un, G * (S_un - sp), 1e-6);
    check("unloading: D unchanged", D, D_before, 0.);
    // Reverse loading: yields at the softened strength, in the other sense.
    const double tau_rev = Laws::bond_stress(G, tau_max, h, sp - 2 * tau_max / G, sp, D);
    check("reversal: tau = -tau_max exp(-h D_before) [Pa]", tau_rev, -tau_max * std::exp(-h * D_before),
          1e-6 * tau_max);
    check("reversal: D grows by the reverse plastic slip", D - D_before,
          (2 * tau_max - tau_max * std::exp(-h * D_before)) / G, 1e-12);
  }
  return test::finish();
}
