/**
 * @file
 * The hanging nodes of a locally refined mesh in the explicit update.
 */
#pragma once

#include <deal.II/base/partitioner.h>
#include <deal.II/lac/affine_constraints.h>

#include <vector>

namespace anvil
{
  /**
   * Where a refined element meets a coarser one (the 2:1 interface, one
   * level at most across a face, an edge or a vertex), the fine side's
   * nodes in the middle of the coarse face or edge are hanging: their
   * motion is the coarse face's, u_i = sum_j w_ij u_j over its corner
   * nodes (deal.II's hanging-node constraints, weights 1/2 and 1/4). With
   * C the matrix of these weights, the explicit update solves the
   * condensed system C^T M C a = C^T f:
   *
   * - the lumped mass and the forces of a hanging node go to its masters,
   *   m_j += w_ij m_i and f_j += w_ij f_i (row-sum lumping of C^T M C, and
   *   C^T f: total mass, momentum and the work f . v are those of the
   *   whole mesh, since the weights of each node sum to one);
   * - the masters move by the central difference, and the hanging nodes
   *   follow them.
   *
   * Every value is a local index of the nodal vectors (owned, then ghost
   * entries). A master's sum adds its hanging nodes in the order of their
   * scene index, the same on any number of processes, so that results stay
   * bitwise independent of the partition.
   */
  class HangingNodes
  {
  public:
    /**
     * Take the lines of @p constraints (closed, homogeneous) whose dof and
     * masters all lie in @p partitioner's owned and ghost indices; @p key
     * gives each local index its place in the summation order. Throws
     * when an owned hanging dof has a master the process does not hold
     * (the ghost layer is too thin for the mesh). Every process calls
     * it, or none.
     */
    void reinit(const dealii::AffineConstraints<double> &constraints,
                const dealii::Utilities::MPI::Partitioner &partitioner,
                const std::vector<unsigned long>          &key);

    /** Whether the scene has no hanging nodes (the same on every process:
        a process whose own cells have none still takes part in the
        exchanges). */
    bool empty() const
    {
      return !in_use;
    }

    /** The number of hanging dofs the process holds (owned and ghost). */
    unsigned int size() const
    {
      return dof.size();
    }

    /** Whether the local index @p i is a hanging dof. */
    bool is_hanging(const unsigned int i) const
    {
      return i < line.size() && line[i] >= 0;
    }

    /** The masters of the hanging dof with local index @p i and their
        weights (local indices; empty where @p i does not hang or its line
        is not held). */
    std::vector<std::pair<unsigned int, double>> masters_of(unsigned int i) const;

    /** C^T: values[j] += w_ij values[i] for each hanging i (all of them
        the process holds, whose values must be complete), then
        values[i] = 0. */
    void condense(double *values) const;

    /** values[i] = sum_j w_ij values[j] for the owned hanging dofs
        (below @p n_owned); the masters' values must be current. */
    void distribute(double *values, unsigned int n_owned) const;

    /** The positions of the owned hanging dofs after a step @p dt with the
        velocities @p v, from the masters' x_j + dt v_j (evaluated as the
        masters' owners evaluate them, so that the constraint holds to the
        bit); written to @p out, one per owned hanging dof in order. */
    void advance(const double        *x,
                 const double        *v,
                 double               dt,
                 unsigned int         n_owned,
                 std::vector<double> &out) const;

    /** Write what advance() computed into @p x. */
    void assign(double *x, unsigned int n_owned, const std::vector<double> &values) const;

  private:
    /** The hanging dofs in summation order, and their masters and weights
        (compressed rows: masters of dof[k] at start[k] .. start[k+1]). */
    std::vector<unsigned int> dof, start, master;
    std::vector<double>       weight;
    /** Each local index's place k in dof (-1: it does not hang). */
    std::vector<int>          line;
    bool                      in_use = false;
  };
} // namespace anvil
