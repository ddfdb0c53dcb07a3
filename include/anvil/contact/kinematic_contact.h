/**
 * @file
 * Kinematic contact enforcement (ABAQUS/Explicit's default for contact
 * pairs): a predictor-corrector that removes the penetration of the step's
 * predicted motion exactly and conserves momentum.
 *
 * Once the next step dt^{n+1/2} is known, the motion of the pair's nodes is
 * predicted from all other forces F^n:
 *
 *   v* = v^{n-1/2} + dt_avg M^{-1} F^n,   x* = x^n + dt^{n+1/2} v*.
 *
 * Each slave node s that x* puts behind a master segment (shape functions
 * phi_a at its projection, outward normal n, gap g < 0) is a constraint
 * g = 0 on the corrections Dx_s = w_s P n, Dx_a = -w_a phi_a P n (w the
 * inverse masses, P >= 0 an impulse times the step, kg m): one equation in
 * P per constraint, solved for all of them together by projected
 * Gauss-Seidel sweeps in an order fixed by the reference coordinates.
 * Between two deformable surfaces the two passes (slaves of either body)
 * are balanced: each corrects the prediction alone and the step takes the
 * mean, which does not over-constrain meshes that do not match; with a
 * rigid surface both passes are solved together.
 * Friction (seed Eqs. (61)-(62)) then takes out the tangential slip of each
 * constraint up to mu P. The contact force on a node is its correction
 * impulse over dt_avg dt, so that x^{n+1} = x* + Dx: no penetration at the
 * end of the step (to the sweeps' tolerance), sum of the forces zero (the
 * phi_a sum to 1): momentum conserved to round-off. A rigid body's nodes,
 * an analytic shape and constrained dofs have w = 0: their motion is the
 * prescribed one (a free rigid body's reaction to the contact within the
 * step is not in the prediction; it follows at the next step).
 *
 * The pair is evaluated whole on every rank, on gathered positions,
 * velocities and forces: np = 2 equals np = 1 bit for bit. It never lowers
 * the time step. Its energy (ContactResult::energy) is the work the contact
 * forces took from the bodies so far (trapezoidal rule, as the reactions of
 * prescribed motion): a plastic impact of two bodies dissipates it.
 */
#pragma once

#include <anvil/contact/interface.h>

#include <array>
#include <memory>
#include <vector>

namespace anvil::Contact
{
  class KinematicContact : public Algorithm
  {
  public:
    /** Its own entries: 'Kinematic tolerance'. Friction and 'Symmetric'
        are the penalty's entries of the same subsection. */
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm) override;

    void setup(const std::vector<SegmentDescription> &first,
               const std::vector<SegmentDescription> &second) override;
    const std::vector<unsigned long> &node_dofs() const override
    {
      return dofs;
    }
    void set_rigid(unsigned int s, bool rigid) override
    {
      surface[s].rigid = rigid;
    }
    void set_analytic(unsigned int s, const AnalyticSurface &a) override
    {
      analytic[s] = a;
    }
    bool has_analytic(unsigned int s) const override
    {
      return analytic[s].shape != nullptr;
    }
    void set_node_masses(const std::vector<double> &masses) override
    {
      node_mass = masses;
    }
    bool needs_velocities() const override
    {
      return true;
    }
    bool kinematic() const override
    {
      return true;
    }
    /** Forces are added by correct() only. */
    ContactResult compute_forces(const std::vector<double> &,
                                 const std::vector<double> &,
                                 double,
                                 std::vector<double> &) override
    {
      return last_result;
    }
    ContactResult correct(const std::vector<double> &x,
                          const std::vector<double> &v,
                          const std::vector<double> &f,
                          const std::vector<double> &inverse_mass,
                          double                     dt_previous,
                          double                     dt,
                          std::vector<double>       &f_contact) override;
    void deactivate_elements(const std::vector<unsigned long> &ids) override;
    void set_hanging_nodes(const std::vector<std::vector<std::pair<unsigned int, double>>> &masters) override;
    void serialize(StateArchive &ar) override;

    bool   symmetric       = true;
    double static_friction = 0, dynamic_friction = 0, friction_decay = 0;
    /** The sweeps stop once no constraint moves by more than this fraction
        of the thinnest element's thickness. */
    double tolerance = 1e-10;

  private:
    struct Surface
    {
      /** Pair-node indices of each segment (outward (x1-x0) x (x3-x0)),
          its element and whether it still takes part, its element's
          reference thickness V / A. */
      std::vector<std::array<unsigned int, 4>> segments;
      std::vector<unsigned long>               element;
      std::vector<char>                        active;
      /** As PenaltyContact's Surface: the element across an interior face
          of an eroding body, and whether the segment's own has eroded. */
      std::vector<unsigned long>               neighbour;
      std::vector<char>                        dead;
      std::vector<double>                      depth;
      /** The pair nodes on this surface. */
      std::vector<unsigned int> nodes;
      bool                      rigid = false;
      double                    max_depth = 0, min_depth = 1e300;
    };

    /** One constraint of this step: slave node, master nodes (or none:
        an analytic shape) with their shape functions, normal. */
    struct Constraint
    {
      unsigned int                slave;
      std::array<unsigned int, 4> master;
      std::array<double, 4>       phi;
      unsigned int                n_master;
      std::array<double, 3>       normal;
      /** The contact point's offset from the shape's centre (analytic). */
      std::array<double, 3>       arm;
      double                      impulse, weight;
      bool                        on_first;
      /** With hanging nodes in the pair: the constraint's gap as a sum
          over nodes that move on their own, each with its coefficient
          (the slave's 1 and the masters' -phi, a hanging node's spread
          over its masters). */
      std::vector<std::pair<unsigned int, double>> nodes;
    };

    std::vector<unsigned long> dofs;
    std::vector<char>          on_first;
    Surface                    surface[2];
    AnalyticSurface            analytic[2];
    std::vector<double>        node_mass;
    std::vector<Constraint>    constraints;
    /** Each pair node's masters where it hangs (set_hanging_nodes), and
        each node's hanging dependants; empty without hanging nodes. */
    std::vector<std::vector<std::pair<unsigned int, double>>> hanging;
    std::vector<std::vector<unsigned int>>                    dependants;
    /** Each slave node's outward normal in a pass (kept from step to step
        so that the step allocates nothing for it). */
    std::vector<std::array<double, 3>> slave_normal;
    /** The step's predicted positions, impulses and forces (and the
        balanced passes' copies), sized once and reused from step to step. */
    std::vector<double> predicted, impulses, friction_impulses, forces, predicted_first, impulses_first;

    /** The state from step to step: the contact forces and positions of
        the last correction (the trapezoidal work), the shape's reaction and
        centre, the work so far. */
    std::vector<double>  previous_force, previous_position;
    std::array<double, 6> previous_shape_load = {{0, 0, 0, 0, 0, 0}};
    std::array<double, 3> previous_centre     = {{0, 0, 0}};
    bool                  has_previous        = false;
    double                work                = 0;
    ContactResult         last_result;
  };
} // namespace anvil::Contact
