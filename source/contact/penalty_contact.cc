/**
 * @file
 * Symmetric node-to-segment penalty contact, seed section 4.3.
 */
#include <anvil/contact/penalty_contact.h>
#include <anvil/utilities/input_error.h>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace anvil::Contact
{
  namespace bg  = boost::geometry;
  namespace bgi = boost::geometry::index;

  namespace
  {
    using BPoint = bg::model::point<double, 3, bg::cs::cartesian>;
    using Value  = std::pair<BPoint, unsigned int>;

    struct Vec
    {
      double x, y, z;
    };
    inline Vec operator-(const Vec &a, const Vec &b)
    {
      return {a.x - b.x, a.y - b.y, a.z - b.z};
    }
    inline Vec operator+(const Vec &a, const Vec &b)
    {
      return {a.x + b.x, a.y + b.y, a.z + b.z};
    }
    inline Vec operator*(const double s, const Vec &a)
    {
      return {s * a.x, s * a.y, s * a.z};
    }
    inline double dot(const Vec &a, const Vec &b)
    {
      return a.x * b.x + a.y * b.y + a.z * b.z;
    }
    inline Vec cross(const Vec &a, const Vec &b)
    {
      return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    }
    inline double norm(const Vec &a)
    {
      return std::sqrt(dot(a, a));
    }

    // How far (in natural coordinates) a segment is extended beyond its
    // edges when no segment contains the projection of a slave node.
    constexpr double edge_tolerance = 0.1;

    // Natural coordinates of the cyclic segment nodes (seed Eq. (54)).
    constexpr double xi_n[4]  = {-1, 1, 1, -1};
    constexpr double eta_n[4] = {-1, -1, 1, 1};

    /**
     * Normal force (seed Eq. (58), with the optional normal damping) and
     * Coulomb friction force (step (6), Eqs. (61)-(62)) on slave node @p s
     * with penetration @p l < 0 along the unit normal @p nn, stiffness @p k
     * and velocity @p vr relative to the surface. Returns the normal force;
     * the friction force goes to @p friction. Updates the node's tangential
     * state in @p ft and the friction work.
     *
     * Friction: the trial tangential force F* = F^n - k delta, with delta
     * the tangential slip of the slave node over the contact point during
     * the last step, vr dt projected on the tangent plane; the previous
     * force is first projected on the current plane. F* is returned to the
     * Coulomb cone mu f_n (Eq. (61)). V in Eq. (62) is the sliding velocity,
     * zero while the node sticks: the static coefficient decides stick or
     * slip, and a sliding node is returned to mu(V) f_n with V its slip
     * rate. (Taking the trial slip rate also in stick would let the elastic
     * vibration of a resting body lower mu below mu_s.) The work of the
     * friction force over the slip, by the trapezoidal rule like every
     * other work in Anvil, goes to the friction energy.
     */
    Vec interface_forces(const PenaltyContact      &pair,
                         const unsigned int         s,
                         const double               l,
                         const Vec                 &nn,
                         const double               k,
                         const Vec                 &vr,
                         const double               dt,
                         const double               node_mass,
                         const std::vector<double> &ft_old,
                         std::vector<double>       &ft,
                         ContactResult             &result,
                         Vec                       &friction)
    {
      double fn = -l * k;
      if (pair.normal_damping > 0 && dt > 0 && node_mass > 0)
        {
          // Damping on the normal relative velocity, never pulling.
          const double c  = 2. * pair.normal_damping * std::sqrt(k * node_mass);
          const double vn = dot(vr, nn);
          const double fd = std::max(-c * vn, -fn);
          fn += fd;
          result.friction_work -= fd * vn * dt;
        }
      friction = {0, 0, 0};
      if (dt > 0 && (pair.static_friction > 0 || pair.dynamic_friction > 0))
        {
          const Vec slip  = dt * (vr - dot(vr, nn) * nn);
          Vec       f_old = {ft_old[3 * s], ft_old[3 * s + 1], ft_old[3 * s + 2]};
          f_old           = f_old - dot(f_old, nn) * nn;
          Vec          trial = f_old - k * slip;
          const double t     = norm(trial);
          if (t > pair.static_friction * fn)
            {
              const double rate  = norm(slip) / dt;
              const double mu    = pair.dynamic_friction + (pair.static_friction - pair.dynamic_friction) *
                                                            std::exp(-pair.friction_decay * rate);
              const double limit = mu * fn;
              if (t > limit)
                trial = (limit / t) * trial;
            }
          ft[3 * s]     = trial.x;
          ft[3 * s + 1] = trial.y;
          ft[3 * s + 2] = trial.z;
          result.friction_work -= 0.5 * dot(f_old + trial, slip);
          friction = trial;
        }
      result.max_penetration = std::max(result.max_penetration, -l);
      result.energy += 0.5 * k * l * l;
      ++result.n_active;
      return fn * nn;
    }
  } // namespace


  // @sect3{The search structure}
  //
  // An R-tree of the master nodes, rebuilt only when some master node has
  // moved more than a safety distance (half the thinnest master element)
  // since the last build. Between builds the nearest master node is still
  // found exactly: if the stale nearest node is at stale distance d0 and no
  // node has moved more than s, the true nearest node lies within stale
  // distance d0 + 2 s of the slave node, and those candidates are compared
  // at their current positions.
  struct PenaltyContact::SearchTree
  {
    bgi::rtree<Value, bgi::rstar<16>> tree;
    std::vector<double>               built;
    double                            safety = 0;
  };


  void PenaltyContact::serialize(StateArchive &ar)
  {
    for (auto &surf : surface)
      ar &surf.stiffness &surf.depth &surf.active &surf.node_stiffness &surf.node_depth;
    ar &tangential_force[0] &tangential_force[1] &previous_tangential_force;
    // The trees are rebuilt from the positions they were built with (the
    // tree over surface s serves the pass with s as master), so the resumed
    // run rebuilds them at the same steps and finds the same candidates.
    for (unsigned int s = 0; s < 2; ++s)
      if (search[s])
        {
          ar &search[s]->built &search[s]->safety;
          if (ar.is_loading() && !search[s]->built.empty())
            {
              const auto        &x = search[s]->built;
              std::vector<Value> values;
              values.reserve(surface[s].nodes.size());
              for (const unsigned int i : surface[s].nodes)
                values.emplace_back(BPoint(x[3 * i], x[3 * i + 1], x[3 * i + 2]), i);
              search[s]->tree = bgi::rtree<Value, bgi::rstar<16>>(values.begin(), values.end());
            }
        }
  }


  void PenaltyContact::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("First body", "", Patterns::Anything(),
                      "Name of the first body of the pair.");
    prm.declare_entry("Second body", "", Patterns::Anything(),
                      "Name of the second body of the pair.");
    prm.declare_entry("Penalty scale factor",
                      "0.1",
                      Patterns::Double(0.),
                      "f in the penalty stiffness k = f K A^2 / V (seed "
                      "Eq. (59)); values above 0.4 may need a smaller time "
                      "step. Units: none.");
    prm.declare_entry("Static friction coefficient",
                      "0",
                      Patterns::Double(0.),
                      "mu_s of seed Eq. (62); 0 together with the dynamic "
                      "coefficient: frictionless. Units: none.");
    prm.declare_entry("Dynamic friction coefficient",
                      "0",
                      Patterns::Double(0.),
                      "mu_d of seed Eq. (62). Units: none.");
    prm.declare_entry("Friction decay coefficient",
                      "0",
                      Patterns::Double(0.),
                      "C of seed Eq. (62), mu = mu_d + (mu_s - mu_d) "
                      "exp(-C |v|) with |v| the slip rate. Units: s/m.");
    prm.declare_entry("Normal damping",
                      "0",
                      Patterns::Double(0., 1.),
                      "Viscous damping of the normal penalty springs as a "
                      "fraction of critical, 2 sqrt(k m) with m the slave "
                      "node's mass (LS-DYNA's VDC; 0.1-0.2 settles bodies "
                      "resting on each other). The normal force never turns "
                      "tensile; the dissipated energy goes to the friction "
                      "column. Damping lowers the stable time step by the factor "
                      "sqrt(1 + xi^2) - xi (0.82 at xi = 0.2): lower 'Time "
                      "step safety factor' with it. Units: none.");
    prm.declare_entry("Symmetric",
                      "true",
                      Patterns::Bool(),
                      "Apply the node-to-segment pass in both directions "
                      "(the symmetric penalty method). If false, the second "
                      "body's nodes are the only slaves.");
  }


  void PenaltyContact::parse_parameters(dealii::ParameterHandler &prm,
                                        const std::string        &pair_name)
  {
    name           = pair_name;
    first_body     = prm.get("First body");
    second_body    = prm.get("Second body");
    penalty_factor = prm.get_double("Penalty scale factor");
    symmetric      = prm.get_bool("Symmetric");
    static_friction  = prm.get_double("Static friction coefficient");
    dynamic_friction = prm.get_double("Dynamic friction coefficient");
    friction_decay   = prm.get_double("Friction decay coefficient");
    normal_damping   = prm.get_double("Normal damping");
    if (static_friction < dynamic_friction)
      throw InputError("subsection 'Contact pair " + name +
                       "': 'Static friction coefficient' (" + std::to_string(static_friction) +
                       ") must not be below 'Dynamic friction coefficient' (" +
                       std::to_string(dynamic_friction) + ")");
    if (first_body.empty() || second_body.empty())
      throw InputError("subsection 'Contact pair " + name +
                       "': 'First body' and 'Second body' are required");
    if (first_body == second_body)
      throw InputError("subsection 'Contact pair " + name +
                       "': self-contact is not supported; name two bodies");
  }


  void PenaltyContact::setup(const std::vector<SegmentDescription> &first,
                             const std::vector<SegmentDescription> &second)
  {
    // Order nodes by reference coordinates so that the evaluation order
    // does not depend on the dof numbering (and so on the partitioning).
    // The body index is part of the key: nodes of the two bodies may
    // coincide in the reference configuration.
    std::map<std::array<double, 4>, unsigned long> by_position;
    std::map<unsigned long, bool>                  dof_on_first;
    for (unsigned int s = 0; s < 2; ++s)
      for (const auto &seg : (s == 0 ? first : second))
        for (unsigned int v = 0; v < 4; ++v)
          {
            by_position[{{double(s),
                          seg.reference_position[3 * v],
                          seg.reference_position[3 * v + 1],
                          seg.reference_position[3 * v + 2]}}] = seg.x_dof[v];
            dof_on_first[seg.x_dof[v]] = (s == 0);
          }
    dofs.clear();
    for (const auto &[p, d] : by_position)
      dofs.push_back(d);
    std::map<unsigned long, unsigned int> index;
    for (unsigned int i = 0; i < dofs.size(); ++i)
      index[dofs[i]] = i;
    on_first.resize(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      on_first[i] = dof_on_first[dofs[i]];

    for (unsigned int s = 0; s < 2; ++s)
      {
        auto segs = (s == 0 ? first : second);
        // Deterministic segment order: by the pair-node indices.
        std::vector<std::pair<std::array<unsigned int, 4>, unsigned int>> order;
        for (unsigned int k = 0; k < segs.size(); ++k)
          {
            std::array<unsigned int, 4> n;
            for (unsigned int v = 0; v < 4; ++v)
              n[v] = index[segs[k].x_dof[v]];
            order.emplace_back(n, k);
          }
        std::sort(order.begin(), order.end());
        Surface &surf = surface[s];
        surf.segments.clear();
        surf.stiffness.clear();
        surf.depth.clear();
        surf.element.clear();
        surf.active.clear();
        surf.node_segments.assign(dofs.size(), {});
        for (const auto &[n, k] : order)
          {
            surf.node_segments[n[0]].push_back(surf.segments.size());
            surf.node_segments[n[1]].push_back(surf.segments.size());
            surf.node_segments[n[2]].push_back(surf.segments.size());
            surf.node_segments[n[3]].push_back(surf.segments.size());
            surf.segments.push_back(n);
            surf.stiffness.push_back(segs[k].stiffness);
            surf.depth.push_back(segs[k].depth);
            surf.element.push_back(segs[k].element);
            surf.active.push_back(true);
          }
        surf.nodes.clear();
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (!surf.node_segments[i].empty())
            surf.nodes.push_back(i);
        tangential_force[s].assign(needs_velocities() ? 3 * dofs.size() : 0, 0.);
        surf.node_stiffness.assign(dofs.size(), 0.);
        surf.node_depth.assign(dofs.size(), 0.);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          {
            for (const unsigned int k : surf.node_segments[i])
              {
                surf.node_stiffness[i] += surf.stiffness[k] / surf.node_segments[i].size();
                surf.node_depth[i] += surf.depth[k] / surf.node_segments[i].size();
              }
          }
      }
  }


  double PenaltyContact::max_spring_frequency_squared() const
  {
    // Slave nodes of surface s meet the master stiffness of surface 1 - s
    // (or their own against a rigid master, or an analytic shape).
    double w2 = 0;
    for (unsigned int s = 0; s < 2; ++s)
      {
        if (s == 0 && !symmetric && !has_analytic(1))
          continue;
        if (has_analytic(s) || surface[s].rigid)
          continue; // a rigid surface's nodes are not slaves that matter
        const Surface &slave = surface[s], &master = surface[1 - s];
        double         k_master = 0;
        for (const double k : master.stiffness)
          k_master = std::max(k_master, k);
        for (const unsigned int i : slave.nodes)
          {
            // Against a rigid surface only the slave node moves: k / m. Between
            // deformable bodies the slave and master nodes move against each
            // other (2 k / m for equal masses), and with both passes a node is
            // held by its own spring and by the other body's (twice that).
            const bool   rigid_master = master.rigid || has_analytic(1 - s);
            const double k            = penalty_factor * (rigid_master ? slave.node_stiffness[i] : k_master);
            const double factor       = rigid_master ? 1. : (symmetric ? 4. : 2.);
            if (node_mass[i] > 0)
              w2 = std::max(w2, factor * k / node_mass[i]);
          }
      }
    return w2;
  }


  void PenaltyContact::deactivate_elements(const std::vector<unsigned long> &ids)
  {
    for (auto &surf : surface)
      for (unsigned int k = 0; k < surf.segments.size(); ++k)
        if (std::binary_search(ids.begin(), ids.end(), surf.element[k]))
          surf.active[k] = false;
  }


  ContactResult PenaltyContact::compute_forces(const std::vector<double> &x,
                                               const std::vector<double> &v,
                                               const double               dt,
                                               std::vector<double>       &f)
  {
    ContactResult result;
    // A rigid body's analytic shape: the other body's nodes against it.
    if (has_analytic(0) || has_analytic(1))
      {
        const unsigned int a = has_analytic(0) ? 0 : 1;
        analytic_pass(surface[1 - a], analytic[a], x, v, dt, f, a == 1, tangential_force[1 - a], result);
        return result;
      }
    // Pass 1: the second body's nodes against the first body's segments.
    for (unsigned int s = 0; s < 2; ++s)
      if (!search[s])
        {
          search[s] = std::make_shared<SearchTree>();
          double thinnest = 1e300;
          for (const double d : surface[s].depth)
            thinnest = std::min(thinnest, d);
          search[s]->safety = 0.5 * thinnest;
        }
    pass(surface[1], surface[0], *search[0], x, v, dt, f, false, tangential_force[1], result);
    // Pass 2 (symmetric): the first body's nodes against the second's.
    if (symmetric)
      pass(surface[0], surface[1], *search[1], x, v, dt, f, true, tangential_force[0], result);
    return result;
  }


  // @sect3{Contact with an analytic rigid shape}
  //
  // Exact geometry: the gap of each slave node is its signed distance from
  // the sphere, cylinder or plane, the normal the shape's normal there; the
  // stiffness is the slave side's (Eq. (59) with the slave element's K, A,
  // V). The reactions act on the rigid body as a resultant force and a
  // torque about its centre.
  void PenaltyContact::analytic_pass(const Surface             &slave,
                                     const AnalyticSurface     &a,
                                     const std::vector<double> &x,
                                     const std::vector<double> &v,
                                     const double               dt,
                                     std::vector<double>       &f,
                                     const bool                 slave_is_first,
                                     std::vector<double>       &ft,
                                     ContactResult             &result) const
  {
    std::vector<double> &ft_old = previous_tangential_force;
    if (needs_velocities())
      {
        ft_old.assign(ft.begin(), ft.end());
        std::fill(ft.begin(), ft.end(), 0.);
      }
    for (const unsigned int s : slave.nodes)
      {
        bool on_surface = false;
        for (const unsigned int k : slave.node_segments[s])
          on_surface |= slave.active[k];
        if (!on_surface)
          continue;
        const dealii::Point<3> xs(x[3 * s], x[3 * s + 1], x[3 * s + 2]);
        dealii::Tensor<1, 3>   normal;
        const double l = a.shape->gap(xs, a.centre, a.rotation, a.reference_centre, normal);
        if (!(l < 0) || -l > slave.node_depth[s])
          continue;
        const Vec    nn = {normal[0], normal[1], normal[2]};
        const double k  = penalty_factor * slave.node_stiffness[s];
        Vec          vr = {0, 0, 0};
        if (needs_velocities() && dt > 0)
          {
            const dealii::Tensor<1, 3> vb =
              a.velocity + cross_product_3d(a.angular_velocity, xs - a.centre);
            vr = Vec{v[3 * s] - vb[0], v[3 * s + 1] - vb[1], v[3 * s + 2] - vb[2]};
          }
        Vec       ff;
        const Vec fs = interface_forces(*this, s, l, nn, k, vr, dt,
                                        node_mass.empty() ? 0. : node_mass[s], ft_old, ft, result, ff);
        const Vec total = fs + ff;
        f[3 * s] += total.x;
        f[3 * s + 1] += total.y;
        f[3 * s + 2] += total.z;
        const dealii::Tensor<1, 3> t({total.x, total.y, total.z});
        result.shape_force -= t;
        result.shape_torque -= cross_product_3d(xs - l * normal - a.centre, t);
        const double sign = slave_is_first ? 1. : -1.;
        result.force_on_first[0] += sign * fs.x;
        result.force_on_first[1] += sign * fs.y;
        result.force_on_first[2] += sign * fs.z;
        result.friction_on_first[0] += sign * ff.x;
        result.friction_on_first[1] += sign * ff.y;
        result.friction_on_first[2] += sign * ff.z;
      }
  }


  void PenaltyContact::pass(const Surface             &slave,
                            const Surface             &master,
                            SearchTree                &search,
                            const std::vector<double> &x,
                            const std::vector<double> &v,
                            const double               dt,
                            std::vector<double>       &f,
                            const bool                 slave_is_first,
                            std::vector<double>       &ft,
                            ContactResult             &result) const
  {
    const bool needs_v = needs_velocities();
    // Friction forces of nodes that leave contact this step are released.
    std::vector<double> &ft_old = previous_tangential_force;
    if (needs_v)
      {
        ft_old.assign(ft.begin(), ft.end());
        std::fill(ft.begin(), ft.end(), 0.);
      }
    auto pos = [&](const unsigned int i) -> Vec {
      return {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    };

    // @sect4{Step (1): nearest master node}
    // The master surface's box and how far its nodes moved since the
    // search tree was built; a rebuild packs the tree in one go
    // (O(n log n)) when the motion exceeds the safety distance.
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    double max_depth = 0, drift2 = 0;
    const bool fresh = search.built.empty();
    for (const unsigned int i : master.nodes)
      {
        double d2 = 0;
        for (unsigned int d = 0; d < 3; ++d)
          {
            lo[d] = std::min(lo[d], x[3 * i + d]);
            hi[d] = std::max(hi[d], x[3 * i + d]);
            if (!fresh)
              d2 += (x[3 * i + d] - search.built[3 * i + d]) * (x[3 * i + d] - search.built[3 * i + d]);
          }
        drift2 = std::max(drift2, d2);
      }
    for (const double d : master.depth)
      max_depth = std::max(max_depth, d);
    if (master.nodes.empty())
      return;
    double drift = std::sqrt(drift2);
    if (fresh || drift > search.safety)
      {
        std::vector<Value> values;
        values.reserve(master.nodes.size());
        for (const unsigned int i : master.nodes)
          values.emplace_back(BPoint(x[3 * i], x[3 * i + 1], x[3 * i + 2]), i);
        search.tree  = bgi::rtree<Value, bgi::rstar<16>>(values.begin(), values.end());
        search.built = x;
        drift        = 0;
      }
    const auto &tree = search.tree;

    // Slave node normals: area-weighted average of the normals of the
    // slave segments around each node, in the current configuration.
    std::vector<Vec> slave_normal(x.size() / 3, Vec{0, 0, 0});
    for (unsigned int k = 0; k < slave.segments.size(); ++k)
      {
        if (!slave.active[k])
          continue;
        const auto &n = slave.segments[k];
        const Vec   a = cross(pos(n[2]) - pos(n[0]), pos(n[3]) - pos(n[1]));
        for (unsigned int j = 0; j < 4; ++j)
          slave_normal[n[j]] = slave_normal[n[j]] + a;
      }

    // Step (3), seed Eqs. (54)-(55): Newton iterations for the closest
    // point r(xi, eta) of the bilinear segment to t:
    // r_xi . (t - r) = 0, r_eta . (t - r) = 0.
    auto project = [&](const Surface &surf, const unsigned int seg, const Vec &t,
                       double &xi, double &eta) {
      const auto &n    = surf.segments[seg];
      const Vec   X[4] = {pos(n[0]), pos(n[1]), pos(n[2]), pos(n[3])};
      Vec         r_xe = {0, 0, 0};
      for (unsigned int j = 0; j < 4; ++j)
        r_xe = r_xe + (0.25 * xi_n[j] * eta_n[j]) * X[j];
      xi = eta = 0;
      for (unsigned int it = 0; it < 10; ++it)
        {
          Vec r = {0, 0, 0}, r_xi = {0, 0, 0}, r_eta = {0, 0, 0};
          for (unsigned int j = 0; j < 4; ++j)
            {
              r     = r + (0.25 * (1 + xi_n[j] * xi) * (1 + eta_n[j] * eta)) * X[j];
              r_xi  = r_xi + (0.25 * xi_n[j] * (1 + eta_n[j] * eta)) * X[j];
              r_eta = r_eta + (0.25 * eta_n[j] * (1 + xi_n[j] * xi)) * X[j];
            }
          const Vec    d   = t - r;
          const double g1  = dot(r_xi, d);
          const double g2  = dot(r_eta, d);
          const double a11 = dot(r_xi, r_xi);
          const double a22 = dot(r_eta, r_eta);
          const double a12 = dot(r_xi, r_eta) - dot(r_xe, d);
          const double det = a11 * a22 - a12 * a12;
          if (!(det > 0))
            break;
          const double dxi  = (a22 * g1 - a12 * g2) / det;
          const double deta = (a11 * g2 - a12 * g1) / det;
          xi  = std::clamp(xi + dxi, -2., 2.);
          eta = std::clamp(eta + deta, -2., 2.);
          if (std::abs(dxi) + std::abs(deta) < 1e-13)
            break;
        }
    };

    std::vector<Value> nearest;
    for (const unsigned int s : slave.nodes)
      {
        // A node whose every segment is eroded is no longer on the surface.
        if (norm(slave_normal[s]) == 0.)
          continue;
        const Vec t = pos(s);
        // Cheap rejection: outside the master surface's box by more than
        // the deepest admissible penetration.
        if (t.x < lo[0] - max_depth || t.x > hi[0] + max_depth ||
            t.y < lo[1] - max_depth || t.y > hi[1] + max_depth ||
            t.z < lo[2] - max_depth || t.z > hi[2] + max_depth)
          continue;
        nearest.clear();
        tree.query(bgi::nearest(BPoint(t.x, t.y, t.z), 1),
                   std::back_inserter(nearest));
        unsigned int m = nearest[0].second;
        if (drift > 0)
          {
            // The true nearest node is among those within d0 + 2 drift of
            // t at their build positions; compare them where they are now.
            const double d0 = bg::distance(nearest[0].first, BPoint(t.x, t.y, t.z));
            const double r  = d0 + 2. * drift;
            nearest.clear();
            tree.query(bgi::intersects(bg::model::box<BPoint>(BPoint(t.x - r, t.y - r, t.z - r),
                                                              BPoint(t.x + r, t.y + r, t.z + r))),
                       std::back_inserter(nearest));
            double best_d2 = 1e300;
            for (const auto &[p, i] : nearest)
              {
                const Vec    g  = t - pos(i);
                const double d2 = dot(g, g);
                if (d2 < best_d2 || (d2 == best_d2 && i < m))
                  {
                    best_d2 = d2;
                    m       = i;
                  }
              }
          }
        const Vec          xm = pos(m);
        const Vec          g  = t - xm;

        // @sect4{Step (2): candidate segments, seed Eqs. (50)-(53)}
        // For each segment S_i around m, C_i and C_{i+1} are its two edges
        // leaving m; S is g projected on the segment's plane. The slave
        // node may touch S_i when S lies between C_i and C_{i+1}.
        //
        // Where the test is undecided (S vanishes or lies along an edge:
        // the slave node sits over m or over an edge), the seed's Eq. (53)
        // picks the segment best aligned with g. At a convex edge that is
        // the wrong face (a node pressed into the end face of a rod would be
        // tested against the rod's side). We decide such cases instead by
        // the segment that faces the slave surface most directly, i.e. the
        // most negative n_master . n_slave, which weighs more than the
        // (50)-(52) test; and no segment facing the same way as the slave
        // surface, or nearly perpendicular to it, is ever a contact partner.
        const Vec    ns    = slave_normal[s];
        const double ns_n  = norm(ns);
        int          chosen = -1;
        double       best   = 1e300;
        double       xi_c = 0, eta_c = 0;
        for (const unsigned int seg : master.node_segments[m])
          {
            if (!master.active[seg])
              continue;
            const auto  &n = master.segments[seg];
            unsigned int k = 0;
            while (n[k] != m)
              ++k;
            const Vec    Ci  = pos(n[(k + 1) % 4]) - xm;
            const Vec    Ci1 = pos(n[(k + 3) % 4]) - xm;
            const Vec    cc  = cross(Ci, Ci1);
            const double cn  = norm(cc);
            if (cn == 0)
              continue;
            const Vec    mn     = (1. / cn) * cc; // Eq. (52)
            const Vec    S      = g - dot(g, mn) * mn; // Eq. (51)
            const double facing = ns_n > 0 ? dot(mn, ns) / ns_n : -1.;
            // A face nearly perpendicular to the slave surface is no partner:
            // "penetration" along its normal is the slave node passing under
            // a convex edge (a block sliding over a slab meets the slab's
            // nodes at its front face).
            if (facing > -0.2)
              continue;
            const bool decided = norm(S) > 1e-6 * norm(g) &&
                                 dot(cross(Ci, S), cc) > 0 &&
                                 dot(cross(Ci, S), cross(S, Ci1)) > 0;
            double xi, eta;
            project(master, seg, t, xi, eta);
            // Inside the segment first; then inside its extension by
            // 'edge_tolerance' (a node pressed against the rim of the master
            // surface stays in contact instead of flickering in and out).
            const double out    = std::max(std::abs(xi), std::abs(eta)) - 1.;
            const double score  = (out <= 1e-9 ? 0. : out <= edge_tolerance ? 5. : 100.) +
                                 (decided ? -1. : 0.) + 2. * facing;
            if (score < best)
              {
                best   = score;
                chosen = seg;
                xi_c   = xi;
                eta_c  = eta;
              }
          }
        if (chosen < 0 || best >= 50.)
          continue;

        // @sect4{Step (3): contact point, seed Eqs. (54)-(55)}
        // (solved in project() for each candidate above)
        const auto  &n   = master.segments[chosen];
        const Vec    X[4] = {pos(n[0]), pos(n[1]), pos(n[2]), pos(n[3])};
        const double xi  = xi_c;
        const double eta = eta_c;
        double       phi[4];
        Vec          r = {0, 0, 0}, r_xi = {0, 0, 0}, r_eta = {0, 0, 0};
        for (unsigned int j = 0; j < 4; ++j)
          {
            phi[j] = 0.25 * (1 + xi_n[j] * xi) * (1 + eta_n[j] * eta);
            r      = r + phi[j] * X[j];
            r_xi   = r_xi + (0.25 * xi_n[j] * (1 + eta_n[j] * eta)) * X[j];
            r_eta  = r_eta + (0.25 * eta_n[j] * (1 + xi_n[j] * xi)) * X[j];
          }

        // @sect4{Step (4): penetration, seed Eqs. (56)-(57)}
        const Vec    nc = cross(r_xi, r_eta);
        const Vec    nn = (1. / norm(nc)) * nc;
        const double l  = dot(nn, t - r);
        if (!(l < 0) || -l > master.depth[chosen])
          continue;

        // @sect4{Step (5): normal force, seed Eqs. (58)-(60)}
        // Against a rigid surface the stiffness is the slave side's (the
        // rigid body's own elements say nothing of the contact stiffness).
        const double k  = penalty_factor * (master.rigid ? slave.node_stiffness[s] : master.stiffness[chosen]);
        Vec          vr = {0, 0, 0};
        if (needs_v && dt > 0)
          {
            vr = {v[3 * s], v[3 * s + 1], v[3 * s + 2]};
            for (unsigned int j = 0; j < 4; ++j)
              vr = vr - phi[j] * Vec{v[3 * n[j]], v[3 * n[j] + 1], v[3 * n[j] + 2]};
          }
        Vec       ff;
        const Vec fs = interface_forces(*this, s, l, nn, k, vr, dt,
                                        node_mass.empty() ? 0. : node_mass[s], ft_old, ft, result, ff);
        // A force on the slave node, its reaction on the master nodes by
        // the segment's shape functions at the contact point (Eq. (60)).
        const Vec total = fs + ff;
        f[3 * s] += total.x;
        f[3 * s + 1] += total.y;
        f[3 * s + 2] += total.z;
        for (unsigned int j = 0; j < 4; ++j)
          {
            f[3 * n[j]] -= phi[j] * total.x;
            f[3 * n[j] + 1] -= phi[j] * total.y;
            f[3 * n[j] + 2] -= phi[j] * total.z;
          }
        const double sg = slave_is_first ? 1. : -1.;
        result.friction_on_first[0] += sg * ff.x;
        result.friction_on_first[1] += sg * ff.y;
        result.friction_on_first[2] += sg * ff.z;

        const double sign = slave_is_first ? 1. : -1.;
        result.force_on_first[0] += sign * fs.x;
        result.force_on_first[1] += sign * fs.y;
        result.force_on_first[2] += sign * fs.z;
      }
  }
} // namespace anvil::Contact
