/**
 * @file
 * The elements a run should know about before it starts (LS-DYNA prints
 * the elements with the smallest time steps): each deformable element's
 * stable step in its reference shape (the step the loop takes for it,
 * ElementGroup::stable_step()), and its scaled Jacobian,
 * the smallest over its eight corners of det[e_x, e_y, e_z] / (|e_x| |e_y|
 * |e_z|) with e_* the edges from that corner (1 for a cube, sin of the
 * corner angle for a sheared one, 0.26 at a 165-degree corner).
 */
#include <anvil/simulator/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // The scaled Jacobian of a hexahedron with lexicographic vertices X.
    double scaled_jacobian(const double (&X)[8][3])
    {
      double smallest = 1e300;
      for (unsigned int i = 0; i < 8; ++i)
        {
          double e[3][3];
          for (unsigned int k = 0; k < 3; ++k)
            {
              const unsigned int j    = i ^ (1u << k);
              const double       sign = (i >> k) & 1 ? -1. : 1.;
              for (unsigned int d = 0; d < 3; ++d)
                e[k][d] = sign * (X[j][d] - X[i][d]);
            }
          const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                             e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                             e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
          double lengths = 1;
          for (unsigned int k = 0; k < 3; ++k)
            lengths *= std::sqrt(e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2]);
          smallest = std::min(smallest, lengths > 0 ? det / lengths : 0.);
        }
      return smallest;
    }
  } // namespace


  void Simulator::report_element_quality()
  {
    // Per owned deformable element: step, scaled Jacobian, id, body, centre.
    struct Entry
    {
      double        step, jacobian;
      unsigned long id;
      double        body, x, y, z;
    };
    std::vector<Entry> entries;
    for (unsigned int g = 0; g < solids->groups().size(); ++g)
      {
        const auto &group    = solids->groups()[g];
        const auto &material = group.get_material();
        if (material.is_rigid())
          continue;
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          if (group.element_is_owned(e))
            {
              double     X[8][3];
              const auto nodes = group.element_nodes(e);
              Entry      entry{0, 0, group.element_global_id(e), double(solids->group_body()[g]), 0, 0, 0};
              for (unsigned int n = 0; n < 8; ++n)
                for (unsigned int d = 0; d < 3; ++d)
                  X[n][d] = reference_position.local_element(nodes[n] + d);
              for (unsigned int n = 0; n < 8; ++n)
                {
                  entry.x += 0.125 * X[n][0];
                  entry.y += 0.125 * X[n][1];
                  entry.z += 0.125 * X[n][2];
                }
              entry.step     = group.stable_step(e, X);
              entry.jacobian = scaled_jacobian(X);
              entries.push_back(entry);
            }
      }
    constexpr unsigned int shown = 5;
    constexpr double       poor  = 0.3;
    auto by_step = [](const Entry &a, const Entry &b) { return a.step < b.step || (a.step == b.step && a.id < b.id); };
    auto by_jacobian = [](const Entry &a, const Entry &b) {
      return a.jacobian < b.jacobian || (a.jacobian == b.jacobian && a.id < b.id);
    };
    std::sort(entries.begin(), entries.end(), by_step);
    std::vector<Entry> smallest(entries.begin(), entries.begin() + std::min<std::size_t>(shown, entries.size()));
    std::sort(entries.begin(), entries.end(), by_jacobian);
    std::vector<Entry> poorest;
    unsigned long      n_poor = 0;
    for (const auto &e : entries)
      if (e.jacobian < poor)
        {
          ++n_poor;
          if (poorest.empty())
            poorest.push_back(e);
        }
    n_poor = Utilities::MPI::sum(n_poor, mpi_communicator);

    // Gathered on every rank (a few entries each), sorted alike.
    auto gather = [&](const std::vector<Entry> &mine, const auto &order, const std::size_t n) {
      std::vector<double> flat;
      for (const auto &e : mine)
        flat.insert(flat.end(), {e.step, e.jacobian, double(e.id), e.body, e.x, e.y, e.z});
      std::vector<Entry> all;
      for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, flat))
        for (std::size_t i = 0; i + 7 <= part.size(); i += 7)
          all.push_back({part[i], part[i + 1], (unsigned long)part[i + 2], part[i + 3], part[i + 4], part[i + 5],
                         part[i + 6]});
      std::sort(all.begin(), all.end(), order);
      all.resize(std::min(all.size(), n));
      return all;
    };
    smallest = gather(smallest, by_step, shown);
    poorest  = gather(poorest, by_jacobian, 1);
    if (smallest.empty())
      return;
    std::ostringstream out;
    out << std::setprecision(3) << "  smallest element steps (in the reference shape, before the safety "
        << "factor):";
    for (const auto &e : smallest)
      out << "\n    element " << e.id << " of body '" << bodies[int(e.body)].name << "' at (" << e.x << ", "
          << e.y << ", " << e.z << "): " << std::setprecision(4) << e.step << " s, scaled Jacobian "
          << std::setprecision(3) << e.jacobian;
    pcout << out.str() << std::endl;
    if (n_poor > 0 && !poorest.empty())
      {
        const auto &e = poorest.front();
        pcout << std::setprecision(3) << "  warning: " << n_poor << " element(s) with a scaled Jacobian below "
              << poor << " (corner angles beyond 163 degrees), the poorest " << e.jacobian << ": element "
              << e.id << " of body '" << bodies[int(e.body)].name << "' at (" << e.x << ", " << e.y << ", "
              << e.z << "); such elements stiffen in bending and carry concentrated strains, a mesh with "
              << "square corners is more accurate" << std::endl;
      }
  }
} // namespace anvil
