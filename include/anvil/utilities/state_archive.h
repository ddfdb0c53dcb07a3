/**
 * @file
 * The state of a run in bytes, for checkpoints: one archive per process,
 * written and read back in the same order (the same class lists its
 * members once, for both directions), so a resumed run continues bitwise.
 */
#pragma once

#include <deal.II/lac/la_parallel_vector.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace anvil
{
  class StateArchive
  {
  public:
    /** An archive to write into. */
    StateArchive() = default;
    /** An archive that reads @p data. */
    explicit StateArchive(std::string data)
      : loading(true)
      , buffer(std::move(data))
    {}

    bool is_loading() const
    {
      return loading;
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
    bool        loading  = false;
    std::string buffer;
    std::size_t position = 0;

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

    /** The locally owned entries; the caller updates the ghosts. */
    void io(dealii::LinearAlgebra::distributed::Vector<double> &v)
    {
      const std::size_t n = size(v.locally_owned_size());
      if (n != v.locally_owned_size())
        throw std::runtime_error("the checkpoint was written with another partition");
      if (n > 0)
        bytes(v.begin(), n * sizeof(double));
    }
  };
} // namespace anvil
