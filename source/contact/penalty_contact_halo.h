/**
 * @file
 * The halo of a mesh-to-mesh penalty pair (PenaltyContact::Halo): which
 * slave nodes a rank evaluates, which master segments it sees, and what it
 * exchanges with the ranks around it. Private to the penalty pair's two
 * source files.
 */
#pragma once

#include <anvil/contact/penalty_contact.h>

#include <mpi.h>

#include <vector>

namespace anvil::Contact
{
  /**
   * A rank evaluates the slave nodes it owns against the master segments
   * within reach of them. The segments of its own and ghost cells it knows;
   * the others come from the ranks that own them, chosen by boxes:
   *
   * - every rank publishes, per surface, the box of the nodes it owns, the
   *   deepest active element (current thickness V / A) and the largest
   *   segment (the diagonal of its bounding box) among the segments it
   *   sends (those whose lowest pair node it owns);
   * - a slave node farther than the reach 2 h + 2.2 d (h the deepest
   *   element, d the largest segment) from every master node touches no
   *   segment: a touch needs |l| < h at a point of the segment extended by
   *   a tenth of its size, and a node of that segment is then within h +
   *   1.2 d; the margin h + d covers the segment that held the node last
   *   step, which may have moved by a step's travel since;
   * - the halo takes every segment whose box comes within reach + 2 d + h
   *   of the box of the rank's own slave nodes: then every master node
   *   within reach of an own slave node, every segment around it and the
   *   other faces of those segments' elements are in it, and the nearest
   *   master node of a node within reach is the one one process finds.
   *
   * One process, or a pair every rank evaluates whole (a rigid body's
   * mesh, on gathered positions), is the same with every node own and
   * every segment seen; nothing is exchanged then.
   */
  struct PenaltyContact::Halo
  {
    ~Halo()
    {
      if (comm != MPI_COMM_NULL)
        {
          int finalized = 0;
          MPI_Finalized(&finalized);
          if (!finalized)
            MPI_Comm_free(&comm);
        }
    }

    /** Whether this rank sees segment @p k of master surface @p m this
        step (its geometry is made). */
    bool sees(const unsigned int m, const unsigned int k) const
    {
      return seen[m].empty() || seen[m][k] == step;
    }

    /** The pair's own communicator (a duplicate: its messages never meet
        another's); MPI_COMM_NULL when nothing is exchanged. */
    MPI_Comm     comm    = MPI_COMM_NULL;
    unsigned int n_ranks = 1, rank = 0;
    /** Per pair node, the rank that owns it. */
    std::vector<int> owner;
    /** Per surface: the nodes this rank owns (its slave nodes), the
        segments with an own node (known from the own and ghost cells), and
        the segments this rank sends (their lowest pair node is its own). */
    std::vector<unsigned int> own_nodes[2], local_segments[2], sent_segments[2];
    /** The nodes of the local segments (positions from the pair's), and
        per surface a mark of the local segments. */
    std::vector<unsigned int> local_nodes;
    std::vector<char>         is_local[2];
    /** This step's positions and velocities of the local and the received
        nodes (3 per pair node). */
    std::vector<double> x, v;
    unsigned int        step = 0;
    /** Per master surface: the segments seen this step, the step each
        segment was last seen at (empty: every segment, every step), and
        the nodes of those seen (the search tree's). */
    std::vector<unsigned int> segments[2], seen[2], nodes[2];
    /** Per surface, over all ranks: the box of its nodes (lo, hi), the
        deepest active element (V / A), the largest segment (its bounding
        box's diagonal); the reach and the halo's radius around it as a
        master surface. Units: m. */
    double box[2][6]     = {};
    double max_depth[2]  = {0, 0};
    double max_size[2]   = {0, 0};
    double reach[2]      = {0, 0};
    double radius[2]     = {0, 0};
    /** Per rank and surface: the box of its own nodes, its deepest
        element and largest segment (8 numbers; ranks x 16). */
    std::vector<double> extents;
    /** The ranks this one sends master segments to (and receives touches
        from), and those it receives segments from (and sends touches to). */
    std::vector<int> send_to, receive_from;
    std::vector<std::vector<double>>                  send_buffer;
    std::vector<double>                               receive_buffer;
    std::vector<std::vector<PenaltyContact::Touch>>   touch_buffer;
    std::vector<PenaltyContact::Touch>                received;
    std::vector<MPI_Request>                          requests;
    /** Work arrays: a mark per pair node; the segments sent to one rank,
        per master surface. */
    std::vector<char>         node_mark;
    std::vector<unsigned int> segment_list[2];
    /** Touches sent to another rank this step. */
    unsigned int sent_touches = 0;
  };
} // namespace anvil::Contact
