/**
 * The batched one-point kernel (the fast path) against the element-by-element
 * reference loop.
 *
 * 13 distorted elements (one full batch of 8 and a padded one of 5) in a
 * non-uniform velocity field, 50 steps with rotation and stretch, for each
 * hourglass control, and with bulk viscosity: stresses, nodal forces,
 * energies and the stable time step must agree to round-off (1e-12
 * relative). The same for full
 * integration, whose eight points the loop updates as one batch, against
 * the point-by-point update. Twice: elastic, and
 * plastic-kinematic steel that yields within the 50 steps (mixed hardening,
 * so the back stress rotates; rate effects on), which runs the per-point
 * batch update and the padded lanes' scratch history.
 *
 * Then concrete damaged plasticity (f'c = 45.4 MPa, rate effects, w_c = 1)
 * with the velocity reversed after 25 steps: elements crack and crush, then
 * unload inside their surfaces with damage, some with principal effective
 * stresses of both signs. That runs every branch of the concrete batch
 * (intact elastic, damaged elastic with one sign and with both, inelastic);
 * the test counts the damaged elastic steps of each kind so that it fails
 * if the scene stops reaching them. Its limit is 1e-10 (the return mapping
 * stops at |F| <= 1e-10 f'c).
 */
#include <anvil/kinematics/tensor3.h>
#include <anvil/material_model/concrete_damaged_plasticity.h>
#include <anvil/material_model/johnson_cook.h>
#include <anvil/material_model/piecewise_linear_plasticity.h>
#include <anvil/material_model/plastic_kinematic.h>

#include "unit_test.h"

using namespace anvil;
using test::check_below;

int main()
{
  MaterialModel::Elastic elastic;
  elastic.set(7850., 2e11, 0.3);
  MaterialModel::PlasticKinematic   plastic;
  MaterialModel::PlasticKinematicLaw law;
  law.sigma_0         = 1e7;
  law.plastic_modulus = 1e9;
  law.beta            = 0.5;
  law.set_cowper_symonds(40, 5);
  plastic.set(7850., 2e11, 0.3, law, false);
  MaterialModel::ConcreteDamagedPlasticity             concrete;
  MaterialModel::ConcreteDamagedPlasticity::Parameters cp;
  cp.curves        = MaterialModel::ConcreteCurves::model_code_2010(45.4e6);
  cp.rate_effects  = true;
  cp.cube_strength = 45.4e6 / 0.8;
  concrete.set(cp);
  // Johnson-Cook with every term acting: rate, heating, damage.
  MaterialModel::JohnsonCook    jc;
  MaterialModel::JohnsonCookLaw jl;
  jl.A                      = 1e7;
  jl.B                      = 5e8;
  jl.n                      = 0.3;
  jl.C                      = 0.02;
  jl.reference_rate         = 1;
  jl.m                      = 1.1;
  jl.melting_temperature    = 1800;
  jl.transition_temperature = 293;
  jl.specific_heat          = 0.46;
  jl.heat_fraction          = 0.9;
  jl.D[0]                   = 0.05;
  jl.D[1]                   = 3.4;
  jl.D[2]                   = -2.1;
  jl.D[3]                   = 0.002;
  jl.D[4]                   = 0.6;
  jc.set(7850., 2e11, 0.3, jl, 293, false);
  // LS-DYNA's VP = 0: the total strain rate's factor scales the yield stress.
  MaterialModel::JohnsonCook jc_total;
  jl.total_rate = true;
  jc_total.set(7850., 2e11, 0.3, jl, 293, false);
  // A tabulated flow curve that hardens, then softens, with rate effects.
  MaterialModel::PiecewiseLinearPlasticity tabulated;
  MaterialModel::FlowCurve                 curve;
  curve.strain       = {0., 1e-3, 1e-2};
  curve.stress       = {1e7, 2e7, 1.5e7};
  curve.C            = 40;
  curve.p            = 5;
  curve.rate_effects = true;
  tabulated.set(7850., 2e11, 0.3, curve, 0.);
  using C = MaterialModel::ConcreteDamagedPlasticity;
  for (const MaterialModel::Interface *m : {static_cast<const MaterialModel::Interface *>(&elastic),
                                            static_cast<const MaterialModel::Interface *>(&plastic),
                                            static_cast<const MaterialModel::Interface *>(&concrete),
                                            static_cast<const MaterialModel::Interface *>(&jc),
                                            static_cast<const MaterialModel::Interface *>(&jc_total),
                                            static_cast<const MaterialModel::Interface *>(&tabulated)})
  for (const int config : {0, 1, 2, 3, 4, 5})
    {
      // One point with each hourglass control; full integration (its
      // eight points as one batch against point by point); the last two
      // again with the bulk viscosity every scene has by default.
      const auto type = std::array<Element::HourglassType, 6>{
        {Element::HourglassType::none, Element::HourglassType::viscous, Element::HourglassType::stiffness,
         Element::HourglassType::none, Element::HourglassType::viscous, Element::HourglassType::none}}[config];
      const auto integration =
        (config == 3 || config == 5 ? Element::Integration::full : Element::Integration::one_point);
      const bool bulk = config >= 4;
      const auto &material = *m;
      std::printf("== %s, %s%s\n",
                  m == &elastic ? "elastic" : m == &plastic ? "plastic kinematic" :
                  m == &jc      ? "johnson cook" :
                  m == &jc_total ? "johnson cook, rate of the total strain" :
                  m == &tabulated ? "piecewise linear plasticity" : "concrete damaged plasticity",
                  integration == Element::Integration::full ? "full integration" :
                                (Element::to_string(type) + " hourglass control").c_str(),
                  bulk ? ", bulk viscosity" : "");
      test::Block block(13, 1, 1);
      for (unsigned int n = 0; n < block.n_nodes(); ++n)
        for (unsigned int d = 0; d < 3; ++d)
          block.X[3 * n + d] += 0.02 * std::sin(1.7 * n + 2.3 * d);
      Element::ElementGroup fast(material, Formulation::updated_lagrangian, integration, type, 0.1);
      Element::ElementGroup ref(material, Formulation::updated_lagrangian, integration, type, 0.1);
      if (bulk)
        {
          fast.set_bulk_viscosity(0.06, 1.2);
          ref.set_bulk_viscosity(0.06, 1.2);
        }
      block.make_elements(fast);
      block.make_elements(ref);
      std::vector<double> x(block.X), v(x.size());
      for (unsigned int n = 0; n < block.n_nodes(); ++n)
        for (unsigned int d = 0; d < 3; ++d)
          v[3 * n + d] = 3. * std::cos(0.9 * n + 1.1 * d) + (d == 1 ? 2. * x[3 * n] : 0.);
      double worst_f = 0, worst_s = 0, worst_e = 0, worst_dt = 0;
      const double dt = 1e-6;
      double e_fast = 0, e_ref = 0, h_fast = 0, h_ref = 0, q_fast = 0, q_ref = 0;
      unsigned int damaged_elastic = 0, damaged_elastic_mixed = 0;
      for (unsigned int step = 0; step < 50; ++step)
        {
          if (m == &concrete && step == 25)
            for (double &vi : v)
              vi = -vi;
          std::vector<double> kappa_before;
          if (m == &concrete)
            for (unsigned int e = 0; e < ref.n_elements(); ++e)
              for (const unsigned int k : {C::i_kappa_t, C::i_kappa_c})
                kappa_before.push_back(ref.history_variable(e, 0, k));
          std::vector<double> f1(x.size(), 0.), f2(x.size(), 0.);
          const auto r1 = fast.compute_internal_forces(x.data(), v.data(), step ? dt : 0., f1.data());
          const auto r2 = ref.compute_internal_forces_reference(x.data(), v.data(), step ? dt : 0., f2.data());
          double fmax = 0;
          for (unsigned int i = 0; i < x.size(); ++i)
            fmax = std::max(fmax, std::abs(f2[i]));
          for (unsigned int i = 0; i < x.size(); ++i)
            worst_f = std::max(worst_f, std::abs(f1[i] - f2[i]) / fmax);
          for (unsigned int e = 0; e < fast.n_elements(); ++e)
            {
              for (unsigned int q = 0; q < ref.n_quadrature_points(); ++q)
                {
                  double smax = 0;
                  for (unsigned int k = 0; k < 6; ++k)
                    smax = std::max(smax, std::abs(ref.stress(e, q)[k]));
                  for (unsigned int k = 0; k < 6; ++k)
                    worst_s = std::max(worst_s, std::abs(fast.stress(e, q)[k] - ref.stress(e, q)[k]) /
                                                  std::max(smax, 1e-300));
                }
            }
          worst_dt = std::max(worst_dt, std::abs(r1.critical_time_step - r2.critical_time_step) / r2.critical_time_step);
          if (m == &concrete)
            for (unsigned int e = 0; e < ref.n_elements(); ++e)
              {
                double h[MaterialModel::Interface::max_history];
                ref.copy_history(e, 0, h);
                if ((h[C::i_tensile_damage] > 0 || h[C::i_compressive_damage] > 0) &&
                    h[C::i_kappa_t] == kappa_before[2 * e] && h[C::i_kappa_c] == kappa_before[2 * e + 1])
                  {
                    ++damaged_elastic;
                    double s1, s3;
                    const double *sb = h + C::i_effective_stress;
                    Kinematics::extreme_principal_values(sb[0], sb[1], sb[2], sb[3], sb[4], sb[5], s1, s3);
                    damaged_elastic_mixed += (s1 > 0 && s3 < 0);
                  }
              }
          e_fast += r1.internal_energy_increment;
          e_ref += r2.internal_energy_increment;
          h_fast += r1.hourglass_energy_increment;
          h_ref += r2.hourglass_energy_increment;
          q_fast += r1.viscous_energy_increment;
          q_ref += r2.viscous_energy_increment;
          for (unsigned int i = 0; i < x.size(); ++i)
            x[i] += dt * v[i];
        }
      if (m == &tabulated)
        {
          double eps_p = 0, worst_h = 0;
          for (unsigned int e = 0; e < ref.n_elements(); ++e)
            {
              eps_p = std::max(eps_p, ref.history_variable(e, 0, 0));
              for (unsigned int k = 0; k < 3; ++k)
                worst_h = std::max(worst_h, std::abs(fast.history_variable(e, 0, k) - ref.history_variable(e, 0, k)) /
                                              (std::abs(ref.history_variable(e, 0, k)) + 1e-30));
            }
          check_below("the tabulated run yields past the curve's peak (1e-3): -(largest effective plastic strain)",
                      -eps_p, -1e-3);
          check_below("history variables, largest relative difference", worst_h, 1e-10);
        }
      if (m == &plastic)
        {
          double eps_p = 0;
          for (unsigned int e = 0; e < ref.n_elements(); ++e)
            eps_p = std::max(eps_p, ref.history_variable(e, 0, 6));
          check_below("the plastic run yields: -(largest effective plastic strain)", -eps_p, -1e-8);
          double worst_h = 0;
          for (unsigned int e = 0; e < ref.n_elements(); ++e)
            for (unsigned int k = 0; k < 9; ++k)
              worst_h = std::max(worst_h, std::abs(fast.history_variable(e, 0, k) - ref.history_variable(e, 0, k)) /
                                            (std::abs(ref.history_variable(e, 0, k)) + 1e-30 + (k < 6 ? 1e3 : 0.)));
          check_below("history variables, largest relative difference", worst_h, 1e-10);
        }
      if (m == &jc || m == &jc_total)
        {
          double eps_p = 0, T = 0;
          for (unsigned int e = 0; e < ref.n_elements(); ++e)
            {
              eps_p = std::max(eps_p, ref.history_variable(e, 0, 0));
              T     = std::max(T, ref.history_variable(e, 0, 2));
            }
          check_below("Johnson-Cook yields: -(largest effective plastic strain)", -eps_p, -1e-8);
          check_below("Johnson-Cook heats: -(largest temperature rise)", -(T - 293), -1e-8);
          // Each variable relative to its largest magnitude over the block.
          double worst_h = 0;
          for (unsigned int k = 0; k < jc.n_updated_lagrangian_history(); ++k)
            {
              double scale = 1e-300;
              for (unsigned int e = 0; e < ref.n_elements(); ++e)
                scale = std::max(scale, std::abs(ref.history_variable(e, 0, k)));
              for (unsigned int e = 0; e < ref.n_elements(); ++e)
                worst_h = std::max(worst_h, std::abs(fast.history_variable(e, 0, k) -
                                                     ref.history_variable(e, 0, k)) / scale);
            }
          // The batch's powers and logarithms are xsimd's (or their series
          // about a point of evaluation), the point's the C library's: an
          // ulp apart, and both returns end within 1e-12 of their bracket.
          check_below("history variables, largest difference / the variable's largest value", worst_h, 1e-12);
        }
      if (m == &concrete)
        {
          double kt = 0, kc = 0;
          for (unsigned int e = 0; e < ref.n_elements(); ++e)
            {
              kt = std::max(kt, ref.history_variable(e, 0, C::i_kappa_t));
              kc = std::max(kc, ref.history_variable(e, 0, C::i_kappa_c));
            }
          check_below("the concrete cracks: -(largest tensile plastic strain)", -kt, -1e-8);
          check_below("the concrete crushes: -(largest compressive plastic strain)", -kc, -1e-8);
          std::printf("  damaged points stepping inside their surfaces: %u (%u with principal "
                      "stresses of both signs)\n", damaged_elastic, damaged_elastic_mixed);
          check_below("-(damaged elastic steps with stresses of both signs)", -double(damaged_elastic_mixed), -0.5);
          check_below("-(damaged elastic steps of one sign)", -double(damaged_elastic - damaged_elastic_mixed), -0.5);
          // Each variable relative to its largest magnitude over the block.
          // An undamaged point's effective stress is its stress (compared
          // below); its stored copy is not kept by the batch.
          const auto stored = [&](const unsigned int e, const unsigned int k) {
            return k < C::i_effective_stress || k >= C::i_effective_stress + 6 ||
                   ref.history_variable(e, 0, C::i_tensile_damage) > 0 ||
                   ref.history_variable(e, 0, C::i_compressive_damage) > 0;
          };
          double worst_h = 0;
          for (unsigned int k = 0; k < concrete.n_updated_lagrangian_history(); ++k)
            {
              double scale = 1e-300;
              for (unsigned int e = 0; e < ref.n_elements(); ++e)
                scale = std::max(scale, std::abs(ref.history_variable(e, 0, k)));
              for (unsigned int e = 0; e < ref.n_elements(); ++e)
                if (stored(e, k))
                  worst_h = std::max(worst_h, std::abs(fast.history_variable(e, 0, k) -
                                                       ref.history_variable(e, 0, k)) / scale);
            }
          // The history integrates the return's residual over the steps
          // (and full integration runs eight returns an element): a few
          // times the return's 1e-10.
          check_below("history variables, largest difference / the variable's largest value", worst_h, 5e-10);
        }
      worst_e = std::max(std::abs(e_fast - e_ref) / std::abs(e_ref), type == Element::HourglassType::none ? 0. : std::abs(h_fast - h_ref) / std::abs(h_ref));
      // Concrete: the return mapping stops at |F| <= 1e-10 f'c, so a
      // round-off difference in a trial may end it one iteration apart.
      const double tol = (m == &concrete ? 1e-10 : 1e-12);
      check_below("largest nodal force difference / largest force", worst_f, tol);
      check_below("largest stress difference / element's largest stress", worst_s, tol);
      check_below("internal and hourglass energy, relative difference", worst_e, 1e-12);
      check_below("stable time step, relative difference", worst_dt, 1e-14);
      if (bulk)
        {
          check_below("the bulk viscosity acts: -(its work / internal energy)", -q_ref / std::abs(e_ref), -1e-6);
          check_below("bulk viscosity's work, relative difference", std::abs(q_fast - q_ref) / q_ref, 1e-12);
        }
      // An inverted Jacobian hands the batch to the reference loop, which
      // would hide a wrong fast path: on this block it must never happen.
      check_below("batches handed to the reference loop", double(fast.n_reference_fallbacks()), 0.5);
    }
  return test::finish();
}
