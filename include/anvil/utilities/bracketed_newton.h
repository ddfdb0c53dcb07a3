/**
 * @file
 * The root of a decreasing scalar function by Newton's method kept inside a
 * bracket: the plastic increments of the rate-dependent returns.
 */
#pragma once

#include <cmath>

namespace anvil
{
  /**
   * Root of @p g, a function falling monotonically on [@p lo, @p hi] with
   * g(lo) > 0 >= g(hi), from the first guess @p x: Newton's steps with the
   * slope that g(x, slope) returns beside its value, bisection where a
   * step would leave the bracket, which every evaluation narrows. Stops
   * when a step or the bracket is below @p tolerance (absolute), or after
   * 100 evaluations.
   */
  template <typename Function>
  double bracketed_newton(const Function &g, double lo, double hi, double x, const double tolerance)
  {
    for (unsigned int it = 0; it < 100; ++it)
      {
        double       slope;
        const double value = g(x, slope);
        (value > 0 ? lo : hi) = x;
        double next = x - value / slope;
        // (At the root to round-off the step may vanish onto the end of
        // the bracket just moved there: it ends the iteration rather than
        // sending it to bisect a bracket the root has already been found in.)
        if (std::abs(next - x) <= tolerance)
          return next;
        if (!(next > lo && next < hi))
          next = 0.5 * (lo + hi);
        const bool done = std::abs(next - x) <= tolerance || hi - lo <= tolerance;
        x               = next;
        if (done)
          break;
      }
    return x;
  }
} // namespace anvil
