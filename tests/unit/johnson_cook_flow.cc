/**
 * Johnson-Cook's batched return in long plastic flow against the point
 * by point update and against its own consistency condition.
 *
 * The batched return (vector registers) starts its iteration from the
 * point's stored state where it can: x^n by the binomial series about the
 * stored plastic strain, the thermal factor by the series about the stored
 * temperature, each where the step is a small part of what the point has
 * accumulated. The point-by-point update evaluates pow and log afresh at
 * every step. Eight lanes (the 42CrMo4 of the DynELA Taylor deck: rate
 * term, thermal softening, adiabatic heating) are driven at constant
 * deformation rates of 1,000 to 30,000 1/s in tension, compression, shear
 * and mixed states for 3,000 steps of 1e-8 s (plastic strains of 0.02 to
 * 0.9, heating by up to 300 K), one lane reversed half way (elastic unloading,
 * then yield in the other direction) and one at rest. Checked:
 * - batched against point by point at every step: stress (of the lane's
 *   largest), plastic strain (of its final value), temperature rise (of
 *   its final value), flow stress and thermal factor (relative);
 * - the consistency condition after every plastic step, q = (A + B
 *   eps_p^n)(1 + C ln(eps_p_dot / eps_0_dot)) theta, theta of the step's
 *   starting temperature, in long double: its residual over its slope in
 *   dep, of q / 3G (the return's own tolerance is 1e-12 of it);
 * - that each lane's results do not depend on the other lanes of its batch
 *   (each lane alone in a batch of points at rest gives the same bits: np =
 *   2 gives np = 1's results), for the seven paths and for 21 paths whose
 *   rates are modulated step by step;
 * - that the series carry the steady flow: evaluations of the functions per
 *   returning pack over the last 1,500 steps;
 * - the capped return ('Return iterations' 1-3) with the total strain
 *   rate's form: batched against point by point, and against the converged
 *   return (final plastic strain; stress from step 100 on, past the first
 *   yield's transient). The same caps with the plastic rate's form are
 *   printed: they stay far from the converged return, which is why the
 *   parameters refuse them.
 */
#include <anvil/material_model/johnson_cook.h>

#include "unit_test.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace anvil;
using test::check_below;

namespace
{
  using M                  = MaterialModel::JohnsonCook;
  constexpr unsigned int W = M::batch_size;
  constexpr unsigned int n_steps = 3000;
  constexpr double       dt      = 1e-8;

  /** Deformation rate of lane l at step i (Voigt, tensor shear). */
  std::array<double, 6> rate_of(const int lane, const unsigned int i)
  {
    std::array<double, 6> D{};
    // Lanes 100-120: the seven paths at 1, 0.37 and 2.9 times their rate,
    // each modulated by 1 + 0.5 sin(0.013 k i): increments that change
    // from step to step, so that lanes stop after different numbers of
    // Newton steps and leave the series' reach at different steps.
    if (lane >= 100)
      {
        const int    k     = lane - 100;
        const double scale = (k / 7) % 3 == 0 ? 1. : (k / 7) % 3 == 1 ? 0.37 : 2.9;
        D                  = rate_of(k % 7, i);
        for (double &d : D)
          d *= scale * (1. + 0.5 * std::sin(0.013 * (k + 1) * i));
        return D;
      }
    switch (lane)
      {
        case 0: // uniaxial tension, 3,000 1/s
          D = {{3e3, -1.5e3, -1.5e3, 0, 0, 0}};
          break;
        case 1: // uniaxial compression, 30,000 1/s
          D = {{-3e4, 1.5e4, 1.5e4, 0, 0, 0}};
          break;
        case 2: // simple shear, 1e4 1/s
          D = {{0, 0, 0, 5e3, 0, 0}};
          break;
        case 3: // tension with shear, reversed half way
          D = {{1e4, -5e3, -5e3, 0, 2e3, 0}};
          if (i >= n_steps / 2)
            for (double &d : D)
              d = -d;
          break;
        case 4: // biaxial compression with a volume change
          D = {{-8e3, -8e3, 1.5e4, 0, 0, 1e3}};
          break;
        case 5: // slow: 1,000 1/s (yields late)
          D = {{1e3, -500, -500, 0, 0, 0}};
          break;
        case 6: // shear in two planes, 2e4 1/s
          D = {{0, 0, 0, 0, 7e3, 7e3}};
          break;
        default: // at rest
          break;
      }
    return D;
  }

  struct Run
  {
    // Per lane, step after step: the 6 stresses and the 7 history values.
    std::vector<std::vector<double>> out;
    // The largest relative residual of the consistency condition.
    double residual = 0;
    unsigned long plastic_steps = 0;
  };

  /** W points' histories as the model initialises them, and the batch's
      view of them (which points into them: not to be copied). */
  struct Points
  {
    std::vector<std::vector<double>> history;
    M::BatchHistory                  batch;

    explicit Points(const M &model)
      : history(W, std::vector<double>(model.n_history(Formulation::updated_lagrangian), 0.))
    {
      for (auto &h : history)
        model.initialize_history(h.data(), MaterialModel::PointData());
      batch.n_hot      = model.n_hot_history(Formulation::updated_lagrangian);
      batch.n_cold     = history[0].size() - batch.n_hot;
      batch.hot_stride = 1;
      for (unsigned int l = 0; l < W; ++l)
        {
          batch.hot[l]  = history[l].data();
          batch.cold[l] = history[l].data() + batch.n_hot;
        }
    }
    Points(const Points &) = delete;
    Points &operator=(const Points &) = delete;
  };

  /** @p model with the DynELA deck's elasticity and initial temperature
      and the Johnson-Cook law @p law. */
  void set_deck_steel(M &model, const MaterialModel::JohnsonCookLaw &law)
  {
    model.set(7830., 2.06e11, 0.3, law, 20., false);
  }

  /** The lanes of @p lanes (-1: at rest) through the batched update. */
  Run run_batch(const M &model, const std::array<int, W> &lanes)
  {
    Points      points(model);
    auto       &history = points.history;
    const auto &batch   = points.batch;
    const auto &law     = model.get_law();
    Run         r;
    r.out.resize(W);
    double D[6][W], spin[3][W] = {}, s[6][W] = {};
    for (unsigned int i = 0; i < n_steps; ++i)
      {
        double theta[W], eps_before[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            const auto d = rate_of(lanes[l], i);
            for (unsigned int k = 0; k < 6; ++k)
              D[k][l] = d[k];
            theta[l]      = history[l][6];
            eps_before[l] = history[l][0];
          }
        model.update_cauchy_stress_batch(D, spin, dt, s, batch);
        for (unsigned int l = 0; l < W; ++l)
          {
            for (unsigned int k = 0; k < 6; ++k)
              r.out[l].push_back(s[k][l]);
            r.out[l].insert(r.out[l].end(), history[l].begin(), history[l].end());
            if (history[l][0] == eps_before[l])
              continue;
            // q after the return against the flow stress it must equal.
            ++r.plastic_steps;
            using LD      = long double;
            const LD p    = (LD(s[0][l]) + s[1][l] + s[2][l]) / 3;
            LD       dev2 = 0;
            for (unsigned int k = 0; k < 6; ++k)
              {
                const LD x = LD(s[k][l]) - (k < 3 ? p : 0);
                dev2 += (k < 3 ? 1 : 2) * x * x;
              }
            const LD q     = std::sqrt(1.5L * dev2);
            const LD eps   = history[l][0], dep = eps - LD(eps_before[l]);
            const LD ratio = LD(history[l][4]) / law.reference_rate;
            const LD H     = LD(law.A) + LD(law.B) * std::pow(eps, LD(law.n));
            const LD H1    = LD(law.n) * LD(law.B) * std::pow(eps, LD(law.n) - 1);
            const LD R     = ratio > 1 ? 1 + LD(law.C) * std::log(ratio) : LD(1);
            const LD R1    = ratio > 1 ? LD(law.C) / dep : LD(0);
            // The condition's residual as a distance in dep (its residual
            // over its slope, 3G + d(flow)/d(dep)), of q / 3G: the measure
            // of the return's tolerance. (Relative to the flow stress, it
            // is large where the point first yields: there d(B eps^n)/d eps
            // is near infinite.)
            const LD three_G = 3 * LD(2.06e11) / (2 * (1 + LD(0.3)));
            const LD g       = q - H * R * LD(theta[l]);
            const LD slope   = three_G + LD(theta[l]) * (H1 * R + H * R1);
            r.residual       = std::max(r.residual, double(std::abs(g) / slope / (q / three_G)));
          }
      }
    return r;
  }

  /** Lane @p lane alone through the point-by-point update. */
  std::vector<double> run_point(const M &model, const int lane)
  {
    std::vector<double> h(model.n_history(Formulation::updated_lagrangian), 0.), out;
    model.initialize_history(h.data(), MaterialModel::PointData());
    double s[6] = {};
    for (unsigned int i = 0; i < n_steps; ++i)
      {
        const auto d = rate_of(lane, i);
        model.update_cauchy_stress(d.data(), dt, s, h.data());
        out.insert(out.end(), s, s + 6);
        out.insert(out.end(), h.begin(), h.end());
      }
    return out;
  }
} // namespace

int main()
{
  // The DynELA Taylor deck's 42CrMo4 (its *Plastic, hardening=JOHNSON
  // COOK, *Rate Dependent and adiabatic heating).
  MaterialModel::JohnsonCookLaw law;
  law.A = 806e6, law.B = 614e6, law.n = 0.168, law.C = 0.0089, law.reference_rate = 1.;
  law.m = 1.1, law.melting_temperature = 1540., law.transition_temperature = 20.;
  law.specific_heat = 460., law.heat_fraction = 0.9;
  M model;
  set_deck_steel(model, law);

  const std::array<int, W> lanes = {{0, 1, 2, 3, 4, 5, 6, -1}};
  const Run                together = run_batch(model, lanes);
  const unsigned int       stride   = 6 + model.n_history(Formulation::updated_lagrangian);

  // Batched against point by point.
  double worst_stress = 0, worst_eps = 0, worst_T = 0, worst_flow = 0, worst_theta = 0;
  double final_eps_min = 1e300, final_eps_max = 0, rise_max = 0;
  for (unsigned int l = 0; l + 1 < W; ++l)
    {
      const auto  point = run_point(model, lanes[l]);
      const auto &batch = together.out[l];
      double      s_max = 0;
      for (unsigned int i = 0; i < n_steps; ++i)
        for (unsigned int k = 0; k < 6; ++k)
          s_max = std::max(s_max, std::abs(point[i * stride + k]));
      const double eps_end = point[(n_steps - 1) * stride + 6];
      const double rise    = point[(n_steps - 1) * stride + 6 + 2] - 20.;
      final_eps_min        = std::min(final_eps_min, eps_end);
      final_eps_max        = std::max(final_eps_max, eps_end);
      rise_max             = std::max(rise_max, rise);
      for (unsigned int i = 0; i < n_steps; ++i)
        {
          const double *a = &batch[i * stride], *b = &point[i * stride];
          for (unsigned int k = 0; k < 6; ++k)
            worst_stress = std::max(worst_stress, std::abs(a[k] - b[k]) / s_max);
          worst_eps   = std::max(worst_eps, std::abs(a[6] - b[6]) / eps_end);
          worst_T     = std::max(worst_T, std::abs(a[8] - b[8]) / rise);
          worst_flow  = std::max(worst_flow, std::abs(a[11] - b[11]) / b[11]);
          worst_theta = std::max(worst_theta, std::abs(a[12] - b[12]) / b[12]);
        }
    }
  std::printf("== 7 lanes in flow, 3,000 steps: final plastic strain %.3f to %.3f, heating up to %.1f K, "
              "%lu plastic point-steps\n",
              final_eps_min, final_eps_max, rise_max, together.plastic_steps);
  check_below("flow: -(smallest final plastic strain) (every lane flows)", -final_eps_min, -0.01);
  check_below("flow: -(largest heating) / K", -rise_max, -50.);
  check_below("batched against point by point: stress / the lane's largest", worst_stress, 1e-12);
  check_below("batched against point by point: plastic strain / its final value", worst_eps, 1e-12);
  check_below("batched against point by point: temperature / the lane's heating", worst_T, 1e-12);
  check_below("batched against point by point: flow stress (relative)", worst_flow, 1e-12);
  check_below("batched against point by point: thermal factor (relative)", worst_theta, 1e-12);
  check_below("consistency after each return: |q - flow stress| / slope, of q / 3G", together.residual, 1e-11);

  // Each lane alone in a batch of points at rest gives the same bits.
  unsigned long differing = 0;
  for (unsigned int l = 0; l + 1 < W; ++l)
    {
      std::array<int, W> alone;
      alone.fill(-1);
      alone[(l + 3) % W] = lanes[l];
      differing += run_batch(model, alone).out[(l + 3) % W] != together.out[l];
    }
  // The same for 21 modulated paths in three batches.
  for (int b = 0; b < 3; ++b)
    {
      std::array<int, W> batch;
      for (unsigned int l = 0; l < W; ++l)
        batch[l] = 8 * b + int(l) < 21 ? 100 + 8 * b + int(l) : -1;
      const Run mixed = run_batch(model, batch);
      for (unsigned int l = 0; l < W; ++l)
        if (batch[l] >= 0)
          {
            std::array<int, W> alone;
            alone.fill(-1);
            alone[(l + 5) % W] = batch[l];
            differing += run_batch(model, alone).out[(l + 5) % W] != mixed.out[l];
          }
    }
  check_below("lanes whose results depend on their batch-mates (7 paths, and 21 modulated ones)",
              double(differing), 0.);

  // The steady flow's cost: the second half of a run of the seven lanes.
  {
    // (The counts at half time and at the end of one run.)
    M m;
    set_deck_steel(m, law);
    Points         points(m);
    M::ReturnCounts first;
    double          D[6][W], spin[3][W] = {}, s[6][W] = {};
    for (unsigned int i = 0; i < n_steps; ++i)
      {
        if (i == n_steps / 2)
          first = m.return_counts();
        for (unsigned int l = 0; l < W; ++l)
          {
            // (Lane 3 not reversed: steady flow throughout.)
            const auto d = rate_of(lanes[l], std::min(i, n_steps / 2 - 1));
            for (unsigned int k = 0; k < 6; ++k)
              D[k][l] = d[k];
          }
        m.update_cauchy_stress_batch(D, spin, dt, s, points.batch);
      }
    const M::ReturnCounts &all = m.return_counts();
    const double packs     = double(all.packs - first.packs);
    const double functions = (all.flow_stress_functions - first.flow_stress_functions) / packs;
    const double thermal   = (all.thermal_functions - first.thermal_functions) / packs;
    std::printf("== steady flow, steps 1,500-3,000: %.0f returning packs, %.2f evaluations of the flow "
                "stress's functions and %.2f of the thermal factor's each\n",
                packs, functions, thermal);
    check_below("steady flow: evaluations of the flow stress's functions per pack (the logarithm at the "
                "first guess, then the series)",
                functions, 1.05);
    check_below("steady flow: evaluations of the thermal factor's functions per pack", thermal, 0.05);
  }

  // The capped return ('Return iterations' N > 0): the batched return
  // against the point-by-point one with the same cap, and each capped run
  // against the converged one (final plastic strain, and the stress over
  // the whole path, of the lane's largest), for both rate forms.
  for (const bool total : {false, true})
    {
      MaterialModel::JohnsonCookLaw exact_law = law;
      exact_law.total_rate                    = total;
      M exact;
      set_deck_steel(exact, exact_law);
      const Run reference = run_batch(exact, lanes);
      for (const unsigned int cap : {1u, 2u, 3u})
        {
          MaterialModel::JohnsonCookLaw capped_law = exact_law;
          capped_law.max_iterations                = cap;
          M capped;
          set_deck_steel(capped, capped_law);
          const Run r           = run_batch(capped, lanes);
          double    worst_point = 0, worst_eps_end = 0, worst_s = 0, worst_s100 = 0;
          for (unsigned int l = 0; l + 1 < W; ++l)
            {
              const auto point = run_point(capped, lanes[l]);
              double     s_max = 0;
              for (unsigned int i = 0; i < n_steps; ++i)
                for (unsigned int k = 0; k < 6; ++k)
                  s_max = std::max(s_max, std::abs(reference.out[l][i * stride + k]));
              for (unsigned int i = 0; i < n_steps; ++i)
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    const double v = r.out[l][i * stride + k];
                    const double e = std::abs(v - reference.out[l][i * stride + k]) / s_max;
                    worst_point    = std::max(worst_point, std::abs(v - point[i * stride + k]) / s_max);
                    worst_s        = std::max(worst_s, e);
                    if (i >= 100)
                      worst_s100 = std::max(worst_s100, e);
                  }
              const unsigned int end   = (n_steps - 1) * stride + 6; // the final plastic strain
              const double       e_ref = reference.out[l][end];
              worst_eps_end = std::max(worst_eps_end, std::abs(r.out[l][end] - e_ref) / e_ref);
            }
          std::printf("== rate form %s, at most %u Newton step(s): batched against point by point %.1e; against "
                      "the converged return: final plastic strain %.2e, stress %.2e, from step 100 on %.2e (of the "
                      "lane's largest)\n",
                      total ? "total" : "plastic", cap, worst_point, worst_eps_end, worst_s, worst_s100);
          if (!total)
            continue; // (refused by the parameters: printed as the reason)
          const std::string what = "total rate, at most " + std::to_string(cap) + " Newton step(s): ";
          check_below(what + "batched against point by point: stress / the lane's largest", worst_point, 1e-12);
          check_below(what + "final plastic strain against the converged return (relative)", worst_eps_end, 1e-6);
          check_below(what + "stress against the converged return from step 100 on / the lane's largest", worst_s100,
                      1e-4);
        }
    }
  return test::finish();
}
