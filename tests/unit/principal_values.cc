/**
 * The extreme principal values without trigonometry
 * (Kinematics::extreme_principal_values, used by the batched concrete update
 * and the strain rate of the concrete DIFs) against the closed form of Smith
 * (Kinematics::principal_values) and against tensors of known eigenvalues.
 *
 * - 100,000 random symmetric tensors (fixed seed): largest and smallest
 *   eigenvalue within 1e-13 of the tensor's largest |eigenvalue|;
 * - the degenerate cases Newton must survive: uniaxial tension and
 *   compression (a double eigenvalue at the top or bottom), pure shear,
 *   a spherical tensor, zero, and a tiny deviator on a large mean, each
 *   rotated arbitrarily, against their exact eigenvalues: a simple extreme
 *   within 1e-13, a double one within 5e-8. The split of a double
 *   eigenvalue from the invariants is conditioned like sqrt(round-off), in
 *   this method as in Smith's (whose acos is the same square root: 4e-9 on
 *   these cases); an error of that size moves the stress of the concrete's
 *   per-direction damage combination by as little, since the combination
 *   is continuous where a principal value changes sign.
 */
#include <anvil/kinematics/rotation.h>
#include <anvil/kinematics/tensor3.h>

#include "unit_test.h"

#include <random>

using namespace anvil;
using test::check_below;

namespace
{
  /** Errors of the largest and smallest eigenvalue of @p A (Voigt)
      against @p s1, @p s3, relative to max(|s1|, |s3|). */
  std::pair<double, double> errors(const double *A, const double s1, const double s3)
  {
    double largest, smallest;
    Kinematics::extreme_principal_values(A[0], A[1], A[2], A[3], A[4], A[5], largest, smallest);
    const double scale = std::max({std::abs(s1), std::abs(s3), 1e-300});
    return {std::abs(largest - s1) / scale, std::abs(smallest - s3) / scale};
  }

  double error(const double *A, const double s1, const double s3)
  {
    const auto [e1, e3] = errors(A, s1, s3);
    return std::max(e1, e3);
  }
} // namespace

int main()
{
  std::mt19937                           rng(12345);
  std::uniform_real_distribution<double> u(-1., 1.);

  std::printf("== random symmetric tensors against Smith's closed form\n");
  double worst = 0;
  for (unsigned int i = 0; i < 100000; ++i)
    {
      double A[6];
      const double scale = std::pow(10., 6. * u(rng));
      for (double &a : A)
        a = scale * u(rng);
      double v[3];
      Kinematics::principal_values(A, v);
      worst = std::max(worst, error(A, v[0], v[2]));
    }
  check_below("largest error / largest |eigenvalue|", worst, 1e-13);

  std::printf("== degenerate spectra, rotated\n");
  const double cases[][3] = {{1., 0., 0.},        // uniaxial tension: double bottom
                             {0., 0., -1.},       // uniaxial compression: double top
                             {1., 0., -1.},       // pure shear
                             {2., 2., 2.},        // spherical
                             {0., 0., 0.},        // zero
                             {1e6 + 1e-3, 1e6, 1e6 - 2e-3}, // tiny deviator, large mean
                             {3., 3., -1.},
                             {5., -2., -2.}};
  double worst_simple = 0, worst_double = 0;
  for (const auto &c : cases)
    for (unsigned int r = 0; r < 20; ++r)
      {
        double A[6] = {c[0], c[1], c[2], 0., 0., 0.};
        Kinematics::rotate_stress(3. * u(rng), 3. * u(rng), 3. * u(rng), 1., A);
        const auto [e1, e3] = errors(A, c[0], c[2]);
        // A double eigenvalue at the top (c[0] = c[1]) or bottom, unless
        // all three are equal.
        const bool spherical = (c[0] == c[2]);
        double &w1 = (c[0] == c[1] && !spherical) ? worst_double : worst_simple;
        double &w3 = (c[1] == c[2] && !spherical) ? worst_double : worst_simple;
        w1 = std::max(w1, e1);
        w3 = std::max(w3, e3);
      }
  check_below("simple eigenvalues: largest error / largest |eigenvalue|", worst_simple, 1e-13);
  check_below("double eigenvalues: largest error / largest |eigenvalue|", worst_double, 5e-8);
  return test::finish();
}
