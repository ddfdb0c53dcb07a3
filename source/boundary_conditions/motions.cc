/**
 * @file
 * Anvil's own boundary conditions: 'fixed', 'velocity' and 'velocity
 * function' (BoundaryConditions::Interface).
 */
#include <anvil/boundary_conditions/interface.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/function_parser.h>

#include <cmath>
#include <iostream>
#include <sstream>

namespace anvil::BoundaryConditions
{
  /** Zero velocity. */
  class Fixed : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &)
    {}

    dealii::Tensor<1, 3> velocity(double) const override
    {
      return {};
    }
  };


  /** The constant 'Velocity' from t = 0 on. */
  class Velocity : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Velocity",
                        "0, 0, 0",
                        dealii::Patterns::List(dealii::Patterns::Double(), 3, 3),
                        "Prescribed velocity for 'Type = velocity'. Units: m/s.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const std::string &where) override
    {
      value = three_numbers(prm.get("Velocity"), "Velocity", where);
    }

    dealii::Tensor<1, 3> velocity(double) const override
    {
      return value;
    }

  private:
    dealii::Tensor<1, 3> value;
  };


  /**
   * Three expressions in t (muparser, separated by ';'): a velocity that
   * changes in time, e.g. a ramp to a constant speed, min(t / 0.001, 1) *
   * 0.25, as ABAQUS's amplitudes and LS-DYNA's load curves give
   * *BOUNDARY_PRESCRIBED_MOTION.
   */
  class VelocityFunction : public Interface
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Velocity function",
                        "0; 0; 0",
                        dealii::Patterns::Anything(),
                        "For 'Type = velocity function': the three components of the prescribed "
                        "velocity as expressions in the time t, separated by ';' (muparser "
                        "syntax, e.g. '0; 0; -0.25 * min(t / 0.001, 1)' for a ramp to "
                        "0.25 m/s over 1 ms). The step takes them at every half step t^{n+1/2}. "
                        "Units: m/s.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const std::string &where) override
    {
      const std::string text = prm.get("Velocity function");
      const auto        parts = dealii::Utilities::split_string_list(text, ';');
      if (parts.size() != 3)
        throw InputError(where + ": entry 'Velocity function' needs three expressions in t separated by "
                                 "';', found " + std::to_string(parts.size()) + " in '" +
                         printable_excerpt(text) + "'");
      function = std::make_unique<dealii::FunctionParser<1>>(3);
      // deal.II's parser writes muparser's diagnosis to std::cerr before it
      // throws: the error is one line.
      std::ostringstream quiet;
      auto *const        cerr_buffer = std::cerr.rdbuf(quiet.rdbuf());
      try
        {
          function->initialize("t", parts, {});
          for (unsigned int c = 0; c < 3; ++c)
            if (!std::isfinite(function->value(dealii::Point<1>(0.), c)))
              throw std::runtime_error("not finite at t = 0");
          std::cerr.rdbuf(cerr_buffer);
        }
      catch (...)
        {
          std::cerr.rdbuf(cerr_buffer);
          throw InputError(where + ": entry 'Velocity function': '" + printable_excerpt(text) +
                           "' is not three expressions in t that are finite at t = 0 (muparser "
                           "syntax, e.g. '0; 0; -0.25 * min(t / 0.001, 1)')");
        }
    }

    dealii::Tensor<1, 3> velocity(const double t) const override
    {
      dealii::Tensor<1, 3> v;
      for (unsigned int c = 0; c < 3; ++c)
        v[c] = function->value(dealii::Point<1>(t), c);
      return v;
    }

    bool time_dependent() const override
    {
      return true;
    }

  private:
    std::unique_ptr<dealii::FunctionParser<1>> function;
  };


  ANVIL_REGISTER_BOUNDARY_CONDITION(Fixed, "fixed", "zero velocity.")
  ANVIL_REGISTER_BOUNDARY_CONDITION(Velocity, "velocity", "the constant 'Velocity' from t = 0 on.")
  ANVIL_REGISTER_BOUNDARY_CONDITION(VelocityFunction, "velocity function",
                                    "'Velocity function', three expressions in t, at every half step.")
} // namespace anvil::BoundaryConditions

template class anvil::Registry<anvil::BoundaryConditions::Interface>;
