/**
 * @file
 * Concrete damaged plasticity. See concrete_damaged_plasticity.h.
 */
#include <anvil/kinematics/rotation.h>
#include <anvil/kinematics/tensor3.h>
#include <anvil/material_model/concrete_damaged_plasticity.h>
#include <anvil/material_model/concrete_dif.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <type_traits>

namespace anvil::MaterialModel
{
  namespace
  {
    constexpr double pi = 3.14159265358979323846;
    const std::string where = "subsection 'concrete damaged plasticity': ";

    // "e1:s1, e2:s2, ..." into two columns.
    void parse_table(const std::string &entry,
                     const std::string &text,
                     std::vector<double> &x,
                     std::vector<double> &y)
    {
      for (const auto &pair : dealii::Utilities::split_string_list(text, ','))
        {
          const auto parts = dealii::Utilities::split_string_list(pair, ':');
          try
            {
              if (parts.size() != 2)
                throw std::invalid_argument(pair);
              x.push_back(std::stod(parts[0]));
              y.push_back(std::stod(parts[1]));
            }
          catch (const std::exception &)
            {
              throw InputError(where + "entry '" + entry + "': '" + pair +
                               "' is not a pair 'abscissa:stress' of numbers");
            }
        }
      if (x.size() < 2)
        throw InputError(where + "entry '" + entry + "' needs at least two pairs");
      if (x.front() != 0.)
        throw InputError(where + "entry '" + entry + "' must start at abscissa 0");
      for (unsigned int i = 1; i < x.size(); ++i)
        if (!(x[i] > x[i - 1]))
          throw InputError(where + "entry '" + entry + "': abscissae must increase");
      for (const double v : y)
        if (v < 0)
          throw InputError(where + "entry '" + entry + "': stresses must be >= 0 (magnitudes)");
      if (!(y.front() > 0))
        throw InputError(where + "entry '" + entry + "': the first stress (the elastic "
                                 "limit) must be positive");
    }

    // Principal values (descending) and directions of a symmetric tensor
    // in Voigt order xx, yy, zz, xy, yz, xz (deal.II's hybrid method: closed
    // form, QL where values are close; 10 % cheaper than Jacobi in the
    // throughput benchmark). Only points at the tension cut-off or with
    // principal stresses of both signs need it.
    std::array<std::pair<double, dealii::Tensor<1, 3>>, 3> principal_frame(const double *v)
    {
      dealii::SymmetricTensor<2, 3> t;
      t[0][0] = v[0];
      t[1][1] = v[1];
      t[2][2] = v[2];
      t[0][1] = v[3];
      t[1][2] = v[4];
      t[0][2] = v[5];
      return dealii::eigenvectors(t, dealii::SymmetricTensorEigenvectorMethod::hybrid);
    }

    // Principal values of a symmetric tensor (Voigt), descending, without
    // trigonometry (Kinematics::extreme_principal_values).
    void principal_values(const double *v, double (&p)[3])
    {
      Kinematics::extreme_principal_values(v[0], v[1], v[2], v[3], v[4], v[5], p[0], p[2]);
      p[1] = (v[0] + v[1] + v[2]) - p[0] - p[2];
    }

    // The damage combination per principal direction of a tensor x (Voigt)
    // with principal values s1 >= s2 >= s3, s1 > 0 > s3: out = f_- x +
    // (f_+ - f_-) sum_{s_i > 0} s_i P_i. The positive part comes from the
    // one principal value whose sign differs from s2's, through its
    // eigenprojection P = (x - a)(x - b) / ((s - a)(s - b)) (a, b the other
    // two values), well conditioned since |s - a|, |s - b| >= |s| there. No
    // eigenvectors; inline, so that a loop over a batch vectorises.
    inline void combine_per_direction(const double x0, const double x1, const double x2,
                                      const double x3, const double x4, const double x5,
                                      const double s1, const double s2, const double s3,
                                      const double f_plus, const double f_minus,
                                      double (&out)[6])
    {
      const bool   two_positive = s2 > 0;
      const double s = two_positive ? s3 : s1, a = two_positive ? s1 : s2,
                   b = two_positive ? s2 : s3;
      const double g = s / ((s - a) * (s - b));
      // x^2 - (a + b) x + a b I
      const double sum = a + b, prod = a * b;
      const double P[6] = {x0 * x0 + x3 * x3 + x5 * x5 - sum * x0 + prod,
                           x3 * x3 + x1 * x1 + x4 * x4 - sum * x1 + prod,
                           x5 * x5 + x4 * x4 + x2 * x2 - sum * x2 + prod,
                           x0 * x3 + x3 * x1 + x5 * x4 - sum * x3,
                           x3 * x5 + x1 * x4 + x4 * x2 - sum * x4,
                           x0 * x5 + x3 * x4 + x5 * x2 - sum * x5};
      const double x[6] = {x0, x1, x2, x3, x4, x5};
      for (unsigned int k = 0; k < 6; ++k)
        {
          const double positive = two_positive ? x[k] - g * P[k] : g * P[k];
          out[k] = f_minus * x[k] + (f_plus - f_minus) * positive;
        }
    }

    // out += value n (x) n, Voigt.
    void add_projection(const double value, const dealii::Tensor<1, 3> &n, double *out)
    {
      static constexpr unsigned int a[6] = {0, 1, 2, 0, 1, 0}, b[6] = {0, 1, 2, 1, 2, 2};
      for (unsigned int k = 0; k < 6; ++k)
        out[k] += value * n[a[k]] * n[b[k]];
    }
  } // namespace


  // @sect3{Parameters}
  void ConcreteDamagedPlasticity::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Compressive strength",
                      "0",
                      Patterns::Double(0.),
                      "Mean uniaxial (cylinder) compressive strength f'c = f_cm, "
                      "required. Units: Pa.");
    prm.declare_entry("Density", "2400", Patterns::Double(0.), "Units: kg/m^3.");
    prm.declare_entry("Poisson's ratio", "0.2", Patterns::Double(-1., 0.5), "Units: none.");
    prm.declare_entry("Curves",
                      "Model Code 2010",
                      Patterns::Selection("Model Code 2010|tabulated"),
                      "Where the uniaxial curves come from: 'Model Code 2010' "
                      "(generated from f'c, fib MC2010 section 5.1: Eq. (5.1-26) "
                      "in compression, bilinear softening with G_F in tension) "
                      "or 'tabulated' (the two tables below). Units: none.");
    prm.declare_entry("Young's modulus",
                      "",
                      Patterns::Anything(),
                      "Empty: the secant modulus of the generated curve at "
                      "0.4 f'c. Required with tabulated curves. Units: Pa.");
    prm.declare_entry("Tensile strength",
                      "",
                      Patterns::Anything(),
                      "Empty: MC2010 f_ctm (generated curves). Units: Pa.");
    prm.declare_entry("Fracture energy",
                      "",
                      Patterns::Anything(),
                      "Mode-I fracture energy G_F. Empty: MC2010 "
                      "73 f_cm^0.18 N/m. Units: J/m^2.");
    prm.declare_entry("Compression table",
                      "",
                      Patterns::Anything(),
                      "Tabulated curves: 'inelastic strain:stress, ...' in "
                      "compression (magnitudes), starting at 0:sigma_c0. Units: "
                      "none:Pa.");
    prm.declare_entry("Tension table",
                      "",
                      Patterns::Anything(),
                      "Tabulated curves: 'crack opening:stress, ...' in tension, "
                      "starting at 0:f_t; the opening is spread over the "
                      "element's characteristic length (crack band). Units: m:Pa.");
    prm.declare_entry("Dilation angle",
                      "",
                      Patterns::Anything(),
                      "Dilation angle psi of the flow potential, required, "
                      "0 < psi < 60; typical 30-40 (ABAQUS examples use 36-38; "
                      "the concrete_cylinder scene 36). Units: degrees.");
    prm.declare_entry("Eccentricity", "0.1", Patterns::Double(0.), "Flow potential eccentricity e. Units: none.");
    prm.declare_entry("Biaxial strength ratio",
                      "1.16",
                      Patterns::Double(1.),
                      "sigma_b0 / sigma_c0, equibiaxial over uniaxial compressive "
                      "strength, 1 <= ratio < 2 (yield function alpha). Units: none.");
    prm.declare_entry("K_c",
                      "0.666666666667",
                      Patterns::Double(0.5, 1.),
                      "Ratio of the second stress invariants on the tensile and "
                      "compressive meridians, 0.5 < K_c <= 1 (yield function "
                      "gamma). Units: none.");
    prm.declare_entry("Viscosity",
                      "0",
                      Patterns::Double(0.),
                      "Duvaut-Lions viscoplastic regularisation time mu applied "
                      "to the effective stress and the damage; 0: none. Units: s.");
    prm.declare_entry("Crush band length",
                      "",
                      Patterns::Anything(),
                      "The length over which the compression curve's softening "
                      "branch holds (the gauge length of the test that measured "
                      "it): beyond the peak, an element of characteristic length "
                      "h reads the curve at the peak's inelastic strain plus h / "
                      "l_c of its own strain beyond it, so that the energy crushing "
                      "dissipates per unit area does not depend on the element "
                      "size (as the crack band does for 'Fracture energy'). "
                      "Empty: none, the curve as given in every element (ABAQUS's "
                      "way: crushing then localises in the smallest elements, and "
                      "the softening dissipates less the smaller they are). Units: m.");
    prm.declare_entry("Compressive plastic fraction",
                      "0.7",
                      Patterns::Double(0., 1.),
                      "b_c: plastic part of the inelastic strain in compression "
                      "(Birtel & Mark 2006); the rest is damage. 0 < b_c <= 1. "
                      "Units: none.");
    prm.declare_entry("Tensile plastic fraction",
                      "0.1",
                      Patterns::Double(0., 1.),
                      "b_t: plastic part of the cracking strain, 0 < b_t < 1 "
                      "(Birtel & Mark 2006). Units: none.");
    prm.declare_entry("Tensile stiffness recovery",
                      "0",
                      Patterns::Double(0., 1.),
                      "w_t: tensile stiffness regained when cracks closed in "
                      "compression reopen. Units: none.");
    prm.declare_entry("Compressive stiffness recovery",
                      "1",
                      Patterns::Double(0., 1.),
                      "w_c: compressive stiffness regained when cracks close "
                      "(1: full). Units: none.");
    prm.declare_entry("Strain rate effects",
                      "false",
                      Patterns::Bool(),
                      "Scale the compressive cohesion by CDIF (seed Eqs. "
                      "(64)-(65), continuous form) and the tensile one by TDIF "
                      "(Eqs. (66)-(67)) of the filtered largest principal strain "
                      "rate. Off: no rate is computed.");
    prm.declare_entry("DIF reference strength",
                      "",
                      Patterns::Anything(),
                      "Cylinder strength the rate curves of Eqs. (64)-(67) are "
                      "evaluated for (the seed's Fig. 13a: concretes of several "
                      "strengths with the one rate curve of 50 MPa). Empty: f'c, "
                      "each strength its own curve (Fig. 13b). Units: Pa.");
    prm.declare_entry("Cube strength",
                      "",
                      Patterns::Anything(),
                      "f_cu of Eq. (64). Empty: the DIF reference strength / 0.8 "
                      "(MC2010 cylinder over cube strength). Units: Pa.");
    prm.declare_entry("Strain rate filter time",
                      "5e-6",
                      Patterns::Double(0.),
                      "Time constant tau of the low-pass filter on the strain "
                      "rate, rate += (rate_now - rate) dt / (tau + dt), started "
                      "at the first step's rate; 0: unfiltered. Units: s.");
    prm.declare_entry("Erosion",
                      "false",
                      Patterns::Bool(),
                      "Erode an element when one of its points reaches "
                      "'Erosion principal strain' or 'Erosion damage' (those "
                      "that are > 0).");
    prm.declare_entry("Erosion principal strain",
                      "0",
                      Patterns::Double(0.),
                      "Largest principal (accumulated logarithmic) strain at "
                      "which a point fails; 0: not used. Units: none.");
    prm.declare_entry("Erosion damage",
                      "0",
                      Patterns::Double(0., 1.),
                      "Damage d at which a point fails; 0: not used. Units: none.");
  }


  void ConcreteDamagedPlasticity::parse_parameters(dealii::ParameterHandler &prm)
  {
    auto optional = [&](const std::string &entry) {
      const std::string text = dealii::Utilities::trim(prm.get(entry));
      if (text.empty())
        return 0.;
      try
        {
          std::size_t used = 0;
          const double v   = std::stod(text, &used);
          if (used != text.size() || !(v > 0))
            throw std::invalid_argument(text);
          return v;
        }
      catch (const std::exception &)
        {
          throw InputError(where + "entry '" + entry + "' = '" + text +
                           "' is not a positive number (allowed: a positive "
                           "number, or empty)");
        }
    };

    Parameters p;
    const double f_c = prm.get_double("Compressive strength");
    if (!(f_c > 0))
      throw InputError(where + "entry 'Compressive strength' must be given (> 0, in Pa)");
    p.density        = prm.get_double("Density");
    if (!(p.density > 0))
      throw InputError(where + "entry 'Density' must be positive");
    p.poissons_ratio = prm.get_double("Poisson's ratio");
    if (p.poissons_ratio <= -1. || p.poissons_ratio >= 0.5)
      throw InputError(where + "entry 'Poisson's ratio' must satisfy -1 < nu < 0.5");

    if (prm.get("Curves") == "Model Code 2010")
      {
        try
          {
            p.curves = ConcreteCurves::model_code_2010(f_c,
                                                       optional("Young's modulus"),
                                                       optional("Tensile strength"),
                                                       optional("Fracture energy"));
          }
        catch (const InputError &e)
          {
            throw InputError(where + "entry 'Compressive strength': " + e.what());
          }
      }
    else
      {
        std::vector<double> ec, sc, wt, st;
        parse_table("Compression table", prm.get("Compression table"), ec, sc);
        parse_table("Tension table", prm.get("Tension table"), wt, st);
        p.curves.youngs_modulus = optional("Young's modulus");
        if (!(p.curves.youngs_modulus > 0))
          throw InputError(where + "entry 'Young's modulus' is required with tabulated curves");
        p.curves.compressive_strength = f_c;
        p.curves.tensile_strength     = st.front();
        double G = 0;
        for (unsigned int i = 1; i < wt.size(); ++i)
          G += 0.5 * (st[i] + st[i - 1]) * (wt[i] - wt[i - 1]);
        p.curves.fracture_energy = G;
        if (st.back() != 0.)
          throw InputError(where + "entry 'Tension table' must end at stress 0 "
                                   "(a finite fracture energy)");
        p.curves.compression = PiecewiseLinear(ec, sc);
        p.curves.tension     = PiecewiseLinear(wt, st);
      }

    const std::string psi = dealii::Utilities::trim(prm.get("Dilation angle"));
    const double      psi_deg = psi.empty() ? 0. : optional("Dilation angle");
    if (!(psi_deg > 0) || !(psi_deg < 60))
      throw InputError(where + "entry 'Dilation angle' must be given in degrees, "
                               "0 < psi < 60 (typical 30-40)");
    p.dilation_angle = psi_deg * pi / 180.;
    p.eccentricity   = prm.get_double("Eccentricity");
    p.biaxial_ratio  = prm.get_double("Biaxial strength ratio");
    if (!(p.biaxial_ratio < 2.))
      throw InputError(where + "entry 'Biaxial strength ratio' must satisfy 1 <= ratio < 2");
    p.K_c = prm.get_double("K_c");
    if (!(p.K_c > 0.5))
      throw InputError(where + "entry 'K_c' must satisfy 0.5 < K_c <= 1");
    p.viscosity                    = prm.get_double("Viscosity");
    p.compressive_plastic_fraction = prm.get_double("Compressive plastic fraction");
    p.tensile_plastic_fraction     = prm.get_double("Tensile plastic fraction");
    if (!(p.compressive_plastic_fraction > 0))
      throw InputError(where + "entry 'Compressive plastic fraction' must satisfy 0 < b_c <= 1");
    if (!(p.tensile_plastic_fraction > 0) || !(p.tensile_plastic_fraction < 1))
      throw InputError(where + "entry 'Tensile plastic fraction' must satisfy 0 < b_t < 1");
    p.tensile_recovery     = prm.get_double("Tensile stiffness recovery");
    p.compressive_recovery = prm.get_double("Compressive stiffness recovery");
    p.rate_effects         = prm.get_bool("Strain rate effects");
    p.dif_strength         = optional("DIF reference strength");
    if (p.dif_strength == 0.)
      p.dif_strength = f_c;
    p.cube_strength = optional("Cube strength");
    if (p.cube_strength == 0.)
      p.cube_strength = p.dif_strength / 0.8;
    p.rate_filter_time         = prm.get_double("Strain rate filter time");
    p.erosion                  = prm.get_bool("Erosion");
    p.erosion_principal_strain = prm.get_double("Erosion principal strain");
    p.erosion_damage           = prm.get_double("Erosion damage");
    p.crush_band_length        = optional("Crush band length");
    if (p.crush_band_length < 0)
      throw InputError(where + "entry 'Crush band length' must be empty (none) or a length > 0");
    if (p.erosion && p.erosion_principal_strain == 0. && p.erosion_damage == 0.)
      throw InputError(where + "'Erosion = true' needs 'Erosion principal strain' "
                               "or 'Erosion damage' > 0");
    set(p);
  }


  void ConcreteDamagedPlasticity::set(const Parameters &p)
  {
    par = p;
    // Parameters set directly (tests, the driver) may leave the rate
    // curves' strength out: f'c, as the parameter file's default.
    if (par.dif_strength == 0.)
      par.dif_strength = p.curves.compressive_strength;
    Elastic::set(p.density, p.curves.youngs_modulus, p.poissons_ratio);
    alpha          = (p.biaxial_ratio - 1.) / (2. * p.biaxial_ratio - 1.);
    gamma          = 3. * (1. - p.K_c) / (2. * p.K_c - 1.);
    tan_psi        = std::tan(p.dilation_angle);
    eccentric_term = p.eccentricity * p.curves.tensile_strength * tan_psi;
    // The compression curve's peak (its first largest stress).
    const auto &ys    = p.curves.compression.values();
    crush_peak_strain = ys.empty() ? 0. :
                          p.curves.compression.abscissae()[std::max_element(ys.begin(), ys.end()) - ys.begin()];
    if (!p.erosion)
      par.erosion_principal_strain = par.erosion_damage = 0.;
    // The history holds what this scene needs.
    unsigned int n = n_base_history;
    if (par.erosion_principal_strain > 0)
      {
        i_max_strain = n;
        i_strain     = n + 1;
        n += 7;
      }
    if (par.viscosity > 0)
      {
        i_viscous_stress = n;
        n += 6;
      }
    n_ul_history = n;
  }


  std::vector<std::string> ConcreteDamagedPlasticity::history_names() const
  {
    std::vector<std::string> names(n_ul_history + 2);
    names[i_tensile_damage]     = "tensile_damage";
    names[i_compressive_damage] = "compressive_damage";
    names[i_damage]             = "damage";
    names[i_kappa_t]            = "tensile_equivalent_plastic_strain";
    names[i_kappa_c]            = "compressive_equivalent_plastic_strain";
    names[i_dissipation]        = "dissipated_energy_density";
    if (par.rate_effects)
      {
        names[i_rate] = "strain_rate";
        names[compressive_dif_index()] = "compressive_DIF";
        names[tensile_dif_index()]     = "tensile_DIF";
      }
    if (par.erosion_principal_strain > 0)
      names[i_max_strain] = "max_principal_strain";
    return names;
  }


  double ConcreteDamagedPlasticity::history_value(const double *h, const unsigned int k) const
  {
    const double rate = std::max(h[i_rate], 0.);
    if (k == i_rate)
      return rate;
    if (k == compressive_dif_index())
      return par.rate_effects ? ConcreteDIF::compressive(rate, par.cube_strength) : 1.;
    if (k == tensile_dif_index())
      return par.rate_effects ? ConcreteDIF::tensile(rate, par.dif_strength) : 1.;
    return h[k];
  }


  void ConcreteDamagedPlasticity::initialize_history(double *h, const PointData &data) const
  {
    h[i_length]          = data.characteristic_length;
    h[i_strength_factor] = data.strength_factor;
    h[i_rate]            = -1.;
    double d;
    tension(0., h[i_length], h[i_strength_factor], d, h[i_tensile_cohesion]);
    compression(0., h[i_length], h[i_strength_factor], d, h[i_compressive_cohesion]);
  }


  bool ConcreteDamagedPlasticity::point_failed(const double *h) const
  {
    return (par.erosion_principal_strain > 0 && h[i_max_strain] >= par.erosion_principal_strain) ||
           (par.erosion_damage > 0 && h[i_damage] >= par.erosion_damage);
  }


  void ConcreteDamagedPlasticity::rotate_history(const double w01,
                                                 const double w12,
                                                 const double w02,
                                                 const double dt,
                                                 double      *h) const
  {
    Kinematics::rotate_stress(w01, w12, w02, dt, h + i_effective_stress);
    if (par.erosion_principal_strain > 0)
      Kinematics::rotate_stress(w01, w12, w02, dt, h + i_strain);
    if (par.viscosity > 0)
      Kinematics::rotate_stress(w01, w12, w02, dt, h + i_viscous_stress);
  }


  // @sect3{Uniaxial damage and cohesion}
  //
  // With eps_p = b eps_in on the uniaxial curve sigma(eps_in):
  // d = (1 - b) E eps_in / (sigma + (1 - b) E eps_in) and the effective
  // cohesion c = sigma / (1 - d) = sigma + (1 - b) E eps_in.
  void ConcreteDamagedPlasticity::tension(const double kappa_t,
                                          const double h,
                                          const double f,
                                          double      &damage,
                                          double      &cohesion) const
  {
    cohesion = tensile_cohesion(kappa_t, h, f);
    damage   = damage_at(kappa_t, par.tensile_plastic_fraction, youngs_modulus(), cohesion);
  }


  void ConcreteDamagedPlasticity::compression(const double kappa_c,
                                              const double h,
                                              const double f,
                                              double      &damage,
                                              double      &cohesion) const
  {
    cohesion = compressive_cohesion(kappa_c, h, f);
    damage   = damage_at(kappa_c, par.compressive_plastic_fraction, youngs_modulus(), cohesion);
  }


  // @sect3{Damage, nominal stress and dissipation across the lanes}
  //
  // ABAQUS's scalar 1 - d at the tension weight r, or, where the principal
  // values have both signs, the combination per direction (see the
  // header); the dissipation is the mid-step stress power minus the change
  // of stored energy. (Always inlined: its loop over the lanes vectorises
  // in the batched update.)
  [[gnu::always_inline]] inline void
  ConcreteDamagedPlasticity::damage_lanes(const double (&x)[6][batch_size],
                                          const double (&p)[3][batch_size],
                                          const double (&d_t)[batch_size],
                                          const double (&d_c)[batch_size],
                                          const double (&old)[6][batch_size],
                                          const double (&D)[6][batch_size],
                                          const double dt,
                                          const double (&stored_old)[batch_size],
                                          const double (&add)[batch_size],
                                          double (&d)[batch_size],
                                          double (&nominal)[6][batch_size],
                                          double (&dissipated)[batch_size]) const
  {
    for (unsigned int l = 0; l < batch_size; ++l)
      {
        const double s1 = p[0][l], s2 = p[1][l], s3 = p[2][l];
        const double dt_l = d_t[l], dc_l = d_c[l];
        auto intact = [&](const double w) { return intact_fraction(w, dt_l, dc_l); };
        d[l]             = 1. - intact(tension_weight(s1, s2, s3));
        const bool mixed = (s1 > 0) & (s3 < 0) & ((dt_l > 0) | (dc_l > 0));
        const double x0 = x[0][l], x1 = x[1][l], x2 = x[2][l], x3 = x[3][l], x4 = x[4][l],
                     x5 = x[5][l];
        double per_direction[6];
        combine_per_direction(x0, x1, x2, x3, x4, x5, s1, s2, s3, intact(1.), intact(0.),
                              per_direction);
        for (unsigned int k = 0; k < 6; ++k)
          nominal[k][l] = mixed ? per_direction[k] : (1. - d[l]) * x[k][l];
        double work = 0;
        for (unsigned int k = 0; k < 6; ++k)
          work += (k < 3 ? 0.5 : 1.) * (old[k][l] + nominal[k][l]) * D[k][l] * dt;
        const double step =
          work -
          stored_energy(nominal[0][l], nominal[1][l], nominal[2][l], nominal[3][l], nominal[4][l],
                        nominal[5][l], x0, x1, x2, x3, x4, x5) +
          stored_old[l];
        dissipated[l] += add[l] != 0. ? step : 0.;
      }
  }


  // @sect3{The return mapping}
  //
  // Two surfaces: Lubliner's F and the tension cut-off max sigma_bar_i <=
  // c_t. Each return is exact on its own; when one leaves the other
  // violated (rare: equibiaxial and triaxial tension) they alternate. The
  // first return to Lubliner's surface is the caller's (the batched update
  // makes those of its inelastic points at once); the rest follows here.
  void ConcreteDamagedPlasticity::complete_return(double      *sbar,
                                                  double      *h,
                                                  const double cdif,
                                                  const double tdif,
                                                  double (&principal)[3],
                                                  bool         lubliner) const
  {
    for (unsigned int it = 0; it < 8; ++it)
      {
        if (it > 0)
          lubliner = lubliner_return(sbar, h, cdif, tdif, principal);
        if (!tension_cutoff(sbar, h, tdif, principal) || (it > 0 && !lubliner))
          break;
      }
  }


  // Rankine cut-off with associated flow: the plastic strain rate is
  // sum dl_i n_i (x) n_i over the principal directions i above c_t, so the
  // principal values drop by lambda S + 2 mu dl_i (S = sum dl_i) and the
  // directions stay. kappa_t grows by S / m (m active directions; dl for
  // one). Active set by elimination: at most three passes.
  bool ConcreteDamagedPlasticity::tension_cutoff(double      *sbar,
                                                 double      *h,
                                                 const double tdif,
                                                 double (&sp)[3]) const
  {
    const double len = h[i_length], f = h[i_strength_factor];
    const double kt0 = h[i_kappa_t];
    auto         cohesion = [&](const double kt) { return tdif * tensile_cohesion(kt, len, f); };
    const double tol = 1e-10 * par.curves.compressive_strength;
    if (!(sp[0] > cohesion(kt0) + tol))
      return false;

    const auto eig  = principal_frame(sbar);
    double     v[3] = {eig[0].first, eig[1].first, eig[2].first};

    bool         active[3] = {true, false, false};
    double       dl[3]     = {0, 0, 0}, S = 0, c = cohesion(kt0);
    unsigned int m         = 1;
    for (unsigned int i = 1; i < 3; ++i)
      active[i] = v[i] > c;
    for (unsigned int pass = 0; pass < 4; ++pass)
      {
        m          = 0;
        double sum = 0;
        for (unsigned int i = 0; i < 3; ++i)
          if (active[i])
            {
              ++m;
              sum += v[i];
            }
        // g(S) = sum_A v_i - m c(kappa_t0 + S / m) - (2 mu + m lambda) S,
        // g(0) > 0 and g(sum / (2 mu + m lambda)) <= 0 since c >= 0.
        const double k = 2. * mu + m * lambda;
        auto g = [&](const double s) { return sum - m * cohesion(kt0 + s / m) - k * s; };
        double lo = 0, hi = std::max(sum, 0.) / k, glo = g(lo), ghi = g(hi);
        S              = glo > 0 ? hi : 0.;
        int side       = 0;
        for (unsigned int it = 0; it < 200 && glo > 0 && ghi < 0; ++it)
          {
            S             = (lo * ghi - hi * glo) / (ghi - glo);
            const double gs = g(S);
            if (std::abs(gs) <= tol || hi - lo <= 1e-15 * hi)
              break;
            if (gs > 0)
              {
                lo  = S;
                glo = gs;
                if (side == 1)
                  ghi *= 0.5;
                side = 1;
              }
            else
              {
                hi  = S;
                ghi = gs;
                if (side == -1)
                  glo *= 0.5;
                side = -1;
              }
          }
        c              = cohesion(kt0 + S / m);
        bool changed   = false;
        for (unsigned int i = 0; i < 3; ++i)
          {
            dl[i] = active[i] ? (v[i] - lambda * S - c) / (2. * mu) : 0.;
            if (active[i] && dl[i] < 0)
              {
                active[i] = false;
                dl[i]     = 0;
                changed   = true;
              }
            else if (!active[i] && v[i] - lambda * S > c + tol)
              {
                active[i] = true;
                changed   = true;
              }
          }
        if (!changed)
          break;
      }
    h[i_kappa_t] = kt0 + S / m;

    std::fill(sbar, sbar + 6, 0.);
    for (unsigned int i = 0; i < 3; ++i)
      {
        sp[i] = v[i] - lambda * S - 2. * mu * dl[i];
        add_projection(sp[i], eig[i].second, sbar);
      }
    std::sort(sp, sp + 3, std::greater<double>());
    return true;
  }


  bool ConcreteDamagedPlasticity::lubliner_return(double      *sbar,
                                                  double      *h,
                                                  const double cdif,
                                                  const double tdif,
                                                  double (&sp)[3]) const
  {
    // One point: lane 0 of the lanes' return (the batched update returns
    // several points at once through the same code, so that a point's
    // result does not depend on how many others share its return).
    constexpr unsigned int W = batch_size;
    double *sbars[W] = {sbar}, *hs[W] = {h};
    alignas(64) double        cdifs[W], tdifs[W], principal[3][W];
    alignas(64) double        tensile[W], compressive[W];
    alignas(64) std::uint64_t active[W] = {1}, returned[W];
    for (unsigned int l = 0; l < W; ++l)
      {
        cdifs[l] = cdif;
        tdifs[l] = tdif;
        for (unsigned int i = 0; i < 3; ++i)
          principal[i][l] = sp[i];
      }
    lubliner_return_lanes(sbars, hs, cdifs, tdifs, principal, active, returned, tensile,
                          compressive);
    for (unsigned int i = 0; i < 3; ++i)
      sp[i] = principal[i][0];
    return returned[0] != 0;
  }


  // The return of the lanes in @p active at once. Every lane runs the same
  // arithmetic, lane by lane in vector registers; where the scalar
  // iteration of one point would branch (its convergence tests, the
  // bracket, Newton's step against the secant), the lanes select. A lane
  // whose iteration has stopped keeps its state while the others go on, so
  // a lane's result is the one it would have alone. Only the curve lookups
  // (a table search each) go lane by lane.
  //
  // (noipa: the one-point wrapper must not get its own copy of this code,
  // specialised for one lane and perhaps contracted differently. aligned:
  // its Newton loops are short and hot; the same code started 16 bytes
  // past a 64-byte boundary took 7 ns an element-cycle more on the
  // cracking block, 142.4 against 134.7-136.6 ns.)
  [[gnu::noipa, gnu::aligned(64)]] void ConcreteDamagedPlasticity::lubliner_return_lanes(
    double *const (&sbar)[batch_size],
    double *const (&h)[batch_size],
    const double (&cdif)[batch_size],
    const double (&tdif)[batch_size],
    double (&sp)[3][batch_size],
    const std::uint64_t (&active)[batch_size],
    std::uint64_t (&returned)[batch_size],
    double (&tensile)[batch_size],
    double (&compressive)[batch_size]) const
  {
    constexpr unsigned int W   = batch_size;
    const double           K   = bulk_modulus();
    const double           a2  = eccentric_term * eccentric_term;
    const double           tol = return_tolerance * par.curves.compressive_strength;
    // (The model's constants as locals: a member read under a condition
    // would be a masked load, which keeps a loop from vectorising.)
    const double mu = this->mu, alpha = this->alpha, gamma = this->gamma, tan_psi = this->tan_psi;

    // The trial: its invariants, hardening variables and static cohesions
    // (an inactive lane gets a zero state, outside no surface).
    alignas(64) double mean_tr[W], s_tr[3][W], q_tr[W], kt0[W], kc0[W], len[W], fs[W];
    alignas(64) double ct0[W], cc0[W], dct0[W], dcc0[W], F0[W], s_trial[3][W];
    for (unsigned int l = 0; l < W; ++l)
      {
        const bool on = active[l] != 0;
        kt0[l]        = on ? h[l][i_kappa_t] : 0.;
        kc0[l]        = on ? h[l][i_kappa_c] : 0.;
        len[l]        = on ? h[l][i_length] : 1.;
        fs[l]         = on ? h[l][i_strength_factor] : 1.;
        ct0[l] = cc0[l] = 1.;
        dct0[l] = dcc0[l] = 0.;
        if (on)
          {
            ct0[l] = tensile_cohesion(kt0[l], len[l], fs[l], dct0[l]);
            cc0[l] = compressive_cohesion(kc0[l], len[l], fs[l], dcc0[l]);
          }
      }
    alignas(64) std::uint64_t going[W];
    std::uint64_t             any_going = 0;
    for (unsigned int l = 0; l < W; ++l)
      {
        for (unsigned int i = 0; i < 3; ++i)
          s_trial[i][l] = active[l] != 0 ? sp[i][l] : 0.;
        const double s0 = s_trial[0][l], s1 = s_trial[1][l], s2 = s_trial[2][l];
        mean_tr[l]      = (s0 + s1 + s2) / 3.;
        s_tr[0][l]      = s0 - mean_tr[l];
        s_tr[1][l]      = s1 - mean_tr[l];
        s_tr[2][l]      = s2 - mean_tr[l];
        q_tr[l]         = std::sqrt(
          1.5 * (s_tr[0][l] * s_tr[0][l] + s_tr[1][l] * s_tr[1][l] + s_tr[2][l] * s_tr[2][l]));
        F0[l]    = yield_function(q_tr[l], mean_tr[l], s0, tdif[l] * ct0[l], cdif[l] * cc0[l]);
        going[l] = (active[l] != 0) & (F0[l] > tol) ? 1 : 0;
        returned[l] = going[l];
      }
    for (unsigned int l = 0; l < W; ++l)
      {
        tensile[l]     = ct0[l];
        compressive[l] = cc0[l];
        any_going |= going[l];
      }
    if (any_going == 0)
      return;
    for (unsigned int l = 0; l < W; ++l)
      lubliner_returns += going[l];

    // The state after plastic multiplier dl: q by Newton on
    // g(q) = q (1 + 3 G dl / sqrt(a^2 + q^2)) - q_tr = 0. g is increasing
    // and concave for q >= 0, so Newton's iterates approach the root
    // monotonically from either side. They start from q_tr - 3 G dl, the
    // root for a = 0 (Drucker-Prager), which lies below the root and within
    // O(a^2 / q) of it: the eccentricity a = e f_t tan psi is small against
    // the q of a return, and one or two steps reach round-off.
    //
    // With the state comes dF/d(dl), for the Newton iteration on dl below:
    // through q (dq/d(dl) = -(3 G q / Q) / g'(q) from g = 0), the mean
    // stress (-K tan psi) and s_max, and through the cohesions along the
    // hardening variables: dkappa_t/d(dl) = r de_1/d(dl), dkappa_c/d(dl) =
    // (1 - r) (-de_3/d(dl)) where the strain increments are active, with
    // dF/dC_t = -C_c <s_max> / C_t^2 and dF/dC_c = <s_max> / C_t - 1 (C the
    // cohesions at the rate's factors), and through the tension weight r
    // (dr from the principal values' rates). Where the flow or a curve has
    // a kink, the iteration below keeps a bracket.
    //
    // (Reciprocals of what a return holds fixed, so that an evaluation
    // divides as little as it can: its divisions and roots are a chain.)
    alignas(64) double inv_q_tr[W], per_q[3][W];
    for (unsigned int l = 0; l < W; ++l)
      {
        inv_q_tr[l] = q_tr[l] > 0 ? 1. / q_tr[l] : 0.;
        for (unsigned int i = 0; i < 3; ++i)
          per_q[i][l] = s_tr[i][l] * inv_q_tr[l];
      }
    const double inv_1_alpha = 1. / (1. - alpha), dmean = -K * tan_psi;
    // dF/d(dl) of lane l at the state (q, s) with the derivatives above.
    const auto slope = [&](const unsigned int l, const double q, const double iQ,
                           const double dg, const double s0, const double s1, const double s2,
                           const double r, const double rate1, const double rate3,
                           const double dl, const double ct, const double cc, const double dct,
                           const double dcc) {
      const double Ct = tdif[l] * ct, Cc = cdif[l] * cc, iCt = 1. / Ct;
      const double dq = q > 0 ? -3. * mu * q * iQ / dg : 0.;
      // (Written out for the three principal values: a local array would
      // keep the loop over the lanes from vectorising.)
      const double ds0 = dmean + per_q[0][l] * dq, ds1 = dmean + per_q[1][l] * dq,
                   ds2  = dmean + per_q[2][l] * dq;
      const double dnum = ((s0 > 0 ? ds0 : 0.) + (s1 > 0 ? ds1 : 0.)) + (s2 > 0 ? ds2 : 0.);
      const double dden = ((s0 > 0 ? ds0 : -ds0) + (s1 > 0 ? ds1 : -ds1)) + (s2 > 0 ? ds2 : -ds2);
      const double den  = (std::abs(s0) + std::abs(s1)) + std::abs(s2);
      const double dr       = den > 0 ? (dnum - r * dden) / den : 0.;
      const double beta     = Cc * iCt * (1. - alpha) - (1. + alpha);
      const double positive = std::max(s0, 0.);
      // (de_1 = dl rate1, de_3 = dl rate3.)
      const double dkt = rate1 > 0 ? (r + dr * dl) * rate1 : 0.;
      const double dkc = rate3 < 0 ? -(1. - r - dr * dl) * rate3 : 0.;
      return (dq + 3. * alpha * dmean + (s0 > 0 ? beta : gamma) * ds0) * inv_1_alpha -
             Cc * positive * (iCt * iCt) * tdif[l] * dct * dkt +
             (positive * iCt - 1.) * cdif[l] * dcc * dkc;
    };

    // The state of each lane at its current dl: what the iteration reads
    // (F, dF) and what the return keeps (q, mean, s, kappas); zero in a
    // lane that never goes.
    alignas(64) double q[W] = {}, mean[W] = {}, s[3][W] = {}, kt[W] = {}, kc[W] = {}, F[W] = {},
                       dF[W] = {}, dl[W];
    const auto evaluate = [&]() {
      for (unsigned int l = 0; l < W; ++l)
        lubliner_evaluations += going[l];
      alignas(64) double c3[W], qn[W], dg[W];
      alignas(64) std::uint64_t newton[W];
      std::uint64_t             any_newton = 0;
      // (With a = 0 and q = 0 the return reached the apex: q stays 0.)
      for (unsigned int l = 0; l < W; ++l)
        {
          c3[l]     = 3. * mu * dl[l];
          qn[l]     = std::max(q_tr[l] - c3[l], 0.);
          dg[l]     = 1.;
          newton[l] = (going[l] != 0) & (q_tr[l] > 0) & ((qn[l] > 0) | (a2 > 0)) ? 1 : 0;
          any_newton |= newton[l];
        }
      for (unsigned int it = 0; it < 50 && any_newton != 0; ++it)
        {
          any_newton = 0;
          for (unsigned int l = 0; l < W; ++l)
            {
              const double iQ   = 1. / std::sqrt(a2 + qn[l] * qn[l]);
              const double g    = qn[l] * (1. + c3[l] * iQ) - q_tr[l];
              const double dgn  = 1. + c3[l] * a2 * (iQ * iQ * iQ);
              const double dq   = g / dgn;
              const double next = std::max(qn[l] - dq, 0.);
              // Converged when the step is at round-off, or when the next
              // one would be: Newton's error after a step of dq is about
              // |g'' / (2 g')| dq^2 <= 1.5 c3 a^2 / Q^4 dq^2 (g' >= 1).
              const bool converged = (std::abs(dq) <= 1e-15 * q_tr[l]) |
                                     (1.5 * c3[l] * a2 * dq * dq * (iQ * iQ) * (iQ * iQ) <=
                                      1e-15 * q_tr[l]);
              const bool on = newton[l] != 0;
              qn[l]         = on ? next : qn[l];
              dg[l]         = on ? dgn : dg[l];
              newton[l]     = on & !converged & ((next > 0) | (a2 > 0)) ? 1 : 0;
              any_newton |= newton[l];
            }
        }
      alignas(64) double mn[W], xn[3][W], iQ[W], rate1[W], rate3[W], r[W], ktn[W], kcn[W];
      for (unsigned int l = 0; l < W; ++l)
        {
          const double scale = qn[l] * inv_q_tr[l];
          mn[l]              = mean_tr[l] + dmean * dl[l];
          for (unsigned int i = 0; i < 3; ++i)
            xn[i][l] = mn[l] + scale * s_tr[i][l];
          iQ[l]            = 1. / std::sqrt(a2 + qn[l] * qn[l]);
          rate1[l]         = 1.5 * scale * s_tr[0][l] * iQ[l] + tan_psi / 3.;
          rate3[l]         = 1.5 * scale * s_tr[2][l] * iQ[l] + tan_psi / 3.;
          const double de1 = dl[l] * rate1[l];
          const double de3 = dl[l] * rate3[l];
          r[l]             = tension_weight(xn[0][l], xn[1][l], xn[2][l]);
          ktn[l]           = kt0[l] + r[l] * std::max(de1, 0.);
          kcn[l]           = kc0[l] + (1. - r[l]) * std::max(-de3, 0.);
        }
      // The cohesions where a hardening variable moved (a variable that
      // did not move keeps its cohesion: no curve lookup).
      alignas(64) double ct[W], cc[W], dct[W], dcc[W];
      for (unsigned int l = 0; l < W; ++l)
        {
          ct[l]  = ct0[l];
          cc[l]  = cc0[l];
          dct[l] = dct0[l];
          dcc[l] = dcc0[l];
          if (going[l] != 0)
            {
              if (ktn[l] != kt0[l])
                ct[l] = tensile_cohesion(ktn[l], len[l], fs[l], dct[l]);
              if (kcn[l] != kc0[l])
                cc[l] = compressive_cohesion(kcn[l], len[l], fs[l], dcc[l]);
            }
        }
      alignas(64) double Fn[W], dFn[W];
      for (unsigned int l = 0; l < W; ++l)
        Fn[l] = yield_function(qn[l], mn[l], xn[0][l], tdif[l] * ct[l], cdif[l] * cc[l]);
      for (unsigned int l = 0; l < W; ++l)
        dFn[l] = slope(l, qn[l], iQ[l], dg[l], xn[0][l], xn[1][l], xn[2][l], r[l], rate1[l],
                       rate3[l], dl[l], ct[l], cc[l], dct[l], dcc[l]);
      // (A lane that has stopped keeps the state it evaluated last.)
      for (unsigned int l = 0; l < W; ++l)
        {
          const bool on = going[l] != 0;
          q[l]          = on ? qn[l] : q[l];
          mean[l]       = on ? mn[l] : mean[l];
          for (unsigned int i = 0; i < 3; ++i)
            s[i][l] = on ? xn[i][l] : s[i][l];
          kt[l] = on ? ktn[l] : kt[l];
          kc[l] = on ? kcn[l] : kc[l];
          tensile[l]     = on ? ct[l] : tensile[l];
          compressive[l] = on ? cc[l] : compressive[l];
          F[l]  = on ? Fn[l] : F[l];
          dF[l] = on ? dFn[l] : dF[l];
        }
    };

    // Newton on F(dl) = 0 from dl = 0 (F0 > 0), its first step with the
    // slope at the trial, keeping a bracket [lo, hi] of the root: a Newton
    // step that leaves the bracket (across a kink of the curves or of the
    // weight r), or a slope that does not fall, gives way to the secant of
    // the bracket's ends, or to bisection when the secant keeps the same
    // end twice; no upper end yet, the step is doubled instead. F falls
    // with dl where the return exists (the cohesions soften slower than
    // the stress relaxes), so the bracket closes.
    alignas(64) double lo[W], Flo[W], hi[W], Fhi[W], bracketed[W], kept[W];
    for (unsigned int l = 0; l < W; ++l)
      {
        const double s0 = s_trial[0][l], s1 = s_trial[1][l], s2 = s_trial[2][l];
        const double iQ    = 1. / std::sqrt(a2 + q_tr[l] * q_tr[l]);
        const double rate1 = 1.5 * s_tr[0][l] * iQ + tan_psi / 3.;
        const double rate3 = 1.5 * s_tr[2][l] * iQ + tan_psi / 3.;
        const double dF0   = slope(l, q_tr[l], iQ, 1., s0, s1, s2, tension_weight(s0, s1, s2), rate1,
                                 rate3, 0., ct0[l], cc0[l], dct0[l], dcc0[l]);
        // (Without a falling slope: the step of the cohesions held fixed.)
        const double beta0 =
          cdif[l] * cc0[l] / (tdif[l] * ct0[l]) * (1. - alpha) - (1. + alpha);
        const double s_weight = s0 > 0 ? beta0 : gamma;
        const double ds_max   = K * tan_psi + 3. * mu * per_q[0][l];
        const double fixed =
          (3. * mu + 3. * alpha * K * tan_psi + std::max(s_weight, 0.) * ds_max) / (1. - alpha);
        dl[l]        = dF0 < 0 ? F0[l] / -dF0 : F0[l] / fixed;
        lo[l]        = 0;
        Flo[l]       = F0[l];
        hi[l]        = 0;
        Fhi[l]       = 0;
        bracketed[l] = 0;
        kept[l]      = 0; // which end the last secant step kept: 1 lo, -1 hi
      }
    for (unsigned int it = 0; it < 200 && any_going != 0; ++it)
      {
        evaluate();
        // The scalar iteration's steps, each a select: stop when F is at
        // the tolerance, when the bracket has closed, or when Newton's
        // step is below round-off of dl. (The conditions are products of
        // 0 and 1, and the new bracket is compared in a loop of its own:
        // the compiler vectorises neither a select of conditions nor a
        // condition on a value selected in the same loop.)
        alignas(64) double on[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            on[l] = (going[l] != 0 ? 1. : 0.) * (std::abs(F[l]) <= tol ? 0. : 1.);
            const double up = on[l] * (F[l] > 0 ? 1. : 0.), down = on[l] - up;
            lo[l]           = up != 0. ? dl[l] : lo[l];
            Flo[l]          = up != 0. ? F[l] : Flo[l];
            hi[l]           = down != 0. ? dl[l] : hi[l];
            Fhi[l]          = down != 0. ? F[l] : Fhi[l];
            bracketed[l]    = down != 0. ? 1. : bracketed[l];
          }
        for (unsigned int l = 0; l < W; ++l)
          {
            const double br     = bracketed[l];
            const double closed = br * (hi[l] - lo[l] <= 1e-15 * hi[l] ? 1. : 0.);
            // (newton = -1 where the slope does not fall: below lo, hi and
            // dl, which are never negative.)
            const double falls  = dF[l] < 0 ? 1. : 0.;
            const double newton = dF[l] < 0 ? dl[l] - F[l] / dF[l] : -1.;
            const double inside =
              br * falls * (newton > lo[l] ? 1. : 0.) * (newton < hi[l] ? 1. : 0.);
            const double end  = F[l] > 0 ? -1. : 1.;
            const double same = end == kept[l] ? 1. : 0.;
            const double next =
              br == 0.     ? (newton > dl[l] ? newton : 2. * dl[l]) :
              inside != 0. ? newton :
              same != 0.   ? 0.5 * (lo[l] + hi[l]) :
                             (lo[l] * Fhi[l] - hi[l] * Flo[l]) / (Fhi[l] - Flo[l]);
            const double next_kept =
              br == 0. ? kept[l] : inside + same != 0. ? 0. : end;
            const double step =
              on[l] * (1. - closed) * (1. - inside * (newton == dl[l] ? 1. : 0.));
            dl[l]    = step != 0. ? next : dl[l];
            kept[l]  = step != 0. ? next_kept : kept[l];
            going[l] = step != 0. ? 1 : 0;
          }
        any_going = 0;
        for (unsigned int l = 0; l < W; ++l)
          any_going |= going[l];
      }

    // The returned lanes' effective stresses: the deviator scaled, the
    // mean stress shifted; their hardening variables.
    for (unsigned int l = 0; l < W; ++l)
      if (returned[l] != 0)
        {
          double      *sb    = sbar[l];
          const double scale = q_tr[l] > 0 ? q[l] / q_tr[l] : 0.;
          const double m_old = (sb[0] + sb[1] + sb[2]) / 3.;
          for (unsigned int k = 0; k < 6; ++k)
            sb[k] = (k < 3 ? mean[l] + scale * (sb[k] - m_old) : scale * sb[k]);
          h[l][i_kappa_t] = kt[l];
          h[l][i_kappa_c] = kc[l];
          for (unsigned int i = 0; i < 3; ++i)
            sp[i][l] = s[i][l];
        }
  }


  // @sect3{The stress update}
  //
  // The one-point form (the reference kernels, the material-point driver,
  // and every scene with viscosity or erosion by principal strain) and the
  // batched form (the fast element loop) share the lane code: the return
  // to Lubliner's surface (lubliner_return_lanes()) and damage, the
  // nominal stress and the dissipation after it (damage_lanes()), which
  // the one-point form runs on its point in every lane; the cut-off is
  // one-point code in both (tests/unit/fast_path compares the two forms).
  void ConcreteDamagedPlasticity::update_cauchy_stress(const double *D,
                                                       const double  dt,
                                                       double       *stress,
                                                       double       *h) const
  {
    // Stored energy sigma : C^-1 : sigma_bar / 2 before the step, for the
    // dissipation.
    const bool viscous = par.viscosity > 0 && dt > 0;
    // An undamaged point's effective stress is its stress (see the header;
    // the batched update does not store it).
    if (par.viscosity == 0 && h[i_tensile_damage] == 0 && h[i_compressive_damage] == 0)
      std::copy(stress, stress + 6, h + i_effective_stress);
    const double *sref       = h + (viscous ? i_viscous_stress : i_effective_stress);
    const double  stored_old = stored_energy(stress, sref);
    double        old_stress[6];
    std::copy(stress, stress + 6, old_stress);

    // Elastic increment of the effective stress.
    const double tr = D[0] + D[1] + D[2];
    double       dsig[6];
    for (unsigned int k = 0; k < 6; ++k)
      dsig[k] = (k < 3 ? lambda * tr + 2. * mu * D[k] : 2. * mu * D[k]) * dt;
    double *sbar = h + i_effective_stress;
    for (unsigned int k = 0; k < 6; ++k)
      sbar[k] += dsig[k];

    track_strain(D, dt, h);
    if (par.rate_effects && dt > 0)
      {
        double largest, smallest;
        Kinematics::extreme_principal_values(D[0], D[1], D[2], D[3], D[4], D[5], largest, smallest);
        h[i_rate] = filtered_rate(h[i_rate], std::max(std::abs(largest), std::abs(smallest)),
                                  rate_filter_weight(dt));
      }
    const bool   rate = par.rate_effects && dt > 0;
    const double cdif = rate ? ConcreteDIF::compressive(h[i_rate], par.cube_strength) : 1.;
    const double tdif = rate ? ConcreteDIF::tensile(h[i_rate], par.dif_strength) : 1.;
    double       principal[3];
    principal_values(sbar, principal);
    const bool lubliner = lubliner_return(sbar, h, cdif, tdif, principal);
    inelastic_update(D, dt, dsig, old_stress, stored_old, cdif, tdif, lubliner, principal, stress,
                     h);
  }


  void ConcreteDamagedPlasticity::track_strain(const double *D, const double dt, double *h) const
  {
    if (!(par.erosion_principal_strain > 0))
      return;
    double *eps = h + i_strain;
    for (unsigned int k = 0; k < 6; ++k)
      eps[k] += D[k] * dt;
    double e[3];
    Kinematics::principal_values(eps, e);
    h[i_max_strain] = e[0];
  }


  // Everything after the first return to Lubliner's surface (the
  // one-point update's): the rest of the return at the dynamic cohesions,
  // damage, the nominal stress and the dissipation.
  void ConcreteDamagedPlasticity::inelastic_update(const double *D,
                                                   const double  dt,
                                                   const double *dsig,
                                                   const double *old_stress,
                                                   const double  stored_old,
                                                   const double  cdif,
                                                   const double  tdif,
                                                   const bool    lubliner,
                                                   double (&principal)[3],
                                                   double       *stress,
                                                   double       *h) const
  {
    const bool viscous = par.viscosity > 0 && dt > 0;
    double    *sref    = h + (viscous ? i_viscous_stress : i_effective_stress);
    double    *sbar    = h + i_effective_stress;
    complete_return(sbar, h, cdif, tdif, principal, lubliner);

    // Damage, the scalar of ABAQUS: 1 - d = (1 - s_t d_c)(1 - s_c d_t).
    double d_t, d_c;
    tension(h[i_kappa_t], h[i_length], h[i_strength_factor], d_t, h[i_tensile_cohesion]);
    compression(h[i_kappa_c], h[i_length], h[i_strength_factor], d_c, h[i_compressive_cohesion]);
    if (viscous)
      {
        // Duvaut-Lions: the viscous state relaxes towards the inviscid one.
        const double eta = dt / par.viscosity;
        for (unsigned int k = 0; k < 6; ++k)
          sref[k] = (sref[k] + dsig[k] + eta * sbar[k]) / (1. + eta);
        d_t = (h[i_tensile_damage] + eta * d_t) / (1. + eta);
        d_c = (h[i_compressive_damage] + eta * d_c) / (1. + eta);
        principal_values(sref, principal);
      }
    h[i_tensile_damage]     = d_t;
    h[i_compressive_damage] = d_c;
    // Damage, the nominal stress and the dissipation: the batch's lane
    // code, this point in every lane.
    constexpr unsigned int W = batch_size;
    alignas(64) double x[6][W], p[3][W], dts[W], dcs[W], old[6][W], Ds[6][W], stored[W], add[W],
      d[W], nominal[6][W], dissipated[W];
    for (unsigned int l = 0; l < W; ++l)
      {
        for (unsigned int k = 0; k < 6; ++k)
          {
            x[k][l]   = sref[k];
            old[k][l] = old_stress[k];
            Ds[k][l]  = D[k];
          }
        for (unsigned int i = 0; i < 3; ++i)
          p[i][l] = principal[i];
        dts[l]        = d_t;
        dcs[l]        = d_c;
        stored[l]     = stored_old;
        add[l]        = 1.;
        dissipated[l] = h[i_dissipation];
      }
    damage_lanes(x, p, dts, dcs, old, Ds, dt, stored, add, d, nominal, dissipated);
    h[i_damage]      = d[0];
    h[i_dissipation] = dissipated[0];
    for (unsigned int k = 0; k < 6; ++k)
      stress[k] = nominal[k][0];
  }


  // @sect3{The batched stress update}
  //
  // Most of a structure's concrete is loaded inside its current surfaces at
  // any time (cracked or crushed a little, perhaps, but not yielding in this
  // step). For such a point the update is the elastic trial and the damage
  // combination of the existing d_t and d_c; the batch computes these, the
  // rate filter and the test across its points. The others return to
  // Lubliner's surface together, lane by lane (lubliner_return_lanes()),
  // take the tension cut-off one at a time where they cross it (rare),
  // and finish together again: damage at the cohesions the return ended
  // with, the nominal stress and the dissipation, by the same code as the
  // trial's damage.
  //
  // The test runs in two stages. First at the cohesions without rate
  // effects, kept in the history: the dynamic increase factors are at least
  // 1, and F does not grow with either cohesion while s_max <= c_t (dF/dc_c
  // = s_max / c_t - 1, dF/dc_t = -c_c s_max / c_t^2), so a trial inside both
  // surfaces at the static cohesions is inside them at the dynamic ones:
  // such points need no DIF (two pow per point). The others, with rate
  // effects, are tested again at the dynamic cohesions. Both stages demand
  // a margin of 1e-7 of the largest principal value (the principal values
  // here and in the one-point return differ by round-off, up to sqrt of it
  // for a double eigenvalue): a point the test passes is elastic in the
  // one-point update too. The choice depends on the point's own state only,
  // never on its lane.
  //
  // Where the principal effective stresses have both signs the combination
  // acts per direction (see the header): sigma = f_- sigma_bar + (f_+ - f_-)
  // sum_{s_i > 0} s_i P_i, with the eigenprojection of the one principal
  // value whose sign differs from the middle one's, P_1 = (A - s_2)(A - s_3)
  // / ((s_1 - s_2)(s_1 - s_3)): well conditioned, since s_1 - s_2 >= s_1 when
  // s_2 <= 0 < s_1 (and likewise for s_3), so no eigenvectors are needed.
  void ConcreteDamagedPlasticity::update_rate(const double (&D)[6][batch_size],
                                              const double dt,
                                              double (&rate)[batch_size]) const
  {
    alignas(64) double now[batch_size];
    for (unsigned int l = 0; l < batch_size; ++l)
      {
        double largest, smallest;
        Kinematics::extreme_principal_values(D[0][l], D[1][l], D[2][l], D[3][l], D[4][l], D[5][l],
                                             largest, smallest);
        now[l] = std::max(std::abs(largest), std::abs(smallest));
      }
    // (The weight once for the batch: one division instead of eight.)
    const double weight = rate_filter_weight(dt);
    for (unsigned int l = 0; l < batch_size; ++l)
      rate[l] = filtered_rate(rate[l], now[l], weight);
  }


  void ConcreteDamagedPlasticity::update_cauchy_stress_batch(const double (&D)[6][batch_size],
                                                             const double (&spin)[3][batch_size],
                                                             const double dt,
                                                             double (&s)[6][batch_size],
                                                             const BatchHistory &history) const
  {
    constexpr unsigned int W = batch_size;
    if (par.viscosity > 0 || par.erosion_principal_strain > 0 || !(dt > 0))
      {
        Interface::update_cauchy_stress_batch(D, spin, dt, s, history);
        return;
      }
    // The hot values through history.load() and hot_value(), the others
    // at cold[l][k - n_hot].
    double *const(&cold)[W] = history.cold;

    alignas(64) double sbar[6][W], sbar_old[6][W], stored_old[W], rate[W],
      hv[6][W], nominal[6][W];
    alignas(64) double damage[W], dissipation[W], margin[W], von_mises[W],
      mean_stress[W];
    alignas(64) double elastic[W]; // 1: inside the surfaces
    alignas(64) double cdif[W], tdif[W], undamaged[W];
    // What every point needs: its damage (d_t, d_c), its cohesions (c_t,
    // c_c) and its filtered rate. The rest of the history is read only
    // where a lane is damaged or leaves the surfaces.
    history.load(i_tensile_cohesion, hv[2]);
    history.load(i_compressive_cohesion, hv[3]);
    history.load(i_tensile_damage, hv[4]);
    history.load(i_compressive_damage, hv[5]);
    history.load(i_rate, rate);
    alignas(64) std::uint64_t damaged[W];
    std::uint64_t             any_damaged = 0;
    for (unsigned int l = 0; l < W; ++l)
      {
        const bool intact = (hv[4][l] == 0.) & (hv[5][l] == 0.);
        undamaged[l]      = intact ? 1. : 0.;
        damaged[l]        = intact ? 0 : 1;
      }
    for (unsigned int l = 0; l < W; ++l)
      any_damaged |= damaged[l];
    const bool undamaged_batch = any_damaged == 0;
    // The filtered rate (it needs only D; where it is computed in the
    // update made no measurable difference).
    if (par.rate_effects)
      update_rate(D, dt, rate);
    // The old effective stress, rotated with the material like the stress.
    // An undamaged point's effective stress is its stress (1 - d = 1; see
    // the header), which arrives rotated: a batch of undamaged points
    // (most of a structure's concrete before it cracks) reads no effective
    // stress from its history.
    if (undamaged_batch)
      for (unsigned int k = 0; k < 6; ++k)
        for (unsigned int l = 0; l < W; ++l)
          sbar_old[k][l] = s[k][l];
    else
      {
        // (A damaged batch's neighbour is most likely damaged too: its
        // history, which follows this batch's where the batch is stored in
        // order, is fetched while this one is updated. The addresses as
        // integers: past the last batch they lie beyond the array, where a
        // prefetch is harmless but a pointer may not point.)
        if (history.hot_batch != nullptr)
          {
            const std::uintptr_t next =
              reinterpret_cast<std::uintptr_t>(cold[W - 1]) + history.n_cold * sizeof(double);
            for (std::uintptr_t b = 0; b < W * history.n_cold * sizeof(double); b += 64)
              __builtin_prefetch(reinterpret_cast<const void *>(next + b));
          }
        for (unsigned int l = 0; l < W; ++l)
          for (unsigned int k = 0; k < 6; ++k)
            sbar_old[k][l] = cold[l][i_effective_stress - n_hot + k];
        for (unsigned int l = 0; l < W; ++l)
          Kinematics::rotate_stress(spin[0][l], spin[1][l], spin[2][l], dt, sbar_old[0][l],
                                    sbar_old[1][l], sbar_old[2][l], sbar_old[3][l],
                                    sbar_old[4][l], sbar_old[5][l]);
        for (unsigned int k = 0; k < 6; ++k)
          for (unsigned int l = 0; l < W; ++l)
            sbar_old[k][l] = undamaged[l] != 0. ? s[k][l] : sbar_old[k][l];
      }
    // The elastic trial, its mean stress and von Mises stress.
    for (unsigned int l = 0; l < W; ++l)
      {
        const double tr = D[0][l] + D[1][l] + D[2][l];
        for (unsigned int k = 0; k < 6; ++k)
          {
            const double dsig = (k < 3 ? lambda * tr + 2. * mu * D[k][l] : 2. * mu * D[k][l]) * dt;
            sbar[k][l]        = sbar_old[k][l] + dsig;
          }
        const double mean = (sbar[0][l] + sbar[1][l] + sbar[2][l]) / 3.;
        const double a = sbar[0][l] - mean, b = sbar[1][l] - mean, c = sbar[2][l] - mean;
        von_mises[l]   = std::sqrt(1.5 * (a * a + b * b + c * c) +
                                 3. * (sbar[3][l] * sbar[3][l] + sbar[4][l] * sbar[4][l] +
                                       sbar[5][l] * sbar[5][l]));
        mean_stress[l] = mean;
      }
    // An undamaged batch whose points are all well inside needs no
    // principal values: s_max <= mean + 2 q / 3 (the largest principal
    // deviator is at most sqrt(2/3) |s|), and F does not fall as s_max
    // grows where beta >= 0 (gamma >= 0 always), so the test at that bound
    // and a margin of 1e-7 (|mean| + q), never smaller than the exact
    // test's, passes only points the exact test passes too. Such a batch
    // takes the trial as its stress (1 - d = 1) and keeps its dissipation:
    // in exact arithmetic an elastic step of an undamaged point dissipates
    // nothing (the trapezoid's work equals the change of stored energy), so
    // the sum of round-off is not kept either. Only its rate is stored.
    if (undamaged_batch)
      {
        // (The test multiplied through by c_t (1 - alpha) > 0, so that it
        // needs no division and the loop becomes a few vector operations:
        // F <= -margin reads c_t (q + 3 alpha p + gamma <s>-) + c_t beta
        // <s>+ <= c_t (1 - alpha) (c_c - margin), c_t beta = c_c (1 -
        // alpha) - (1 + alpha) c_t. It differs from the quotient form by
        // round-off, far inside the margin.)
        alignas(64) std::uint64_t outside[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            const double q = von_mises[l], mean = mean_stress[l], c_t = hv[2][l], c_c = hv[3][l];
            const double s_max     = mean + 2. / 3. * q;
            const double margin    = 1e-7 * (std::abs(mean) + q);
            const double beta_ct   = c_c * (1. - alpha) - (1. + alpha) * c_t;
            const double lhs       = c_t * (q + 3. * alpha * mean + gamma * std::min(s_max, 0.)) +
                               beta_ct * std::max(s_max, 0.);
            const bool   inside    = (beta_ct >= 0.) & (s_max <= c_t - margin) &
                                (lhs <= c_t * (1. - alpha) * (c_c - margin));
            outside[l] = inside ? 0 : 1;
          }
        std::uint64_t any_outside = 0;
        for (unsigned int l = 0; l < W; ++l)
          any_outside |= outside[l];
        if (any_outside == 0)
          {
            if (par.rate_effects)
              history.store(i_rate, rate);
            for (unsigned int k = 0; k < 6; ++k)
              for (unsigned int l = 0; l < W; ++l)
                s[k][l] = sbar[k][l];
            return;
          }
      }

    // The rest of the history, and the stored energy before the step (for
    // the dissipation).
    for (unsigned int l = 0; l < W; ++l)
      {
        hv[0][l]       = cold[l][i_kappa_t - n_hot];
        hv[1][l]       = cold[l][i_kappa_c - n_hot];
        dissipation[l] = cold[l][i_dissipation - n_hot];
      }
    for (unsigned int l = 0; l < W; ++l)
      stored_old[l] = stored_energy(s[0][l], s[1][l], s[2][l], s[3][l], s[4][l], s[5][l],
                                    sbar_old[0][l], sbar_old[1][l], sbar_old[2][l],
                                    sbar_old[3][l], sbar_old[4][l], sbar_old[5][l]);

    // The trial's principal values, across the lanes (a loop of their
    // own, which vectorises).
    alignas(64) double trial_s[3][W];
    for (unsigned int l = 0; l < W; ++l)
      {
        Kinematics::extreme_principal_values(sbar[0][l], sbar[1][l], sbar[2][l], sbar[3][l],
                                             sbar[4][l], sbar[5][l], trial_s[0][l],
                                             trial_s[2][l]);
        trial_s[1][l] = 3. * mean_stress[l] - trial_s[0][l] - trial_s[2][l];
      }

    // The two surfaces at the static cohesions: inside (first stage; see
    // above), with a margin for the round-off of the principal values.
    for (unsigned int l = 0; l < W; ++l)
      {
        const double s1 = trial_s[0][l], s3 = trial_s[2][l];
        margin[l]       = 1e-7 * std::max(std::abs(s1), std::abs(s3));
        elastic[l] =
          inside_surfaces(von_mises[l], mean_stress[l], s1, hv[2][l], hv[3][l], margin[l]) ? 1. :
                                                                                            0.;
      }
    if (undamaged_batch)
      {
        for (unsigned int l = 0; l < W; ++l)
          {
            damage[l] = 0.;
            for (unsigned int k = 0; k < 6; ++k)
              nominal[k][l] = sbar[k][l];
          }
      }
    else
      {
        // Damage of the existing d_t, d_c at the trial. (An undamaged
        // point keeps its dissipation, as in an undamaged batch above: its
        // result does not depend on its batch-mates.)
        alignas(64) double add[W];
        for (unsigned int l = 0; l < W; ++l)
          add[l] = 1. - undamaged[l];
        damage_lanes(sbar, trial_s, hv[4], hv[5], s, D, dt, stored_old, add, damage, nominal,
                     dissipation);
      }

    // The rate's factors of a batch with a point outside its static
    // surfaces, across the lanes (ConcreteDIF::factors()).
    alignas(64) double tdif_lanes[W], cdif_lanes[W];
    if (par.rate_effects)
      {
        bool any_outside_static = false;
        for (unsigned int l = 0; l < W; ++l)
          any_outside_static = any_outside_static || elastic[l] == 0.;
        if (any_outside_static)
          ConcreteDIF::factors(rate, W, par.cube_strength, par.dif_strength, tdif_lanes, cdif_lanes);
      }
    for (unsigned int l = 0; l < W; ++l)
      {
        double *cl = cold[l];
        for (unsigned int k = 0; k < 6; ++k)
          cl[i_effective_stress - n_hot + k] = sbar[k][l];
        if (par.rate_effects)
          {
            history.hot_value(l, i_rate) = rate[l];
            // Second stage: outside at the static cohesions, perhaps inside
            // at the dynamic ones.
            // (The return mapping of a point outside at both takes its
            // factors from here.)
            if (elastic[l] == 0.)
              {
                tdif[l]    = tdif_lanes[l];
                cdif[l]    = cdif_lanes[l];
                elastic[l] = inside_surfaces(von_mises[l], mean_stress[l], trial_s[0][l],
                                             tdif[l] * hv[2][l], cdif[l] * hv[3][l], margin[l]);
              }
          }
        if (elastic[l] != 0.)
          {
            cl[i_damage - n_hot]      = damage[l];
            cl[i_dissipation - n_hot] = dissipation[l];
            for (unsigned int k = 0; k < 6; ++k)
              s[k][l] = nominal[k][l];
          }
      }

    // The others: their histories in one piece, their returns to
    // Lubliner's surface together, then the tension cut-off where a point
    // lies above it (one at a time: rare), and damage, the nominal stress
    // and the dissipation across the lanes again.
    alignas(64) std::uint64_t outside[W], returned[W];
    std::uint64_t             any_outside = 0;
    for (unsigned int l = 0; l < W; ++l)
      {
        outside[l] = elastic[l] == 0. ? 1 : 0;
        any_outside |= outside[l];
      }
    if (any_outside == 0)
      return;
    double             h[W][max_history];
    double            *hp[W], *sb[W];
    alignas(64) double principal[3][W] = {};
    for (unsigned int l = 0; l < W; ++l)
      {
        hp[l] = h[l];
        sb[l] = h[l] + i_effective_stress;
        if (!par.rate_effects || outside[l] == 0)
          cdif[l] = tdif[l] = 1.;
        if (outside[l] != 0)
          {
            history.gather(l, h[l]);
            double p[3];
            principal_values(sb[l], p);
            for (unsigned int i = 0; i < 3; ++i)
              principal[i][l] = p[i];
          }
      }
    // (c_t, c_c: the static cohesions at the hardening variables after the
    // return, from the return's last evaluation.)
    alignas(64) double c_t[W], c_c[W];
    lubliner_return_lanes(sb, hp, cdif, tdif, principal, outside, returned, c_t, c_c);
    const double tol = 1e-10 * par.curves.compressive_strength;
    for (unsigned int l = 0; l < W; ++l)
      if (outside[l] != 0 && principal[0][l] > tdif[l] * c_t[l] + tol)
        {
          double p[3] = {principal[0][l], principal[1][l], principal[2][l]};
          complete_return(sb[l], h[l], cdif[l], tdif[l], p, returned[l] != 0);
          for (unsigned int i = 0; i < 3; ++i)
            principal[i][l] = p[i];
          c_t[l] = tensile_cohesion(h[l][i_kappa_t], h[l][i_length], h[l][i_strength_factor]);
          c_c[l] = compressive_cohesion(h[l][i_kappa_c], h[l][i_length], h[l][i_strength_factor]);
        }
    // The damage variables at the new cohesions (tension() and
    // compression() without their lookups), zero where a lane stayed
    // inside.
    alignas(64) double x[6][W] = {}, d_t[W] = {}, d_c[W] = {}, add[W];
    const double       E = youngs_modulus();
    for (unsigned int l = 0; l < W; ++l)
      {
        add[l] = outside[l] != 0 ? 1. : 0.;
        if (outside[l] != 0)
          {
            for (unsigned int k = 0; k < 6; ++k)
              x[k][l] = sb[l][k];
            d_t[l] = damage_at(h[l][i_kappa_t], par.tensile_plastic_fraction, E, c_t[l]);
            d_c[l] = damage_at(h[l][i_kappa_c], par.compressive_plastic_fraction, E, c_c[l]);
            dissipation[l] = h[l][i_dissipation];
          }
      }
    damage_lanes(x, principal, d_t, d_c, s, D, dt, stored_old, add, damage, nominal, dissipation);
    for (unsigned int l = 0; l < W; ++l)
      if (outside[l] != 0)
        {
          h[l][i_tensile_cohesion]     = c_t[l];
          h[l][i_compressive_cohesion] = c_c[l];
          h[l][i_tensile_damage]       = d_t[l];
          h[l][i_compressive_damage]   = d_c[l];
          h[l][i_damage]               = damage[l];
          h[l][i_dissipation]          = dissipation[l];
          history.scatter(l, h[l]);
          for (unsigned int k = 0; k < 6; ++k)
            s[k][l] = nominal[k][l];
        }
  }


  ANVIL_REGISTER_MATERIAL_MODEL(
    ConcreteDamagedPlasticity,
    "concrete damaged plasticity",
    "concrete damaged plasticity (Lubliner / Lee-Fenves, ABAQUS CDP) with "
    "curves from f'c by fib Model Code 2010, crack-band tension softening "
    "and the dynamic increase factors of seed Eqs. (64)-(67).")
} // namespace anvil::MaterialModel
