/**
 * @file
 * 'Type = harmonic': a boundary condition that shakes the nodes it holds,
 * u(t) = A sin(2 pi f t), i.e. the velocity v(t) = 2 pi f A cos(2 pi f t);
 * a boundary-condition plugin (doc/extending.md, "A boundary condition as a
 * plugin"), checked by tests/verification/boundary_condition_plugin.py
 * against u(t).
 */
#include <anvil/boundary_conditions/interface.h>
#include <anvil/utilities/input_error.h>

#include <cmath>

namespace anvil::BoundaryConditions
{
  class Harmonic : public Interface
  {
  public:
    // Its entries, in the condition's subsection beside the selection's
    // ('Body', 'Boundary ids', 'Components', ...).
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Amplitude", "0, 0, 0", dealii::Patterns::List(dealii::Patterns::Double(), 3, 3),
                        "For 'Type = harmonic': the displacement amplitude A. Units: m.");
      prm.declare_entry("Frequency", "1", dealii::Patterns::Double(),
                        "For 'Type = harmonic': the frequency f. Units: Hz.");
    }

    void parse_parameters(dealii::ParameterHandler &prm, const std::string &where) override
    {
      amplitude       = three_numbers(prm.get("Amplitude"), "Amplitude", where);
      const double f  = prm.get_double("Frequency");
      if (!(f > 0))
        throw InputError(where + ": entry 'Frequency' must be positive (Hz), not " + prm.get("Frequency"));
      omega = 2. * M_PI * f;
    }

    // The velocity at time t; the step asks for it at every half step.
    dealii::Tensor<1, 3> velocity(const double t) const override
    {
      return omega * std::cos(omega * t) * amplitude;
    }

    bool time_dependent() const override
    {
      return true;
    }

  private:
    dealii::Tensor<1, 3> amplitude;
    double               omega = 0;
  };

  ANVIL_REGISTER_BOUNDARY_CONDITION(Harmonic, "harmonic",
                                    "u = A sin(2 pi f t) ('Amplitude', 'Frequency'; a plugin: doc/extending.md).")
} // namespace anvil::BoundaryConditions
