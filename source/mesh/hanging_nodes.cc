/**
 * @file
 * Hanging nodes: condensation onto the masters and the masters' motion.
 */
#include <anvil/mesh/hanging_nodes.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <numeric>

namespace anvil
{
  void HangingNodes::reinit(const dealii::AffineConstraints<double>   &constraints,
                            const dealii::Utilities::MPI::Partitioner &partitioner,
                            const std::vector<unsigned long>          &key)
  {
    const unsigned int n_local = partitioner.locally_owned_size() + partitioner.n_ghost_indices();
    struct Line
    {
      unsigned int                                   dof;
      std::vector<std::pair<unsigned int, double>> entries;
    };
    std::vector<Line> lines;
    for (const auto &line : constraints.get_lines())
      {
        if (!partitioner.in_local_range(line.index) && !partitioner.is_ghost_entry(line.index))
          continue;
        Line l;
        l.dof        = partitioner.global_to_local(line.index);
        bool visible = true;
        for (const auto &[j, w] : line.entries)
          {
            if (!partitioner.in_local_range(j) && !partitioner.is_ghost_entry(j))
              visible = false;
            else
              l.entries.emplace_back(partitioner.global_to_local(j), w);
          }
        // The masters in the order of their scene keys: deal.II lists them
        // by global dof index, which depends on the partition, and the
        // weighted sums below must add in the same order on any number
        // of processes.
        std::sort(l.entries.begin(), l.entries.end(),
                  [&](const auto &a, const auto &b) { return key[a.first] < key[b.first]; });
        AssertThrow(line.inhomogeneity == 0., dealii::ExcMessage("hanging-node constraints are homogeneous"));
        AssertThrow(visible || l.dof >= partitioner.locally_owned_size(),
                    dealii::ExcMessage("an owned hanging node has a master outside the ghost layer"));
        if (visible)
          lines.push_back(std::move(l));
      }
    std::sort(lines.begin(), lines.end(), [&](const Line &a, const Line &b) { return key[a.dof] < key[b.dof]; });
    dof.clear();
    start.assign(1, 0);
    master.clear();
    weight.clear();
    line.assign(n_local, -1);
    in_use = true;
    for (const auto &l : lines)
      {
        dof.push_back(l.dof);
        line[l.dof] = dof.size() - 1;
        for (const auto &[j, w] : l.entries)
          {
            master.push_back(j);
            weight.push_back(w);
          }
        start.push_back(master.size());
      }
  }


  std::vector<std::pair<unsigned int, double>> HangingNodes::masters_of(const unsigned int i) const
  {
    std::vector<std::pair<unsigned int, double>> out;
    if (is_hanging(i))
      for (unsigned int e = start[line[i]]; e < start[line[i] + 1]; ++e)
        out.emplace_back(master[e], weight[e]);
    return out;
  }


  void HangingNodes::condense(double *values) const
  {
    for (unsigned int k = 0; k < dof.size(); ++k)
      {
        const double value = values[dof[k]];
        for (unsigned int e = start[k]; e < start[k + 1]; ++e)
          values[master[e]] += weight[e] * value;
      }
    for (const unsigned int i : dof)
      values[i] = 0.;
  }


  void HangingNodes::distribute(double *values, const unsigned int n_owned) const
  {
    for (unsigned int k = 0; k < dof.size(); ++k)
      if (dof[k] < n_owned)
        {
          double value = 0;
          for (unsigned int e = start[k]; e < start[k + 1]; ++e)
            value += weight[e] * values[master[e]];
          values[dof[k]] = value;
        }
  }


  void HangingNodes::advance(const double        *x,
                             const double        *v,
                             const double         dt,
                             const unsigned int   n_owned,
                             std::vector<double> &out) const
  {
    out.clear();
    for (unsigned int k = 0; k < dof.size(); ++k)
      if (dof[k] < n_owned)
        {
          double value = 0;
          for (unsigned int e = start[k]; e < start[k + 1]; ++e)
            {
              // (A master's x^{n+1} as its owner computes it: x += dt v.)
              double xj = x[master[e]];
              xj += dt * v[master[e]];
              value += weight[e] * xj;
            }
          out.push_back(value);
        }
  }


  void HangingNodes::assign(double *x, const unsigned int n_owned, const std::vector<double> &values) const
  {
    unsigned int n = 0;
    for (unsigned int k = 0; k < dof.size(); ++k)
      if (dof[k] < n_owned)
        x[dof[k]] = values[n++];
  }
} // namespace anvil
