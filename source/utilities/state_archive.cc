/**
 * @file
 * The keyed tables of a checkpoint: how one process's file holds them and
 * how a resumed run merges every process's (include/anvil/utilities/
 * state_archive.h).
 */
#include <anvil/utilities/state_archive.h>

#include <numeric>

namespace anvil
{
  namespace
  {
    /** A table in a file: its name, values an item, keys and values. */
    struct StoredTable
    {
      std::string                name;
      unsigned int               n_values = 0;
      std::vector<std::uint64_t> keys;
      std::vector<double>        values;

      void serialize(StateArchive &ar)
      {
        ar &name &n_values &keys &values;
      }
    };
  } // namespace


  // The file: the stream as one string, then the tables.
  std::string StateArchive::file_data() const
  {
    StateArchive             out;
    std::string              stream = buffer;
    std::vector<StoredTable> stored;
    for (const auto &[name, t] : *tables)
      stored.push_back({name, t.n_values, t.keys, t.values});
    out &stream &stored;
    return out.data();
  }


  std::pair<std::string, KeyedTables> StateArchive::split_file_data(const std::string &data)
  {
    StateArchive             in(data);
    std::string              stream;
    std::vector<StoredTable> stored;
    in &stream &stored;
    if (!in.exhausted())
      throw std::runtime_error("the checkpoint file is longer than its state");
    KeyedTables tables;
    for (auto &t : stored)
      {
        if (t.values.size() != std::size_t(t.n_values) * t.keys.size())
          throw std::runtime_error("the checkpoint's table '" + t.name + "' is not whole");
        tables[t.name] = KeyedTable{t.n_values, std::move(t.keys), std::move(t.values)};
      }
    return {std::move(stream), std::move(tables)};
  }


  std::shared_ptr<const KeyedTables> StateArchive::merge(const std::vector<KeyedTables> &parts)
  {
    auto merged = std::make_shared<KeyedTables>();
    // Every table's parts, in the order of the processes that wrote them.
    std::map<std::string, std::vector<const KeyedTable *>> by_name;
    for (const auto &part : parts)
      for (const auto &[name, t] : part)
        by_name[name].push_back(&t);
    for (const auto &[name, pieces] : by_name)
      {
        const unsigned int n_values = pieces.front()->n_values;
        std::vector<std::pair<std::uint64_t, const double *>> items;
        for (const KeyedTable *t : pieces)
          {
            if (t->n_values != n_values)
              throw std::runtime_error("the checkpoint's table '" + name + "' has items of " +
                                       std::to_string(t->n_values) + " and of " + std::to_string(n_values) +
                                       " values");
            for (std::size_t i = 0; i < t->keys.size(); ++i)
              items.emplace_back(t->keys[i], t->values.data() + i * n_values);
          }
        std::stable_sort(items.begin(), items.end(),
                         [](const auto &a, const auto &b) { return a.first < b.first; });
        KeyedTable &out = (*merged)[name];
        out.n_values    = n_values;
        for (std::size_t i = 0; i < items.size(); ++i)
          {
            if (i > 0 && items[i].first == items[i - 1].first)
              {
                // A set's key named by several processes is one key; an
                // item's values written twice are a checkpoint that is
                // not one run's.
                if (n_values == 0)
                  continue;
                throw std::runtime_error("the checkpoint's table '" + name + "' holds item " +
                                         std::to_string(items[i].first) + " twice");
              }
            out.keys.push_back(items[i].first);
            out.values.insert(out.values.end(), items[i].second, items[i].second + n_values);
          }
      }
    return merged;
  }
} // namespace anvil
