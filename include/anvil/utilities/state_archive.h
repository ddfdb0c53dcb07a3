/**
 * @file
 * The state of a run in bytes, for checkpoints: one archive per process,
 * written and read back in the same order (the same class lists its
 * members once, for both directions), so a resumed run continues bitwise.
 *
 * What every process holds alike (the clock, the energies, a rigid body)
 * goes into the archive's stream; what belongs to one process's share of
 * the scene (a node, an element, a bar's node, a contact pair's node) goes
 * into keyed tables, by a key that names the item in the whole scene (a
 * node's scene vertex, an element's id). A run resumed on another number
 * of processes, or after a new partition, reads the stream of one process
 * and finds each of its items in the tables whichever process wrote them.
 */
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace anvil
{
  /**
   * Per-item values by scene-wide key: n_values doubles per key, the keys
   * in the order written (one process's) or sorted (merged over the
   * processes). A table of n_values = 0 is a set of keys (several processes
   * may name the same key).
   */
  struct KeyedTable
  {
    unsigned int               n_values = 0;
    std::vector<std::uint64_t> keys;
    std::vector<double>        values;
  };
  using KeyedTables = std::map<std::string, KeyedTable>;

  /** Where an element of a mesh refined or coarsened during the run takes
      its state from (doc/adaptivity.md, "Refinement during the run"): an
      element of the mesh before, with the weight of its intensive values
      (stress, history: 1 for a child, the child's share of the volume
      for a coarsened parent's children) and of its extensive ones
      (energies: the child's share, 1), and the octant (child index) that
      pairs the quadrature points of the two. */
  struct ElementSource
  {
    std::uint64_t id;
    double        intensive;
    double        extensive;
    unsigned int  octant;
    /** The new element is the same cell (its record is copied), a child
        of the source, or the parent of the sources. */
    enum Kind : unsigned char
    {
      same,
      child,
      parent
    } kind;
  };
  using ElementTransfer = std::map<std::uint64_t, std::vector<ElementSource>>;


  /**
   * One item's record in a keyed table, read or written value by value:
   * saving, each call copies a value of the item's arrays into the record;
   * loading, the record's next value into the array (integers and flags
   * through a double, exact).
   */
  class RecordCursor
  {
  public:
    RecordCursor(double *record, const bool save)
      : at(record)
      , save(save)
    {}
    template <typename T>
    void operator()(T &x)
    {
      if (save)
        *at++ = static_cast<double>(x);
      else
        x = static_cast<T>(*at++);
    }
    template <typename T>
    void operator()(std::vector<T> &v, const std::size_t first, const unsigned int n)
    {
      for (unsigned int k = 0; k < n; ++k)
        {
          T x = v[first + k];
          (*this)(x);
          v[first + k] = x;
        }
    }

  private:
    double    *at;
    const bool save;
  };

  class StateArchive
  {
  public:
    /** An archive to write into. */
    StateArchive()
      : tables(std::make_shared<KeyedTables>())
    {}
    /** An archive that reads @p data, its keyed tables merged from every
        process's in @p merged (none: an archive without tables). */
    explicit StateArchive(std::string data, std::shared_ptr<const KeyedTables> merged = nullptr)
      : loading(true)
      , buffer(std::move(data))
      , tables(std::const_pointer_cast<KeyedTables>(merged ? merged : std::make_shared<KeyedTables>()))
    {}

    /** An archive of its own stream that shares this one's tables, its
        table names under @p prefix (a family's record). */
    StateArchive nested(const std::string &prefix, std::string data = {}) const
    {
      StateArchive a;
      a.loading  = loading;
      a.transfer = transfer;
      a.buffer  = std::move(data);
      a.tables  = tables;
      a.prefix  = this->prefix + prefix + "/";
      return a;
    }

    /** The keyed tables written so far (writing). */
    const KeyedTables &keyed_tables() const
    {
      return *tables;
    }

    /**
     * Per-item values by key. Writing, the items this process owns: @p
     * keys and their n_values values each in @p values (item-major).
     * Reading, the items this process holds: @p values is sized and filled
     * from the merged tables for @p keys; an item no process wrote is an
     * error (the checkpoint is not of this scene), or with @p may_be_new
     * an item the scene has gained since (a stage's new boundary
     * condition), which keeps @p fresh.
     */
    void keyed(const std::string &name, const std::vector<std::uint64_t> &keys, const unsigned int n_values,
               std::vector<double> &values, const bool may_be_new = false, const double fresh = 0.)
    {
      const std::string full = prefix + name;
      if (!loading)
        {
          if (values.size() != std::size_t(n_values) * keys.size())
            throw std::logic_error("keyed state '" + full + "': " + std::to_string(values.size()) +
                                   " values for " + std::to_string(keys.size()) + " items");
          auto &t    = (*tables)[full];
          t.n_values = n_values;
          t.keys.insert(t.keys.end(), keys.begin(), keys.end());
          t.values.insert(t.values.end(), values.begin(), values.end());
          return;
        }
      values.assign(std::size_t(n_values) * keys.size(), fresh);
      if (keys.empty())
        return;
      const auto t = tables->find(full);
      if (t == tables->end() && may_be_new)
        return;
      if (t == tables->end() || t->second.n_values != n_values)
        throw std::runtime_error("the checkpoint holds no table '" + full + "' of " + std::to_string(n_values) +
                                 " values an item");
      const auto &k = t->second.keys;
      for (std::size_t i = 0; i < keys.size(); ++i)
        {
          const auto at = std::lower_bound(k.begin(), k.end(), keys[i]);
          if ((at == k.end() || *at != keys[i]) && may_be_new)
            continue;
          if (at == k.end() || *at != keys[i])
            throw std::runtime_error("the checkpoint holds no item " + std::to_string(keys[i]) + " of '" + full +
                                     "'");
          const std::size_t j = at - k.begin();
          std::copy_n(t->second.values.begin() + j * n_values, n_values, values.begin() + i * n_values);
        }
    }

    /** keyed() with each item's values moved by @p transfer(k,
        RecordCursor &) between its arrays and its record (k: the item's
        index in @p keys): out of the arrays when writing, into them when
        reading. */
    template <typename Transfer>
    void keyed_items(const std::string                &name,
                     const std::vector<std::uint64_t> &keys,
                     const unsigned int                n_values,
                     const Transfer                   &transfer,
                     const bool                        may_be_new = false)
    {
      std::vector<double> values(loading ? 0 : std::size_t(n_values) * keys.size());
      if (!loading)
        for (std::size_t k = 0; k < keys.size(); ++k)
          {
            RecordCursor out(values.data() + n_values * k, true);
            transfer(k, out);
          }
      keyed(name, keys, n_values, values, may_be_new);
      if (loading)
        for (std::size_t k = 0; k < keys.size(); ++k)
          {
            RecordCursor in(values.data() + n_values * k, false);
            transfer(k, in);
          }
    }

    /** A set of keys that several processes may each hold part of (or
        the same keys): writing, this process's; reading, the sorted union
        of every process's. */
    void key_union(const std::string &name, std::vector<std::uint64_t> &keys)
    {
      std::vector<double> none;
      if (!loading)
        {
          keyed(name, keys, 0, none);
          return;
        }
      const auto t = tables->find(prefix + name);
      keys.clear();
      if (t != tables->end())
        keys = t->second.keys;
    }

    /** The tables of every process's file merged (reading): the keys
        sorted with their values, a set's keys made unique; a key written
        twice in a table of values is an error. */
    static std::shared_ptr<const KeyedTables> merge(const std::vector<KeyedTables> &parts);

    /** The stream and the tables in one string (a checkpoint file), and
        back. */
    std::string file_data() const;
    static std::pair<std::string, KeyedTables> split_file_data(const std::string &data);

    bool is_loading() const
    {
      return loading;
    }
    /** Loading onto a mesh refined or coarsened since the checkpoint: the
        sources of its new elements (doc/adaptivity.md); the tables keyed
        by node then hold no items for the new nodes. */
    void set_transfer(std::shared_ptr<const ElementTransfer> t)
    {
      transfer = std::move(t);
    }
    const ElementTransfer *element_transfer() const
    {
      return transfer.get();
    }
    /** The merged table @p name (reading), or none. */
    const KeyedTable *table(const std::string &name) const
    {
      const auto t = tables->find(prefix + name);
      return t == tables->end() ? nullptr : &t->second;
    }

    const std::string &data() const
    {
      return buffer;
    }

    /** Whether every byte has been read back (a check of the layout). */
    bool exhausted() const
    {
      return position == buffer.size();
    }

    template <typename T>
    StateArchive &operator&(T &x)
    {
      io(x);
      return *this;
    }

  private:
    bool                         loading = false;
    std::string                  buffer;
    std::size_t                  position = 0;
    std::shared_ptr<KeyedTables> tables;
    std::string                  prefix;
    std::shared_ptr<const ElementTransfer> transfer;

    void bytes(void *p, const std::size_t n)
    {
      if (!loading)
        buffer.append(static_cast<const char *>(p), n);
      else
        {
          if (position + n > buffer.size())
            throw std::runtime_error("the checkpoint is shorter than the state it should hold");
          std::memcpy(p, buffer.data() + position, n);
          position += n;
        }
    }

    std::size_t size(std::size_t n)
    {
      bytes(&n, sizeof(n));
      return n;
    }

    template <typename T>
    void io(T &x)
    {
      if constexpr (std::is_trivially_copyable_v<T>)
        bytes(&x, sizeof(T));
      else
        x.serialize(*this);
    }

    void io(std::string &s)
    {
      s.resize(size(s.size()));
      bytes(s.data(), s.size());
    }

    void io(std::vector<bool> &v)
    {
      v.resize(size(v.size()));
      for (std::size_t i = 0; i < v.size(); ++i)
        {
          bool b = v[i];
          bytes(&b, sizeof(b));
          v[i] = b;
        }
    }

    template <typename T>
    void io(std::vector<T> &v)
    {
      v.resize(size(v.size()));
      if constexpr (std::is_trivially_copyable_v<T>)
        {
          if (!v.empty())
            bytes(v.data(), v.size() * sizeof(T));
        }
      else
        for (auto &x : v)
          io(x);
    }

    template <typename A, typename B>
    void io(std::pair<A, B> &p)
    {
      io(p.first);
      io(p.second);
    }

  };
} // namespace anvil
