/**
 * @file
 * Von Mises plasticity along a tabulated flow curve. See
 * piecewise_linear_plasticity.h.
 */
#include <anvil/material_model/piecewise_linear_plasticity.h>
#include <anvil/utilities/bracketed_newton.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/utilities.h>

#include <sstream>

namespace anvil::MaterialModel
{
  // @sect3{The return}
  //
  // Rate-free, q - 3G d = sigma_y(eps_p + d) is linear on each piece of
  // the curve: solved on the piece that holds eps_p, and on the next one
  // from its start where the solution lies beyond it. g(d) = q - 3G d -
  // sigma_y falls along every piece (slopes > -3G), so the first solution
  // within its piece is the root. With rate effects g(d) = q - 3G d - R(d /
  // dt) sigma_y(eps_p + d) is positive at 0 and not positive at the
  // rate-free root (R >= 1): Newton's method in that bracket, in y = (d /
  // C dt)^(1/p).
  double FlowCurve::increment(const double q, const double eps_p, const double dt, const double three_G) const
  {
    double H;
    if (!(q > flow_stress(eps_p, H)))
      return 0.;
    double d = 0, eps = eps_p;
    for (unsigned int piece = 0; piece <= strain.size(); ++piece)
      {
        const double s = flow_stress(eps, H), end = piece_end(eps);
        const double x = (q - three_G * d - s) / (three_G + H);
        if (eps + x <= end)
          {
            d += x;
            break;
          }
        d += end - eps;
        eps = end;
      }
    if (!rate_effects || !(dt > 0))
      return d;
    // In the rate term's own variable y = (d / C dt)^(1/p) (R = 1 + y, d =
    // C dt y^p), where g is smooth at 0 (in d it has the infinite slope of
    // d^(1/p), doc/theory.md), from Newton's first step from y = 0.
    const double Cdt = C * dt, y_max = std::pow(d / Cdt, 1. / p);
    auto         g   = [&](const double y, double &slope) {
      const double y_p1 = std::pow(y, p - 1.); // y^(p-1)
      const double x    = Cdt * y_p1 * y, dx = p * Cdt * y_p1;
      const double s    = flow_stress(eps_p + x, H);
      slope             = -three_G * dx - s - (1. + y) * H * dx;
      return q - three_G * x - (1. + y) * s;
    };
    const double s0 = flow_stress(eps_p, H);
    const double y1 = p > 1. ? (q - s0) / s0 : y_max;
    const double y  = bracketed_newton(g, 0., y_max, std::min(y1, y_max), 1e-14 / p * y_max);
    return std::min(Cdt * std::pow(y, p), d);
  }


  // @sect3{The stress update}
  //
  // The trial sigma* = sigma + (lambda tr(D) I + 2 mu D) dt (the stress
  // arrives rotated by the spin), q = sqrt(3/2 s*:s*) of its deviator, and
  // the radial return s = (1 - 3G dep / q) s*. The plastic work sigma :
  // d eps_p = dep (q - 3G dep), the flow stress times the increment.
  void PiecewiseLinearPlasticity::update_cauchy_stress(const double *D,
                                                       const double  dt,
                                                       double       *s,
                                                       double       *h) const
  {
    add_elastic_trial(D, dt, s);
    const double p = (s[0] + s[1] + s[2]) / 3.;
    const double a = s[0] - p, b = s[1] - p, c = s[2] - p;
    const double q = std::sqrt(1.5 * (a * a + b * b + c * c) + 3. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
    const double dep = curve.increment(q, h[0], dt, 3. * mu);
    if (curve.rate_effects)
      h[2] = dt > 0 ? dep / dt : 0.;
    if (dep == 0.)
      return;
    const double factor = 1. - 3. * mu * dep / q;
    s[0]                = p + factor * a;
    s[1]                = p + factor * b;
    s[2]                = p + factor * c;
    for (unsigned int k = 3; k < 6; ++k)
      s[k] *= factor;
    h[0] += dep;
    h[1] += dep * (q - 3. * mu * dep);
  }


  std::string PiecewiseLinearPlasticity::rate_law() const
  {
    if (!curve.rate_effects)
      return "";
    std::ostringstream out;
    out << "Cowper-Symonds (C = " << curve.C << " 1/s, p = " << curve.p << ")";
    return out.str();
  }


  // @sect3{Parameters}
  void PiecewiseLinearPlasticity::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Density", "0", Patterns::Double(0.), "Reference mass density (required). Units: kg/m^3.");
    prm.declare_entry("Young's modulus", "0", Patterns::Double(0.), "Young's modulus E (required). Units: Pa.");
    prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(-1., 0.5), "Poisson's ratio nu. Units: none.");
    prm.declare_entry("Flow curve",
                      "",
                      Patterns::Anything(),
                      "The yield stress against the effective plastic strain, "
                      "'eps_p:sigma_y, ...' (required): the first at eps_p = 0 "
                      "(the initial yield stress, > 0), eps_p increasing, "
                      "sigma_y >= 0, straight between the points, every slope "
                      "above -3G. Units: none:Pa.");
    prm.declare_entry("Beyond the curve",
                      "extrapolate",
                      Patterns::Selection("extrapolate|constant"),
                      "After the last point: 'extrapolate' continues the last "
                      "segment's slope (LS-DYNA's *MAT_024 curves; a falling "
                      "one ends at 0), 'constant' keeps the last yield stress "
                      "(ABAQUS's *Plastic). Units: none.");
    prm.declare_entry("Cowper-Symonds C",
                      "0",
                      Patterns::Double(0.),
                      "C of the rate factor 1 + (eps_p_dot / C)^(1/p) of the "
                      "yield stress, eps_p_dot the effective plastic strain rate "
                      "of the increment (ABAQUS's *Rate Dependent, POWER LAW; "
                      "LS-DYNA's VP = 1); 0: no rate effects. Units: 1/s.");
    prm.declare_entry("Cowper-Symonds p", "0", Patterns::Double(0.), "p of the rate factor; 0: no rate effects. Units: none.");
    prm.declare_entry("Failure strain",
                      "0",
                      Patterns::Double(0.),
                      "Effective plastic strain at which a point fails and its "
                      "element is eroded (LS-DYNA's FAIL); 0: never. Units: none.");
  }


  void PiecewiseLinearPlasticity::parse_parameters(dealii::ParameterHandler &prm)
  {
    const std::string where = "subsection 'piecewise linear plasticity': ";
    auto positive = [&](const std::string &entry) {
      const double v = prm.get_double(entry);
      if (!(v > 0))
        throw InputError(where + "entry '" + entry + "' = " + prm.get(entry) + " must be positive");
      return v;
    };
    const double density = positive("Density"), youngs = positive("Young's modulus"),
                 poisson = prm.get_double("Poisson's ratio");
    auto number = [](const double x) {
      std::ostringstream out;
      out << x;
      return out.str();
    };
    FlowCurve         c;
    const std::string text = prm.get("Flow curve");
    for (const auto &point : dealii::Utilities::split_string_list(text, ','))
      {
        const auto pair = dealii::Utilities::split_string_list(point, ':');
        double     e = 0, sy = 0;
        try
          {
            if (pair.size() != 2)
              throw std::invalid_argument(point);
            std::size_t used_e = 0, used_s = 0;
            e  = std::stod(pair[0], &used_e);
            sy = std::stod(pair[1], &used_s);
            if (used_e != pair[0].size() || used_s != pair[1].size())
              throw std::invalid_argument(point);
          }
        catch (const std::exception &)
          {
            throw InputError(where + "entry 'Flow curve': '" + printable_excerpt(point) +
                             "' is not 'eps_p:sigma_y' (two numbers)");
          }
        c.strain.push_back(e);
        c.stress.push_back(sy);
      }
    if (c.strain.empty())
      throw InputError(where + "entry 'Flow curve' is empty (required: 'eps_p:sigma_y, ...', the first at eps_p = 0)");
    if (c.strain[0] != 0. || !(c.stress[0] > 0))
      throw InputError(where + "entry 'Flow curve': the first point must be at eps_p = 0 with a positive yield "
                       "stress (it has " + number(c.strain[0]) + ":" + number(c.stress[0]) + ")");
    const double three_G = 3. * youngs / (2. * (1. + poisson));
    for (unsigned int i = 1; i < c.strain.size(); ++i)
      {
        const std::string at = "point " + std::to_string(i + 1) + " (" + number(c.strain[i]) + ":" +
                               number(c.stress[i]) + ")";
        if (!(c.strain[i] > c.strain[i - 1]))
          throw InputError(where + "entry 'Flow curve': the plastic strain must increase, and does not at " + at);
        if (!(c.stress[i] >= 0))
          throw InputError(where + "entry 'Flow curve': the yield stress is negative at " + at);
        if (!((c.stress[i] - c.stress[i - 1]) / (c.strain[i] - c.strain[i - 1]) > -three_G))
          throw InputError(where + "entry 'Flow curve': the curve falls faster than 3G = " +
                           number(three_G) + " Pa before " + at + " (the return would have no unique root)");
      }
    c.extrapolate = prm.get("Beyond the curve") == "extrapolate" && c.strain.size() > 1;
    // A falling continuation ends at 0: its zero becomes the last point.
    if (c.extrapolate)
      {
        const std::size_t n = c.strain.size();
        const double      H = (c.stress[n - 1] - c.stress[n - 2]) / (c.strain[n - 1] - c.strain[n - 2]);
        if (H < 0)
          {
            c.strain.push_back(c.strain[n - 1] - c.stress[n - 1] / H);
            c.stress.push_back(0.);
            c.extrapolate = false;
          }
      }
    c.C            = prm.get_double("Cowper-Symonds C");
    c.p            = prm.get_double("Cowper-Symonds p");
    c.rate_effects = c.C > 0 && c.p > 0;
    if ((c.C > 0) != (c.p > 0))
      throw InputError(where + "entries 'Cowper-Symonds C' and 'Cowper-Symonds p': give both (rate effects) or "
                       "neither");
    set(density, youngs, poisson, c, prm.get_double("Failure strain"));
  }


  void PiecewiseLinearPlasticity::set(const double     density,
                                      const double     youngs_modulus,
                                      const double     poissons_ratio,
                                      const FlowCurve &c,
                                      const double     failure)
  {
    Elastic::set(density, youngs_modulus, poissons_ratio);
    curve          = c;
    failure_strain = failure;
  }


  ANVIL_REGISTER_MATERIAL_MODEL(PiecewiseLinearPlasticity,
                                "piecewise linear plasticity",
                                "Von Mises metal with isotropic hardening along a tabulated flow curve, "
                                "Cowper-Symonds rate effects and erosion at a failure strain (LS-DYNA "
                                "*MAT_PIECEWISE_LINEAR_PLASTICITY, ABAQUS *Plastic with a table).")
} // namespace anvil::MaterialModel
