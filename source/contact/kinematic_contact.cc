/**
 * @file
 * Kinematic contact enforcement (contact/kinematic_contact.h).
 */
#include <anvil/contact/kinematic_contact.h>
#include <anvil/laws/seed_laws.h>
#include <anvil/utilities/input_error.h>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace anvil::Contact
{
  namespace bg  = boost::geometry;
  namespace bgi = boost::geometry::index;

  namespace
  {
    using BPoint = bg::model::point<double, 3, bg::cs::cartesian>;
    using BBox   = bg::model::box<BPoint>;
    using Vec    = std::array<double, 3>;

    inline Vec at(const std::vector<double> &x, const unsigned int i)
    {
      return {{x[3 * i], x[3 * i + 1], x[3 * i + 2]}};
    }
    inline double dot(const Vec &a, const Vec &b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }
    inline Vec cross(const Vec &a, const Vec &b)
    {
      return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
    }

    /** The cross product of a face's diagonals @p d1 = x2 - x0 and @p d2 =
        x3 - x1 (outward, twice the area of a flat face). */
    inline Vec diagonals_normal(const std::vector<double> &x, const std::array<unsigned int, 4> &q, Vec &d1, Vec &d2)
    {
      for (unsigned int d = 0; d < 3; ++d)
        {
          d1[d] = x[3 * q[2] + d] - x[3 * q[0] + d];
          d2[d] = x[3 * q[3] + d] - x[3 * q[1] + d];
        }
      return cross(d1, d2);
    }

    /**
     * The point of the bilinear quadrilateral @p X (cyclic corners at
     * (xi, eta) = (-1,-1), (1,-1), (1,1), (-1,1)) nearest to @p p, by
     * Gauss-Newton from the centre: its shape functions, and the outward
     * unit normal there (t_xi x t_eta). Returns false if the nearest point
     * lies outside the face.
     */
    bool project(const std::array<Vec, 4> &X, const Vec &p, std::array<double, 4> &phi, Vec &normal,
                 Vec &foot)
    {
      constexpr double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
      double           xi = 0, eta = 0;
      Vec              t1{}, t2{};
      for (unsigned int it = 0; it < 12; ++it)
        {
          foot = {{0, 0, 0}}, t1 = {{0, 0, 0}}, t2 = {{0, 0, 0}};
          for (unsigned int a = 0; a < 4; ++a)
            {
              const double N  = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
              const double Nx = 0.25 * sx[a] * (1 + sy[a] * eta);
              const double Ny = 0.25 * sy[a] * (1 + sx[a] * xi);
              for (unsigned int d = 0; d < 3; ++d)
                {
                  foot[d] += N * X[a][d];
                  t1[d] += Nx * X[a][d];
                  t2[d] += Ny * X[a][d];
                }
            }
          const Vec    r   = {{foot[0] - p[0], foot[1] - p[1], foot[2] - p[2]}};
          const double a11 = dot(t1, t1), a12 = dot(t1, t2), a22 = dot(t2, t2);
          const double b1 = -dot(t1, r), b2 = -dot(t2, r);
          const double det = a11 * a22 - a12 * a12;
          if (!(det > 0))
            return false;
          const double dxi = (b1 * a22 - b2 * a12) / det, deta = (a11 * b2 - a12 * b1) / det;
          xi  = std::clamp(xi + dxi, -2., 2.);
          eta = std::clamp(eta + deta, -2., 2.);
          if (std::abs(dxi) + std::abs(deta) < 1e-13)
            break;
        }
      // A node just beyond a face's edge (1 % of its width) still takes it:
      // where the faces of the two bodies end together (two rods' ends
      // widening under the impact), an edge node would otherwise slip
      // behind the other face unseen for a step.
      constexpr double extension = 0.02;
      if (std::abs(xi) > 1 + extension || std::abs(eta) > 1 + extension)
        return false;
      xi  = std::clamp(xi, -1., 1.);
      eta = std::clamp(eta, -1., 1.);
      foot = {{0, 0, 0}}, t1 = {{0, 0, 0}}, t2 = {{0, 0, 0}};
      for (unsigned int a = 0; a < 4; ++a)
        {
          phi[a]          = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
          const double Nx = 0.25 * sx[a] * (1 + sy[a] * eta);
          const double Ny = 0.25 * sy[a] * (1 + sx[a] * xi);
          for (unsigned int d = 0; d < 3; ++d)
            {
              foot[d] += phi[a] * X[a][d];
              t1[d] += Nx * X[a][d];
              t2[d] += Ny * X[a][d];
            }
        }
      normal           = cross(t1, t2);
      const double len = std::sqrt(dot(normal, normal));
      if (!(len > 0))
        return false;
      for (auto &c : normal)
        c /= len;
      return true;
    }
  } // namespace


  void KinematicContact::declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Kinematic tolerance",
                      "1e-10",
                      dealii::Patterns::Double(0., 1e-2),
                      "'Algorithm = kinematic': the corrections of a step "
                      "are iterated (projected Gauss-Seidel over the pair's "
                      "constraints) until none moves a node by more than this "
                      "fraction of the thinnest element's thickness; the "
                      "penetration left at the end of a step is of this order. "
                      "Units: none.");
  }


  void KinematicContact::parse_parameters(dealii::ParameterHandler &prm)
  {
    symmetric        = prm.get_bool("Symmetric");
    static_friction  = prm.get_double("Static friction coefficient");
    dynamic_friction = prm.get_double("Dynamic friction coefficient");
    friction_decay   = prm.get_double("Friction decay coefficient");
    tolerance        = prm.get_double("Kinematic tolerance");
    if (static_friction < dynamic_friction)
      throw InputError("subsection 'Contact pair " + name +
                       "': 'Static friction coefficient' (" + std::to_string(static_friction) +
                       ") must not be below 'Dynamic friction coefficient' (" +
                       std::to_string(dynamic_friction) + ")");
    // The penalty's own entries would be ignored here: a scene that sets
    // one was written for the penalty.
    const bool damping   = prm.get_double("Normal damping") > 0;
    const bool factor    = prm.get_double("Penalty scale factor") != 0.1;
    const bool stiffness = prm.get("Penalty stiffness") != "element";
    const bool mass      = prm.get_double("Mass penalty scale factor") != 0.1;
    if (damping || factor || stiffness || mass)
      throw InputError("subsection 'Contact pair " + name + "': '" +
                       (damping   ? "Normal damping" :
                        factor    ? "Penalty scale factor" :
                        stiffness ? "Penalty stiffness" :
                                    "Mass penalty scale factor") +
                       "' is for 'Algorithm = penalty'; this pair's contact is kinematic (no "
                       "springs; 'automatic' chooses it): set 'Algorithm = penalty' to use the "
                       "entry, or remove it");
  }


  // The nodes in an order fixed by (body, reference coordinates), the
  // segments by their nodes: the same on any number of processes.
  void KinematicContact::setup(const std::vector<SegmentDescription> &first,
                               const std::vector<SegmentDescription> &second)
  {
    std::map<unsigned long, unsigned int> index;
    order_pair_nodes(first, second, dofs, on_first, index);
    for (unsigned int s = 0; s < 2; ++s)
      {
        const auto &segs = (s == 0 ? first : second);
        const auto order = order_segments(segs, index);
        Surface &surf = surface[s];
        surf.segments.clear(), surf.element.clear(), surf.active.clear(), surf.depth.clear();
        surf.neighbour.clear(), surf.dead.clear();
        surf.max_depth = 0, surf.min_depth = 1e300;
        std::vector<char> on_surface(dofs.size(), 0);
        for (const auto &[n, k] : order)
          {
            const auto &X = segs[k].reference_position;
            std::array<Vec, 4> corners;
            for (unsigned int v = 0; v < 4; ++v)
              corners[v] = {{X[3 * v], X[3 * v + 1], X[3 * v + 2]}};
            const Vec d1 = {{corners[2][0] - corners[0][0], corners[2][1] - corners[0][1],
                             corners[2][2] - corners[0][2]}};
            const Vec d2 = {{corners[3][0] - corners[1][0], corners[3][1] - corners[1][1],
                             corners[3][2] - corners[1][2]}};
            const Vec    c = cross(d1, d2);
            const double A = 0.5 * std::sqrt(dot(c, c));
            const double h = A > 0 ? segs[k].volume / A : 0.;
            surf.segments.push_back(n);
            surf.element.push_back(segs[k].element);
            surf.active.push_back(segs[k].neighbour == SegmentDescription::no_neighbour ? 1 : 0);
            surf.neighbour.push_back(segs[k].neighbour);
            surf.dead.push_back(0);
            surf.depth.push_back(h);
            surf.max_depth = std::max(surf.max_depth, h);
            if (h > 0)
              surf.min_depth = std::min(surf.min_depth, h);
            for (const unsigned int i : n)
              on_surface[i] = 1;
          }
        surf.nodes.clear();
        for (unsigned int i = 0; i < dofs.size(); ++i)
          if (on_surface[i])
            surf.nodes.push_back(i);
      }
    previous_force.assign(3 * dofs.size(), 0.);
    previous_position.assign(3 * dofs.size(), 0.);
    has_previous = false;
    work         = 0;
  }


  void KinematicContact::set_hanging_nodes(const std::vector<std::vector<std::pair<unsigned int, double>>> &masters)
  {
    hanging.clear();
    dependants.clear();
    if (std::all_of(masters.begin(), masters.end(), [](const auto &m) { return m.empty(); }))
      return;
    hanging = masters;
    dependants.assign(masters.size(), {});
    for (unsigned int i = 0; i < masters.size(); ++i)
      for (const auto &[j, w] : masters[i])
        dependants[j].push_back(i);
  }


  // As PenaltyContact's: an eroded element's faces leave, the interior
  // faces it exposes on living elements join.
  void KinematicContact::deactivate_elements(const std::vector<unsigned long> &ids)
  {
    for (auto &surf : surface)
      for (unsigned int k = 0; k < surf.segments.size(); ++k)
        {
          const auto [active, dead] =
            segment_after_erosion(surf.element[k], surf.neighbour[k], ids, surf.active[k], surf.dead[k]);
          surf.active[k] = active;
          surf.dead[k]   = dead;
        }
  }


  // The stream holds what every rank holds alike; the last correction's
  // forces and positions of each node go by its scene vertex (node_keys),
  // so that a run refined or coarsened since (a new mesh, new pair nodes)
  // finds the nodes it kept. A new node has no last correction: its
  // position is left unknown (NaN), and the first step's work takes its
  // motion over the step before from its velocity.
  void KinematicContact::serialize(StateArchive &ar)
  {
    const bool adapted = ar.is_loading() && ar.element_transfer() != nullptr;
    for (auto &surf : surface)
      {
        std::vector<char> active = surf.active, dead = surf.dead;
        ar &active;
        ar &dead;
        if (!adapted)
          surf.active = active, surf.dead = dead;
      }
    ar &previous_shape_load &previous_centre &has_previous &work &last_result;
    const unsigned int         n_nodes = dofs.size();
    if (ar.is_loading())
      {
        previous_force.assign(3 * n_nodes, 0.);
        previous_position.assign(3 * n_nodes, 0.);
      }
    std::vector<std::uint64_t> index, keys;
    keyed_nodes(ar.is_loading(), index, keys);
    ar.keyed_items("nodes", keys, 7, [&](const std::size_t k, RecordCursor &io) {
      const auto i     = index[k];
      double     known = 1;
      io(known);
      io(previous_force, 3 * i, 3);
      io(previous_position, 3 * i, 3);
      if (known == 0)
        for (unsigned int d = 0; d < 3; ++d)
          previous_position[3 * i + d] = std::numeric_limits<double>::quiet_NaN();
    }, adapted);
  }


  // @sect3{The correction of one step}
  ContactResult KinematicContact::correct(const std::vector<double> &x,
                                          const std::vector<double> &v,
                                          const std::vector<double> &f,
                                          const std::vector<double> &w,
                                          const double               dt_previous,
                                          const double               dt_next,
                                          std::vector<double>       &f_contact)
  {
    ContactResult result;
    const unsigned int n_nodes = dofs.size();
    // The last call of a run (dt = 0) makes the forces of a step like the
    // one before.
    const double dt     = dt_next > 0 ? dt_next : dt_previous;
    const double dt_avg = 0.5 * (dt_previous + dt);
    if (!(dt > 0) || !(dt_avg > 0))
      return last_result = result;

    // The predicted motion without this pair's forces.
    std::vector<double> &xp = predicted;
    xp.resize(3 * n_nodes);
    for (unsigned int j = 0; j < 3 * n_nodes; ++j)
      xp[j] = x[j] + dt * (v[j] + dt_avg * f[j] * w[j]);
    // A hanging node (on a refinement interface) has no mass of its own
    // (w = 0, its forces condensed onto its masters): its place is its
    // masters', before and after every correction.
    const auto follow = [&](const unsigned int i) {
      for (unsigned int d = 0; d < 3; ++d)
        {
          double value = 0;
          for (const auto &[j, weight] : hanging[i])
            value += weight * xp[3 * j + d];
          xp[3 * i + d] = value;
        }
    };
    const auto follow_all = [&]() {
      for (unsigned int i = 0; i < hanging.size(); ++i)
        if (!hanging[i].empty())
          follow(i);
    };
    follow_all();
    std::array<Vec, 2> centre{};
    for (unsigned int s = 0; s < 2; ++s)
      if (analytic[s].shape)
        for (unsigned int d = 0; d < 3; ++d)
          centre[s][d] = analytic[s].centre[d] + dt * analytic[s].velocity[d];
    auto shape_gap = [&](const unsigned int s, const Vec &p, Vec &normal) {
      dealii::Tensor<1, 3> n;
      const double         g = analytic[s].shape->gap(dealii::Point<3>(p[0], p[1], p[2]),
                                                      dealii::Point<3>(centre[s][0], centre[s][1], centre[s][2]),
                                                      analytic[s].rotation,
                                                      analytic[s].reference_centre,
                                                      n);
      normal = {{n[0], n[1], n[2]}};
      return g;
    };

    // Two deformable surfaces: the passes are balanced (below).
    const bool balanced = symmetric && !surface[0].rigid && !surface[1].rigid && !analytic[0].shape &&
                          !analytic[1].shape;

    // The constraints: each pass's slave nodes behind the other surface.
    constraints.clear();
    for (const unsigned int slave_surface : {1u, 0u})
      {
        const unsigned int m = 1 - slave_surface;
        if ((slave_surface == 0 && !symmetric && !analytic[1].shape) || analytic[slave_surface].shape)
          continue;
        const Surface &slaves = surface[slave_surface], &masters = surface[m];
        // Solved together (a rigid surface in the pair), the second pass
        // leaves out the nodes the first already holds (a master node of a
        // first-pass constraint with phi >= 1/2): where the meshes match,
        // the two passes' constraints coincide, and Gauss-Seidel converges
        // slowly on nearly parallel ones. Balanced passes are solved apart.
        std::vector<char> held(slave_surface == 0 && !balanced ? dofs.size() : 0, 0);
        for (const auto &c : constraints)
          for (unsigned int a = 0; a < c.n_master && !held.empty(); ++a)
            if (c.phi[a] >= 0.5)
              held[c.master[a]] = 1;
        if (analytic[m].shape)
          {
            for (const unsigned int i : slaves.nodes)
              {
                Vec          n;
                const double g = shape_gap(m, at(xp, i), n);
                if (g < 0 && -g <= slaves.max_depth)
                  {
                    Constraint c{};
                    c.slave    = i;
                    c.n_master = 0;
                    c.normal   = n;
                    c.on_first = slave_surface == 0;
                    constraints.push_back(c);
                  }
              }
            continue;
          }
        // Each face's candidate box: where a node it takes can lie, the
        // face swept behind itself by the depth the test below accepts
        // (half its element's thickness), with a margin of a quarter of the
        // face's size and of that depth all round (the test's 2 % beyond
        // the edges, a warped face's normals). A box grown by the whole
        // depth in every direction held some 25 faces of a wall of 2.5 mm
        // faces 5 mm thick for each node near it, 24 of which then failed
        // the projection (doc/performance.md, "Kinematic contact's
        // candidates").
        std::vector<std::pair<BBox, unsigned int>> boxes;
        for (unsigned int k = 0; k < masters.segments.size(); ++k)
          if (masters.active[k])
            {
              const auto  &q = masters.segments[k];
              Vec          d1, d2;
              const Vec    c     = diagonals_normal(xp, q, d1, d2);
              const double len   = std::sqrt(dot(c, c));
              const double reach = 0.5 * masters.depth[k];
              const double margin =
                0.25 * (std::sqrt(std::max(dot(d1, d1), dot(d2, d2))) + reach);
              Vec lo{{1e300, 1e300, 1e300}}, hi{{-1e300, -1e300, -1e300}};
              for (const unsigned int a : q)
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    // (A degenerate face, no normal: the depth all round.)
                    const double behind = len > 0 ? xp[3 * a + d] - reach * c[d] / len : xp[3 * a + d];
                    const double r      = len > 0 ? 0. : reach;
                    lo[d] = std::min({lo[d], xp[3 * a + d] - r, behind});
                    hi[d] = std::max({hi[d], xp[3 * a + d] + r, behind});
                  }
              boxes.emplace_back(BBox(BPoint(lo[0] - margin, lo[1] - margin, lo[2] - margin),
                                      BPoint(hi[0] + margin, hi[1] + margin, hi[2] + margin)),
                                 k);
            }
        if (boxes.empty())
          continue;
        const bgi::rtree<std::pair<BBox, unsigned int>, bgi::quadratic<16>> tree(boxes.begin(), boxes.end());
        // Each slave node's outward normal, the sum of its faces' unit
        // normals in the predicted motion: a face of the other body is a
        // contact only where the two face each other.
        slave_normal.assign(dofs.size(), Vec{{0, 0, 0}});
        for (unsigned int k = 0; k < slaves.segments.size(); ++k)
          if (slaves.active[k])
            {
              const auto  &q = slaves.segments[k];
              Vec          d1, d2;
              const Vec    c   = diagonals_normal(xp, q, d1, d2);
              const double len = std::sqrt(dot(c, c));
              if (len > 0)
                for (const unsigned int a : q)
                  for (unsigned int d = 0; d < 3; ++d)
                    slave_normal[a][d] += c[d] / len;
            }
        std::vector<std::pair<BBox, unsigned int>> found;
        for (const unsigned int i : slaves.nodes)
          {
            if ((slaves.rigid && masters.rigid) || (!held.empty() && held[i]))
              continue;
            const Vec p = at(xp, i);
            found.clear();
            tree.query(bgi::intersects(BPoint(p[0], p[1], p[2])), std::back_inserter(found));
            // (The segments in the order of the surface: the choice does
            // not depend on the tree.)
            std::sort(found.begin(), found.end(),
                      [](const auto &a, const auto &b) { return a.second < b.second; });
            // Of the faces the node is behind (within half their element's
            // thickness: a node in the middle of the other body's end face
            // lies a whole element deep behind its side faces), the one it approached most over the step (the
            // face it crossed: at a body's edge it may lie in the plane of
            // a side face as well), then the one it is least deep behind.
            double     best_approach = -1e300, best_depth = 1e300;
            Constraint c{};
            for (const auto &[box, k] : found)
              {
                std::array<Vec, 4> X;
                for (unsigned int a = 0; a < 4; ++a)
                  X[a] = at(xp, masters.segments[k][a]);
                std::array<double, 4> phi;
                Vec                   n, foot;
                if (!project(X, p, phi, n, foot))
                  continue;
                const double g = dot({{p[0] - foot[0], p[1] - foot[1], p[2] - foot[2]}}, n);
                if (!(g < 0 && -g <= 0.5 * masters.depth[k]))
                  continue;
                // The faces must face each other (their normals more than
                // about 100 degrees apart): a node of one body's end face
                // lies in the plane of the other's side face where the two
                // bodies' edges meet (a plate pushing a block of its size,
                // two rods of one section), side by side with it, not
                // against it; taken, such faces kicked the nodes sideways
                // as the bodies parted, until the run blew up.
                const Vec &ns = slave_normal[i];
                if (!(dot(ns, n) < -0.2 * std::sqrt(dot(ns, ns))))
                  continue;
                double g0 = 0;
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    double xm = 0;
                    for (unsigned int a = 0; a < 4; ++a)
                      xm += phi[a] * x[3 * masters.segments[k][a] + d];
                    g0 += (x[3 * i + d] - xm) * n[d];
                  }
                const double approach = g0 - g;
                const double tie      = 1e-9 * masters.depth[k];
                if (approach > best_approach + tie ||
                    (approach > best_approach - tie && -g < best_depth))
                  {
                    best_approach = std::max(best_approach, approach);
                    best_depth    = -g;
                    c.slave       = i;
                    c.master      = masters.segments[k];
                    c.phi         = phi;
                    c.n_master    = 4;
                    c.normal      = n;
                    c.on_first    = slave_surface == 0;
                  }
              }
            if (c.n_master == 4)
              constraints.push_back(c);
          }
      }

    // Projected Gauss-Seidel over the constraints (their order fixed).
    std::vector<double> &impulse = impulses, &friction_impulse = friction_impulses;
    impulse.assign(3 * n_nodes, 0.);
    friction_impulse.assign(3 * n_nodes, 0.);
    Vec                 shape_impulse{}, shape_moment{}, shape_friction{};
    auto                gap_of = [&](const Constraint &c) {
      if (c.n_master == 0)
        {
          Vec n;
          return shape_gap(c.on_first ? 1 : 0, at(xp, c.slave), n);
        }
      double g = 0;
      for (unsigned int d = 0; d < 3; ++d)
        {
          double xm = 0;
          for (unsigned int a = 0; a < 4; ++a)
            xm += c.phi[a] * xp[3 * c.master[a] + d];
          g += (xp[3 * c.slave + d] - xm) * c.normal[d];
        }
      return g;
    };
    // Move the constraint's nodes by the impulse @p P along @p dir (with
    // hanging nodes: the nodes that move on their own, and the hanging
    // nodes with them).
    auto apply = [&](const Constraint &c, const Vec &P, std::vector<double> &imp) {
      if (!c.nodes.empty())
        {
          for (const auto &[k, a] : c.nodes)
            for (unsigned int d = 0; d < 3; ++d)
              {
                xp[3 * k + d] += w[3 * k + d] * a * P[d];
                imp[3 * k + d] += a * P[d];
              }
          for (const auto &[k, a] : c.nodes)
            for (const unsigned int h : dependants[k])
              follow(h);
          return;
        }
      for (unsigned int d = 0; d < 3; ++d)
        {
          xp[3 * c.slave + d] += w[3 * c.slave + d] * P[d];
          imp[3 * c.slave + d] += P[d];
          for (unsigned int a = 0; a < c.n_master; ++a)
            {
              xp[3 * c.master[a] + d] -= w[3 * c.master[a] + d] * c.phi[a] * P[d];
              imp[3 * c.master[a] + d] -= c.phi[a] * P[d];
            }
        }
    };
    // With hanging nodes, each constraint's gap as a sum over the nodes
    // that move on their own: g = sum_k a_k x_k . n, a hanging node's
    // coefficient spread over its masters by their weights.
    const auto expand = [&](Constraint &c) {
      c.nodes.clear();
      const auto put = [&](const unsigned int k, const double a) {
        for (auto &[j, b] : c.nodes)
          if (j == k)
            {
              b += a;
              return;
            }
        c.nodes.emplace_back(k, a);
      };
      const auto add = [&](const unsigned int i, const double a) {
        if (hanging[i].empty())
          put(i, a);
        else
          for (const auto &[j, weight] : hanging[i])
            put(j, a * weight);
      };
      add(c.slave, 1.);
      for (unsigned int a = 0; a < c.n_master; ++a)
        add(c.master[a], -c.phi[a]);
    };
    std::vector<Constraint> kept;
    for (auto &c : constraints)
      {
        c.weight = 0;
        if (!hanging.empty())
          {
            expand(c);
            for (const auto &[k, a] : c.nodes)
              for (unsigned int d = 0; d < 3; ++d)
                c.weight += c.normal[d] * c.normal[d] * a * a * w[3 * k + d];
          }
        else
          for (unsigned int d = 0; d < 3; ++d)
            {
              double wd = w[3 * c.slave + d];
              for (unsigned int a = 0; a < c.n_master; ++a)
                wd += c.phi[a] * c.phi[a] * w[3 * c.master[a] + d];
              c.weight += c.normal[d] * c.normal[d] * wd;
            }
        c.impulse = 0;
        if (c.weight > 0)
          kept.push_back(c);
      }
    constraints.swap(kept);
    const double min_depth = std::min(surface[0].min_depth, surface[1].min_depth);
    const double stop      = tolerance * (min_depth < 1e300 ? min_depth : 1.);
    // Projected Gauss-Seidel over the constraints of one pass (or of both),
    // the constraints [begin, end).
    auto solve = [&](const unsigned int begin, const unsigned int end) {
      for (unsigned int sweep = 0; sweep < 500 && begin < end; ++sweep)
        {
          double largest = 0;
          for (unsigned int k = begin; k < end; ++k)
            {
              Constraint  &c     = constraints[k];
              const double g     = gap_of(c);
              const double P     = std::max(0., c.impulse - g / c.weight);
              const double delta = P - c.impulse;
              if (delta == 0)
                continue;
              c.impulse = P;
              apply(c, {{delta * c.normal[0], delta * c.normal[1], delta * c.normal[2]}}, impulse);
              largest = std::max(largest, std::abs(delta) * c.weight);
            }
          if (largest <= stop)
            break;
        }
    };
    // Balanced (two deformable surfaces): each pass corrects the predicted
    // motion alone, and the step takes the mean of the two corrections
    // (ABAQUS/Explicit's balanced master-slave). Both passes' constraints
    // at once over-constrain an interface whose meshes do not match: each
    // body's nodes pinned to the other's facets, which one-point elements
    // can follow only by hourglass-like kinks (a graded ball on a graded
    // block: force spikes of 45 % of the peak at 0.2 m/s, a stop at 0.4).
    // Where the meshes match, the two corrections are the same; where they
    // do not, half of their difference is left as penetration (reported)
    // and taken out at the next steps. A step in which only one pass
    // finds constraints applies that pass whole.
    const unsigned int n_first_pass =
      std::find_if(constraints.begin(), constraints.end(), [](const Constraint &c) { return c.on_first; }) -
      constraints.begin();
    const bool averaged = balanced && n_first_pass > 0 && n_first_pass < constraints.size();
    if (averaged)
      {
        std::vector<double> &xp0 = predicted_first, &first_impulse = impulses_first;
        xp0 = xp;
        solve(0, n_first_pass);
        first_impulse.assign(3 * n_nodes, 0.);
        first_impulse.swap(impulse);
        xp = xp0;
        solve(n_first_pass, constraints.size());
        for (unsigned int j = 0; j < 3 * n_nodes; ++j)
          {
            impulse[j] = 0.5 * (impulse[j] + first_impulse[j]);
            xp[j]      = xp0[j] + w[j] * impulse[j];
          }
        follow_all();
        for (auto &c : constraints)
          c.impulse *= 0.5;
      }
    else
      solve(0, constraints.size());

    // Friction (seed Eqs. (61)-(62)): each constraint's tangential slip
    // over the step taken out, up to mu times its normal impulse.
    const double friction_share = averaged ? 0.5 : 1.;
    if (static_friction > 0 || dynamic_friction > 0)
      for (auto &c : constraints)
        if (c.impulse > 0)
          {
            Vec slip;
            for (unsigned int d = 0; d < 3; ++d)
              {
                slip[d] = xp[3 * c.slave + d] - x[3 * c.slave + d];
                if (c.n_master == 0)
                  {
                    const unsigned int s = c.on_first ? 1 : 0;
                    slip[d] -= dt * analytic[s].velocity[d];
                  }
                for (unsigned int a = 0; a < c.n_master; ++a)
                  slip[d] -= c.phi[a] * (xp[3 * c.master[a] + d] - x[3 * c.master[a] + d]);
              }
            const double sn = dot(slip, c.normal);
            for (unsigned int d = 0; d < 3; ++d)
              slip[d] -= sn * c.normal[d];
            const double s = std::sqrt(dot(slip, slip));
            if (!(s > 0))
              continue;
            const double mu =
              Laws::friction_coefficient(static_friction, dynamic_friction, friction_decay, s / dt);
            // (The normal weight stands for the tangential one; balanced,
            // each of the two passes takes out half of the slip.)
            const double P = std::min(friction_share * s / c.weight, mu * c.impulse);
            apply(c, {{-P * slip[0] / s, -P * slip[1] / s, -P * slip[2] / s}}, friction_impulse);
          }

    // The forces, the reaction on an analytic shape, the pair's figures.
    const double to_force = 1. / (dt * dt_avg);
    std::vector<double> &force = forces;
    force.resize(3 * n_nodes);
    for (unsigned int j = 0; j < 3 * n_nodes; ++j)
      {
        force[j] = (impulse[j] + friction_impulse[j]) * to_force;
        f_contact[j] += force[j];
        if (on_first[j / 3])
          {
            result.force_on_first[j % 3] += impulse[j] * to_force;
            result.friction_on_first[j % 3] += friction_impulse[j] * to_force;
          }
      }
    for (const auto &c : constraints)
      {
        const double g = gap_of(c);
        if (c.impulse > 0)
          ++result.n_active;
        result.max_penetration = std::max(result.max_penetration, -g);
      }
    for (unsigned int s = 0; s < 2; ++s)
      if (analytic[s].shape)
        {
          // The shape takes the opposite of its slave nodes' forces.
          for (const unsigned int i : surface[1 - s].nodes)
            {
              const Vec Pn = at(impulse, i), Pf = at(friction_impulse, i);
              const Vec r  = {{xp[3 * i] - centre[s][0], xp[3 * i + 1] - centre[s][1],
                              xp[3 * i + 2] - centre[s][2]}};
              const Vec P = {{Pn[0] + Pf[0], Pn[1] + Pf[1], Pn[2] + Pf[2]}};
              const Vec m = cross(r, P);
              for (unsigned int d = 0; d < 3; ++d)
                {
                  shape_impulse[d] -= Pn[d];
                  shape_friction[d] -= Pf[d];
                  shape_moment[d] -= m[d];
                }
            }
          for (unsigned int d = 0; d < 3; ++d)
            {
              result.shape_force[d]  = (shape_impulse[d] + shape_friction[d]) * to_force;
              result.shape_torque[d] = shape_moment[d] * to_force;
              if (s == 0)
                {
                  result.force_on_first[d]    = shape_impulse[d] * to_force;
                  result.friction_on_first[d] = shape_friction[d] * to_force;
                }
            }
        }
    result.max_penetration = std::max(0., result.max_penetration);
    result.max_penetration_ratio =
      min_depth < 1e300 && min_depth > 0 ? result.max_penetration / min_depth : 0.;

    // The work the contact forces did on the bodies over the step just
    // made (trapezoidal rule, as for the reactions of prescribed motion):
    // taken from the bodies, it is the contact's energy.
    if (has_previous)
      {
        double step_work = 0;
        // (A node new since a round of refinement has no last position:
        // x^n - x^(n-1) = dt v^(n-1/2) stands for it, and no last force.)
        for (unsigned int j = 0; j < 3 * n_nodes; ++j)
          step_work += 0.5 * (previous_force[j] + force[j]) *
                       (std::isnan(previous_position[j]) ? dt_previous * v[j] : x[j] - previous_position[j]);
        for (unsigned int s = 0; s < 2; ++s)
          if (analytic[s].shape)
            for (unsigned int d = 0; d < 3; ++d)
              step_work += 0.5 * (previous_shape_load[d] + result.shape_force[d]) *
                             (analytic[s].centre[d] - previous_centre[d]) +
                           0.5 * (previous_shape_load[3 + d] + result.shape_torque[d]) *
                             analytic[s].angular_velocity[d] * dt_previous;
        work -= step_work;
      }
    has_previous      = true;
    previous_force.swap(force);
    previous_position = x;
    for (unsigned int s = 0; s < 2; ++s)
      if (analytic[s].shape)
        for (unsigned int d = 0; d < 3; ++d)
          {
            previous_centre[d]         = analytic[s].centre[d];
            previous_shape_load[d]     = result.shape_force[d];
            previous_shape_load[3 + d] = result.shape_torque[d];
          }
    result.energy = work;
    return last_result = result;
  }


  ANVIL_REGISTER_CONTACT_ALGORITHM(KinematicContact,
                                   "kinematic",
                                   "kinematic enforcement (ABAQUS/Explicit's default for contact "
                                   "pairs): the penetration of each step's predicted motion removed, "
                                   "momentum conserved, the time step untouched; 'Penalty scale "
                                   "factor' does not apply. Against rigid impactors and in stiff, "
                                   "short impacts it removes the penalty's compliance (doc/accuracy.md: "
                                   "a rigid sphere's Hertz force +1.5 % against -27 % at the default "
                                   "penalty factor, two unequal rods' contact time +0.45 % against "
                                   "+4.9 %).")
} // namespace anvil::Contact
