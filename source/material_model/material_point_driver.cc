/**
 * @file
 * The material-point driver. See material_point_driver.h.
 */
#include <anvil/kinematics/rotation.h>
#include <anvil/kinematics/tensor3.h>
#include <anvil/material_model/material_point_driver.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/plugins.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace anvil::MaterialModel
{
  using Kinematics::invert;
  using Kinematics::multiply;


  void MaterialPointDriver::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Output file",
                      "material_point.csv",
                      Patterns::Anything(),
                      "CSV file written by the driver, relative to the working "
                      "directory.");
    prm.declare_entry("Additional shared libraries",
                      "",
                      dealii::Patterns::Anything(),
                      "Plugins to load first (shared libraries, relative to this "
                      "file, separated by commas; doc/extending.md).");
    prm.declare_entry("Overwrite existing output",
                      "false",
                      Patterns::Bool(),
                      "If false, the driver stops when 'Output file' exists.");
    prm.enter_subsection("Material");
    MaterialModel::declare_parameters(prm);
    prm.leave_subsection();
    prm.enter_subsection("Loading");
    prm.declare_entry("Mode",
                      "uniaxial stress",
                      Patterns::Selection("uniaxial stress|biaxial stress|uniaxial strain|simple shear|truss"),
                      "Deformation of the point: 'uniaxial stress' (lateral "
                      "stresses held at 'Lateral stress'), 'biaxial stress' "
                      "(equal strains in x and y, sigma_zz held at zero), "
                      "'uniaxial strain' (lateral strains zero), 'simple shear' "
                      "(velocity gradient L_xy), 'truss' (the model's "
                      "one-dimensional form).");
    prm.declare_entry("Lateral stress",
                      "0",
                      Patterns::Double(),
                      "Uniaxial stress mode: the lateral Cauchy stresses "
                      "sigma_yy = sigma_zz, reached in the first step and held "
                      "(negative: a confining pressure, a triaxial test). Units: Pa.");
    prm.declare_entry("Characteristic length",
                      "0.1",
                      Patterns::Double(0.),
                      "Element size the point stands for (crack-band "
                      "regularisation of softening materials). Units: m.");
    prm.declare_entry("Formulation",
                      "updated Lagrangian",
                      Patterns::Selection("updated Lagrangian|total Lagrangian"),
                      "Which form of the 3D model is driven.");
    prm.declare_entry("Strain rate",
                      "1",
                      Patterns::Double(0.),
                      "Rate of the control strain (axial logarithmic strain, "
                      "or shear strain gamma = 2 eps_xy). Units: 1/s.");
    prm.declare_entry("Strain path",
                      "0.05",
                      Patterns::List(Patterns::Double()),
                      "Successive targets of the control strain, from 0, "
                      "followed linearly (e.g. 0.02, -0.02, 0.02 for a cycle). "
                      "Units: none.");
    prm.declare_entry("Strain increment",
                      "1e-4",
                      Patterns::Double(0.),
                      "Control strain per step. Units: none.");
    prm.leave_subsection();
  }


  MaterialPointDriver::MaterialPointDriver(const std::string &file)
    : driver_file(file)
  {
    if (!std::filesystem::exists(file))
      throw InputError(file + ": the driver file does not exist");
    // Plugins first: their models join the 'Model' selection.
    {
      dealii::ParameterHandler libraries;
      libraries.declare_entry("Additional shared libraries", "", dealii::Patterns::Anything());
      try
        {
          libraries.parse_input(file, "", true);
        }
      catch (const dealii::ExceptionBase &e)
        {
          throw InputError(file + ": " + one_line_message(e));
        }
      const std::string dir = std::filesystem::path(file).parent_path().string();
      load_shared_libraries(libraries.get("Additional shared libraries"), dir.empty() ? "." : dir, file);
    }
    dealii::ParameterHandler prm;
    declare_parameters(prm);
    try
      {
        prm.parse_input(file);
      }
    catch (const dealii::ExceptionBase &e)
      {
        throw InputError(file + ": " + one_line_message(e));
      }
    try
      {
        output_file = prm.get("Output file");
        overwrite   = prm.get_bool("Overwrite existing output");
        prm.enter_subsection("Material");
        material = MaterialModel::create(prm);
        prm.leave_subsection();
        prm.enter_subsection("Loading");
        mode        = prm.get("Mode");
        formulation = prm.get("Formulation") == "total Lagrangian" ?
                        Formulation::total_lagrangian :
                        Formulation::updated_lagrangian;
        strain_rate = prm.get_double("Strain rate");
        lateral_stress        = prm.get_double("Lateral stress");
        characteristic_length = prm.get_double("Characteristic length");
        increment   = prm.get_double("Strain increment");
        for (const auto &v : dealii::Utilities::split_string_list(prm.get("Strain path")))
          path.push_back(dealii::Utilities::string_to_double(v));
        prm.leave_subsection();
      }
    catch (const InputError &e)
      {
        throw InputError(file + ": " + e.what());
      }
    if (!(strain_rate > 0))
      throw InputError(file + ": entry 'Loading/Strain rate' must be positive (a "
                              "rate-free run switches the model's rate effects off)");
    if (!(characteristic_length > 0))
      throw InputError(file + ": entry 'Loading/Characteristic length' must be positive");
    if (!(increment > 0))
      throw InputError(file + ": entry 'Loading/Strain increment' must be positive");
    if (path.empty())
      throw InputError(file + ": entry 'Loading/Strain path' is empty");
    if (mode == "truss" && !material->has_uniaxial_form())
      throw InputError(file + ": the material model has no uniaxial (truss) form");
    if (mode != "truss" && !material->supports(formulation))
      throw InputError(file + ": the material model does not support the " +
                       to_string(formulation) + " formulation");
  }


  void MaterialPointDriver::step(const double (&A)[9], const double dt, State &s) const
  {
    // F_new = (I - A/2)^-1 (I + A/2) F_old.
    double Im[9], Ip[9], Imi[9], Q[9], F[9];
    for (unsigned int k = 0; k < 9; ++k)
      {
        Im[k] = (k % 4 == 0) - 0.5 * A[k];
        Ip[k] = (k % 4 == 0) + 0.5 * A[k];
      }
    invert(Im, Imi);
    multiply(Imi, Ip, Q);
    multiply(Q, s.F, F);
    std::copy(F, F + 9, s.F);
    if (formulation == Formulation::updated_lagrangian)
      {
        const double w01 = 0.5 * (A[1] - A[3]) / dt, w12 = 0.5 * (A[5] - A[7]) / dt,
                     w02 = 0.5 * (A[2] - A[6]) / dt;
        Kinematics::rotate_stress(w01, w12, w02, dt, s.stress);
        if (material->has_tensorial_history())
          material->rotate_history(w01, w12, w02, dt, s.history.data());
        const double D[6] = {A[0] / dt,
                             A[4] / dt,
                             A[8] / dt,
                             0.5 * (A[1] + A[3]) / dt,
                             0.5 * (A[5] + A[7]) / dt,
                             0.5 * (A[2] + A[6]) / dt};
        material->update_cauchy_stress(D, dt, s.stress, s.history.data());
      }
    else
      {
        double E[6];
        auto   C = [&](unsigned int i, unsigned int j) {
          return F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
        };
        E[0] = 0.5 * (C(0, 0) - 1.);
        E[1] = 0.5 * (C(1, 1) - 1.);
        E[2] = 0.5 * (C(2, 2) - 1.);
        E[3] = 0.5 * C(0, 1);
        E[4] = 0.5 * C(1, 2);
        E[5] = 0.5 * C(0, 2);
        material->update_pk2_stress(F, E, dt, s.stress, s.history.data());
      }
  }


  void MaterialPointDriver::cauchy(const State &s, double (&sigma)[6]) const
  {
    if (formulation == Formulation::updated_lagrangian)
      {
        std::copy(s.stress, s.stress + 6, sigma);
        return;
      }
    Kinematics::congruence(s.F, s.stress, Kinematics::determinant(s.F), sigma);
  }


  std::string MaterialPointDriver::run()
  {
    if (std::filesystem::exists(output_file) && !overwrite)
      throw InputError(driver_file + ": the output file '" + output_file +
                       "' exists; set 'Overwrite existing output = true' or "
                       "choose another 'Output file'");
    std::ofstream out(output_file);
    if (!out)
      throw InputError(driver_file + ": cannot write '" + output_file + "'");
    out << std::setprecision(12);

    const bool truss = (mode == "truss");
    const auto names = truss ? material->uniaxial_history_names() : material->history_names();
    if (truss)
      out << "time,strain_xx,stress_xx";
    else
      out << "time,strain_xx,strain_yy,strain_zz,strain_xy,strain_yz,strain_xz,"
             "stress_xx,stress_yy,stress_zz,stress_xy,stress_yz,stress_xz";
    for (const auto &n : names)
      if (!n.empty())
        out << ',' << n;
    out << '\n';

    State state;
    state.history.assign(truss ? material->n_uniaxial_history() : material->n_history(formulation), 0.);
    if (!truss)
      {
        PointData data;
        data.characteristic_length = characteristic_length;
        material->initialize_history(state.history.data(), data);
      }
    double time = 0, control = 0, strain[6] = {0, 0, 0, 0, 0, 0};
    double lateral = -0.3; // ratio of lateral to axial increment, refined by Newton
    auto   write = [&]() {
      out << time;
      if (truss)
        out << ',' << strain[0] << ',' << state.stress[0];
      else
        {
          double sigma[6];
          cauchy(state, sigma);
          for (const double e : strain)
            out << ',' << e;
          for (const double s : sigma)
            out << ',' << s;
        }
      for (unsigned int k = 0; k < names.size(); ++k)
        if (!names[k].empty())
          out << ',' << material->history_value(state.history.data(), k);
      out << '\n';
    };
    write();

    // The first call of a model (dt = 0) fixes its reference state.
    if (!truss && formulation == Formulation::total_lagrangian)
      {
        double E[6] = {0, 0, 0, 0, 0, 0};
        material->update_pk2_stress(state.F, E, 0., state.stress, state.history.data());
      }

    for (const double target : path)
      {
        const unsigned int n  = std::max(1., std::ceil(std::abs(target - control) / increment - 1e-9));
        const double       de = (target - control) / n;
        const double       dt = std::abs(de) / strain_rate;
        for (unsigned int i = 0; i < n; ++i)
          {
            if (truss)
              {
                state.stress[0] = material->update_uniaxial_stress(de, dt, state.stress[0],
                                                                   state.history.data());
                strain[0] += de;
              }
            else if (mode == "simple shear")
              {
                const double A[9] = {0, de, 0, 0, 0, 0, 0, 0, 0};
                step(A, dt, state);
                strain[3] += 0.5 * de;
              }
            else if (mode == "uniaxial strain")
              {
                const double A[9] = {de, 0, 0, 0, 0, 0, 0, 0, 0};
                step(A, dt, state);
                strain[0] += de;
              }
            else
              {
                // Uniaxial stress: secant iterations on the lateral
                // increment a (the same in y and z for these isotropic
                // models) until the lateral Cauchy stress reaches its
                // target. Biaxial stress: equal strains in x and y, a in z.
                const bool biaxial = (mode == "biaxial stress");
                auto residual = [&](const double a, State &trial) {
                  trial = state;
                  const double A[9] = {de, 0, 0, 0, biaxial ? de : a * de, 0, 0, 0, a * de};
                  step(A, dt, trial);
                  double sigma[6];
                  cauchy(trial, sigma);
                  return biaxial ? sigma[2] : 0.5 * (sigma[1] + sigma[2]) - lateral_stress;
                };
                State        trial;
                double       a0 = lateral, a1 = lateral * (1. + 1e-4) + 1e-6;
                double       r0 = residual(a0, trial), r1 = residual(a1, trial);
                const double scale = std::max({1., material->youngs_modulus() * std::abs(de),
                                               std::abs(lateral_stress)});
                for (unsigned int it = 0; it < 50 && std::abs(r1) > 1e-12 * scale; ++it)
                  {
                    if (r1 == r0)
                      break;
                    // A secant step is held to 0.1 in the ratio a: in the
                    // softening range a long step can land on a second root
                    // (the lateral directions cracked open, their stress
                    // zero again) that the continuous path never reaches.
                    const double a2 =
                      a1 - std::clamp(r1 * (a1 - a0) / (r1 - r0), -0.1, 0.1);
                    a0              = a1;
                    r0              = r1;
                    a1              = a2;
                    r1              = residual(a1, trial);
                  }
                lateral = a1;
                state   = trial;
                strain[0] += de;
                strain[1] += (biaxial ? 1. : a1) * de;
                strain[2] += a1 * de;
              }
            time += dt;
            control += de;
            write();
          }
        control = target;
      }
    return output_file;
  }
} // namespace anvil::MaterialModel
