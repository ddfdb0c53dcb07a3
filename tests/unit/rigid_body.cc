/**
 * Rigid bodies without a mesh (RigidBody::Shape and RigidBody::Motion):
 *
 * - analytic contact shapes: the gap and normal of a sphere, a cylinder and
 *   a plane, carried by a body translated and rotated by 90 degrees about z,
 *   against their closed forms (to round-off);
 * - translation under a constant force: central differences are exact for
 *   constant acceleration, x(t) = x0 + v0 t + F t^2 / (2M);
 * - torque-free rotation about a principal axis: the angular velocity stays
 *   constant, the rotation after time t is the exact rotation by omega t
 *   (Rodrigues update), and the kinetic energy 1/2 omega . I omega stays
 *   constant;
 * - constraints: a constrained component keeps its initial velocity under
 *   any force.
 */
#include <anvil/rigid_body/rigid_body.h>

#include <deal.II/base/symmetric_tensor.h>

#include "unit_test.h"

using namespace anvil;
using namespace dealii;
using test::check;

int main()
{
  // @sect3{Shapes}
  std::printf("== analytic shapes on a moved and rotated body\n");
  const Point<3> c0(0, 0, 0), c(1, 2, 3);
  Tensor<2, 3>   R; // 90 degrees about z: (x, y, z) -> (-y, x, z)
  R[0][1] = -1;
  R[1][0] = 1;
  R[2][2] = 1;
  Tensor<1, 3> n;
  {
    RigidBody::Shape s;
    s.type   = RigidBody::Shape::Type::sphere;
    s.point  = Point<3>(0.5, 0, 0); // placed at c + R (0.5, 0, 0) = (1, 2.5, 3)
    s.radius = 0.2;
    const double g = s.gap(Point<3>(1, 2.5, 3.1), c, R, c0, n);
    check("sphere: gap of a point 0.1 from the centre", g, -0.1, 1e-14);
    check("sphere: normal z", n[2], 1., 1e-14);
  }
  {
    RigidBody::Shape s;
    s.type      = RigidBody::Shape::Type::cylinder;
    s.point     = Point<3>(0, 0, 0);
    s.direction = Tensor<1, 3>({1., 0., 0.}); // axis becomes y
    s.radius    = 0.5;
    const double g = s.gap(Point<3>(1.3, 7, 3), c, R, c0, n);
    check("cylinder: gap of a point 0.3 off the rotated axis", g, -0.2, 1e-14);
    check("cylinder: normal x", n[0], 1., 1e-14);
    check("cylinder: no axial component", n[1], 0., 1e-14);
  }
  {
    RigidBody::Shape s;
    s.type      = RigidBody::Shape::Type::plane;
    s.point     = Point<3>(0, 0, 0);
    s.direction = Tensor<1, 3>({1., 0., 0.}); // normal becomes +y
    const double g = s.gap(Point<3>(5, 2.25, -4), c, R, c0, n);
    check("plane: signed distance along the rotated normal", g, 0.25, 1e-14);
    check("plane: normal y", n[1], 1., 1e-14);
  }

  // @sect3{Translation under a constant force}
  std::printf("== constant force\n");
  {
    RigidBody::Motion m;
    m.free = true;
    m.initialize(2., Point<3>(0, 0, 0), Tensor<2, 3>(unit_symmetric_tensor<3>()),
                 Tensor<1, 3>({1., 0., 0.}));
    const Tensor<1, 3> F({0., 0., -4.});
    const double       dt = 1e-3;
    double             t  = 0, dt_prev = 0;
    for (unsigned int k = 0; k < 1000; ++k, t += dt, dt_prev = dt)
      m.advance(F, Tensor<1, 3>(), dt_prev, dt);
    check("x(1 s) = v0 t", m.centre[0], 1., 1e-12);
    // Leapfrog started with v^{1/2} = v0 + dt/2 a: exact for constant a.
    check("z(1 s) = a t^2 / 2", m.centre[2], -1., 1e-12);
  }

  // @sect3{Torque-free rotation}
  std::printf("== torque-free rotation about a principal axis\n");
  {
    RigidBody::Motion m;
    m.free                     = true;
    m.initial_angular_velocity = Tensor<1, 3>({0., 0., 2.});
    Tensor<2, 3> I;
    I[0][0] = 1;
    I[1][1] = 2;
    I[2][2] = 3;
    m.initialize(1., Point<3>(0, 0, 0), I, Tensor<1, 3>());
    const double dt = 1e-3;
    double       e0 = 0.5 * m.angular_velocity * (I * m.angular_velocity);
    double       dt_prev = 0, worst = 0;
    for (unsigned int k = 0; k < 1000; ++k, dt_prev = dt)
      {
        const double e = m.advance(Tensor<1, 3>(), Tensor<1, 3>(), dt_prev, dt);
        worst          = std::max(worst, std::abs(e - e0) / e0);
      }
    const Point<3> x = m.placement(Point<3>(1, 0, 0));
    check("point (1,0,0) after 1 s at 2 rad/s: x = cos 2", x[0], std::cos(2.), 1e-12);
    check("point (1,0,0) after 1 s at 2 rad/s: y = sin 2", x[1], std::sin(2.), 1e-12);
    test::check_below("largest relative change of the kinetic energy", worst, 1e-12);
  }

  // @sect3{Constraints}
  std::printf("== constraints\n");
  {
    RigidBody::Motion m;
    m.free           = true;
    m.constrained[1] = true; // y
    m.constrained[5] = true; // rotation about z
    m.initialize(1., Point<3>(0, 0, 0), Tensor<2, 3>(unit_symmetric_tensor<3>()),
                 Tensor<1, 3>({0., 0.5, 0.}));
    for (unsigned int k = 0; k < 10; ++k)
      m.advance(Tensor<1, 3>({1., 7., 1.}), Tensor<1, 3>({0., 0., 3.}), k ? 1e-2 : 0., 1e-2);
    check("constrained v_y keeps its initial 0.5", m.velocity[1], 0.5, 1e-15);
    check("constrained omega_z stays 0", m.angular_velocity[2], 0., 1e-15);
    check("free v_x = F t / M", m.velocity[0], 0.1 - 0.005, 1e-12);
  }
  return test::finish();
}
