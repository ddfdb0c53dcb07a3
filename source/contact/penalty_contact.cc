/**
 * @file
 * Symmetric node-to-segment penalty contact, seed section 4.3.
 */
#include <anvil/contact/penalty_contact.h>
#include <anvil/laws/seed_laws.h>

#include "penalty_contact_halo.h"
#include <anvil/utilities/input_error.h>

#include <deal.II/base/partitioner.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

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

    /** The area vector A n of a bilinear quadrilateral with cyclic
        vertices x0..x3: half the cross product of its diagonals. */
    inline Vec quad_area_vector(const Vec &x0, const Vec &x1, const Vec &x2, const Vec &x3)
    {
      return 0.5 * cross(x2 - x0, x3 - x1);
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
                         Vec                       &friction,
                         double                    *work_terms = nullptr)
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
          if (work_terms)
            work_terms[0] = fd * vn * dt;
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
              const double mu    = Laws::friction_coefficient(pair.static_friction, pair.dynamic_friction,
                                                             pair.friction_decay, rate);
              const double limit = mu * fn;
              if (t > limit)
                trial = (limit / t) * trial;
            }
          ft[3 * s]     = trial.x;
          ft[3 * s + 1] = trial.y;
          ft[3 * s + 2] = trial.z;
          result.friction_work -= 0.5 * dot(f_old + trial, slip);
          if (work_terms)
            work_terms[1] = 0.5 * dot(f_old + trial, slip);
          friction = trial;
        }
      result.max_penetration = std::max(result.max_penetration, -l);
      ++result.n_active;
      return fn * nn;
    }


    /**
     * The tributary area of node @p i of @p surf that a contact along the
     * unit normal @p nn (out of the partner surface) presses on: the
     * projection of the node's area vector, at least a tenth of its patch's
     * area (a node at a corner whose patch stands nearly edge-on to the
     * partner keeps a spring).
     */
    double tributary_area(const Surface &surf, const unsigned int i, const Vec &nn)
    {
      const double projected = -(surf.area_vector[3 * i] * nn.x + surf.area_vector[3 * i + 1] * nn.y +
                                 surf.area_vector[3 * i + 2] * nn.z);
      return std::max(projected, 0.1 * surf.node_area[i]);
    }

    /**
     * The penalty stiffness of node @p i of @p surf pressed along @p nn
     * against a rigid partner, from its own side: each segment around it
     * contributes its pressure modulus f K A / V (applied by the caller)
     * over its quarter area projected on the contact normal. A segment
     * edge-on to the partner (the side of a bar at the rim of its impact
     * face) carries no pressure and adds nothing, so a rim node is as stiff
     * per area as the face it belongs to. At least a tenth of the mean
     * modulus over the node's patch.
     */
    double own_stiffness(const Surface &surf, const unsigned int i, const Vec &nn, bool *floored = nullptr)
    {
      double k = 0;
      for (const unsigned int seg : surf.node_segments[i])
        if (surf.active[seg])
          {
            const double projected =
              -(surf.segment_area_vector[3 * seg] * nn.x + surf.segment_area_vector[3 * seg + 1] * nn.y +
                surf.segment_area_vector[3 * seg + 2] * nn.z);
            if (projected > 0)
              k += surf.modulus[seg] * 0.25 * projected;
          }
      const double floor = 0.1 * surf.node_modulus[i] * surf.node_area[i];
      if (floored)
        *floored = !(k > floor);
      return std::max(k, floor);
    }
  } // namespace


  // @sect3{The search structure}
  //
  // An R-tree of the master nodes a rank sees, rebuilt only when they
  // change or some has moved more than a safety distance (half the thinnest
  // master element) since the last build. Between builds the nearest master
  // node is still found exactly: if the stale nearest node is at stale
  // distance d0 and no node has moved more than s, the true nearest node
  // lies within stale distance d0 + 2 s of the slave node, and those
  // candidates are compared at their current positions.
  struct PenaltyContact::SearchTree
  {
    bgi::rtree<Value, bgi::rstar<16>> tree;
    /** The nodes in the tree, and their positions when it was packed (3
        per pair node; the others' entries are not used). */
    std::vector<unsigned int> nodes;
    std::vector<double>       built;
    /** Per pair node, whether it is in the tree. */
    std::vector<char> in_tree;
    double            safety = 0;
    /** Work array of the queries (kept: a step allocates nothing). */
    std::vector<Value> candidates;
  };


  // The surfaces' segments (erosion) and the work are every rank's alike;
  // each node's springs, partners, friction and gradient forces are its
  // owner's, by the node's index in the pair.
  void PenaltyContact::serialize(StateArchive &ar)
  {
    // (Onto a mesh refined or coarsened since the checkpoint, the segments
    // are new: every one starts active, the erosion is applied anew by the
    // driver, and no node keeps its partner segment.)
    const bool adapted = ar.is_loading() && ar.element_transfer() != nullptr;
    for (auto &surf : surface)
      {
        std::vector<bool> active = surf.active, dead = surf.dead;
        ar &active;
        ar &dead;
        if (!adapted)
          surf.active = active, surf.dead = dead;
      }
    ar &spring_work;
    std::uint64_t n_previous = previous_position.size();
    ar &n_previous;
    const unsigned int n_nodes    = dofs.size();
    const bool         friction   = !tangential_force[0].empty();
    const unsigned int record     = 2 * (6 + (friction ? 3 : 0)) + (n_previous > 0 ? 3 : 0);
    if (adapted && n_previous > 0)
      n_previous = 3 * n_nodes;
    if (ar.is_loading())
      previous_position.assign(n_previous, 0.);
    std::vector<std::uint64_t> index, keys;
    keyed_nodes(ar.is_loading(), index, keys);
    ar.keyed_items("nodes", keys, record, [&](const std::size_t k, RecordCursor &io) {
      const auto i = index[k];
      for (unsigned int s = 0; s < 2; ++s)
        {
          io(partner[s][i]);
          io(spring_force[s][i]);
          io(spring_depth[s][i]);
          io(geometric_force[s], 3 * i, 3);
          if (friction)
            io(tangential_force[s], 3 * i, 3);
        }
      if (n_previous > 0)
        io(previous_position, 3 * i, 3);
    }, adapted);
    if (adapted)
      for (auto &p : partner)
        std::fill(p.begin(), p.end(), -1);
    // The analytic pass's lists of the own nodes with a spring or a
    // gradient force (its old values are made anew from these at the
    // next step): every rank's joined, each rank taking its own.
    for (auto [list, table] : {std::make_pair(&springs_now, "springs"), std::make_pair(&gradients_now, "gradients")})
      {
        std::vector<std::uint64_t> joined;
        for (const auto i : *list)
          joined.push_back(node_keys[i]);
        ar.key_union(table, joined);
        if (ar.is_loading())
          {
            // (By key back to the node's index: the keys sorted with it.)
            std::vector<std::pair<std::uint64_t, unsigned int>> by_key;
            for (unsigned int i = 0; i < n_nodes; ++i)
              by_key.emplace_back(node_keys[i], i);
            std::sort(by_key.begin(), by_key.end());
            list->clear();
            for (const auto key : joined)
              {
                const auto at = std::lower_bound(by_key.begin(), by_key.end(), std::make_pair(key, 0u));
                if (at == by_key.end() || at->first != key)
                  continue;
                const unsigned int i = at->second;
                if (owned.empty() || owned[i])
                  list->push_back(i);
              }
            std::sort(list->begin(), list->end());
          }
      }
    if (ar.is_loading())
      {
        springs_before.clear();
        gradients_before.clear();
        old_spring_force.clear();
        old_spring_depth.clear();
        old_geometric_force.clear();
        near_nodes.clear();
        previous_tangential_force.clear();
        spring_load.assign(dofs.size(), 0.);
        loaded.clear();
        load_mark.assign(dofs.size(), 0);
      }
    // (The search trees are not part of the state: a resumed run packs
    // them anew, and the nearest master node does not depend on when a
    // tree was packed.)
    if (ar.is_loading())
      search[0].reset(), search[1].reset();
  }


  void PenaltyContact::declare_parameters(dealii::ParameterHandler &prm)
  {
    using namespace dealii;
    prm.declare_entry("Penalty scale factor",
                      "0.1",
                      Patterns::Double(0.),
                      "f in the penalty stiffness of seed Eq. (59), k = f K A^2 / V, "
                      "with the segment's current area A (a face that spreads "
                      "under the impact stiffens with it, as in LS-DYNA) and "
                      "per slave node scaled by its tributary area (k = f (K A "
                      "/ V) A_node, so that a node on a symmetry plane or an "
                      "edge carries its share); K, A, V of the master "
                      "segment's element, or against a rigid surface of the "
                      "slave node's own. Under a pressure p a face sinks p / "
                      "(f K) of its element's thickness (doc/theory.md). The "
                      "springs in contact lower the time step while they act "
                      "(with f = 1, for example, by about 13 % on a bar against "
                      "a rigid wall, a third between two deformable bodies). "
                      "0.1 (LS-DYNA's SLSFAC) is the best of the accuracy "
                      "study's values for two deformable bodies; against a "
                      "rigid impactor 1 was closer to the reference (the "
                      "Taylor bar's foot, Hertz) at 1.1 times the steps "
                      "(doc/accuracy.md). Units: none.");
    prm.declare_entry("Penalty stiffness",
                      "element",
                      Patterns::Selection("element|nodal mass"),
                      "'element': seed Eq. (59), k from the pressed element's "
                      "bulk modulus and size ('Penalty scale factor'); "
                      "'nodal mass': as LS-DYNA's SOFT = 1, the larger of that "
                      "and s m / dt^2 with the slave node's mass m, the last "
                      "time step dt and s = 'Mass penalty scale factor': stiff "
                      "where the nodes are heavy (a soft material against a "
                      "hard one), and a mass-based spring never lowers the "
                      "time step (with a time step safety factor of at most "
                      "0.9).");
    prm.declare_entry("Mass penalty scale factor",
                      "0.1",
                      Patterns::Double(0., 0.4),
                      "s of 'Penalty stiffness = nodal mass' (LS-DYNA's SOFSCL): "
                      "the spring's frequency is sqrt(s) / dt. Units: none.");
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
                      "body's nodes are the only slaves. Kinematic contact "
                      "between two deformable bodies balances the two passes "
                      "(the mean of their corrections, as ABAQUS/Explicit's "
                      "balanced master-slave); with a rigid body it solves "
                      "them together.");
  }


  void PenaltyContact::parse_parameters(dealii::ParameterHandler &prm)
  {
    penalty_factor     = prm.get_double("Penalty scale factor");
    mass_penalty       = prm.get("Penalty stiffness") == "nodal mass";
    mass_penalty_scale = prm.get_double("Mass penalty scale factor");
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
  }


  std::string PenaltyContact::parse_note() const
  {
    if (mass_penalty || !(penalty_factor > 0.4))
      return "";
    std::ostringstream s;
    s << "Warning: contact pair '" << name << "': penalty scale factor " << penalty_factor
      << " > 0.4 (seed section 4.3): the penalty springs need a "
         "smaller time step than the elements; the step is reduced "
         "to 2 / sqrt(omega_e^2 + omega_c^2) while they act (the run's last lines "
         "and summary.csv say how many steps they set).";
    return s.str();
  }


  void PenaltyContact::setup(const std::vector<SegmentDescription> &first,
                             const std::vector<SegmentDescription> &second)
  {
    std::map<unsigned long, unsigned int> index;
    order_pair_nodes(first, second, dofs, on_first, index);

    for (unsigned int s = 0; s < 2; ++s)
      {
        const auto &segs = (s == 0 ? first : second);
        // Deterministic segment order: by the pair-node indices.
        const auto order = order_segments(segs, index);
        Surface &surf = surface[s];
        surf.segments.clear();
        surf.bulk.clear();
        surf.volume.clear();
        surf.element.clear();
        surf.active.clear();
        surf.neighbour.clear();
        surf.dead.clear();
        surf.node_segments.assign(dofs.size(), {});
        std::map<unsigned long, std::vector<unsigned int>> element_segments;
        for (const auto &[n, k] : order)
          {
            for (unsigned int v = 0; v < 4; ++v)
              surf.node_segments[n[v]].push_back(surf.segments.size());
            element_segments[segs[k].element].push_back(surf.segments.size());
            surf.segments.push_back(n);
            surf.bulk.push_back(segs[k].bulk_modulus);
            surf.volume.push_back(segs[k].volume);
            surf.element.push_back(segs[k].element);
            surf.active.push_back(segs[k].neighbour == SegmentDescription::no_neighbour);
            surf.neighbour.push_back(segs[k].neighbour);
            surf.dead.push_back(false);
          }
        // The thickest element's reference thickness V / A.
        surf.max_reference_depth = 0;
        surf.min_reference_depth = 1e300;
        for (const auto &[n, k] : order)
          {
            const auto  &X = segs[k].reference_position;
            const double A = norm(quad_area_vector(
              {X[0], X[1], X[2]}, {X[3], X[4], X[5]}, {X[6], X[7], X[8]}, {X[9], X[10], X[11]}));
            if (A > 0)
              {
                surf.max_reference_depth = std::max(surf.max_reference_depth, segs[k].volume / A);
                surf.min_reference_depth = std::min(surf.min_reference_depth, segs[k].volume / A);
              }
          }
        surf.same_element.assign(surf.segments.size(), {});
        for (const auto &[e, list] : element_segments)
          for (const unsigned int k : list)
            for (const unsigned int j : list)
              if (j != k)
                surf.same_element[k].push_back(j);
        surf.nodes.clear();
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (!surf.node_segments[i].empty())
            surf.nodes.push_back(i);
        tangential_force[s].assign(needs_velocities() ? 3 * dofs.size() : 0, 0.);
        partner[s].assign(dofs.size(), -1);
        spring_force[s].assign(dofs.size(), 0.);
        spring_depth[s].assign(dofs.size(), 0.);
        geometric_force[s].assign(3 * dofs.size(), 0.);
        surf.area.assign(surf.segments.size(), 0.);
        surf.modulus.assign(surf.segments.size(), 0.);
        surf.segment_area_vector.assign(3 * surf.segments.size(), 0.);
        surf.area_vector.assign(3 * dofs.size(), 0.);
        surf.node_area.assign(dofs.size(), 0.);
        surf.node_modulus.assign(dofs.size(), 0.);
        surf.node_depth.assign(dofs.size(), 0.);
      }
    spring_work = 0;
  }


  void Surface::update_segment(const unsigned int k, const std::vector<double> &x)
  {
    auto pos = [&](const unsigned int i) -> Vec {
      return {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    };
    const auto  &n = segments[k];
    const Vec    a = quad_area_vector(pos(n[0]), pos(n[1]), pos(n[2]), pos(n[3]));
    const double A = norm(a);
    area[k]                        = A;
    segment_area_vector[3 * k]     = a.x;
    segment_area_vector[3 * k + 1] = a.y;
    segment_area_vector[3 * k + 2] = a.z;
    modulus[k]                     = A > 0 ? bulk[k] * A / volume[k] : 0.;
  }


  void Surface::update_node(const unsigned int i)
  {
    double       av[3] = {0, 0, 0}, sum_area = 0, sum_modulus = 0, sum_depth = 0;
    unsigned int count = 0;
    for (const unsigned int k : node_segments[i])
      if (active[k])
        {
          for (unsigned int d = 0; d < 3; ++d)
            av[d] += 0.25 * segment_area_vector[3 * k + d];
          sum_area += 0.25 * area[k];
          sum_modulus += modulus[k];
          sum_depth += area[k] > 0 ? volume[k] / area[k] : 0.;
          ++count;
        }
    for (unsigned int d = 0; d < 3; ++d)
      area_vector[3 * i + d] = av[d];
    node_area[i]    = sum_area;
    node_modulus[i] = count > 0 ? sum_modulus / count : 0.;
    node_depth[i]   = count > 0 ? sum_depth / count : 0.;
  }


  // @sect3{The current geometry}
  //
  // Seed Eq. (59) sets a segment's stiffness from its element, k = f K A^2
  // / V. Evaluated once in the reference configuration, a face that spreads
  // to five times its area under a Taylor impact keeps the stiffness of the
  // small face, so each of its nodes carries five times the load on the
  // same spring and sinks about an element deep. Here A is the current area
  // (V stays the reference volume: plastic flow keeps it, and the elastic
  // change under a contact pressure p is p / K, a few per cent at most), so
  // the penetration under a pressure p stays l / h = p / (f K) of the
  // element's current thickness h = V / A. Written per unit area, the
  // spring is a pressure p = f (K A / V) l; a slave node carries it over its
  // tributary area, the projection on the contact normal of the area
  // vector sum A_k n_k / 4 of the segments around it, so that an interior
  // node of a regular mesh has k = f K A^2 / V as in Eq. (59), a node on an
  // edge or a symmetry plane half of it, and a quarter model carries a
  // quarter of the full model's force.
  //
  // Against an analytic shape only the nodes within reach of it need this
  // (@p near; the column struck by a hammer has a few hundred of its
  // thousands of surface nodes there): their segments and their sums are
  // refreshed, nothing else.
  void PenaltyContact::update_geometry(const unsigned int               s,
                                       const std::vector<double>       &x,
                                       const std::vector<unsigned int> *near)
  {
    Surface &surf    = surface[s];
    auto     segment = [&](const unsigned int k) { surf.update_segment(k, x); };
    auto     node    = [&](const unsigned int i) { surf.update_node(i); };
    if (near == nullptr)
      {
        for (unsigned int k = 0; k < surf.segments.size(); ++k)
          if (surf.active[k])
            segment(k);
        for (const unsigned int i : surf.nodes)
          node(i);
        return;
      }
    surf.seen.resize(surf.segments.size(), 0);
    surf.touched.clear();
    for (const unsigned int i : *near)
      for (const unsigned int k : surf.node_segments[i])
        if (surf.active[k] && !surf.seen[k])
          {
            surf.seen[k] = 1;
            surf.touched.push_back(k);
            segment(k);
          }
    for (const unsigned int i : *near)
      node(i);
    for (const unsigned int k : surf.touched)
      surf.seen[k] = 0;
  }


  // An eroded element's faces leave; the interior faces it exposes on
  // the elements that live join (eroding contact).
  // The springs this changes (those of the nodes on a changed segment,
  // or pressed against one) are booked at the next evaluation
  // (topology_energy).
  void PenaltyContact::deactivate_elements(const std::vector<unsigned long> &ids)
  {
    bool any = false;
    for (auto &surf : surface)
      {
        if (!topology_pending)
          surf.changed.assign(surf.segments.size(), 0);
        for (unsigned int k = 0; k < surf.segments.size(); ++k)
          {
            const auto [active, dead] =
              segment_after_erosion(surf.element[k], surf.neighbour[k], ids, surf.active[k], surf.dead[k]);
            if (active != surf.active[k])
              surf.changed[k] = 1, any = true;
            surf.active[k] = active;
            surf.dead[k]   = dead;
          }
      }
    if (!any)
      return;
    for (unsigned int s = 0; s < 2; ++s)
      {
        if (!topology_pending)
          topology_node[s].assign(dofs.size(), 0);
        const Surface &own = surface[s], &other = surface[1 - s];
        for (unsigned int i = 0; i < dofs.size(); ++i)
          {
            for (const unsigned int k : own.node_segments[i])
              topology_node[s][i] |= own.changed[k];
            if (i < partner[s].size() && partner[s][i] >= 0)
              topology_node[s][i] |= other.changed[partner[s][i]];
          }
      }
    topology_pending = true;
  }


  // The work terms of pass @p s's own springs that appeared or vanished
  // with an erosion (topology_term()).
  double PenaltyContact::topology_step(const unsigned int s) const
  {
    double energy = 0;
    if (topology_pending)
      for (const unsigned int i : halo->own_nodes[s])
        energy += topology_term(s, i, last_spring_force[s][i], spring_force[s][i], last_spring_depth[s][i],
                                spring_depth[s][i]);
    return energy;
  }


  // @sect3{The springs' share of the stable step}
  //
  // The springs in reach of a partner form a stiffness K_c = sum k w w^T
  // (times n n^T) over the pair's nodes. By Gershgorin's theorem over node
  // blocks, the highest frequency it adds is at most max_a sum_springs k
  // |w_a| sum_b |w_b| / m_a: per node, from the springs that actually act
  // on it, with its own mass (a light master node under a heavy slave's
  // spring counts, and a stiff face far from the contact does not). With
  // the elements' omega_e, omega^2 <= omega_e^2 + omega_c^2 (the simulator's
  // stable step). On a regular mesh of equal masses this gives 4 k / m with
  // both passes, 2 k / m with one, k / m against a rigid surface.
  double PenaltyContact::stable_frequency_squared() const
  {
    double w2 = 0;
    for (const unsigned int i : loaded)
      if (spring_load[i] > 0 && i < node_mass.size() && node_mass[i] > 0)
        w2 = std::max(w2, spring_load[i] / node_mass[i]);
    return w2;
  }


  namespace
  {
    // Start a step's gradient forces of a pass from zero, keeping last
    // step's for the work.
    void start_pass(std::vector<double> &current, std::vector<double> &old)
    {
      old.assign(current.begin(), current.end());
      std::fill(current.begin(), current.end(), 0.);
    }
  } // namespace


  ContactResult PenaltyContact::compute_forces(const std::vector<double> &x,
                                               const std::vector<double> &v,
                                               const double               dt,
                                               std::vector<double>       &f)
  {
    ContactResult result;
    if (dt > 0)
      penalty_dt = dt;
    // A rigid body's analytic shape: the other body's nodes against it
    // (which refreshes the geometry near the shape; it clears its own
    // nodes' spring loads).
    if (has_analytic(0) || has_analytic(1))
      {
        spring_load.resize(dofs.size(), 0.);
        const unsigned int a = has_analytic(0) ? 0 : 1;
        analytic_pass(1 - a, x, v, dt, f, result);
        result.energy    = spring_work;
        topology_pending = false;
        return result;
      }

    // Two meshes. A pair no rank shares out (a rigid body's mesh) is
    // evaluated whole by every rank, on the gathered positions.
    if (!halo)
      setup_halo(MPI_COMM_SELF, nullptr);
    const Halo &h = *halo;
    spring_load.resize(dofs.size(), 0.);
    load_mark.resize(dofs.size(), 0);
    for (const unsigned int i : loaded)
      {
        spring_load[i] = 0;
        load_mark[i]   = 0;
      }
    loaded.clear();
    // The geometry this rank sees; the segments within reach of its slave
    // nodes from the other ranks.
    exchange_halo(x, v);
    const std::vector<double> &xh = h.n_ranks > 1 ? h.x : x;
    const std::vector<double> &vh = h.n_ranks > 1 ? h.v : v;
    for (unsigned int s = 0; s < 2; ++s)
      if (!search[s])
        {
          search[s]         = std::make_shared<SearchTree>();
          search[s]->safety = 0.5 * surface[s].min_reference_depth;
        }
    const bool rigid = surface[0].rigid || surface[1].rigid;
    if (rigid)
      for (unsigned int s = 0; s < 2; ++s)
        start_pass(geometric_force[s], last_geometric_force[s]);
    touches.clear();
    touch_normals.clear();
    // Pass 1: the second body's nodes against the first body's segments.
    pass(1, *search[0], xh, vh, dt, result);
    // Pass 2 (symmetric): the first body's nodes against the second's.
    if (symmetric)
      pass(0, *search[1], xh, vh, dt, result);
    exchange_touches();
    apply_touches(xh, f);

    // A spring that starts on a segment an erosion has just exposed.
    if (topology_pending)
      for (const unsigned int s : {1u, symmetric ? 0u : 1u})
        for (const unsigned int i : h.own_nodes[s])
          if (last_spring_force[s][i] == 0 && spring_force[s][i] != 0 && partner[s][i] >= 0 &&
              surface[1 - s].changed[partner[s][i]])
            topology_node[s][i] = 1;
    double topology = topology_step(1) + (symmetric ? topology_step(0) : 0.);
    double work     = spring_work_step(1) + (symmetric ? spring_work_step(0) : 0.);
    if (rigid)
      {
        // The gradient forces' work needs this step's positions next step.
        work += gradient_work_step(1, x) + (symmetric ? gradient_work_step(0, x) : 0.);
        previous_position = x;
      }
    result.frequency_squared = stable_frequency_squared();
    result.n_springs_across_partitions = h.sent_touches;
    if (h.n_ranks > 1)
      {
        // The pair's sums and maxima over the ranks (the sums to round-off
        // of the order of one process; the motion does not depend on them).
        double sums[12] = {result.force_on_first[0], result.force_on_first[1], result.force_on_first[2],
                           result.friction_on_first[0], result.friction_on_first[1],
                           result.friction_on_first[2], result.friction_work, work, double(result.n_active),
                           double(result.n_passed_through), double(result.n_springs_across_partitions),
                           topology};
        double maxima[4] = {result.frequency_squared, result.max_penetration, result.max_penetration_ratio,
                            result.passed_through_ratio};
        MPI_Allreduce(MPI_IN_PLACE, sums, 12, MPI_DOUBLE, MPI_SUM, h.comm);
        MPI_Allreduce(MPI_IN_PLACE, maxima, 4, MPI_DOUBLE, MPI_MAX, h.comm);
        for (unsigned int d = 0; d < 3; ++d)
          {
            result.force_on_first[d]    = sums[d];
            result.friction_on_first[d] = sums[3 + d];
          }
        result.friction_work               = sums[6];
        work                               = sums[7];
        result.n_active                    = static_cast<unsigned int>(sums[8]);
        result.n_passed_through            = static_cast<unsigned int>(sums[9]);
        result.n_springs_across_partitions = static_cast<unsigned int>(sums[10]);
        topology                           = sums[11];
        result.frequency_squared           = maxima[0];
        result.max_penetration             = maxima[1];
        result.max_penetration_ratio       = maxima[2];
        result.passed_through_ratio        = maxima[3];
      }
    spring_work += work;
    result.energy          = spring_work;
    result.topology_energy = topology;
    topology_pending       = false;
    return result;
  }


  // The touches' forces and spring loads on this rank's nodes. Each node's
  // sum is made in the order of one process (by pass, then by slave node),
  // from the touches of every rank that evaluated a slave node next to it:
  // the forces do not depend on the number of processes, bit for bit.
  void PenaltyContact::apply_touches(const std::vector<double> &x, std::vector<double> &f)
  {
    const bool all_mine = owned.empty();
    auto       mine     = [&](const unsigned int i) { return all_mine || owned[i] != 0; };
    auto       load     = [&](const unsigned int i, const double value) {
      if (!load_mark[i])
        {
          load_mark[i] = 1;
          loaded.push_back(i);
        }
      spring_load[i] += value;
    };
    const std::vector<Touch> *list = &touches;
    if (!halo->received.empty())
      {
        auto &all = halo->received;
        all.insert(all.end(), touches.begin(), touches.end());
        std::sort(all.begin(), all.end(), [](const Touch &a, const Touch &b) { return a.key < b.key; });
        list = &all;
      }
    const unsigned long n = dofs.size();
    for (std::size_t q = 0; q < list->size(); ++q)
      {
        const Touch       &t           = (*list)[q];
        const unsigned int slave_index = 1 - static_cast<unsigned int>(t.key / n);
        const unsigned int node        = t.key % n;
        const Surface     &slave       = surface[slave_index];
        const Surface     &master      = surface[1 - slave_index];
        const auto        &nodes       = master.segments[t.segment];
        // The spring's weight sum |w_a| sum_b |w_b| (see pass()).
        const double w_sum = (slave.rigid ? 0. : 1.) +
                             (master.rigid ? 0. :
                                             std::abs(t.phi[0]) + std::abs(t.phi[1]) + std::abs(t.phi[2]) +
                                               std::abs(t.phi[3]));
        if (!slave.rigid && mine(node))
          load(node, t.k * w_sum);
        if (!master.rigid)
          for (unsigned int j = 0; j < 4; ++j)
            if (mine(nodes[j]))
              load(nodes[j], t.k * std::abs(t.phi[j]) * w_sum);
        if (!(t.flags & 1))
          continue;
        if (mine(node))
          for (unsigned int d = 0; d < 3; ++d)
            f[3 * node + d] += t.force[d];
        if (t.flags & 2) // (a rigid body's mesh: every rank evaluates the whole pair, in order)
          {
            const auto &g = touch_normals[q];
            add_stiffness_gradient(slave_index, node, g[1], g[2], g[3], g[0], x, f);
          }
        for (unsigned int j = 0; j < 4; ++j)
          if (mine(nodes[j]))
            for (unsigned int d = 0; d < 3; ++d)
              f[3 * nodes[j] + d] -= t.phi[j] * t.force[d];
      }
    halo->received.clear();
  }


  // The work on a pass's springs over the step, by the trapezoidal rule in
  // the penetration l (the energy of every other force in Anvil is booked
  // the same way): 1/2 (f^{n-1} + f^n)(l^n - l^{n-1}), with f = l = 0 for a
  // node out of contact. With a constant stiffness the sum telescopes to
  // 1/2 k l^2; with a stiffness that follows the geometry it is the work
  // the springs actually took, so the energy balance stays closed.
  double PenaltyContact::spring_work_step(const unsigned int s) const
  {
    const auto &f1 = spring_force[s], &l1 = spring_depth[s];
    const auto &f0 = last_spring_force[s], &l0 = last_spring_depth[s];
    double      work = 0;
    for (const unsigned int i : halo->own_nodes[s])
      if (f1[i] != 0 || f0[i] != 0)
        work += 0.5 * (f0[i] + f1[i]) * (l1[i] - l0[i]);
    return work;
  }


  // The gradient forces of add_stiffness_gradient() over the nodes' motion
  // (every rank evaluates such a pair whole).
  double PenaltyContact::gradient_work_step(const unsigned int s, const std::vector<double> &x) const
  {
    const auto &g1 = geometric_force[s], &g0 = last_geometric_force[s];
    double      work = 0;
    if (previous_position.size() == x.size() && g0.size() == g1.size())
      for (const unsigned int i : surface[s].nodes)
        for (unsigned int d = 0; d < 3; ++d)
          if (g1[3 * i + d] != 0 || g0[3 * i + d] != 0)
            work -= 0.5 * (g0[3 * i + d] + g1[3 * i + d]) * (x[3 * i + d] - previous_position[3 * i + d]);
    return work;
  }


  // @sect3{A stiffness that follows the geometry, as a potential}
  //
  // Against a rigid surface the spring of slave node i is the potential
  // 1/2 kappa_i(x) l^2 with kappa_i = f sum_seg (K / 4 V) |a| (-a . n) over
  // its segments' area vectors a = (x_2 - x_0) x (x_3 - x_1) / 2
  // (own_stiffness). Its force on the slave nodes is the normal force
  // -kappa l grad l and, besides, -1/2 l^2 grad kappa: a face that spreads
  // while pressed into the wall feels its springs' resistance to spreading.
  // Without that term the springs were not conservative: loaded while the
  // face was small and unloaded once it had spread, they gave back more
  // than they took (2.6 % of the impact energy of the shipped Taylor bar at
  // f = 0.1). With it the contact energy returns to zero when the bar
  // leaves the wall. The term sums to zero over the nodes (kappa does not
  // change under translation), so momentum is kept; the normal n of the
  // rigid surface is held fixed in the derivative.
  namespace
  {
    /**
     * d kappa / d x_j of the four nodes of segment @p seg of @p surf (the
     * segment's share of kappa_i, pressed along @p nn), from d a = (d x_2 -
     * d x_0) x d2 / 2 + d1 x (d x_3 - d x_1) / 2. False if the segment
     * adds nothing (edge-on, or of no area).
     */
    bool stiffness_gradient(const Surface             &surf,
                            const unsigned int         seg,
                            const Vec                 &nn,
                            const double               penalty_factor,
                            const std::vector<double> &x,
                            Vec                        dk[4])
    {
      auto pos = [&](const unsigned int j) -> Vec {
        return {x[3 * j], x[3 * j + 1], x[3 * j + 2]};
      };
      const Vec    a    = {surf.segment_area_vector[3 * seg], surf.segment_area_vector[3 * seg + 1],
                           surf.segment_area_vector[3 * seg + 2]};
      const double A    = norm(a);
      const double proj = -dot(a, nn);
      if (!(proj > 0) || !(A > 0))
        return false;
      const double c     = penalty_factor * surf.bulk[seg] / (4. * surf.volume[seg]);
      const Vec    dk_da = c * ((proj / A) * a - A * nn);
      const auto  &n     = surf.segments[seg];
      const Vec    d1    = pos(n[2]) - pos(n[0]);
      const Vec    d2    = pos(n[3]) - pos(n[1]);
      const Vec    k2    = 0.5 * cross(d2, dk_da);
      const Vec    k3    = 0.5 * cross(dk_da, d1);
      dk[0]              = -1. * k2;
      dk[1]              = -1. * k3;
      dk[2]              = k2;
      dk[3]              = k3;
      return true;
    }
  } // namespace


  void PenaltyContact::add_stiffness_gradient(const unsigned int         slave_index,
                                              const unsigned int         i,
                                              const double               nx,
                                              const double               ny,
                                              const double               nz,
                                              const double               l,
                                              const std::vector<double> &x,
                                              std::vector<double>       &f)
  {
    const Surface &surf = surface[slave_index];
    auto          &g    = geometric_force[slave_index];
    const Vec      nn   = {nx, ny, nz};
    for (const unsigned int seg : surf.node_segments[i])
      {
        Vec dk[4];
        if (!surf.active[seg] || !stiffness_gradient(surf, seg, nn, penalty_factor, x, dk))
          continue;
        const auto &n = surf.segments[seg];
        for (unsigned int j = 0; j < 4; ++j)
          {
            const Vec F = (-0.5 * l * l) * dk[j];
            f[3 * n[j]] += F.x;
            f[3 * n[j] + 1] += F.y;
            f[3 * n[j] + 2] += F.z;
            g[3 * n[j]] += F.x;
            g[3 * n[j] + 1] += F.y;
            g[3 * n[j] + 2] += F.z;
          }
      }
  }


  // @sect3{Contact with an analytic rigid shape}
  //
  // Exact geometry: the gap of each slave node is its signed distance from
  // the sphere, cylinder or plane, the normal the shape's normal there; the
  // stiffness is the slave side's (Eq. (59) with the slave element's K, A,
  // V, over the node's tributary area). The reactions act on the rigid body
  // as a resultant force and a torque about its centre.
  //
  // Each rank evaluates the slave nodes it owns (distribute()), on the
  // positions of its own and ghost cells; nothing of the pair is gathered.
  // The result does not depend on the number of processes, bit for bit:
  // - a node's force is summed by its owner in the order of one process
  //   (by slave node, then by segment), from its own spring and the
  //   gradient terms of the springs around it; a neighbour on another rank
  //   sends its spring's state (in contact, l, n) through a ghost exchange
  //   of the slave nodes next to the rank's own;
  // - the pair's sums (the rigid body's force and torque, the work) are
  //   replayed on every rank from all ranks' per-node terms, gathered (the
  //   nodes in contact only) and put in that same order.
  struct PenaltyContact::Exchange
  {
    /** Per slave node, 6 slots at 2 x-dof .. 2 x-dof + 5: in contact
        (1; 2 with the gradient term), l, n. Owned: the rank's own range. */
    dealii::LinearAlgebra::distributed::Vector<double> state;
    /** The first owned dof. */
    unsigned long first_dof = 0;
    /** The slave nodes of other ranks next to this rank's own, and the
        local index of their first slot. */
    std::vector<unsigned int> ghosts, ghost_local;
    /** The own nodes whose slots were written last step. */
    std::vector<unsigned int> written;
  };


  bool PenaltyContact::distribute(MPI_Comm comm, const dealii::IndexSet &owned_dofs)
  {
    // Two meshes: each rank its own slave nodes against the master
    // segments of its halo; a rigid body's mesh (its nodes' gradient terms
    // reach past the halo) is evaluated whole by every rank.
    const bool meshes = !has_analytic(0) && !has_analytic(1);
    if (meshes && (surface[0].rigid || surface[1].rigid))
      return false;
    communicator = comm;
    owned.assign(dofs.size(), 0);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      owned[i] = owned_dofs.is_element(dofs[i]);
    if (meshes)
      {
        setup_halo(comm, &owned_dofs);
        return true;
      }
    contact_state.assign(dofs.size(), {});
    target_mark.assign(dofs.size(), 0);
    state_nodes.clear();
    own_slave_nodes.clear();
    for (const unsigned int i : surface[has_analytic(0) ? 1 : 0].nodes)
      if (owned[i])
        own_slave_nodes.push_back(i);
    exchange.reset();
    if (dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
      return true;
    AssertThrow(owned_dofs.is_contiguous(), dealii::ExcMessage("contact: the owned dofs are not contiguous"));
    const Surface &slave = surface[has_analytic(0) ? 1 : 0];
    std::vector<char> needed(dofs.size(), 0);
    for (const auto &n : slave.segments)
      if (owned[n[0]] || owned[n[1]] || owned[n[2]] || owned[n[3]])
        for (const unsigned int i : n)
          if (!owned[i])
            needed[i] = 1;
    exchange = std::make_shared<Exchange>();
    const dealii::types::global_dof_index size = 2 * owned_dofs.size();
    dealii::IndexSet                       own(size), ghost(size);
    if (owned_dofs.n_elements() > 0)
      {
        exchange->first_dof = owned_dofs.nth_index_in_set(0);
        own.add_range(2 * exchange->first_dof, 2 * (exchange->first_dof + owned_dofs.n_elements()));
      }
    for (unsigned int i = 0; i < dofs.size(); ++i)
      if (needed[i])
        {
          ghost.add_range(2 * dofs[i], 2 * dofs[i] + 6);
          exchange->ghosts.push_back(i);
        }
    auto partitioner = std::make_shared<dealii::Utilities::MPI::Partitioner>(own, ghost, comm);
    exchange->state.reinit(partitioner);
    for (const unsigned int i : exchange->ghosts)
      exchange->ghost_local.push_back(partitioner->global_to_local(2 * dofs[i]));
    return true;
  }


  void PenaltyContact::analytic_pass(const unsigned int         slave_index,
                                     const std::vector<double> &x,
                                     const std::vector<double> &v,
                                     const double               dt,
                                     std::vector<double>       &f,
                                     ContactResult             &result)
  {
    Surface               &slave          = surface[slave_index];
    const AnalyticSurface &a              = analytic[1 - slave_index];
    const bool             slave_is_first = slave_index == 0;
    std::vector<double>   &ft             = tangential_force[slave_index];
    std::vector<double>   &ft_old         = previous_tangential_force;
    std::vector<double>   &g              = geometric_force[slave_index];
    const bool             all_mine       = owned.empty();
    auto                   mine = [&](const unsigned int i) { return all_mine || owned[i] != 0; };
    const bool             needs_v        = needs_velocities();
    if (contact_state.size() != dofs.size())
      {
        contact_state.assign(dofs.size(), {});
        target_mark.assign(dofs.size(), 0);
      }
    if (old_spring_force.size() != dofs.size())
      {
        old_spring_force.assign(dofs.size(), 0.);
        old_spring_depth.assign(dofs.size(), 0.);
        old_geometric_force.assign(3 * dofs.size(), 0.);
        if (needs_v)
          ft_old.assign(3 * dofs.size(), 0.);
        springs_before.clear();
        gradients_before.clear();
      }
    if (owned.empty() && own_slave_nodes.empty())
      own_slave_nodes = slave.nodes; // never distributed: every node is own
    // This step's springs start from zero, last step's become the old
    // ones (the work, the friction's history): only the nodes that had a
    // spring or a gradient force in the last two steps are touched (as
    // pass() does for its own nodes).
    {
      // Entries (width per node) of the nodes @p before are cleared in
      // @p old, those of @p now move from @p current to @p old.
      auto shift = [](const std::vector<unsigned int> &before, const std::vector<unsigned int> &now,
                      std::vector<double> &current, std::vector<double> &old, const unsigned int width) {
        for (const unsigned int i : before)
          for (unsigned int d = 0; d < width; ++d)
            old[width * i + d] = 0;
        for (const unsigned int i : now)
          for (unsigned int d = 0; d < width; ++d)
            {
              old[width * i + d]     = current[width * i + d];
              current[width * i + d] = 0;
            }
      };
      shift(springs_before, springs_now, spring_force[slave_index], old_spring_force, 1);
      shift(springs_before, springs_now, spring_depth[slave_index], old_spring_depth, 1);
      if (needs_v)
        shift(springs_before, springs_now, ft, ft_old, 3);
      springs_before.swap(springs_now);
      springs_now.clear();
      shift(gradients_before, gradients_now, g, old_geometric_force, 3);
      gradients_before.swap(gradients_now);
      gradients_now.clear();
    }
    // The own nodes within twice the thickest element's reference thickness
    // of the shape; the geometry of those only.
    for (const unsigned int s : near_nodes)
      spring_load[s] = 0;
    near_nodes.clear();
    near_gaps.clear();
    for (const unsigned int s : own_slave_nodes)
        {
          const dealii::Point<3> xs(x[3 * s], x[3 * s + 1], x[3 * s + 2]);
          dealii::Tensor<1, 3>   normal;
          const double l = a.shape->gap(xs, a.centre, a.rotation, a.reference_centre, normal);
          if (l < 2. * slave.max_reference_depth)
            {
              near_nodes.push_back(s);
              near_gaps.push_back({{l, normal[0], normal[1], normal[2]}});
            }
        }
    update_geometry(slave_index, x, &near_nodes);

    // The springs of the own nodes. Per node in contact a record of its
    // terms in the pair's sums: node, the two work terms, the force on the
    // shape, its torque, normal and friction force (16 numbers).
    for (const unsigned int s : state_nodes)
      contact_state[s] = {};
    state_nodes.clear();
    records.assign(header_size, 0.);
    ContactResult own;
    for (unsigned int c = 0; c < near_nodes.size(); ++c)
      {
        const unsigned int s = near_nodes[c];
        if (!(slave.node_area[s] > 0)) // every segment around it eroded
          continue;
        const dealii::Point<3> xs(x[3 * s], x[3 * s + 1], x[3 * s + 2]);
        const dealii::Tensor<1, 3> normal({near_gaps[c][1], near_gaps[c][2], near_gaps[c][3]});
        const double               l     = near_gaps[c][0];
        const double               depth = slave.node_depth[s];
        if (!(l < depth) || -l > depth)
          continue;
        const Vec    nn = {normal[0], normal[1], normal[2]};
        bool         floored = false;
        bool         bounds_step = true;
        const double k           = spring_stiffness(
          s, penalty_factor * own_stiffness(slave, s, nn, &floored), floored, bounds_step);
        spring_load[s] += bounds_step ? k : 0.; // the shape does not move with the spring
        if (!(l < 0))
          continue;
        Vec vr = {0, 0, 0};
        if (needs_velocities() && dt > 0)
          {
            const dealii::Tensor<1, 3> vb =
              a.velocity + cross_product_3d(a.angular_velocity, xs - a.centre);
            vr = Vec{v[3 * s] - vb[0], v[3 * s + 1] - vb[1], v[3 * s + 2] - vb[2]};
          }
        spring_force[slave_index][s] = -k * l;
        spring_depth[slave_index][s] = -l;
        own.max_penetration_ratio    = std::max(own.max_penetration_ratio, -l / depth);
        Vec       ff;
        double    work[2] = {0, 0};
        const Vec fs      = interface_forces(*this, s, l, nn, k, vr, dt, node_mass.empty() ? 0. : node_mass[s],
                                        ft_old, ft, own, ff, work);
        const Vec total   = fs + ff;
        contact_state[s]  = {{floored ? 1. : 2., l, nn.x, nn.y, nn.z, total.x, total.y, total.z}};
        state_nodes.push_back(s);
        springs_now.push_back(s);
        const dealii::Tensor<1, 3> t({total.x, total.y, total.z});
        const dealii::Tensor<1, 3> torque = cross_product_3d(xs - l * normal - a.centre, t);
        records.insert(records.end(), {double(s), work[0], work[1], t[0], t[1], t[2], torque[0], torque[1],
                                       torque[2], fs.x, fs.y, fs.z, ff.x, ff.y, ff.z, 0.});
      }
    const unsigned int n_own_contact = state_nodes.size();

    // The springs of the neighbours on other ranks (their state).
    if (exchange)
      {
        auto &state = exchange->state;
        state.zero_out_ghost_values();
        for (const unsigned int s : exchange->written)
          for (unsigned int k = 0; k < 6; ++k)
            state.local_element(2 * (dofs[s] - exchange->first_dof) + k) = 0;
        exchange->written.assign(state_nodes.begin(), state_nodes.end());
        for (const unsigned int s : state_nodes)
          for (unsigned int k = 0; k < 5; ++k)
            state.local_element(2 * (dofs[s] - exchange->first_dof) + k) = contact_state[s][k];
        state.update_ghost_values();
        for (unsigned int q = 0; q < exchange->ghosts.size(); ++q)
          if (state.local_element(exchange->ghost_local[q]) == 2.)
            {
              const unsigned int s = exchange->ghosts[q];
              for (unsigned int k = 0; k < 5; ++k)
                contact_state[s][k] = state.local_element(exchange->ghost_local[q] + k);
              state_nodes.push_back(s);
            }
      }

    // The forces of the own nodes: the own spring, and the gradient terms
    // -1/2 l^2 grad kappa (add_stiffness_gradient()) of the springs around
    // them, summed by slave node and segment as one process would.
    targets.clear();
    auto mark = [&](const unsigned int j) {
      if (mine(j) && !target_mark[j])
        {
          target_mark[j] = 1;
          targets.push_back(j);
        }
    };
    for (unsigned int q = 0; q < state_nodes.size(); ++q)
      {
        const unsigned int s = state_nodes[q];
        if (q < n_own_contact)
          mark(s);
        if (contact_state[s][0] != 2.)
          continue;
        for (const unsigned int seg : slave.node_segments[s])
          if (slave.active[seg])
            {
              const auto &n = slave.segments[seg];
              if (q >= n_own_contact) // a neighbour's segment: its geometry where it touches ours
                {
                  if (!(mine(n[0]) || mine(n[1]) || mine(n[2]) || mine(n[3])))
                    continue;
                  slave.update_segment(seg, x);
                }
              for (const unsigned int j : n)
                mark(j);
            }
      }
    gradients_now.assign(targets.begin(), targets.end());
    for (const unsigned int j : targets)
      {
        target_mark[j] = 0;
        candidates.assign(1, j);
        for (const unsigned int seg : slave.node_segments[j])
          for (const unsigned int i : slave.segments[seg])
            candidates.push_back(i);
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        for (const unsigned int s : candidates)
          {
            const auto &st = contact_state[s];
            if (s == j && st[0] != 0)
              for (unsigned int d = 0; d < 3; ++d)
                f[3 * j + d] += st[5 + d];
            if (st[0] != 2.)
              continue;
            const Vec    nn = {st[2], st[3], st[4]};
            const double l  = st[1];
            for (const unsigned int seg : slave.node_segments[s])
              {
                if (!slave.active[seg])
                  continue;
                const auto        &n  = slave.segments[seg];
                const unsigned int kk = std::find(n.begin(), n.end(), j) - n.begin();
                Vec                dk[4];
                if (kk == 4 || !stiffness_gradient(slave, seg, nn, penalty_factor, x, dk))
                  continue;
                const Vec F = (-0.5 * l * l) * dk[kk];
                f[3 * j] += F.x;
                f[3 * j + 1] += F.y;
                f[3 * j + 2] += F.z;
                g[3 * j] += F.x;
                g[3 * j + 1] += F.y;
                g[3 * j + 2] += F.z;
              }
          }
      }

    // The own terms of the springs' work (spring_work_step()), over the
    // nodes with a spring or a gradient force in this step or the last
    // (the replay puts them in order).
    const std::size_t n_contact = (records.size() - header_size) / contact_record_size;
    {
      const auto &f1 = spring_force[slave_index], &l1 = spring_depth[slave_index];
      for (const auto *list : {&springs_now, &springs_before})
        for (const unsigned int i : *list)
          if (!target_mark[i] && (f1[i] != 0 || old_spring_force[i] != 0))
            {
              target_mark[i] = 1;
              records.insert(records.end(), {double(i), 0.5 * (old_spring_force[i] + f1[i]) *
                                                          (l1[i] - old_spring_depth[i])});
              records[8] += topology_term(slave_index, i, old_spring_force[i], f1[i], old_spring_depth[i], l1[i]);
            }
      for (const auto *list : {&springs_now, &springs_before})
        for (const unsigned int i : *list)
          target_mark[i] = 0;
    }
    const std::size_t n_spring = (records.size() - header_size - contact_record_size * n_contact) / 2;
    if (previous_position.size() == x.size())
      {
        for (const auto *list : {&gradients_now, &gradients_before})
          for (const unsigned int i : *list)
            if (!target_mark[i])
              {
                target_mark[i] = 1;
                for (unsigned int d = 0; d < 3; ++d)
                  if (g[3 * i + d] != 0 || old_geometric_force[3 * i + d] != 0)
                    records.insert(records.end(),
                                   {double(3 * i + d), 0.5 * (old_geometric_force[3 * i + d] + g[3 * i + d]) *
                                                         (x[3 * i + d] - previous_position[3 * i + d])});
              }
        for (const auto *list : {&gradients_now, &gradients_before})
          for (const unsigned int i : *list)
            target_mark[i] = 0;
      }
    const std::size_t n_geometric =
      (records.size() - header_size - contact_record_size * n_contact - 2 * n_spring) / 2;
    // The positions the gradient forces' work needs next step (the own
    // nodes'; compute_forces() keeps all of them between two meshes).
    if (previous_position.size() != x.size())
      previous_position.assign(x.size(), 0.);
    for (const unsigned int i : own_slave_nodes)
      for (unsigned int d = 0; d < 3; ++d)
        previous_position[3 * i + d] = x[3 * i + d];
    double w2 = 0;
    for (const unsigned int i : near_nodes)
      if (spring_load[i] > 0 && i < node_mass.size() && node_mass[i] > 0)
        w2 = std::max(w2, spring_load[i] / node_mass[i]);
    records[0] = w2;
    records[1] = own.max_penetration;
    records[2] = own.max_penetration_ratio;
    records[3] = own.n_active;
    records[4] = n_contact;
    records[5] = n_spring;
    records[6] = n_geometric;
    records[7] = state_nodes.size() - n_own_contact;
    replay_records(slave_is_first, result);
  }


  // The pair's sums from every rank's records, in the order of one
  // process: the maxima and counts, then per node in contact (by node) its
  // work, force, torque; then the springs' work by node.
  void PenaltyContact::replay_records(const bool slave_is_first, ContactResult &result)
  {
    const double *all   = records.data();
    unsigned int  ranks = 1;
    if (exchange)
      {
        ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
        int n = records.size();
        record_counts.resize(ranks);
        record_offsets.resize(ranks);
        MPI_Allgather(&n, 1, MPI_INT, record_counts.data(), 1, MPI_INT, communicator);
        int total = 0;
        for (unsigned int r = 0; r < ranks; ++r)
          {
            record_offsets[r] = total;
            total += record_counts[r];
          }
        gathered.resize(total);
        MPI_Allgatherv(records.data(), n, MPI_DOUBLE, gathered.data(), record_counts.data(),
                       record_offsets.data(), MPI_DOUBLE, communicator);
        all = gathered.data();
      }
    // Per rank, where its three kinds of record start.
    order.clear();
    double frequency_squared = 0;
    for (unsigned int r = 0; r < ranks; ++r)
      {
        const double *h = all + (exchange ? record_offsets[r] : 0);
        frequency_squared            = std::max(frequency_squared, h[0]);
        result.max_penetration       = std::max(result.max_penetration, h[1]);
        result.max_penetration_ratio = std::max(result.max_penetration_ratio, h[2]);
        result.n_active += static_cast<unsigned int>(h[3]);
        const std::size_t c = h[4], sp = h[5], ge = h[6];
        result.n_springs_across_partitions += static_cast<unsigned int>(h[7]);
        result.topology_energy += h[8];
        const std::size_t base    = (h - all) + header_size;
        const std::size_t springs = base + contact_record_size * c, geometric = springs + 2 * sp;
        for (std::size_t q = 0; q < c; ++q)
          order.emplace_back(0, all[base + contact_record_size * q], base + contact_record_size * q);
        for (std::size_t q = 0; q < sp; ++q)
          order.emplace_back(1, all[springs + 2 * q], springs + 2 * q);
        for (std::size_t q = 0; q < ge; ++q)
          order.emplace_back(2, all[geometric + 2 * q], geometric + 2 * q);
      }
    std::sort(order.begin(), order.end());
    const double sign = slave_is_first ? 1. : -1.;
    for (const auto &[kind, key, at] : order)
      {
        const double *r = all + static_cast<std::size_t>(at);
        if (kind == 0)
          {
            result.friction_work -= r[1];
            result.friction_work -= r[2];
            for (unsigned int d = 0; d < 3; ++d)
              {
                result.shape_force[d] -= r[3 + d];
                result.shape_torque[d] -= r[6 + d];
                result.force_on_first[d] += sign * r[9 + d];
                result.friction_on_first[d] += sign * r[12 + d];
              }
          }
        else if (kind == 1)
          spring_work += r[1];
        else
          spring_work -= r[1];
      }
    result.frequency_squared = frequency_squared;
  }


  void PenaltyContact::pass(const unsigned int         slave_index,
                            SearchTree                &search,
                            const std::vector<double> &x,
                            const std::vector<double> &v,
                            const double               dt,
                            ContactResult             &result)
  {
    Surface             &slave          = surface[slave_index];
    const unsigned int   master_index   = 1 - slave_index;
    const Surface       &master         = surface[master_index];
    const Halo          &h              = *halo;
    const bool           slave_is_first = slave_index == 0;
    const bool           needs_v        = needs_velocities();
    std::vector<double> &ft             = tangential_force[slave_index];
    std::vector<int>    &partners       = partner[slave_index];
    const auto          &own            = h.own_nodes[slave_index];
    // This step's springs (and friction forces) of the own nodes start
    // from zero; last step's are kept for the work and the friction's
    // history. (Those of a node that leaves contact are released.)
    std::vector<double> &ft_old = previous_tangential_force;
    auto shift = [&](std::vector<double> &current, std::vector<double> &old, const unsigned int width) {
      if (old.size() != current.size())
        old.assign(current.size(), 0.);
      for (const unsigned int i : own)
        for (unsigned int d = 0; d < width; ++d)
          {
            old[width * i + d]     = current[width * i + d];
            current[width * i + d] = 0;
          }
    };
    if (needs_v)
      shift(ft, ft_old, 3);
    shift(spring_force[slave_index], last_spring_force[slave_index], 1);
    shift(spring_depth[slave_index], last_spring_depth[slave_index], 1);
    auto pos = [&](const unsigned int i) -> Vec {
      return {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    };

    // @sect4{Step (1): nearest master node}
    // The tree over the master nodes this rank sees, kept while they are
    // the same and none has moved more than the safety distance since it
    // was packed (O(n log n)).
    const auto &tree_nodes = h.nodes[master_index];
    if (tree_nodes.empty())
      {
        for (const unsigned int s : own)
          partners[s] = -1;
        return;
      }
    double drift = 0;
    bool   build = search.nodes != tree_nodes;
    if (!build)
      {
        double drift2 = 0;
        for (const unsigned int i : tree_nodes)
          {
            double d2 = 0;
            for (unsigned int d = 0; d < 3; ++d)
              d2 += (x[3 * i + d] - search.built[3 * i + d]) * (x[3 * i + d] - search.built[3 * i + d]);
            drift2 = std::max(drift2, d2);
          }
        drift = std::sqrt(drift2);
        build = drift > search.safety;
      }
    if (build)
      {
        std::vector<Value> values;
        values.reserve(tree_nodes.size());
        search.built.resize(x.size());
        for (const unsigned int i : tree_nodes)
          {
            values.emplace_back(BPoint(x[3 * i], x[3 * i + 1], x[3 * i + 2]), i);
            for (unsigned int d = 0; d < 3; ++d)
              search.built[3 * i + d] = x[3 * i + d];
          }
        search.tree = bgi::rtree<Value, bgi::rstar<16>>(values.begin(), values.end());
        search.in_tree.resize(dofs.size(), 0);
        for (const unsigned int i : search.nodes)
          search.in_tree[i] = 0;
        for (const unsigned int i : tree_nodes)
          search.in_tree[i] = 1;
        search.nodes = tree_nodes;
        drift        = 0;
      }
    const auto  &tree      = search.tree;
    const double *lo       = h.box[master_index], *hi = h.box[master_index] + 3;
    const double max_depth = h.max_depth[master_index];
    const double reach     = h.reach[master_index];

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

    auto &nearest = search.candidates;
    // Per slave node, its nearest master node of the last step (a guess).
    std::vector<unsigned int> &guess = nearest_guess[slave_index];
    guess.resize(dofs.size(), ~0u);
    const unsigned long key_base = static_cast<unsigned long>(master_index) * dofs.size();
    for (const unsigned int s : own)
      {
        const int previous = partners[s];
        partners[s]        = -1;
        const Vec t        = pos(s);
        // Cheap rejection: outside the master surface's box by more than
        // the deepest admissible penetration.
        if (t.x < lo[0] - max_depth || t.x > hi[0] + max_depth ||
            t.y < lo[1] - max_depth || t.y > hi[1] + max_depth ||
            t.z < lo[2] - max_depth || t.z > hi[2] + max_depth)
          continue;
        // The node's tributary area and the like (its segments' geometry
        // is made); a node whose every segment is eroded is no longer on
        // the surface.
        slave.update_node(s);
        if (!(slave.node_area[s] > 0))
          continue;
        // The nearest master node, exactly, and of equally near ones the
        // lowest. A node at current distance d (last step's nearest, if the
        // tree holds it) bounds the true nearest one's packing distance by
        // d + drift; else the tree's nearest node d0 (at its packing
        // positions) bounds it by d0 + 2 drift. Those candidates are
        // compared where they are now. The choice does not depend on the
        // tree or the guess, so not on which nodes a rank sees beyond the
        // reach, nor on when the tree was packed.
        unsigned int m     = guess[s];
        double       bound = 0;
        if (m < search.in_tree.size() && search.in_tree[m])
          {
            const Vec g = t - pos(m);
            bound       = std::sqrt(dot(g, g)) + drift;
          }
        else
          {
            nearest.clear();
            tree.query(bgi::nearest(BPoint(t.x, t.y, t.z), 1), std::back_inserter(nearest));
            if (nearest.empty())
              continue;
            m     = nearest[0].second;
            bound = bg::distance(nearest[0].first, BPoint(t.x, t.y, t.z)) + 2. * drift;
          }
        {
          const double r = bound * (1. + 1e-12);
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
          guess[s] = m;
          // Beyond the reach of every master node: no segment is within
          // reach either (Halo).
          if (!(best_d2 <= reach * reach))
            continue;
        }

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
        //
        // Two more candidates make the search hold through thin walls. The
        // segment that held the node last step stays a candidate: once a
        // node has passed the middle of a wall one element thick, its
        // nearest master node is on the back face, whose segments face
        // away. And where the segments around m give no partner, the other
        // faces of their elements are tried (the front face of that wall).
        const Vec    ns    = {slave.area_vector[3 * s], slave.area_vector[3 * s + 1],
                              slave.area_vector[3 * s + 2]};
        const double ns_n  = norm(ns);
        int          chosen = -1;
        double       best   = 1e300;
        double       xi_c = 0, eta_c = 0;
        auto consider = [&](const unsigned int seg) {
          if (!master.active[seg])
            return;
          if (!h.sees(master_index, seg))
            return; // beyond the reach (Halo): not in this rank's halo
          const auto  &n = master.segments[seg];
          // The two edges at the segment's node nearest to t (m, where m
          // is one of its nodes).
          unsigned int k = 0;
          double       d_min = 1e300;
          for (unsigned int j = 0; j < 4; ++j)
            {
              const Vec    gj = t - pos(n[j]);
              const double dj = n[j] == m ? -1. : dot(gj, gj);
              if (dj < d_min)
                {
                  d_min = dj;
                  k     = j;
                }
            }
          const Vec    xk  = pos(n[k]);
          const Vec    gk  = t - xk;
          const Vec    Ci  = pos(n[(k + 1) % 4]) - xk;
          const Vec    Ci1 = pos(n[(k + 3) % 4]) - xk;
          const Vec    cc  = cross(Ci, Ci1);
          const double cn  = norm(cc);
          if (cn == 0)
            return;
          const Vec    mn     = (1. / cn) * cc;         // Eq. (52)
          const Vec    S      = gk - dot(gk, mn) * mn;  // Eq. (51)
          const double facing = ns_n > 0 ? dot(mn, ns) / ns_n : -1.;
          // A face nearly perpendicular to the slave surface is no partner:
          // "penetration" along its normal is the slave node passing under
          // a convex edge (a block sliding over a slab meets the slab's
          // nodes at its front face).
          if (facing > -0.2)
            return;
          const bool decided = norm(S) > 1e-6 * norm(gk) &&
                               dot(cross(Ci, S), cc) > 0 &&
                               dot(cross(Ci, S), cross(S, Ci1)) > 0;
          double xi, eta;
          project(master, seg, t, xi, eta);
          // Inside the segment first; then inside its extension by
          // 'edge_tolerance' (a node pressed against the rim of the master
          // surface stays in contact instead of flickering in and out).
          const double out   = std::max(std::abs(xi), std::abs(eta)) - 1.;
          const double score = (out <= 1e-9 ? 0. : out <= edge_tolerance ? 5. : 100.) +
                               (decided ? -1. : 0.) + 2. * facing;
          if (score < best)
            {
              best   = score;
              chosen = seg;
              xi_c   = xi;
              eta_c  = eta;
            }
        };
        for (const unsigned int seg : master.node_segments[m])
          consider(seg);
        if (previous >= 0)
          {
            const auto &around = master.node_segments[m];
            if (std::find(around.begin(), around.end(), (unsigned int)previous) == around.end())
              consider(previous);
          }
        if (chosen < 0 || best >= 50.)
          for (const unsigned int seg : master.node_segments[m])
            for (const unsigned int other : master.same_element[seg])
              consider(other);
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
        const Vec    nc    = cross(r_xi, r_eta);
        const Vec    nn    = (1. / norm(nc)) * nc;
        const double l     = dot(nn, t - r);
        const double depth = master.volume[chosen] / master.area[chosen];
        if (-l > depth && previous >= 0)
          {
            // A node held last step that is now deeper than the element it
            // pressed on: it has passed through the master surface between
            // two steps (the springs could not stop it). It would leave
            // contact silently; the run stops instead (Simulator).
            ++result.n_passed_through;
            result.passed_through_ratio = std::max(result.passed_through_ratio, -l / depth);
          }
        if (!(l < depth) || -l > depth)
          continue;

        // @sect4{Step (5): normal force, seed Eqs. (58)-(60)}
        // The pressure stiffness f K A / V of the master segment's element
        // over the slave node's tributary area; against a rigid surface the
        // slave side's (the rigid body's own elements say nothing of the
        // contact stiffness).
        bool         floored = true;
        bool         bounds_step = true;
        const double k           = spring_stiffness(
          s,
          penalty_factor * (master.rigid ? own_stiffness(slave, s, nn, &floored) :
                                           master.modulus[chosen] * tributary_area(slave, s, nn)),
          floored,
          bounds_step);
        // The stable step: a node within the thickness of its partner's
        // element may be in contact by the next step, so its spring counts
        // (see stable_frequency_squared()): the spring k (n . (u_s - sum_j
        // phi_j u_j))^2 adds k |w_a| sum_b |w_b| to the row of each of its
        // nodes a, with w = (1, -phi_j) over the nodes that move (a rigid
        // body's do not: its mass is the body's). apply_touches() adds it.
        Touch touch;
        touch.key     = key_base + s;
        touch.segment = chosen;
        touch.flags   = 0;
        for (unsigned int j = 0; j < 4; ++j)
          touch.phi[j] = phi[j];
        touch.k        = bounds_step ? k : 0.; // (mass-based springs do not bound the step)
        touch.force[0] = touch.force[1] = touch.force[2] = 0;
        if (master.rigid || slave.rigid)
          touch_normals.push_back({{l, nn.x, nn.y, nn.z}});
        if (!(l < 0))
          {
            touches.push_back(touch);
            continue;
          }
        partners[s] = chosen;
        spring_force[slave_index][s] = -k * l;
        spring_depth[slave_index][s] = -l;
        // The thickness of the element the spring stands for: the master's,
        // or against a rigid surface the slave's own.
        result.max_penetration_ratio =
          std::max(result.max_penetration_ratio, -l / (master.rigid ? slave.node_depth[s] : depth));
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
        // the segment's shape functions at the contact point (Eq. (60)),
        // applied by apply_touches().
        const Vec total = fs + ff;
        touch.force[0]  = total.x;
        touch.force[1]  = total.y;
        touch.force[2]  = total.z;
        touch.flags     = floored ? 1 : 3; // against a rigid surface, the gradient term
        touches.push_back(touch);
        const double sign = slave_is_first ? 1. : -1.;
        result.friction_on_first[0] += sign * ff.x;
        result.friction_on_first[1] += sign * ff.y;
        result.friction_on_first[2] += sign * ff.z;
        result.force_on_first[0] += sign * fs.x;
        result.force_on_first[1] += sign * fs.y;
        result.force_on_first[2] += sign * fs.z;
      }
  }


  ANVIL_REGISTER_CONTACT_ALGORITHM(PenaltyContact,
                                   "penalty",
                                   "symmetric node-to-segment penalty contact with Coulomb friction "
                                   "(seed section 4.3); its entries are the pair's own.")
} // namespace anvil::Contact
