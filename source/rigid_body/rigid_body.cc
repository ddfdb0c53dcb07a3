/**
 * @file
 * Rigid-body motion and analytic contact shapes. See rigid_body.h.
 */
#include <anvil/rigid_body/rigid_body.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>

#include <cmath>

namespace anvil::RigidBody
{
  using namespace dealii;

  namespace
  {
    /** exp([w]) for the rotation vector w (Rodrigues' formula). */
    Tensor<2, 3> rotation_matrix(const Tensor<1, 3> &w)
    {
      const double theta = w.norm();
      Tensor<2, 3> K;
      K[0][1] = -w[2];
      K[0][2] = w[1];
      K[1][0] = w[2];
      K[1][2] = -w[0];
      K[2][0] = -w[1];
      K[2][1] = w[0];
      const Tensor<2, 3> I = Tensor<2, 3>(unit_symmetric_tensor<3>());
      if (theta < 1e-12)
        return I + K + 0.5 * K * K;
      return I + std::sin(theta) / theta * K + (1. - std::cos(theta)) / (theta * theta) * K * K;
    }
  } // namespace


  double Shape::gap(const Point<3>     &x,
                    const Point<3>     &c,
                    const Tensor<2, 3> &R,
                    const Point<3>     &c0,
                    Tensor<1, 3>       &normal) const
  {
    const Point<3> p = c + R * (point - c0);
    switch (type)
      {
        case Type::sphere:
          {
            const Tensor<1, 3> r = x - p;
            const double       d = r.norm();
            normal               = d > 0 ? r / d : Tensor<1, 3>({0., 0., 1.});
            return d - radius;
          }
        case Type::cylinder:
          {
            const Tensor<1, 3> a = R * direction;
            Tensor<1, 3>       r = x - p;
            r -= (r * a) * a;
            const double d = r.norm();
            normal         = d > 0 ? r / d : Tensor<1, 3>();
            return d - radius;
          }
        case Type::plane:
          normal = R * direction;
          return (x - p) * normal;
        default:
          return 1e300;
      }
  }


  void Motion::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Rigid body");
    prm.declare_entry("Motion",
                      "prescribed",
                      Patterns::Selection("prescribed|free"),
                      "For bodies of material 'rigid': 'prescribed' keeps the "
                      "initial (angular) velocity for the whole run (zero: a "
                      "fixed wall); 'free' integrates the motion from the "
                      "contact and gravity forces on the body.");
    prm.declare_entry("Constraints",
                      "",
                      Patterns::MultipleSelection("x|y|z|rx|ry|rz"),
                      "Free motion: translations (x, y, z) and rotations "
                      "about the axes (rx, ry, rz) held at their initial "
                      "velocity, e.g. 'y, z, rx, ry, rz' for a hammer that "
                      "only moves along x.");
    prm.declare_entry("Initial angular velocity",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Angular velocity about the centre of mass. Units: rad/s.");
    prm.declare_entry("Mass",
                      "0",
                      Patterns::Double(0.),
                      "Mass of the body; 0: from its mesh and the material "
                      "density. A given mass scales the inertia with it. "
                      "Units: kg.");
    prm.declare_entry("Inertia",
                      "",
                      Patterns::Anything(),
                      "Inertia tensor about the centre of mass, 'Ixx, Iyy, "
                      "Izz, Ixy, Iyz, Ixz'; empty: from the mesh. Units: kg m^2.");
    prm.declare_entry("Contact shape",
                      "mesh",
                      Patterns::Selection("mesh|sphere|cylinder|plane"),
                      "The surface other bodies touch: the mesh's faces, or an "
                      "exact analytic sphere, cylinder or plane carried by the "
                      "body (given in the mesh's coordinates).");
    prm.declare_entry("Shape point",
                      "0, 0, 0",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Sphere: centre; cylinder: a point on the axis; plane: a "
                      "point of the plane. Units: m.");
    prm.declare_entry("Shape direction",
                      "0, 0, 1",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Cylinder: axis; plane: outward normal (towards the "
                      "other body). Units: none.");
    prm.declare_entry("Shape radius",
                      "0",
                      Patterns::Double(0.),
                      "Sphere and cylinder radius. Units: m.");
    prm.leave_subsection();
  }


  void Motion::parse_parameters(ParameterHandler &prm, const std::string &body)
  {
    const std::string where = "Body " + body + "/Rigid body";
    prm.enter_subsection("Rigid body");
    free = prm.get("Motion") == "free";
    const std::string names[6] = {"x", "y", "z", "rx", "ry", "rz"};
    for (const auto &c : Utilities::split_string_list(prm.get("Constraints")))
      for (unsigned int k = 0; k < 6; ++k)
        if (c == names[k])
          constrained[k] = true;
    initial_angular_velocity = three_numbers(prm.get("Initial angular velocity"),
                                           "Initial angular velocity", "subsection '" + where + "'");
    given_mass               = prm.get_double("Mass");
    given_inertia.clear();
    const std::string inertia = Utilities::trim(prm.get("Inertia"));
    if (!inertia.empty())
      {
        for (const auto &v : Utilities::split_string_list(inertia))
          given_inertia.push_back(Utilities::string_to_double(v));
        if (given_inertia.size() != 6)
          throw InputError("subsection '" + where +
                           "': entry 'Inertia' needs six numbers (Ixx, Iyy, Izz, Ixy, Iyz, Ixz)");
      }
    const std::string s = prm.get("Contact shape");
    shape.type = s == "sphere" ? Shape::Type::sphere :
                 s == "cylinder" ? Shape::Type::cylinder :
                 s == "plane"    ? Shape::Type::plane :
                                   Shape::Type::mesh;
    shape.point     = Point<3>(three_numbers(prm.get("Shape point"), "Shape point", "subsection '" + where + "'"));
    shape.direction = three_numbers(prm.get("Shape direction"), "Shape direction", "subsection '" + where + "'");
    shape.radius    = prm.get_double("Shape radius");
    prm.leave_subsection();
    if (shape.type != Shape::Type::mesh && shape.type != Shape::Type::sphere)
      {
        if (!(shape.direction.norm() > 0))
          throw InputError("subsection '" + where + "': entry 'Shape direction' must not be zero");
        shape.direction /= shape.direction.norm();
      }
    if ((shape.type == Shape::Type::sphere || shape.type == Shape::Type::cylinder) &&
        !(shape.radius > 0))
      throw InputError("subsection '" + where + "': a " + s +
                       " contact shape needs a positive 'Shape radius'");
  }


  void Motion::initialize(const double        m,
                          const Point<3>     &c,
                          const Tensor<2, 3> &inertia,
                          const Tensor<1, 3> &v)
  {
    mass              = m;
    reference_centre  = c;
    centre            = c;
    previous_centre   = c;
    reference_inertia = inertia;
    rotation          = Tensor<2, 3>(unit_symmetric_tensor<3>());
    previous_rotation = rotation;
    velocity          = v;
    initial_velocity  = v;
    angular_velocity  = initial_angular_velocity;
    angular_momentum  = reference_inertia * angular_velocity;
  }


  double Motion::advance(const Tensor<1, 3> &force,
                         const Tensor<1, 3> &torque,
                         const double        dt_previous,
                         const double        dt)
  {
    last_force                    = force;
    const double       dt_avg     = 0.5 * (dt_previous + dt);
    const Tensor<1, 3> v_old      = velocity;
    const Tensor<1, 3> w_old      = angular_velocity;
    const Tensor<1, 3> L_old      = angular_momentum;
    const Tensor<2, 3> I          = rotation * reference_inertia * transpose(rotation);
    if (free)
      {
        velocity += dt_avg / mass * force;
        angular_momentum += dt_avg * torque;
        angular_velocity = invert(I) * angular_momentum;
        for (unsigned int d = 0; d < 3; ++d)
          {
            if (constrained[d])
              velocity[d] = initial_velocity[d];
            if (constrained[3 + d])
              angular_velocity[d] = initial_angular_velocity[d];
          }
        angular_momentum = I * angular_velocity;
      }
    // The total force and torque that moved the body, M dV / dt_avg and
    // dL / dt_avg; what the applied ones do not explain is the reaction.
    Tensor<1, 3> f_total, t_total;
    if (dt_avg > 0)
      {
        f_total = mass * (velocity - v_old) / dt_avg;
        t_total = (angular_momentum - L_old) / dt_avg;
      }
    const Tensor<1, 3> r_force  = f_total - force;
    const Tensor<1, 3> r_torque = t_total - torque;
    last_reaction_work = 0.5 * dt_previous *
                         ((reaction_force + r_force) * v_old + (reaction_torque + r_torque) * w_old);
    reaction_force  = r_force;
    reaction_torque = r_torque;
    kinetic_energy  = 0.5 * (v_old * (mass * v_old + dt_previous * f_total) +
                            w_old * (I * w_old + dt_previous * t_total));
    previous_centre   = centre;
    previous_rotation = rotation;
    if (dt > 0)
      {
        centre += dt * velocity;
        rotation = rotation_matrix(dt * angular_velocity) * rotation;
      }
    return kinetic_energy;
  }
} // namespace anvil::RigidBody
