/**
 * @file
 * The material-point driver: one material point of any model through a
 * prescribed deformation history, without a mesh (`anvil --material-point
 * DRIVER.prm`).
 */
#pragma once

#include <anvil/material_model/interface.h>

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil::MaterialModel
{
  /**
   * Drives one point of a material model along a piecewise-linear path of
   * a control strain at a constant rate, and writes
   * `time,strain_xx..strain_xz,stress_xx..stress_xz,<history>` as CSV.
   *
   * Modes: uniaxial stress (the lateral strains are found by secant
   * iteration so that the lateral Cauchy stresses equal a given value, zero
   * or a confining pressure), biaxial stress (equal strains in x and y,
   * sigma_zz = 0), uniaxial strain,
   * simple shear (velocity gradient L_xy only: the material rotates), and
   * the uniaxial (truss) form of the model. The 3D modes evaluate the model
   * in either formulation exactly as the element kernels do: with the
   * mid-step velocity gradient A = dt L the deformation gradient advances by
   * F <- (I - A/2)^-1 (I + A/2) F, so that (F_new - F_old) F_mid^-1 = A.
   * Strains are the accumulated sym(A), the logarithmic strain for coaxial
   * paths; stresses are Cauchy stresses.
   */
  class MaterialPointDriver
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);

    /** Read the driver file @p file; throws InputError on bad input. */
    explicit MaterialPointDriver(const std::string &file);

    /** Run the path and write the CSV file; returns its name. */
    std::string run();

  private:
    struct State
    {
      double              F[9]      = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      double              stress[6] = {0, 0, 0, 0, 0, 0};
      std::vector<double> history;
    };

    /** Advance @p state by the velocity-gradient increment @p A over dt. */
    void step(const double (&A)[9], double dt, State &state) const;

    /** Cauchy stress of @p state. */
    void cauchy(const State &state, double (&sigma)[6]) const;

    std::string                driver_file;
    std::unique_ptr<Interface> material;
    Formulation                formulation;
    std::string                mode;
    double                     strain_rate;
    double                     lateral_stress        = 0;
    double                     characteristic_length = 0.1;
    double                     increment;
    std::vector<double>        path;
    std::string                output_file;
    bool                       overwrite;
  };
} // namespace anvil::MaterialModel
