/**
 * Element throughput of the explicit step on one core.
 *
 * A block of n^3 hexahedra (default n = 47: 103823 elements), elastic,
 * updated Lagrangian, in a smooth non-uniform velocity field. One cycle is
 * the whole explicit step: zeroing forces, the element loop (stress update,
 * internal and hourglass forces, stable time step) and the central
 * difference update of all nodes. Prints nanoseconds per element-cycle for
 * one-point integration with viscous hourglass control (and the same through
 * the element-by-element reference loop) and for full integration, for
 * plastic steel, for cracking concrete and for concrete below cracking, the
 * solver state per element and the peak memory per element. Speed-ups are
 * ratios within one run (these machines differ by 30 % between runs).
 *
 * Usage: element_throughput [n] [cycles] [one-point | materials | CASE]
 * (one-point: the one-point elastic step and the reference loop alone,
 * three times in turn, then the same with the bulk viscosity every scene
 * has by default, for A/B comparisons of builds; materials: the
 * elastic step and each material's ratio to it, five times in turn, and
 * the ratios of the fastest runs; CASE: one of elastic, steel-elastic,
 * steel-yielding, steel-yielding-rate (Cowper-Symonds), concrete-elastic,
 * concrete-cracking, jc-elastic, jc-yielding, jc-flowing (steady flow),
 * jc-yielding-total, jc-flowing-total (Rate form = total, LS-DYNA's VP =
 * 0), jc-yielding-total-1, jc-flowing-total-1 (the same with 'Return
 * iterations = 1'), elastic-bulk
 * (with bulk viscosity), full, full-bulk (full integration, elastic)
 * alone, for profiling)
 */
#include <anvil/element/element_group.h>
#include <anvil/material_model/concrete_damaged_plasticity.h>
#include <anvil/material_model/elastic.h>
#include <anvil/material_model/johnson_cook.h>
#include <anvil/material_model/plastic_kinematic.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace anvil;

namespace
{
  struct Result
  {
    double ns_per_element_cycle;
    double state_bytes_per_element;
  };

  Result run(const unsigned int             n,
             const unsigned int             cycles,
             const Element::Integration     integration,
             const Element::HourglassType   hourglass = Element::HourglassType::viscous,
             const Formulation              formulation = Formulation::updated_lagrangian,
             const bool                     steel       = false,
             const bool                     rate        = false,
             const bool                     concrete    = false,
             const double                   velocity_scale = 1.,
             const bool                     reference   = false,
             const double                   steel_yield = 1e5,
             const bool                     johnson_cook = false,
             const bool                     total_rate   = false,
             const bool                     bulk_viscosity = false,
             const unsigned int             warm_up = 3,
             const bool                     driven  = false,
             const unsigned int             jc_iterations = 0)
  {
    // Elastic, or the seed's Table 1 steel with a yield stress low enough
    // that the block flows plastically from the first cycles.
    MaterialModel::Elastic          elastic;
    MaterialModel::PlasticKinematic plastic;
    elastic.set(7850., 2.06e11, 0.3);
    MaterialModel::PlasticKinematicLaw law;
    law.sigma_0         = steel_yield;
    law.plastic_modulus = 206e9 * 1.2e9 / (206e9 - 1.2e9);
    if (rate)
      law.set_cowper_symonds(40, 5);
    plastic.set(7850., 2.06e11, 0.3, law, false);
    // Concrete: the seed's column concrete (f'c = 45.4 MPa, MC2010 curves);
    // the velocity field (strain rates ~10 1/s) passes f_t / E after about
    // ten cycles, so most timed cycles run the return mappings.
    MaterialModel::ConcreteDamagedPlasticity          concrete_model;
    MaterialModel::ConcreteDamagedPlasticity::Parameters cp;
    cp.curves = MaterialModel::ConcreteCurves::model_code_2010(45.4e6);
    // Rate effects where asked (the seed's column has them: the rate
    // filter at every point, two pow per inelastic one).
    cp.rate_effects  = rate;
    cp.cube_strength = 45.4e6 / 0.8;
    concrete_model.set(cp);
    // Johnson-Cook: the 42CrMo4 of the DynELA Taylor deck (rate term,
    // thermal softening, adiabatic heating), its A replaced by steel_yield.
    MaterialModel::JohnsonCook    jc_model;
    MaterialModel::JohnsonCookLaw jc;
    jc.A = steel_yield, jc.B = 614e6, jc.n = 0.168, jc.C = 0.0089, jc.reference_rate = 1.;
    jc.m = 1.1, jc.melting_temperature = 1540., jc.transition_temperature = 20.;
    jc.specific_heat = 460., jc.heat_fraction = 0.9;
    jc.total_rate = total_rate; // LS-DYNA's VP = 0 (keyword decks' default)
    jc.max_iterations = jc_iterations; // 0: the return to its tolerance
    jc_model.set(7830., 2.06e11, 0.3, jc, 20., false);
    const MaterialModel::Interface &material =
      johnson_cook ? static_cast<const MaterialModel::Interface &>(jc_model) :
      concrete ? static_cast<const MaterialModel::Interface &>(concrete_model) :
      steel    ? static_cast<const MaterialModel::Interface &>(plastic) :
                 static_cast<const MaterialModel::Interface &>(elastic);
    Element::ElementGroup group(material, formulation, integration, hourglass, 0.1);
    if (bulk_viscosity)
      group.set_bulk_viscosity(0.06, 1.2); // every scene's default (ABAQUS/Explicit's)
    const unsigned int    nn = n + 1;
    const double          h  = 1e-2;
    std::vector<double>   x(3 * nn * nn * nn), v(x.size()), f(x.size()), m(x.size(), 0.);
    for (unsigned int k = 0; k < nn; ++k)
      for (unsigned int j = 0; j < nn; ++j)
        for (unsigned int i = 0; i < nn; ++i)
          {
            const unsigned int id = i + nn * (j + nn * k);
            x[3 * id]             = i * h;
            x[3 * id + 1]         = j * h;
            x[3 * id + 2]         = k * h;
            // A smooth velocity field with shear and stretch.
            v[3 * id]     = velocity_scale * (1.0 * std::sin(0.1 * j) + 0.5 * std::cos(0.07 * k));
            v[3 * id + 1] = velocity_scale * 0.3 * std::sin(0.05 * i);
            v[3 * id + 2] = velocity_scale * 0.2 * std::cos(0.11 * j);
          }
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          {
            std::array<unsigned int, 8> node;
            double                      X[8][3], me[8];
            for (unsigned int c = 0; c < 8; ++c)
              {
                const unsigned int id = (i + (c & 1)) + nn * ((j + ((c >> 1) & 1)) + nn * (k + ((c >> 2) & 1)));
                node[c]               = 3 * id;
                for (unsigned int d = 0; d < 3; ++d)
                  X[c][d] = x[3 * id + d];
              }
            group.add_element(node, X, group.n_elements());
            Element::lumped_mass(X, material.density(), me);
            for (unsigned int c = 0; c < 8; ++c)
              for (unsigned int d = 0; d < 3; ++d)
                m[node[c] + d] += me[c];
          }
    group.finalize();
    // Driven: the velocity field is held and the block deforms at its
    // constant rate (the forces' response still computed, into a vector of
    // its own, so that a cycle does the same work as a free one).
    std::vector<double> response(driven ? v.size() : 0);

    double       dt    = 0.;
    const auto   cycle = [&]() {
      std::fill(f.begin(), f.end(), 0.);
      const auto r = reference ? group.compute_internal_forces_reference(x.data(), v.data(), dt, f.data()) :
                                 group.compute_internal_forces(x.data(), v.data(), dt, f.data());
      dt           = 0.9 * r.critical_time_step;
      if (driven)
        for (std::size_t i = 0; i < x.size(); ++i)
          {
            response[i] += dt * f[i] / m[i];
            x[i] += dt * v[i];
          }
      else
        for (std::size_t i = 0; i < x.size(); ++i)
          {
            v[i] += dt * f[i] / m[i];
            x[i] += dt * v[i];
          }
    };
    for (unsigned int c = 0; c < warm_up; ++c) // warm up (and, for a flowing state, load)
      cycle();
    const auto jc_before = jc_model.return_counts();
    const auto start     = std::chrono::steady_clock::now();
    for (unsigned int c = 0; c < cycles; ++c)
      cycle();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (concrete && concrete_model.n_lubliner_returns() > 0)
      std::printf("  (concrete: %.2f evaluations of F per return to Lubliner's surface, %lu returns, "
                  "%.1f %% of the point updates)\n",
                  double(concrete_model.n_lubliner_evaluations()) / concrete_model.n_lubliner_returns(),
                  concrete_model.n_lubliner_returns(),
                  100. * concrete_model.n_lubliner_returns() / (double(cycles + warm_up) * group.n_elements()));
    if (johnson_cook)
      {
        // The state the timed cycles ended in: the points that flowed in
        // the last cycle (history 4, the plastic rate, is 0 where a point
        // stayed elastic), the medians of their plastic strain (history 0)
        // and of the last increment over it.
        std::vector<double> eps, ratio;
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          if (const double rate = group.history_variable(e, 0, 4); rate > 0)
            {
              eps.push_back(group.history_variable(e, 0, 0));
              ratio.push_back(rate * dt / eps.back());
            }
        const auto median = [](std::vector<double> &a) {
          if (a.empty())
            return 0.;
          std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
          return a[a.size() / 2];
        };
        const auto  &after = jc_model.return_counts();
        const double packs = std::max(1., double(after.packs - jc_before.packs));
        std::printf("  (Johnson-Cook: %.1f %% of the points flowed in the last cycle; their plastic strain, "
                    "median %.2e; its last increment / it, median %.2e; a returning pack of lanes evaluated "
                    "the flow stress's functions %.2f times, the thermal factor's %.2f times)\n",
                    100. * eps.size() / group.n_elements(), median(eps), median(ratio),
                    (after.flow_stress_functions - jc_before.flow_stress_functions) / packs,
                    (after.thermal_functions - jc_before.thermal_functions) / packs);
      }
    const double nodal   = 4. * x.size() * sizeof(double) / group.n_elements(); // x, v, f, m
    return {1e9 * seconds / (double(cycles) * group.n_elements()), group.memory_per_element() + nodal};
  }
} // namespace

int main(int argc, char **argv)
{
  // n and cycles: whole numbers, n from 2 to 200 (200^3 elements take
  // about 2 GB), cycles from 1 to 100,000.
  const auto whole = [&](const int k, const long low, const long high, const long fallback) {
    if (argc <= k)
      return fallback;
    char      *end   = nullptr;
    const long value = std::strtol(argv[k], &end, 10);
    if (end == argv[k] || *end != '\0' || value < low || value > high)
      {
        std::fprintf(stderr,
                     "element_throughput: argument %d '%s' must be a whole number from %ld to %ld "
                     "(usage: element_throughput [n] [cycles] [one-point | materials | CASE])\n",
                     k, argv[k], low, high);
        std::exit(1);
      }
    return value;
  };
  const unsigned int n      = whole(1, 2, 200, 47);
  const unsigned int cycles = whole(2, 1, 100000, 40);
  std::printf("element_throughput: %u elements (%u^3), %u cycles, one core\n", n * n * n, n, cycles);
  run(n, cycles / 4 + 1, Element::Integration::one_point); // warm up the machine
  // The one-point elastic step through the element-by-element reference loop.
  const auto reference = [&](const bool bulk = false) {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 1., true, 1e5, false, false, bulk);
  };
  // The same step with the bulk viscosity every scene has by default.
  const auto with_bulk = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 1., false, 1e5, false, false, true);
  };
  if (argc > 3 && std::string(argv[3]) == "one-point")
    {
      // The one-point elastic step alone and through the reference loop,
      // three times in turn (A/B comparisons of the batched loop).
      for (unsigned int k = 0; k < 3; ++k)
        {
          const double b = run(n, cycles, Element::Integration::one_point).ns_per_element_cycle;
          const double r = reference().ns_per_element_cycle;
          std::printf("one-point: %.1f ns per element-cycle; reference loop: %.1f ns; one-point / reference: %.3f\n",
                      b, r, b / r);
        }
      for (unsigned int k = 0; k < 3; ++k)
        {
          const double b = with_bulk().ns_per_element_cycle;
          const double r = reference(true).ns_per_element_cycle;
          std::printf("with bulk viscosity: one-point %.1f ns per element-cycle; reference loop: %.1f ns; "
                      "one-point / reference: %.3f\n",
                      b, r, b / r);
        }
      return 0;
    }
  // Each material against the elastic step, in turn (A/B comparisons of
  // the material updates).
  const auto steel_yielding = [&](const bool rate) {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, true, rate);
  };
  // Steel below yield (the seed's 235 MPa), with rate effects: most of a
  // structure's steel at any time.
  const auto steel_elastic = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, true, true, false, 0.2, false, 2.35e8);
  };
  const auto concrete_cracking = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, true);
  };
  // Concrete loaded below cracking (the velocity field / 50: strains below
  // 3e-5 by the last cycle, f_t / E = 1e-4), with rate effects: most of a
  // structure's concrete at any time.
  const auto concrete_elastic = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, true, true, 0.02);
  };
  // Johnson-Cook below its yield stress (A = 806 MPa) and flowing from the
  // first cycles (A = 0.1 MPa, the hardening B eps_p^n of the deck).
  const auto jc_elastic = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 0.2, false, 8.06e8, true);
  };
  const auto jc_yielding = [&]() {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 1., false, 1e5, true);
  };
  // Johnson-Cook in steady plastic flow (the deck's A = 806 MPa): the
  // velocity field held (ten times the one above, rates up to about 100
  // 1/s) for 100 loading cycles before the timed ones, so that the points
  // flow at plastic strains of 1e-4 to 1e-2, each step's increment a few
  // per cent of the strain or less, as behind a Taylor bar's foot.
  // (total: 'Rate form = total'; iterations: 'Return iterations', the
  // return's cap, which needs it; 0: none.)
  const auto jc_flowing = [&](const bool total = false, const unsigned int iterations = 0) {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 10., false, 8.06e8, true, total, false, 100,
               true, iterations);
  };
  const auto jc_yielding_total = [&](const unsigned int iterations = 0) {
    return run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
               Formulation::updated_lagrangian, false, false, false, 1., false, 1e5, true, true, false, 3, false,
               iterations);
  };
  // One case alone, for profiling (perf record) the material updates.
  if (argc > 3 && std::string(argv[3]) != "materials")
    {
      const std::string name = argv[3];
      const Result      r    = name == "steel-elastic"     ? steel_elastic() :
                               name == "steel-yielding"    ? steel_yielding(false) :
                               name == "steel-yielding-rate" ? steel_yielding(true) :
                               name == "concrete-elastic"  ? concrete_elastic() :
                               name == "concrete-cracking" ? concrete_cracking() :
                               name == "jc-elastic"        ? jc_elastic() :
                               name == "jc-yielding"       ? jc_yielding() :
                               name == "jc-flowing"        ? jc_flowing() :
                               name == "jc-flowing-total"  ? jc_flowing(true) :
                               name == "jc-flowing-total-1" ? jc_flowing(true, 1) :
                               name == "jc-yielding-total" ? jc_yielding_total() :
                               name == "jc-yielding-total-1" ? jc_yielding_total(1) :
                               name == "elastic" ? run(n, cycles, Element::Integration::one_point) :
                               name == "elastic-bulk" ? with_bulk() :
                               name == "full" ? run(n, cycles, Element::Integration::full) :
                               name == "full-bulk" ?
                                                   run(n, cycles, Element::Integration::full,
                                                       Element::HourglassType::viscous, Formulation::updated_lagrangian,
                                                       false, false, false, 1., false, 1e5, false, false, true) :
                                                   Result{-1., 0.};
      if (r.ns_per_element_cycle < 0)
        {
          std::fprintf(stderr,
                       "element_throughput: unknown case '%s' (allowed: one-point, materials, "
                       "elastic, steel-elastic, steel-yielding, steel-yielding-rate, concrete-elastic, "
                       "concrete-cracking, jc-elastic, jc-yielding, jc-flowing, jc-yielding-total, "
                       "jc-yielding-total-1, jc-flowing-total, jc-flowing-total-1, elastic-bulk, full, full-bulk)\n",
                       name.c_str());
          return 1;
        }
      std::printf("%s: %.1f ns per element-cycle\n", name.c_str(), r.ns_per_element_cycle);
      return 0;
    }
  if (argc > 3 && std::string(argv[3]) == "materials")
    {
      // Each round runs every case once; the fastest of the rounds is the
      // figure least disturbed by other work on the machine. Beside it, the
      // median of the rounds' own ratios: each ratio compares cases run
      // seconds apart, so that a slow spell of the host moves both terms.
      constexpr unsigned int rounds = 5, n_cases = 12;
      const char *const      name[n_cases] = {"elastic",
                                              "steel elastic range",
                                              "steel yielding",
                                              "concrete elastic range",
                                              "concrete cracking",
                                              "Johnson-Cook elastic range",
                                              "Johnson-Cook yielding",
                                              "Johnson-Cook flowing",
                                              "Johnson-Cook yielding, total rate",
                                              "Johnson-Cook yielding, total rate, one step",
                                              "Johnson-Cook flowing, total rate",
                                              "Johnson-Cook flowing, total rate, one step"};
      // One line: the elastic step's time, then each case over it.
      const auto print = [&](const char *what, const double (&t)[n_cases]) {
        std::printf("%selastic %.1f ns; / elastic:", what, t[0]);
        for (unsigned int c = 1; c < n_cases; ++c)
          std::printf("%s %s %.2f", c > 1 ? "," : "", name[c], t[c] / t[0]);
        std::printf("\n");
      };
      double              best[n_cases];
      std::vector<double> ratios[n_cases];
      std::fill(std::begin(best), std::end(best), 1e300);
      for (unsigned int k = 0; k < rounds; ++k)
        {
          const double t[n_cases] = {run(n, cycles, Element::Integration::one_point).ns_per_element_cycle,
                                     steel_elastic().ns_per_element_cycle,
                                     steel_yielding(false).ns_per_element_cycle,
                                     concrete_elastic().ns_per_element_cycle,
                                     concrete_cracking().ns_per_element_cycle,
                                     jc_elastic().ns_per_element_cycle,
                                     jc_yielding().ns_per_element_cycle,
                                     jc_flowing().ns_per_element_cycle,
                                     jc_yielding_total().ns_per_element_cycle,
                                     jc_yielding_total(1).ns_per_element_cycle,
                                     jc_flowing(true).ns_per_element_cycle,
                                     jc_flowing(true, 1).ns_per_element_cycle};
          for (unsigned int c = 0; c < n_cases; ++c)
            {
              best[c] = std::min(best[c], t[c]);
              ratios[c].push_back(t[c] / t[0]);
            }
          print("", t);
        }
      print("fastest of 5: ", best);
      std::printf("median of the rounds' ratios (lowest-highest) / elastic:");
      for (unsigned int c = 1; c < n_cases; ++c)
        {
          std::sort(ratios[c].begin(), ratios[c].end());
          std::printf("%s %s %.2f (%.2f-%.2f)", c > 1 ? "," : "", name[c], ratios[c][rounds / 2],
                      ratios[c].front(), ratios[c].back());
        }
      std::printf("\n");
      return 0;
    }
  const Result one  = run(n, cycles, Element::Integration::one_point);
  const Result ref  = reference();
  const Result full = run(n, cycles / 4 + 1, Element::Integration::full);
  const Result none  = run(n, cycles, Element::Integration::one_point, Element::HourglassType::none);
  const Result stiff = run(n, cycles, Element::Integration::one_point, Element::HourglassType::stiffness);
  const Result tl    = run(n, cycles, Element::Integration::one_point, Element::HourglassType::viscous,
                           Formulation::total_lagrangian);
  const Result pk          = steel_yielding(false);
  const Result pkr         = steel_yielding(true);
  const Result cdp         = concrete_cracking();
  const Result cdp_elastic = concrete_elastic();
  const Result pk_elastic  = steel_elastic();
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  const double peak = usage.ru_maxrss * 1024.;
  std::printf("one-point: %.1f ns per element-cycle (updated Lagrangian, elastic, viscous hourglass)\n",
              one.ns_per_element_cycle);
  std::printf("reference loop (element by element, scalar): %.1f ns per element-cycle; one-point / "
              "reference: %.2f\n",
              ref.ns_per_element_cycle, one.ns_per_element_cycle / ref.ns_per_element_cycle);
  std::printf("full: %.1f ns per element-cycle (updated Lagrangian, elastic, 2x2x2 Gauss)\n",
              full.ns_per_element_cycle);
  std::printf("full / one-point: %.2f\n", full.ns_per_element_cycle / one.ns_per_element_cycle);
  std::printf("one-point without hourglass control: %.1f ns; stiffness hourglass control: %.1f ns; "
              "total Lagrangian (viscous): %.1f ns per element-cycle\n",
              none.ns_per_element_cycle, stiff.ns_per_element_cycle, tl.ns_per_element_cycle);
  std::printf("one-point, plastic-kinematic steel (yielding): %.1f ns per element-cycle; with "
              "Cowper-Symonds rate effects: %.1f ns; steel / elastic: %.2f\n",
              pk.ns_per_element_cycle, pkr.ns_per_element_cycle,
              pk.ns_per_element_cycle / one.ns_per_element_cycle);
  std::printf("steel elastic range: %.1f ns per element-cycle (below yield, rate effects on); "
              "steel elastic range / elastic: %.2f\n",
              pk_elastic.ns_per_element_cycle, pk_elastic.ns_per_element_cycle / one.ns_per_element_cycle);
  std::printf("one-point, concrete damaged plasticity (cracking): %.1f ns per element-cycle; "
              "concrete / elastic: %.2f; state %.0f bytes per element\n",
              cdp.ns_per_element_cycle, cdp.ns_per_element_cycle / one.ns_per_element_cycle,
              cdp.state_bytes_per_element);
  std::printf("concrete elastic range: %.1f ns per element-cycle (below cracking, rate effects on); "
              "concrete elastic range / elastic: %.2f\n",
              cdp_elastic.ns_per_element_cycle, cdp_elastic.ns_per_element_cycle / one.ns_per_element_cycle);
  std::printf("memory: %.0f bytes per element (one-point solver state incl. nodal vectors; full: %.0f)\n",
              one.state_bytes_per_element, full.state_bytes_per_element);
  std::printf("peak resident memory: %.0f bytes per element (process peak / elements, largest run)\n",
              peak / (n * n * n));
  return 0;
}
