/**
 * @file
 * The halo of a mesh-to-mesh penalty pair: what each rank sees of the
 * master surfaces and what it exchanges (penalty_contact_halo.h).
 */
#include "penalty_contact_halo.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace anvil::Contact
{
  namespace
  {
    constexpr int halo_tag = 7301, touch_tag = 7302;

    /** Whether the box @p a (8 numbers: -lo, hi, ...) grown by @p grow_a
        meets the box @p b grown by @p grow_b. An empty box (lo = +inf)
        meets nothing. */
    bool boxes_meet(const double *a, const double grow_a, const double *b, const double grow_b)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (-a[d] - grow_a > b[3 + d] + grow_b || -b[d] - grow_b > a[3 + d] + grow_a)
          return false;
      return true;
    }

    /** The box (-lo, hi) of the nodes @p nodes at positions @p x (3 per
        pair node) into @p e; of no node, an empty box. */
    template <typename Nodes>
    void node_box(const std::vector<double> &x, const Nodes &nodes, double *e)
    {
      for (unsigned int d = 0; d < 3; ++d)
        e[d] = e[3 + d] = -1e300;
      for (const unsigned int i : nodes)
        for (unsigned int d = 0; d < 3; ++d)
          {
            e[d]     = std::max(e[d], -x[3 * i + d]);
            e[3 + d] = std::max(e[3 + d], x[3 * i + d]);
          }
    }
  } // namespace


  // @sect3{Setting up the halo}
  //
  // Which nodes are the rank's own, which segments it knows from its own
  // and ghost cells (those with an own node: their element shares a vertex
  // with an own cell) and which it sends (those whose lowest pair node it
  // owns: each segment has one sender, and it knows the segment's four
  // nodes).
  void PenaltyContact::setup_halo(MPI_Comm comm, const dealii::IndexSet *owned_dofs)
  {
    halo     = std::make_shared<Halo>();
    Halo &h  = *halo;
    h.n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
    h.rank    = dealii::Utilities::MPI::this_mpi_process(comm);
    const unsigned int n    = dofs.size();
    const bool         all  = owned.empty();
    auto               mine = [&](const unsigned int i) { return all || owned[i] != 0; };
    for (unsigned int s = 0; s < 2; ++s)
      {
        const Surface &surf = surface[s];
        for (const unsigned int i : surf.nodes)
          if (mine(i))
            h.own_nodes[s].push_back(i);
        for (unsigned int k = 0; k < surf.segments.size(); ++k)
          {
            const auto &nodes = surf.segments[k];
            if (mine(nodes[0]) || mine(nodes[1]) || mine(nodes[2]) || mine(nodes[3]))
              h.local_segments[s].push_back(k);
            if (mine(*std::min_element(nodes.begin(), nodes.end())))
              h.sent_segments[s].push_back(k);
          }
      }
    if (h.n_ranks == 1)
      {
        // Every segment seen, every node in the trees.
        for (unsigned int m = 0; m < 2; ++m)
          {
            h.segments[m].resize(surface[m].segments.size());
            for (unsigned int k = 0; k < h.segments[m].size(); ++k)
              h.segments[m][k] = k;
            h.nodes[m] = surface[m].nodes;
          }
        return;
      }
    AssertThrow(owned_dofs != nullptr && owned_dofs->is_contiguous(),
                dealii::ExcMessage("contact: the owned dofs are not contiguous"));
    h.comm = dealii::Utilities::MPI::duplicate_communicator(comm);
    // The owner of each pair node, from the ranks' ranges of dofs.
    const unsigned long first = owned_dofs->n_elements() > 0 ? owned_dofs->nth_index_in_set(0) : 0;
    const std::array<unsigned long, 2> range = {{first, first + owned_dofs->n_elements()}};
    const auto ranges = dealii::Utilities::MPI::all_gather(comm, range);
    std::vector<std::array<unsigned long, 3>> starts;
    for (unsigned int r = 0; r < h.n_ranks; ++r)
      if (ranges[r][1] > ranges[r][0])
        starts.push_back({{ranges[r][0], ranges[r][1], r}});
    std::sort(starts.begin(), starts.end());
    h.owner.assign(n, -1);
    for (unsigned int i = 0; i < n; ++i)
      {
        auto it = std::upper_bound(starts.begin(), starts.end(),
                                   std::array<unsigned long, 3>{{dofs[i], ~0ul, ~0ul}});
        AssertThrow(it != starts.begin() && dofs[i] < (it - 1)->at(1),
                    dealii::ExcMessage("contact: a pair node no rank owns"));
        h.owner[i] = static_cast<int>((it - 1)->at(2));
      }
    h.node_mark.assign(n, 0);
    for (unsigned int s = 0; s < 2; ++s)
      {
        h.is_local[s].assign(surface[s].segments.size(), 0);
        h.seen[s].assign(surface[s].segments.size(), 0);
        for (const unsigned int k : h.local_segments[s])
          {
            h.is_local[s][k] = 1;
            for (const unsigned int i : surface[s].segments[k])
              if (!h.node_mark[i])
                {
                  h.node_mark[i] = 1;
                  h.local_nodes.push_back(i);
                }
          }
      }
    for (const unsigned int i : h.local_nodes)
      h.node_mark[i] = 0;
    h.x.assign(3 * n, 0.);
    if (needs_velocities())
      h.v.assign(3 * n, 0.);
    h.extents.resize(16 * h.n_ranks);
  }


  // @sect3{The halo of a step}
  //
  // The geometry of the segments the rank knows (the sums of a slave node
  // are made when it comes within the master surface's box), the extents
  // of all ranks (one gather of 16 numbers each), then the segments within
  // the halo's radius of each rank's own slave nodes from the ranks that
  // send them. Which ranks send to which follows from the extents alone,
  // so every rank knows whom to wait for; a message may be empty.
  void PenaltyContact::exchange_halo(const std::vector<double> &x, const std::vector<double> &v)
  {
    Halo      &h       = *halo;
    const bool needs_v = needs_velocities() && !v.empty();
    ++h.step;
    for (unsigned int s = 0; s < 2; ++s)
      {
        Surface &surf = surface[s];
        for (const unsigned int k : h.local_segments[s])
          if (surf.active[k])
            surf.update_segment(k, x);
      }

    // Per surface: the box of the own nodes (-lo, hi), the deepest active
    // element and the largest segment among those the rank sends.
    double own[16];
    for (unsigned int s = 0; s < 2; ++s)
      {
        const Surface &surf = surface[s];
        double        *e    = own + 8 * s;
        node_box(x, h.own_nodes[s], e);
        double depth = 0, size = 0;
        for (const unsigned int k : h.sent_segments[s])
          {
            if (surf.active[k])
              depth = std::max(depth, surf.volume[k] / surf.area[k]);
            double b[6];
            node_box(x, surf.segments[k], b);
            double d2 = 0;
            for (unsigned int d = 0; d < 3; ++d)
              d2 += (b[3 + d] + b[d]) * (b[3 + d] + b[d]);
            size = std::max(size, std::sqrt(d2));
          }
        e[6] = depth;
        e[7] = size;
      }
    const double *all = own;
    if (h.n_ranks > 1)
      {
        MPI_Allgather(own, 16, MPI_DOUBLE, h.extents.data(), 16, MPI_DOUBLE, h.comm);
        all = h.extents.data();
      }
    for (unsigned int m = 0; m < 2; ++m)
      {
        double e[8];
        std::copy(all + 8 * m, all + 8 * m + 8, e);
        for (unsigned int r = 1; r < h.n_ranks; ++r)
          for (unsigned int q = 0; q < 8; ++q)
            e[q] = std::max(e[q], all[16 * r + 8 * m + q]);
        for (unsigned int d = 0; d < 3; ++d)
          {
            h.box[m][d]     = -e[d];
            h.box[m][3 + d] = e[3 + d];
          }
        h.max_depth[m] = e[6];
        h.max_size[m]  = e[7];
        h.reach[m]     = 2. * e[6] + 2.2 * e[7];
        h.radius[m]    = h.reach[m] + 2. * e[7] + e[6];
      }
    if (h.n_ranks == 1)
      return;

    // This step's positions of the nodes the rank knows.
    for (const unsigned int i : h.local_nodes)
      for (unsigned int d = 0; d < 3; ++d)
        {
          h.x[3 * i + d] = x[3 * i + d];
          if (needs_v)
            h.v[3 * i + d] = v[3 * i + d];
        }
    // The passes: slave surface s against master surface 1 - s.
    const unsigned int n_passes = symmetric ? 2 : 1;
    auto extent = [&](const unsigned int r, const unsigned int s) { return all + 16 * r + 8 * s; };
    h.send_to.clear();
    h.receive_from.clear();
    for (unsigned int q = 0; q < h.n_ranks; ++q)
      if (q != h.rank)
        {
          bool to = false, from = false;
          for (unsigned int p = 0; p < n_passes; ++p)
            {
              const unsigned int s = 1 - p, m = p;
              to   = to || boxes_meet(extent(h.rank, m), h.max_size[m], extent(q, s), h.radius[m]);
              from = from || boxes_meet(extent(q, m), h.max_size[m], extent(h.rank, s), h.radius[m]);
            }
          if (to)
            h.send_to.push_back(q);
          if (from)
            h.receive_from.push_back(q);
        }

    // The segments a rank sends to rank q: its own segments whose box
    // meets q's slave box grown by the halo's radius.
    auto sent = [&](const unsigned int q, const unsigned int m, std::vector<unsigned int> &list) {
      const Surface &surf = surface[m];
      const double  *b    = extent(q, 1 - m);
      for (const unsigned int k : h.sent_segments[m])
        {
          double e[6];
          node_box(x, surf.segments[k], e);
          if (boxes_meet(e, 0., b, h.radius[m]))
            list.push_back(k);
        }
    };
    auto &list = h.segment_list;
    h.send_buffer.resize(h.send_to.size());
    h.requests.resize(h.send_to.size());
    const unsigned int width = needs_v ? 7 : 4;
    for (unsigned int c = 0; c < h.send_to.size(); ++c)
      {
        const unsigned int q = h.send_to[c];
        auto              &b = h.send_buffer[c];
        b.assign(2, 0.);
        for (unsigned int p = 0; p < n_passes; ++p)
          {
            const unsigned int m = p;
            list[m].clear();
            sent(q, m, list[m]);
            b[m] = list[m].size();
            b.insert(b.end(), list[m].begin(), list[m].end());
          }
        const std::size_t first_node = b.size();
        for (unsigned int p = 0; p < n_passes; ++p)
          for (const unsigned int k : list[p])
            for (const unsigned int i : surface[p].segments[k])
              if (!h.node_mark[i])
                {
                  h.node_mark[i] = 1;
                  b.push_back(i);
                  for (unsigned int d = 0; d < 3; ++d)
                    b.push_back(x[3 * i + d]);
                  if (needs_v)
                    for (unsigned int d = 0; d < 3; ++d)
                      b.push_back(v[3 * i + d]);
                }
        for (std::size_t j = first_node; j < b.size(); j += width)
          h.node_mark[static_cast<unsigned int>(b[j])] = 0;
        MPI_Isend(b.data(), b.size(), MPI_DOUBLE, q, halo_tag, h.comm, &h.requests[c]);
      }

    // The segments the rank sees: its own within the radius of its own
    // slave nodes, then those received.
    for (unsigned int m = 0; m < 2; ++m)
      h.segments[m].clear();
    auto see = [&](const unsigned int m, const unsigned int k) {
      if (h.seen[m][k] != h.step)
        {
          h.seen[m][k] = h.step;
          h.segments[m].push_back(k);
        }
    };
    for (unsigned int p = 0; p < n_passes; ++p)
      {
        list[p].clear();
        sent(h.rank, p, list[p]);
        for (const unsigned int k : list[p])
          see(p, k);
      }
    for (const unsigned int q : h.receive_from)
      {
        MPI_Status status;
        MPI_Probe(q, halo_tag, h.comm, &status);
        int count = 0;
        MPI_Get_count(&status, MPI_DOUBLE, &count);
        h.receive_buffer.resize(count);
        MPI_Recv(h.receive_buffer.data(), count, MPI_DOUBLE, q, halo_tag, h.comm, MPI_STATUS_IGNORE);
        const double     *b = h.receive_buffer.data();
        const std::size_t c0 = b[0], c1 = b[1];
        for (std::size_t j = 0; j < c0; ++j)
          see(0, static_cast<unsigned int>(b[2 + j]));
        for (std::size_t j = 0; j < c1; ++j)
          see(1, static_cast<unsigned int>(b[2 + c0 + j]));
        for (std::size_t j = 2 + c0 + c1; j < std::size_t(count); j += width)
          {
            const unsigned int i = b[j];
            for (unsigned int d = 0; d < 3; ++d)
              {
                h.x[3 * i + d] = b[j + 1 + d];
                if (needs_v)
                  h.v[3 * i + d] = b[j + 4 + d];
              }
          }
      }
    MPI_Waitall(h.requests.size(), h.requests.data(), MPI_STATUSES_IGNORE);

    // The geometry of the segments received, and the nodes of all seen
    // (the search trees').
    for (unsigned int m = 0; m < 2; ++m)
      {
        Surface &surf = surface[m];
        h.nodes[m].clear();
        for (const unsigned int k : h.segments[m])
          {
            if (surf.active[k] && !h.is_local[m][k])
              surf.update_segment(k, h.x);
            for (const unsigned int i : surf.segments[k])
              if (!h.node_mark[i])
                {
                  h.node_mark[i] = 1;
                  h.nodes[m].push_back(i);
                }
          }
        for (const unsigned int i : h.nodes[m])
          h.node_mark[i] = 0;
      }
  }


  // @sect3{The touches}
  //
  // A touch goes to every other rank that owns one of its segment's nodes.
  // Such a rank's box of own nodes, grown by the largest segment, meets
  // this rank's slave box grown by the halo's radius (the segment is in
  // the halo), so it is one of the ranks this one receives segments from;
  // conversely this rank receives touches from the ranks it sends
  // segments to. (A touch to any other rank would be an internal error.)
  void PenaltyContact::exchange_touches()
  {
    Halo &h        = *halo;
    h.sent_touches = 0;
    h.received.clear();
    if (h.n_ranks == 1)
      return;
    h.touch_buffer.resize(h.receive_from.size());
    for (auto &b : h.touch_buffer)
      b.clear();
    const unsigned long n = dofs.size();
    for (const Touch &t : touches)
      {
        const unsigned int master_index = t.key / n;
        const auto        &nodes        = surface[master_index].segments[t.segment];
        for (unsigned int j = 0; j < 4; ++j)
          {
            const int o       = h.owner[nodes[j]];
            bool      already = o == int(h.rank);
            for (unsigned int jj = 0; jj < j; ++jj)
              already = already || h.owner[nodes[jj]] == o;
            if (already)
              continue;
            const auto c = std::lower_bound(h.receive_from.begin(), h.receive_from.end(), o);
            AssertThrow(c != h.receive_from.end() && *c == o,
                        dealii::ExcMessage("contact pair '" + name +
                                           "': a touch on a segment from outside the halo (internal error)"));
            h.touch_buffer[c - h.receive_from.begin()].push_back(t);
            ++h.sent_touches;
          }
      }
    h.requests.resize(h.receive_from.size());
    for (unsigned int c = 0; c < h.receive_from.size(); ++c)
      MPI_Isend(h.touch_buffer[c].data(), h.touch_buffer[c].size() * sizeof(Touch), MPI_BYTE, h.receive_from[c],
                touch_tag, h.comm, &h.requests[c]);
    for (const unsigned int q : h.send_to)
      {
        MPI_Status status;
        MPI_Probe(q, touch_tag, h.comm, &status);
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        const std::size_t first = h.received.size();
        h.received.resize(first + bytes / sizeof(Touch));
        MPI_Recv(h.received.data() + first, bytes, MPI_BYTE, q, touch_tag, h.comm, MPI_STATUS_IGNORE);
      }
    MPI_Waitall(h.requests.size(), h.requests.data(), MPI_STATUSES_IGNORE);
  }
} // namespace anvil::Contact
