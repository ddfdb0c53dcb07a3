/**
 * @file
 * Small helpers for Anvil's unit tests: checks that print measured value,
 * expected value and tolerance, and a single-body element mesh on plain
 * arrays (node n's x, y, z at 3n, 3n+1, 3n+2).
 */
#pragma once

#include <anvil/element/element_group.h>
#include <anvil/material_model/elastic.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace anvil::test
{
  inline int n_failed = 0, n_passed = 0;

  /** |measured - expected| <= tolerance. */
  inline bool check(const std::string &what,
                    const double       measured,
                    const double       expected,
                    const double       tolerance)
  {
    const double error = std::abs(measured - expected);
    const bool   ok    = error <= tolerance;
    std::printf("  [%s] %s: measured %.12g, expected %.12g, error %.3g (tolerance %.3g)\n",
                ok ? "PASS" : "FAIL", what.c_str(), measured, expected, error, tolerance);
    (ok ? n_passed : n_failed)++;
    return ok;
  }

  inline bool check_below(const std::string &what, const double measured, const double limit)
  {
    const bool ok = measured <= limit;
    std::printf("  [%s] %s: measured %.3g (limit %.3g)\n", ok ? "PASS" : "FAIL",
                what.c_str(), measured, limit);
    (ok ? n_passed : n_failed)++;
    return ok;
  }

  inline int finish()
  {
    std::printf("%d passed, %d failed\n", n_passed, n_failed);
    return n_failed ? 1 : 0;
  }

  /** A structured block of nx x ny x nz hexahedra on [0,1]^3 whose nodes
      can be moved before the elements are made. */
  struct Block
  {
    unsigned int        nx, ny, nz;
    std::vector<double> X; // reference positions

    Block(unsigned int nx, unsigned int ny, unsigned int nz)
      : nx(nx), ny(ny), nz(nz)
    {
      for (unsigned int k = 0; k <= nz; ++k)
        for (unsigned int j = 0; j <= ny; ++j)
          for (unsigned int i = 0; i <= nx; ++i)
            {
              X.push_back(double(i) / nx);
              X.push_back(double(j) / ny);
              X.push_back(double(k) / nz);
            }
    }
    unsigned int node(unsigned int i, unsigned int j, unsigned int k) const
    {
      return i + (nx + 1) * (j + (ny + 1) * k);
    }
    unsigned int n_nodes() const
    {
      return X.size() / 3;
    }

    /** Fill @p group with the block's elements (lexicographic vertices). */
    void make_elements(Element::ElementGroup &group) const
    {
      for (unsigned int k = 0; k < nz; ++k)
        for (unsigned int j = 0; j < ny; ++j)
          for (unsigned int i = 0; i < nx; ++i)
            {
              std::array<unsigned int, 8> n;
              double                      x[8][3];
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const unsigned int id = node(i + (v & 1), j + ((v >> 1) & 1), k + ((v >> 2) & 1));
                  n[v]                  = 3 * id;
                  for (unsigned int d = 0; d < 3; ++d)
                    x[v][d] = X[3 * id + d];
                }
              group.add_element(n, x, group.n_elements());
            }
      group.finalize();
    }
  };
} // namespace anvil::test
