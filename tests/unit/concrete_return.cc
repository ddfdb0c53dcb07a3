/**
 * The return to Lubliner's surface (concrete damaged plasticity, f'c =
 * 45.4 MPa, MC2010 curves, h = 50 mm), driven along four strain paths past
 * their peaks: uniaxial and biaxial compression into softening, shear
 * under compression, and tension into cracking, updated Lagrangian form
 * called as the element loop does. (The paths keep the principal values
 * apart: at a double eigenvalue the test's own principal values are good
 * to sqrt(round-off) only, tests/unit/principal_values.)
 *
 * Checks:
 * - consistency: after every step the effective stress lies on or inside
 *   Lubliner's surface at the step's hardening variables, F <= 2 tol, tol
 *   the return's stop (1e-6 f'c)
 *   (F recomputed here from the history: principal values, cohesions from
 *   the curves), and on the compression paths, where no tension cut-off
 *   acts, a step that returned ends on the surface, |F| <= 2 tol;
 * - the Newton iteration on dlambda converges as Newton does: at most 3
 *   evaluations of F per return over all paths, 400 steps each (1.58
 *   measured; 2.0 with the stop at 1e-10 f'c; with the stress part of
 *   dF/ddlambda scaled by 0.7 on purpose, 7.22, and 13.7 at 1e-10 f'c: a
 *   wrong derivative makes the iteration linear, or leaves it to the
 *   bracket's secant and bisection);
 * - the batched update returns the points of a batch together, lane by
 *   lane: a point's stress and history do not depend on its lane or on the
 *   points beside it. The four paths run in one batch twice (lanes 0-3 and,
 *   reversed, 4-7) and each alone in a batch of points at rest; every
 *   lane's stress and history must agree bit for bit.
 */
#include <anvil/kinematics/tensor3.h>

#include "concrete_point.h"
#include "unit_test.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

using namespace anvil::MaterialModel;
using anvil::test::check_below;

int main()
{
  const auto                p = anvil::test::column_concrete();
  ConcreteDamagedPlasticity model;
  model.set(p);
  using M             = ConcreteDamagedPlasticity;
  const double h      = 0.05;
  const double fc     = p.curves.compressive_strength;
  const double tol    = M::return_tolerance * fc; // the return's own stop
  const double alpha  = model.get_alpha(), gamma = model.get_gamma();
  // Lubliner's F of the effective stress in the history, at its cohesions.
  auto yield = [&](const std::vector<double> &hist) {
    const double *s    = &hist[M::i_effective_stress];
    double        s1, s3;
    anvil::Kinematics::extreme_principal_values(s[0], s[1], s[2], s[3], s[4], s[5], s1, s3);
    const double mean = (s[0] + s[1] + s[2]) / 3.;
    const double a = s[0] - mean, b = s[1] - mean, c = s[2] - mean;
    const double q =
      std::sqrt(1.5 * (a * a + b * b + c * c) + 3. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
    const double ct   = model.tensile_cohesion(hist[M::i_kappa_t], hist[M::i_length],
                                             hist[M::i_strength_factor]);
    const double cc   = model.compressive_cohesion(hist[M::i_kappa_c], hist[M::i_length], hist[M::i_strength_factor]);
    const double beta = cc / ct * (1. - alpha) - (1. + alpha);
    return (q + 3. * alpha * mean + beta * std::max(s1, 0.) + gamma * std::min(s1, 0.)) /
             (1. - alpha) -
           cc;
  };

  struct Path
  {
    std::string name;
    double      D[6];
    double      strain; // largest strain component at the end
    bool        compression;
  };
  const Path paths[] = {
    {"uniaxial compression (lateral expansion 0.2 and 0.15)", {-1., 0.2, 0.15, 0., 0., 0.}, 6e-3, true},
    {"biaxial compression", {-1., -0.8, 0.3, 0., 0., 0.}, 6e-3, true},
    {"shear under compression", {-0.3, 0., 0., 1., 0., 0.}, 6e-3, true},
    {"uniaxial tension (lateral contraction 0.2)", {1., -0.2, -0.2, 0., 0., 0.}, 2e-3, false},
  };
  const unsigned long returns0 = model.n_lubliner_returns();
  const unsigned long evals0   = model.n_lubliner_evaluations();
  for (const Path &path : paths)
    {
      std::vector<double> history = anvil::test::fresh_history(model, h);
      const unsigned int n  = 400;
      const double       dt = 1e-6, rate = path.strain / (n * dt);
      double             D[6], stress[6] = {0, 0, 0, 0, 0, 0};
      for (unsigned int k = 0; k < 6; ++k)
        D[k] = rate * path.D[k];
      double worst = -1e300, worst_on_surface = 0;
      unsigned long returned_steps = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned long before = model.n_lubliner_returns();
          model.update_cauchy_stress(D, dt, stress, history.data());
          const double F = yield(history);
          worst          = std::max(worst, F);
          if (model.n_lubliner_returns() > before)
            {
              ++returned_steps;
              if (path.compression)
                worst_on_surface = std::max(worst_on_surface, std::abs(F));
            }
        }
      std::printf("== %s: %lu of %u steps returned, damage %.3f\n", path.name.c_str(),
                  returned_steps, n, history[M::i_damage]);
      check_below(path.name + ": largest F after a step / f'c (inside or on the surface)",
                  std::max(worst, 0.) / fc, 2. * tol / fc);
      if (path.compression)
        check_below(path.name + ": largest |F| after a return / f'c (on the surface)",
                    worst_on_surface / fc, 2. * tol / fc);
      check_below(path.name + ": -(steps that returned) (the path goes past the peak)",
                  -double(returned_steps), -50.);
    }
  const double per_return = double(model.n_lubliner_evaluations() - evals0) /
                            double(model.n_lubliner_returns() - returns0);
  std::printf("== %lu returns, %.2f evaluations of F each\n", model.n_lubliner_returns() - returns0,
              per_return);
  check_below("evaluations of F per return (Newton on dlambda)", per_return, 3.);

  // The batched update, 400 steps of the four paths (lane l runs path
  // lanes[l], -1: a point at rest).
  constexpr unsigned int W = M::batch_size;
  using Lanes              = std::array<int, W>;
  auto run_batch           = [&](const Lanes &lanes) {
    std::vector<std::vector<double>> history(W, anvil::test::fresh_history(model, h));
    std::vector<std::vector<double>> out(W);
    const unsigned int n = 400;
    const double       dt = 1e-6;
    double D[6][W], spin[3][W] = {}, stress[6][W] = {};
    for (unsigned int l = 0; l < W; ++l)
      for (unsigned int k = 0; k < 6; ++k)
        D[k][l] = lanes[l] < 0 ? 0. : paths[lanes[l]].strain / (n * dt) * paths[lanes[l]].D[k];
    M::BatchHistory batch;
    batch.n_hot      = model.n_hot_history(anvil::Formulation::updated_lagrangian);
    batch.n_cold     = model.n_history(anvil::Formulation::updated_lagrangian) - batch.n_hot;
    batch.hot_stride = 1;
    for (unsigned int l = 0; l < W; ++l)
      {
        batch.hot[l]  = history[l].data();
        batch.cold[l] = history[l].data() + batch.n_hot;
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        model.update_cauchy_stress_batch(D, spin, dt, stress, batch);
        for (unsigned int l = 0; l < W; ++l)
          {
            for (unsigned int k = 0; k < 6; ++k)
              out[l].push_back(stress[k][l]);
            out[l].insert(out[l].end(), history[l].begin(), history[l].end());
            // (An undamaged point's effective stress is its stress: the
            // stored one is valid once the point is damaged, see the
            // model's history layout.)
            if (history[l][M::i_tensile_damage] == 0 && history[l][M::i_compressive_damage] == 0)
              for (unsigned int k = 0; k < 6; ++k)
                out[l][out[l].size() - history[l].size() + M::i_effective_stress + k] =
                  stress[k][l];
          }
      }
    return out;
  };
  const auto together = run_batch(Lanes{{0, 1, 2, 3, 3, 2, 1, 0}});
  unsigned long differing = 0;
  for (int path = 0; path < 4; ++path)
    {
      Lanes alone;
      alone.fill(-1);
      alone[path] = path;
      const auto single = run_batch(alone);
      differing += together[path] != single[path];
      differing += together[path] != together[W - 1 - path];
    }
  std::printf("== batched: %zu values of each lane compared, 12 pairs of lanes\n",
              together[0].size());
  check_below("batched update: lanes that differ from the same point elsewhere (bit for bit)",
              double(differing), 0.);
  return anvil::test::finish();
}
