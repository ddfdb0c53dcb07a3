/**
 * @file
 * Reinforcement in the simulator: truss elements embedded in a host body
 * with perfect bond (seed sections 5.1, 5.3, 5.4). See rebar/rebar.h.
 */
#include <anvil/laws/seed_laws.h>
#include <anvil/rebar/reinforcement.h>
#include <anvil/mesh/body.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/vtu_file.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/text.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <map>
#include <set>

namespace anvil::Rebar
{
  using namespace dealii;

  namespace
  {
    /** Natural coordinates of @p p in the hexahedron with vertices @p X
        (lexicographic) by Newton's method on the trilinear map; true if
        the point is inside (with a small tolerance). */
    bool inverse_map(const std::array<Point<3>, 8> &X, const Point<3> &p, std::array<double, 3> &xi)
    {
      xi = {{0., 0., 0.}};
      for (unsigned int it = 0; it < 20; ++it)
        {
          const auto   N = Trusses::shape_values(xi);
          Tensor<1, 3> r;
          Tensor<2, 3> J;
          for (unsigned int I = 0; I < 8; ++I)
            {
              r -= N[I] * X[I];
              const double s[3] = {(I & 1) ? 1. : -1., (I & 2) ? 1. : -1., (I & 4) ? 1. : -1.};
              for (unsigned int c = 0; c < 3; ++c)
                {
                  double d = 0.125 * s[c];
                  for (unsigned int e = 0; e < 3; ++e)
                    if (e != c)
                      d *= 1. + s[e] * xi[e];
                  for (unsigned int a = 0; a < 3; ++a)
                    J[a][c] += d * X[I][a];
                }
            }
          r += p;
          if (!(determinant(J) > 0))
            return false;
          const Tensor<1, 3> dxi = invert(J) * r;
          for (unsigned int c = 0; c < 3; ++c)
            xi[c] += dxi[c];
          if (dxi.norm() < 1e-13)
            break;
        }
      for (unsigned int c = 0; c < 3; ++c)
        if (std::abs(xi[c]) > 1. + 1e-8)
          return false;
      for (unsigned int c = 0; c < 3; ++c)
        xi[c] = std::max(-1., std::min(1., xi[c]));
      return true;
    }
  } // namespace


  // @sect3{Embedding}
  //
  // Each process locates the truss nodes in the host body's cells it owns
  // (an R-tree of the cells' boxes, then the inverse trilinear map); the
  // claims are gathered, and a node on a face shared by several cells goes
  // to the cell with the smallest scene-wide id, so every partition embeds
  // it the same way.
  Reinforcement::Reinforcement(Simulator &simulator, std::vector<Layout> layouts)
    : ForceContributor(simulator)
    , layouts(std::move(layouts))
  {}


  void Reinforcement::setup()
  {
    const auto        &bodies           = get_bodies();
    const std::string &scene_file       = get_scene_file();
    const auto        &dof_handler      = get_dof_handler();
    const VectorType  &position         = get_position();
    const MPI_Comm     mpi_communicator = get_mpi_communicator();
    const auto        &pcout            = get_pcout();
    namespace bg  = boost::geometry;
    namespace bgi = boost::geometry::index;
    using BPoint  = bg::model::point<double, 3, bg::cs::cartesian>;
    using Box     = bg::model::box<BPoint>;
    bars.assign(layouts.size(), {});
    for (unsigned int r = 0; r < layouts.size(); ++r)
      {
        const auto    &layout = layouts[r];
        auto          &T      = bars[r];
        unsigned int   host   = 0;
        while (bodies[host].name != layout.host)
          ++host;
        if (bodies[host].is_rigid())
          throw InputError(scene_file + ": subsection 'Rebar " + layout.name +
                           "': the host body is rigid");

        // Nodes and elements: every polyline segment cut into pieces no
        // longer than the element length.
        for (const auto &line : layout.polylines())
          {
            T.X.push_back(line[0]);
            for (unsigned int k = 0; k + 1 < line.size(); ++k)
              {
                const double len = line[k].distance(line[k + 1]);
                check_size(scene_file + ": subsection 'Rebar " + layout.name + "'",
                           "'Element length' and a bar " + std::to_string(len) + " m long", "truss nodes",
                           T.X.size() + len / layout.element_length, 512.);
                const unsigned int n = std::max(1., std::ceil(len / layout.element_length - 1e-9));
                for (unsigned int i = 1; i <= n; ++i)
                  {
                    T.X.push_back(line[k] + (double(i) / n) * (line[k + 1] - line[k]));
                    T.elements.push_back({{static_cast<unsigned int>(T.X.size() - 2),
                                           static_cast<unsigned int>(T.X.size() - 1)}});
                  }
              }
          }
        T.tributary.assign(T.X.size(), 0.);
        for (const auto &e : T.elements)
          {
            T.reference_length.push_back(T.X[e[0]].distance(T.X[e[1]]));
            T.tributary[e[0]] += 0.5 * T.reference_length.back();
            T.tributary[e[1]] += 0.5 * T.reference_length.back();
          }
        if (layout.has_probe)
          {
            double best = 1e300;
            for (unsigned int k = 0; k < T.elements.size(); ++k)
              {
                const double dist =
                  layout.probe.distance(0.5 * (T.X[T.elements[k][0]] + T.X[T.elements[k][1]]));
                if (dist < best - 1e-12)
                  {
                    best            = dist;
                    T.probe_element = k;
                  }
              }
          }
        T.length    = T.reference_length;
        T.stress    = std::vector<double>(T.elements.size(), 0.);
        T.force     = T.stress;
        T.energy    = T.stress;
        T.n_history = layout.material->n_uniaxial_history();
        T.history.assign(T.n_history * T.elements.size(), 0.);

        // Locate the nodes in the owned host cells.
        std::vector<std::pair<Box, unsigned long>> boxes;
        std::map<unsigned long, std::array<Point<3>, 8>> vertices;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == host)
            {
              const unsigned long id = element_id(cell->active_cell_index());
              std::array<Point<3>, 8> X;
              BPoint lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
              for (unsigned int v = 0; v < 8; ++v)
                {
                  X[v] = cell->vertex(v);
                  bg::set<0>(lo, std::min(bg::get<0>(lo), X[v][0]));
                  bg::set<1>(lo, std::min(bg::get<1>(lo), X[v][1]));
                  bg::set<2>(lo, std::min(bg::get<2>(lo), X[v][2]));
                  bg::set<0>(hi, std::max(bg::get<0>(hi), X[v][0]));
                  bg::set<1>(hi, std::max(bg::get<1>(hi), X[v][1]));
                  bg::set<2>(hi, std::max(bg::get<2>(hi), X[v][2]));
                }
              vertices[id] = X;
              boxes.emplace_back(Box(lo, hi), id);
            }
        const bgi::rtree<std::pair<Box, unsigned long>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
        std::vector<double> claims;
        for (unsigned int i = 0; i < T.X.size(); ++i)
          {
            const double eps = 1e-9 * (1. + T.X[i].norm());
            const Box    q(BPoint(T.X[i][0] - eps, T.X[i][1] - eps, T.X[i][2] - eps),
                        BPoint(T.X[i][0] + eps, T.X[i][1] + eps, T.X[i][2] + eps));
            std::vector<std::pair<Box, unsigned long>> hits;
            tree.query(bgi::intersects(q), std::back_inserter(hits));
            for (const auto &[box, id] : hits)
              {
                std::array<double, 3> xi;
                if (inverse_map(vertices[id], T.X[i], xi))
                  claims.insert(claims.end(), {double(i), double(id), xi[0], xi[1], xi[2]});
              }
          }
        T.host_cell.assign(T.X.size(), static_cast<unsigned long>(-1));
        T.xi.assign(T.X.size(), {{0., 0., 0.}});
        for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, claims))
          for (std::size_t k = 0; k + 5 <= part.size(); k += 5)
            {
              const unsigned int  i  = static_cast<unsigned int>(part[k]);
              const unsigned long id = static_cast<unsigned long>(part[k + 1]);
              if (id < T.host_cell[i])
                {
                  T.host_cell[i] = id;
                  T.xi[i]        = {{part[k + 2], part[k + 3], part[k + 4]}};
                }
            }
        for (unsigned int i = 0; i < T.X.size(); ++i)
          if (T.host_cell[i] == static_cast<unsigned long>(-1))
            {
              std::ostringstream s;
              s << scene_file << ": subsection 'Rebar " << layout.name << "': the bar point ("
                << T.X[i] << ") lies outside the host body '" << layout.host
                << "' (check the cover, the member corners or the polyline file)";
              throw InputError(s.str());
            }

        T.shape.resize(T.X.size());
        for (unsigned int i = 0; i < T.X.size(); ++i)
          T.shape[i] = Trusses::shape_values(T.xi[i]);

        // The host cells' vertex dofs on this process.
        std::map<unsigned long, std::pair<std::array<long, 8>, bool>> local;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial() && cell->material_id() == host)
            {
              std::array<long, 8> dofs;
              for (unsigned int v = 0; v < 8; ++v)
                dofs[v] = position.get_partitioner()->global_to_local(cell->vertex_dof_index(v, 0));
              local[element_id(cell->active_cell_index())] = {dofs, cell->is_locally_owned()};
            }
        T.host_dofs.assign(T.X.size(), std::array<long, 8>{{-1, -1, -1, -1, -1, -1, -1, -1}});
        T.host_owned.assign(T.X.size(), false);
        for (unsigned int i = 0; i < T.X.size(); ++i)
          {
            const auto it = local.find(T.host_cell[i]);
            if (it != local.end())
              {
                T.host_dofs[i]  = it->second.first;
                T.host_owned[i] = it->second.second;
              }
          }
        // The factor on each element's stable step L / c: 1 unless mass
        // scaling raises it (below).
        T.step_factor.assign(T.elements.size(), 1.);
        T.added_mass = 0;
        if (layout.bond_slip)
          {
            const unsigned int n = T.X.size();
            T.xs.resize(3 * n);
            T.vs.assign(3 * n, 0.);
            T.fs.assign(3 * n, 0.);
            T.xh.assign(3 * n, 0.);
            T.bond_force.assign(3 * n, 0.);
            T.ms.assign(n, 0.);
            T.plastic_slip.assign(n, 0.);
            T.damage.assign(n, 0.);
            T.bond_stress.assign(n, 0.);
            T.slip.assign(n, 0.);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int d = 0; d < 3; ++d)
                {
                  T.xs[3 * i + d] = T.X[i][d];
                  T.vs[3 * i + d] = bodies[host].initial_velocity[d];
                }
            for (unsigned int i = 0; i < n; ++i)
              T.ms[i] = layout.material->density() * layout.area() * T.tributary[i];
            // Selective mass scaling: an element whose step L / c is below
            // the one asked for gets f - 1 times its own mass on top, half
            // at each node, f = (step c / L)^2; its step is then sqrt(f) L / c.
            if (layout.mass_scaling_step > 0)
              {
                const double c = std::sqrt(layout.material->youngs_modulus() /
                                           layout.material->density());
                for (unsigned int k = 0; k < T.elements.size(); ++k)
                  {
                    const double L = T.reference_length[k];
                    const double f = std::pow(layout.mass_scaling_step * c / L, 2);
                    if (!(f > 1))
                      continue;
                    const double added = (f - 1) * layout.material->density() * layout.area() * L;
                    T.ms[T.elements[k][0]] += 0.5 * added;
                    T.ms[T.elements[k][1]] += 0.5 * added;
                    T.step_factor[k] = std::sqrt(f);
                    T.added_mass += added;
                  }
              }
            // The last node of every bar, for a pull-out.
            T.pulled.assign(n, false);
            T.pull_reaction.assign(3 * n, 0.);
            if (layout.pulled)
              for (unsigned int k = 0; k < T.elements.size(); ++k)
                if (k + 1 == T.elements.size() || T.elements[k + 1][0] != T.elements[k][1])
                  {
                    T.pulled[T.elements[k][1]] = true;
                    for (unsigned int d = 0; d < 3; ++d)
                      T.vs[3 * T.elements[k][1] + d] = layout.pull_velocity[d];
                  }
          }
        pcout << "  rebar '" << layout.name << "' in '" << layout.host << "': "
              << layout.ratio_summary() << "; " << T.elements.size() << " truss elements"
              << std::endl;
        if (T.added_mass > 0)
          {
            double own = 0;
            for (unsigned int k = 0; k < T.elements.size(); ++k)
              own += layout.material->density() * layout.area() * T.reference_length[k];
            std::ostringstream line;
            line << "  rebar '" << layout.name << "': mass scaling to a step of "
                 << layout.mass_scaling_step << " s adds " << std::setprecision(4) << T.added_mass
                 << " kg (" << std::setprecision(3) << 100. * T.added_mass / own
                 << " % of the bars' own mass)";
            pcout << line.str() << std::endl;
          }
      }
    setup_partition();
  }


  // @sect3{The partition of the bars}
  //
  // Each process's share (Share in reinforcement.h), and one exchange for
  // all layouts: a deal.II vector over the bars' nodes numbered process by
  // process (the own nodes of rank 0, then rank 1's, ...), three entries a
  // node, whose ghosts are the halo.
  void Reinforcement::setup_partition()
  {
    const MPI_Comm comm = get_mpi_communicator();
    partitioned         = Utilities::MPI::n_mpi_processes(comm) > 1 && !bars.empty();
    shares.assign(bars.size(), {});
    history_rows.assign(bars.size(), {});
    std::vector<unsigned int> own_keys; // (layout, node) pairs
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        const auto        &T = bars[r];
        auto              &S = shares[r];
        const unsigned int n = T.X.size();
        std::vector<char>  relevant(n, 0), touched(n, 0);
        for (unsigned int i = 0; i < n; ++i)
          {
            relevant[i] = T.host_dofs[i][0] >= 0;
            if (T.host_owned[i])
              {
                S.own_nodes.push_back(i);
                own_keys.insert(own_keys.end(), {r, i});
              }
            if (relevant[i])
              S.relevant_nodes.push_back(i);
          }
        for (unsigned int k = 0; k < T.elements.size(); ++k)
          if (relevant[T.elements[k][0]] || relevant[T.elements[k][1]])
            {
              S.elements.push_back(k);
              S.own_element.push_back(T.host_owned[T.elements[k][0]]);
              touched[T.elements[k][0]] = touched[T.elements[k][1]] = 1;
            }
        for (unsigned int i = 0; i < n; ++i)
          if (touched[i] || relevant[i])
            S.nodes.push_back(i);
      }
    if (!partitioned)
      return;
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const auto         all  = Utilities::MPI::all_gather(comm, own_keys);
    std::vector<std::vector<unsigned long>> global(bars.size());
    for (unsigned int r = 0; r < bars.size(); ++r)
      global[r].assign(bars[r].X.size(), 0);
    unsigned long g = 0, first = 0;
    for (unsigned int p = 0; p < all.size(); ++p)
      {
        if (p == rank)
          first = g;
        for (std::size_t q = 0; q + 1 < all[p].size(); q += 2)
          global[all[p][q]][all[p][q + 1]] = g++;
      }
    IndexSet owned(3 * g), ghost(3 * g);
    owned.add_range(3 * first, 3 * (first + own_keys.size() / 2));
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        const auto &T = bars[r];
        auto       &S = shares[r];
        // What this process does not compute itself: the bars' own
        // positions of nodes not its own (bond-slip), the host points of
        // nodes outside its own and ghost cells (perfect bond).
        for (const unsigned int i : S.nodes)
          if (!(layouts[r].bond_slip ? T.host_owned[i] : T.host_dofs[i][0] >= 0))
            {
              S.halo.push_back(i);
              ghost.add_range(3 * global[r][i], 3 * global[r][i] + 3);
            }
      }
    auto partitioner = std::make_shared<Utilities::MPI::Partitioner>(owned, ghost, comm);
    exchange.reinit(partitioner);
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        auto &S = shares[r];
        for (const unsigned int i : S.own_nodes)
          S.own_slot.push_back(3 * (global[r][i] - first));
        for (const unsigned int i : S.halo)
          S.halo_slot.push_back(partitioner->global_to_local(3 * global[r][i]));
      }
  }


  // Rebar mass m_r = rho A (half the adjacent element lengths) to the host
  // nodes as N_I m_r: the embedded constraint conserves momentum.
  void Reinforcement::add_mass(VectorType &mass)
  {
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        if (layouts[r].bond_slip)
          continue; // the bars' own nodes carry their mass
        const auto         &T   = bars[r];
        const double        rho = layouts[r].material->density();
        const double        A   = layouts[r].area();
        for (unsigned int i = 0; i < T.X.size(); ++i)
          if (T.host_dofs[i][0] >= 0)
            {
              const auto &N = T.shape[i];
              for (unsigned int I = 0; I < 8; ++I)
                if (T.host_dofs[i][I] < long(mass.locally_owned_size()))
                  for (unsigned int d = 0; d < 3; ++d)
                    mass.local_element(T.host_dofs[i][I] + d) += N[I] * rho * A * T.tributary[i];
            }
      }
  }


  // @sect3{Truss forces}
  //
  // The nodes' positions x_r = sum N_I x_I come from the host cells,
  // which are the process's own or ghost cells for its share (Share); what
  // the ends of its elements need beyond those comes through the exchange.
  // Each process evaluates its share's truss elements (T3D2: axial strain
  // increment ln(l / l_old) from the current length, the steel's uniaxial
  // form, force N = sigma A L0 / l for the Cauchy stress of a bar of
  // constant volume) in element order and adds N_I f_r to the host nodes it
  // owns. Work of the axial force, (N_old + N) / 2 (l - l_old), goes to the
  // internal energy (each element's on the process of its first node).
  double Reinforcement::add_forces(const double dt)
  {
    const VectorType &position         = get_position();
    VectorType       &force            = get_force();
    Energies         &energies         = get_energies();
    const MPI_Comm    mpi_communicator = get_mpi_communicator();
    double dt_crit = 1e300;
    // The host points of the share's nodes in own and ghost cells.
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        auto       &T  = bars[r];
        const auto &S  = shares[r];
        auto       &xr = T.x;
        xr.resize(3 * T.X.size());
        T.nodal_force.resize(3 * T.X.size());
        for (const unsigned int i : S.nodes)
          for (unsigned int d = 0; d < 3; ++d)
            xr[3 * i + d] = 0;
        for (const unsigned int i : S.relevant_nodes)
          {
            const auto &N = T.shape[i];
            for (unsigned int I = 0; I < 8; ++I)
              for (unsigned int d = 0; d < 3; ++d)
                xr[3 * i + d] += N[I] * position.local_element(T.host_dofs[i][I] + d);
          }
      }
    work_done.assign(2 * bars.size() + 1, 0.);
    own_step.resize(bars.size(), 1e300);
    if (dt > 0)
      subcycle();
    // To the exchange, each own node's position (bond-slip: the bar's own
    // node).
    if (partitioned)
      {
        exchange.zero_out_ghost_values();
        for (unsigned int r = 0; r < bars.size(); ++r)
          {
            const auto &T   = bars[r];
            const auto &S   = shares[r];
            const auto &own = layouts[r].bond_slip ? T.xs : T.x;
            for (unsigned int q = 0; q < S.own_nodes.size(); ++q)
              for (unsigned int d = 0; d < 3; ++d)
                exchange.local_element(S.own_slot[q] + d) = own[3 * S.own_nodes[q] + d];
          }
        exchange.update_ghost_values();
      }
    bool subcycled = false;
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        auto       &T    = bars[r];
        const auto &S    = shares[r];
        auto       &xr   = T.x;
        auto       &fr   = T.nodal_force;
        const bool  slip = layouts[r].bond_slip;
        if (partitioned)
          {
            auto &into = slip ? T.xs : xr;
            for (unsigned int q = 0; q < S.halo.size(); ++q)
              for (unsigned int d = 0; d < 3; ++d)
                into[3 * S.halo[q] + d] = exchange.local_element(S.halo_slot[q] + d);
          }
        if (slip)
          {
            // The bars move on their own; xr are the host points they sit in.
            for (const unsigned int i : S.relevant_nodes)
              for (unsigned int d = 0; d < 3; ++d)
                T.xh[3 * i + d] = xr[3 * i + d];
            for (const unsigned int i : S.nodes)
              for (unsigned int d = 0; d < 3; ++d)
                xr[3 * i + d] = T.xs[3 * i + d];
          }
        // A subcycled layout's histories advance by its substep.
        const bool   sub = layouts[r].subcycling;
        const double h   = sub ? (dt > 0 ? T.substep : 0.) : dt;
        const double step = evaluate(r, h, xr);
        if (sub)
          {
            own_step[r] = step;
            subcycled   = true;
          }
        else
          dt_crit = std::min(dt_crit, step);
        if (slip)
          // The bars' nodes keep their forces; the host gets the bond
          // reactions, -f, through the shape functions.
          for (const unsigned int i : S.nodes)
            for (unsigned int q = 0; q < 3; ++q)
              {
                T.fs[3 * i + q] = fr[3 * i + q];
                fr[3 * i + q]   = -T.bond_force[3 * i + q];
              }
        for (const unsigned int i : S.relevant_nodes)
          {
            const auto &N = T.shape[i];
            for (unsigned int I = 0; I < 8; ++I)
              if (T.host_dofs[i][I] < long(force.locally_owned_size()))
                for (unsigned int d = 0; d < 3; ++d)
                  force.local_element(T.host_dofs[i][I] + d) += N[I] * fr[3 * i + d];
          }
      }
    // Each process booked the work of its own elements and bonds (and, in
    // substeps, the pull's and gravity's on its own nodes).
    if (partitioned)
      {
        Utilities::MPI::sum(work_done, mpi_communicator, work_done);
        for (unsigned int r = 0; r < bars.size(); ++r)
          {
            energies.internal += work_done[2 * r];
            energies.bond += work_done[2 * r + 1];
          }
        energies.external_work += work_done.back();
        if (subcycled)
          Utilities::MPI::min(own_step, mpi_communicator, own_step);
      }
    return dt_crit;
  }


  double Reinforcement::evaluate(const unsigned int r, const double dt, const std::vector<double> &xb)
  {
    double element_work = 0, bond_work = 0;
    auto               &T        = bars[r];
    const auto         &S        = shares[r];
    const auto         &material = *layouts[r].material;
    const double        A        = layouts[r].area();
    const double        c        = std::sqrt(material.youngs_modulus() / material.density());
    auto               &fr       = T.nodal_force;
    double              dt_crit  = 1e300;
    for (const unsigned int i : S.nodes)
      for (unsigned int d = 0; d < 3; ++d)
        fr[3 * i + d] = 0;
    for (unsigned int e = 0; e < S.elements.size(); ++e)
      {
        const unsigned int k = S.elements[e];
        const unsigned int a = T.elements[k][0], b = T.elements[k][1];
        Tensor<1, 3>       d;
        for (unsigned int q = 0; q < 3; ++q)
          d[q] = xb[3 * b + q] - xb[3 * a + q];
        const double l = d.norm();
        if (dt > 0)
          {
            double *h     = T.n_history ? &T.history[T.n_history * k] : nullptr;
            T.stress[k]   = material.update_uniaxial_stress(std::log(l / T.length[k]), dt, T.stress[k], h);
            const double N = T.stress[k] * A * T.reference_length[k] / l;
            const double w = 0.5 * (T.force[k] + N) * (l - T.length[k]);
            T.energy[k] += w;
            if (S.own_element[e])
              element_work += w;
            T.force[k]  = N;
            T.length[k] = l;
          }
        const Tensor<1, 3> f = (T.force[k] / l) * d;
        for (unsigned int q = 0; q < 3; ++q)
          {
            fr[3 * a + q] += f[q];
            fr[3 * b + q] -= f[q];
          }
        dt_crit = std::min(dt_crit, T.step_factor[k] * l / c);
      }
    if (layouts[r].bond_slip)
      dt_crit = std::min(dt_crit, evaluate_bond(r, dt, xb, bond_work));
    // This process's share of the work: summed over the processes at the
    // end of add_forces().
    if (partitioned)
      {
        work_done[2 * r] += element_work;
        work_done[2 * r + 1] += bond_work;
      }
    else
      {
        get_energies().internal += element_work;
        get_energies().bond += bond_work;
      }
    return dt_crit;
  }


  double Reinforcement::evaluate_bond(const unsigned int r, const double dt, const std::vector<double> &xb,
                                      double &bond_work)
  {
    auto              &T       = bars[r];
    const auto        &S       = shares[r];
    const unsigned int n       = T.X.size();
    auto              &fr      = T.nodal_force;
    double             dt_crit = 1e300;
    // @sect4{Bond-slip, seed Eq. (68)}
    // Along the bar: slip S = (x_bar - x_host) . t with t the bar's
    // current tangent at the node; bond stress by the law below,
    // force tau pi d l_trib; across the bar the node is tied to the
    // host by a spring of the same stiffness G_s pi d l_trib. The
    // reaction goes to the host through the shape functions; the
    // work of the bond forces is the 'bond' energy.
    const auto  &L       = layouts[r];
    const double tau_max = L.bond_modulus * L.slip_at_peak;
    const auto  &trib    = T.tributary;
    auto        &tangent = T.tangent;
    tangent.resize(n);
    for (const unsigned int i : S.nodes)
      tangent[i] = Tensor<1, 3>();
    for (const unsigned int k : S.elements)
      {
        const unsigned int a = T.elements[k][0], b = T.elements[k][1];
        Tensor<1, 3>       dd;
        for (unsigned int q = 0; q < 3; ++q)
          dd[q] = xb[3 * b + q] - xb[3 * a + q];
        dd /= dd.norm();
        tangent[a] += dd;
        tangent[b] += dd;
      }
    const double perimeter = 3.14159265358979323846 * L.diameter;
    if (T.x_bond_old.empty())
      T.x_bond_old.assign(3 * n, 0.);
    for (const unsigned int i : S.relevant_nodes)
      {
        const Tensor<1, 3> t = tangent[i] / tangent[i].norm();
        Tensor<1, 3>       u;
        for (unsigned int q = 0; q < 3; ++q)
          u[q] = xb[3 * i + q] - T.xh[3 * i + q];
        const double S = u * t;
        if (dt > 0)
          {
            // Seed Eq. (68): elastic predictor from the plastic slip;
            // beyond the (softening) strength tau_max exp(-h D) the slip
            // goes plastic and D accumulates it. Unloading follows G_s.
            T.bond_stress[i] =
              Laws::bond_stress(L.bond_modulus, tau_max, L.damage_rate, S, T.plastic_slip[i], T.damage[i]);
            T.slip[i]        = S;
          }
        const double       k_t = L.bond_modulus * perimeter * trib[i];
        const Tensor<1, 3> f   = -(T.bond_stress[i] * perimeter * trib[i]) * t - k_t * (u - S * t);
        // Work done on the bond over the step (trapezoidal rule).
        Tensor<1, 3> f_old, du;
        for (unsigned int q = 0; q < 3; ++q)
          {
            f_old[q] = T.bond_force[3 * i + q];
            T.bond_force[3 * i + q] = f[q];
          }
        if (dt > 0 && T.host_owned[i])
          {
            for (unsigned int q = 0; q < 3; ++q)
              du[q] = u[q] - T.x_bond_old[3 * i + q];
            bond_work -= 0.5 * (f_old + f) * du;
          }
        for (unsigned int q = 0; q < 3; ++q)
          {
            T.x_bond_old[3 * i + q] = u[q];
            fr[3 * i + q] += f[q];
          }
        dt_crit = std::min(dt_crit, 2. * std::sqrt(T.ms[i] / (2. * k_t)));
      }
    return dt_crit;
  }


  // @sect3{Subcycling of the bars}
  //
  // A subcycled bond-slip layout takes m substeps h = dt / m in the
  // scene's step dt (m chosen in update_velocity() from the bars' own
  // stable step). Substep 0 goes with the host's update (update_velocity,
  // update_position); substeps 1 ... m - 1 follow here, once the host has
  // reached the step's end: the host points the bond ties the bars to are
  // interpolated linearly between their places at the start and at the end
  // of the step, x_h(k h) = x_h^n + (k / m) (x_h^{n+1} - x_h^n), the
  // bars' elements and bond are evaluated there, and the bars' own nodes
  // advance by central differences with h. The host gets the bond reactions
  // of the step's ends only (the evaluation in add_forces()), as in the
  // subcycling of Belytschko, Yen and Mullen (1979) with the host as the
  // large-step partition; the work of the bond on the bars' path is booked
  // substep by substep. On several processes each substep exchanges the
  // halo of the bars' own nodes, as the step does.
  void Reinforcement::subcycle()
  {
    unsigned int m = 1;
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (layouts[r].subcycling)
        m = std::max(m, bars[r].substeps);
    if (m < 2)
      return;
    Energies   &energies = get_energies();
    const auto &gravity  = get_gravity();
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (layouts[r].subcycling && bars[r].substeps > 1)
        {
          auto &T = bars[r];
          T.xh_start.resize(3 * T.X.size());
          for (const unsigned int i : shares[r].relevant_nodes)
            for (unsigned int d = 0; d < 3; ++d)
              T.xh_start[3 * i + d] = T.xh[3 * i + d];
        }
    double external = 0;
    for (unsigned int k = 1; k < m; ++k)
      {
        if (partitioned)
          {
            exchange.zero_out_ghost_values();
            for (unsigned int r = 0; r < bars.size(); ++r)
              if (layouts[r].subcycling && bars[r].substeps > k)
                for (unsigned int q = 0; q < shares[r].own_nodes.size(); ++q)
                  for (unsigned int d = 0; d < 3; ++d)
                    exchange.local_element(shares[r].own_slot[q] + d) =
                      bars[r].xs[3 * shares[r].own_nodes[q] + d];
            exchange.update_ghost_values();
          }
        for (unsigned int r = 0; r < bars.size(); ++r)
          if (layouts[r].subcycling && bars[r].substeps > k)
            {
              auto        &T = bars[r];
              const auto  &S = shares[r];
              const double h = T.substep, s = double(k) / T.substeps;
              for (unsigned int q = 0; q < S.halo.size(); ++q)
                for (unsigned int d = 0; d < 3; ++d)
                  T.xs[3 * S.halo[q] + d] = exchange.local_element(S.halo_slot[q] + d);
              for (const unsigned int i : S.relevant_nodes)
                for (unsigned int d = 0; d < 3; ++d)
                  T.xh[3 * i + d] = T.xh_start[3 * i + d] + s * (T.x[3 * i + d] - T.xh_start[3 * i + d]);
              evaluate(r, h, T.xs);
              for (const unsigned int i : S.nodes)
                for (unsigned int q = 0; q < 3; ++q)
                  T.fs[3 * i + q] = T.nodal_force[3 * i + q];
              double kinetic = 0, power = 0;
              advance_velocity(r, h, h, kinetic, external, power);
              for (const unsigned int i : S.own_nodes)
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    if (gravity.norm() > 0)
                      external += T.ms[i] * gravity[d] * h * T.vs[3 * i + d];
                    T.xs[3 * i + d] += h * T.vs[3 * i + d];
                  }
            }
      }
    if (partitioned)
      work_done.back() += external;
    else
      energies.external_work += external;
  }


  void Reinforcement::output_frame(const double t, const unsigned int count)
  {
    // Rank 0 writes the bars whole: each process sends its own nodes'
    // positions (slip, bond stress) and its own elements' force, stress
    // and history.
    if (partitioned)
      for (unsigned int r = 0; r < bars.size(); ++r)
        {
          auto               &T = bars[r];
          const auto         &S = shares[r];
          const bool          slip = !T.slip.empty();
          std::vector<double> mine;
          for (const unsigned int i : S.own_nodes)
            {
              mine.insert(mine.end(), {double(i), T.x.empty() ? T.X[i][0] : T.x[3 * i],
                                       T.x.empty() ? T.X[i][1] : T.x[3 * i + 1],
                                       T.x.empty() ? T.X[i][2] : T.x[3 * i + 2]});
              if (slip)
                mine.insert(mine.end(), {T.slip[i], T.bond_stress[i]});
            }
          const std::size_t node_numbers = mine.size();
          for (unsigned int e = 0; e < S.elements.size(); ++e)
            if (S.own_element[e])
              {
                const unsigned int k = S.elements[e];
                mine.insert(mine.end(), {double(k), T.force[k], T.stress[k]});
                for (unsigned int q = 0; q < T.n_history; ++q)
                  mine.push_back(T.history[T.n_history * k + q]);
              }
          mine.insert(mine.begin(), double(node_numbers));
          const auto parts = Utilities::MPI::gather(get_mpi_communicator(), mine, 0);
          if (!is_root())
            continue;
          T.x.resize(3 * T.X.size());
          const std::size_t per_node = slip ? 6 : 4, per_element = 3 + T.n_history;
          for (const auto &part : parts)
            {
              const std::size_t nodes_end = 1 + static_cast<std::size_t>(part[0]);
              for (std::size_t q = 1; q + per_node <= nodes_end; q += per_node)
                {
                  const unsigned int i = static_cast<unsigned int>(part[q]);
                  for (unsigned int d = 0; d < 3; ++d)
                    T.x[3 * i + d] = part[q + 1 + d];
                  if (slip)
                    {
                      T.slip[i]        = part[q + 4];
                      T.bond_stress[i] = part[q + 5];
                    }
                }
              for (std::size_t q = nodes_end; q + per_element <= part.size(); q += per_element)
                {
                  const unsigned int k = static_cast<unsigned int>(part[q]);
                  T.force[k]           = part[q + 1];
                  T.stress[k]          = part[q + 2];
                  for (unsigned int h = 0; h < T.n_history; ++h)
                    T.history[T.n_history * k + h] = part[q + 3 + h];
                }
            }
        }
    if (!is_root())
      return;
    const std::string &output_directory = get_output_directory();
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        auto &T = bars[r];
        if (T.x.empty())
          {
            T.x.resize(3 * T.X.size());
            for (unsigned int i = 0; i < T.X.size(); ++i)
              for (unsigned int d = 0; d < 3; ++d)
                T.x[3 * i + d] = T.X[i][d];
          }
        const auto  names = layouts[r].material->uniaxial_history_names();
        const auto  it    = std::find(names.begin(), names.end(), "effective_plastic_strain");
        std::string file  = "rebar_" + layouts[r].name + "_" + Utilities::int_to_string(count, 4) + ".vtu";
        record_output(file);
        record_output("rebar_" + layouts[r].name + ".pvd");
        std::ostringstream out;
        out << std::setprecision(10)
            << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
            << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << T.X.size() << "\" NumberOfCells=\""
            << T.elements.size() << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
        for (unsigned int i = 0; i < T.X.size(); ++i)
          out << T.x[3 * i] << ' ' << T.x[3 * i + 1] << ' ' << T.x[3 * i + 2] << '\n';
        out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
        for (const auto &e : T.elements)
          out << e[0] << ' ' << e[1] << '\n';
        out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
        for (unsigned int k = 0; k < T.elements.size(); ++k)
          out << 2 * (k + 1) << '\n';
        out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
        for (unsigned int k = 0; k < T.elements.size(); ++k)
          out << "3\n"; // VTK_LINE
        out << "</DataArray>\n</Cells>\n<CellData>\n";
        auto field = [&](const std::string &name, auto value) {
          out << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
          for (unsigned int k = 0; k < T.elements.size(); ++k)
            out << value(k) << '\n';
          out << "</DataArray>\n";
        };
        field("axial_force", [&](unsigned int k) { return T.force[k]; });
        field("axial_stress", [&](unsigned int k) { return T.stress[k]; });
        field("effective_plastic_strain", [&](unsigned int k) {
          return it == names.end() ? 0. : T.history[T.n_history * k + (it - names.begin())];
        });
        out << "</CellData>\n";
        if (!T.slip.empty())
          {
            // Bond-slip: slip and bond stress at the nodes.
            out << "<PointData>\n";
            for (const auto *v : {&T.slip, &T.bond_stress})
              {
                out << "<DataArray type=\"Float64\" Name=\"" << (v == &T.slip ? "slip" : "bond_stress")
                    << "\" format=\"ascii\">\n";
                for (const double x : *v)
                  out << x << '\n';
                out << "</DataArray>\n";
              }
            out << "</PointData>\n";
          }
        out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
        write_atomically(output_directory + "/" + file, out.str());
        T.pvd_records.emplace_back(t, file);
        write_atomically(output_directory + "/rebar_" + layouts[r].name + ".pvd",
                         Vtu::pvd_text(T.pvd_records));
      }
  }


  // @sect3{The bars' own nodes (bond-slip)}
  //
  // Each process advances its own nodes by the same central differences as
  // the host nodes; a pulled node keeps its velocity, and the work of the
  // force that holds it is external work. The energy terms of the own
  // nodes are summed over the processes.
  void Reinforcement::advance_velocity(const unsigned int r, const double h_previous, const double h,
                                       double &kinetic, double &work, double &power)
  {
    const auto  &gravity = get_gravity();
    auto        &T       = bars[r];
    const double dt_avg  = 0.5 * (h_previous + h);
    for (const unsigned int i : shares[r].own_nodes)
      for (unsigned int d = 0; d < 3; ++d)
        {
          const unsigned int j     = 3 * i + d;
          const double       v_old = T.vs[j];
          const double       f     = T.fs[j] + T.ms[i] * gravity[d];
          // As for the host nodes (Simulator::update_velocity): the
          // kinetic energy of the variable-step identity, and the
          // pull reaction's work by the trapezoidal rule.
          double f_total = f;
          if (T.pulled[i])
            {
              const double vp = layouts[r].pull_velocity[d];
              const double reaction =
                dt_avg > 0 ? T.ms[i] * (vp - (v_old + dt_avg * f / T.ms[i])) / dt_avg : 0.;
              work += 0.5 * (T.pull_reaction[j] + reaction) * v_old * h_previous;
              T.pull_reaction[j] = reaction;
              f_total += reaction;
              T.vs[j] = vp;
            }
          else
            T.vs[j] += dt_avg * f / T.ms[i];
          kinetic += 0.5 * v_old * (T.ms[i] * v_old + h_previous * f_total);
          power += f_total * (T.vs[j] - v_old);
        }
  }


  // @sect3{The bars' own nodes (bond-slip)}
  //
  // Each process advances its own nodes by the same central differences as
  // the host nodes; a pulled node keeps its velocity, and the work of the
  // force that holds it is external work. The energy terms of the own
  // nodes are summed over the processes. A subcycled layout advances by its
  // first substep h = dt / m here, m the fewest substeps that keep h within
  // the safety factor times the bars' own stable step; its step-change
  // term, 1/4 (h - h_previous) F dv, is booked here (the host's by the
  // simulator, with dt).
  void Reinforcement::update_velocity(const double dt_previous, const double dt, OwnMotion &motion)
  {
    double sums[4] = {0, 0, 0, 0};
    double &kinetic = partitioned ? sums[0] : motion.kinetic;
    double &work    = partitioned ? sums[1] : motion.work;
    double &power   = partitioned ? sums[2] : motion.power;
    double &sub_power = sums[3];
    bool    subcycled = false;
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (layouts[r].bond_slip)
        {
          if (!layouts[r].subcycling)
            {
              advance_velocity(r, dt_previous, dt, kinetic, work, power);
              continue;
            }
          auto        &T      = bars[r];
          const double h_prev = dt_previous > 0 ? T.substep : 0.;
          const double limit  = get_time_step_factor() * own_step[r];
          T.substeps = dt > 0 ? static_cast<unsigned int>(std::max(1., std::ceil(dt / limit * (1. - 1e-12)))) : 1;
          const double h = dt / T.substeps;
          double       p = 0;
          advance_velocity(r, h_prev, h, kinetic, work, p);
          sub_power += 0.25 * (h - h_prev) * p;
          T.substep = h;
          subcycled = true;
        }
    if (partitioned)
      {
        Utilities::MPI::sum(ArrayView<const double>(sums, 4), get_mpi_communicator(), ArrayView<double>(sums, 4));
        motion.kinetic += sums[0];
        motion.work += sums[1];
        motion.power += sums[2];
      }
    if (subcycled)
      {
        get_energies().step_change += pending_step_change;
        pending_step_change = dt > 0 ? sub_power : 0.;
      }
  }


  void Reinforcement::update_position(const double dt)
  {
    const auto &gravity  = get_gravity();
    Energies   &energies = get_energies();
    double      own_work = 0;
    double     &work     = partitioned ? own_work : energies.external_work;
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (layouts[r].bond_slip)
        {
          auto        &T = bars[r];
          const double h = layouts[r].subcycling ? T.substep : dt;
          for (const unsigned int i : shares[r].own_nodes)
            for (unsigned int d = 0; d < 3; ++d)
              {
                if (gravity.norm() > 0)
                  work += T.ms[i] * gravity[d] * h * T.vs[3 * i + d];
                T.xs[3 * i + d] += h * T.vs[3 * i + d];
              }
        }
    if (partitioned && gravity.norm() > 0)
      energies.external_work += Utilities::MPI::sum(own_work, get_mpi_communicator());
  }


  void Reinforcement::write_history(const double t, double)
  {
    const std::string &output_directory = get_output_directory();
    if (files.empty())
      for (const auto &layout : layouts)
        {
          record_output("rebar_" + layout.name + ".csv");
          files.emplace_back(output_directory + "/rebar_" + layout.name + ".csv");
          files.back() << "time,max_axial_force,min_axial_force,max_stress,min_stress,"
                                "max_effective_plastic_strain,probe_axial_force,probe_stress,probe_slip,"
                                "probe_bond_stress\n";
        }
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        const auto &h = history_rows[r];
        files[r] << std::setprecision(12) << t << ',' << h[0] << ',' << -h[1] << ',' << h[2] << ',' << -h[3]
                 << ',' << h[4] << ',' << h[5] << ',' << h[6] << ',' << h[7] << ',' << h[8] << '\n';
      }
  }


  // The row's extremes over each process's own elements, and the probe
  // element's and node's values from their process.
  void Reinforcement::prepare_history()
  {
    for (unsigned int r = 0; r < bars.size(); ++r)
      {
        const auto  &T     = bars[r];
        const auto  &S     = shares[r];
        const auto   names = layouts[r].material->uniaxial_history_names();
        const auto   it    = std::find(names.begin(), names.end(), "effective_plastic_strain");
        double       fmax = -1e300, fmin = 1e300, smax = -1e300, smin = 1e300, ep = 0;
        for (unsigned int e = 0; e < S.elements.size(); ++e)
          if (S.own_element[e])
            {
              const unsigned int k = S.elements[e];
              fmax = std::max(fmax, T.force[k]);
              fmin = std::min(fmin, T.force[k]);
              smax = std::max(smax, T.stress[k]);
              smin = std::min(smin, T.stress[k]);
              if (it != names.end())
                ep = std::max(ep, T.history[T.n_history * k + (it - names.begin())]);
            }
        // The probed element's first node: its slip and bond stress.
        const unsigned int probe = T.probe_element;
        const unsigned int pn    = T.elements[probe][0];
        auto              &h     = history_rows[r];
        h = {{fmax, -fmin, smax, -smin, ep, 0., 0., 0., 0.}};
        if (T.host_owned[pn])
          h = {{fmax, -fmin, smax, -smin, ep, T.force[probe], T.stress[probe],
                T.slip.empty() ? 0. : T.slip[pn], T.bond_stress.empty() ? 0. : T.bond_stress[pn]}};
        if (partitioned)
          {
            const MPI_Comm comm = get_mpi_communicator();
            Utilities::MPI::max(ArrayView<const double>(h.data(), 5), comm, ArrayView<double>(h.data(), 5));
            Utilities::MPI::sum(ArrayView<const double>(h.data() + 5, 4), comm, ArrayView<double>(h.data() + 5, 4));
          }
      }
  }



  void Reinforcement::add_kinetic_energy(double &kinetic) const
  {
    double  own = 0;
    double &sum = partitioned ? own : kinetic;
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (!bars[r].vs.empty())
        for (const unsigned int i : shares[r].own_nodes)
          for (unsigned int j = 3 * i; j < 3 * i + 3; ++j)
            sum += 0.5 * bars[r].ms[j / 3] * bars[r].vs[j] * bars[r].vs[j];
    if (partitioned)
      kinetic += Utilities::MPI::sum(own, get_mpi_communicator());
  }


  // Bond-slip bars (each process its own nodes): their momentum at time n with the host
  // body's.
  void Reinforcement::add_momentum(const double dt, std::vector<double> &momentum) const
  {
    const auto         &gravity = get_gravity();
    std::vector<double> own(partitioned ? momentum.size() : 0, 0.);
    auto               &sum = partitioned ? own : momentum;
    for (unsigned int r = 0; r < bars.size(); ++r)
      if (layouts[r].bond_slip)
        {
          const unsigned int host = body_index(layouts[r].host);
          const auto        &T    = bars[r];
          const double        h    = layouts[r].subcycling ? T.substep : dt;
          for (const unsigned int i : shares[r].own_nodes)
            for (unsigned int j = 3 * i; j < 3 * i + 3; ++j)
              sum[3 * host + j % 3] +=
                T.ms[j / 3] * T.vs[j] - 0.5 * h * (T.fs[j] + T.ms[j / 3] * gravity[j % 3]);
        }
    if (partitioned)
      {
        Utilities::MPI::sum(own, get_mpi_communicator(), own);
        for (unsigned int k = 0; k < own.size(); ++k)
          momentum[k] += own[k];
      }
  }


  std::string Reinforcement::describe() const
  {
    if (bars.empty())
      return "no bars";
    std::size_t trusses = 0;
    for (const auto &r : bars)
      trusses += r.elements.size();
    unsigned int          subcycled = 0, rate = 0;
    std::set<std::string> laws;
    for (const auto &layout : layouts)
      {
        subcycled += layout.subcycling;
        if (layout.material->rate_dependent())
          {
            ++rate;
            laws.insert(layout.material->rate_law());
          }
      }
    return std::to_string(trusses) + " bar elements in " + std::to_string(bars.size()) + " rebar set" +
           (bars.size() == 1 ? "" : "s") +
           (subcycled == 0 ? "" : " (" + std::to_string(subcycled) + " subcycled in substeps of their own stable step)") +
           (rate == 0 ? "; no rate effects in bars" :
                        "; rate effects in " + std::to_string(rate) + " of " + std::to_string(layouts.size()) +
                          " rebar sets (" + join(laws) + ")");
  }


  void Reinforcement::write_summary(std::ostream &out) const
  {
    double added_mass = 0;
    for (const auto &T : bars)
      added_mass += T.added_mass;
    if (added_mass > 0)
      out << "bar_added_mass_kg," << added_mass << '\n';
  }
} // namespace anvil::Rebar
