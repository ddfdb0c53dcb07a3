/**
 * @file
 * The explicit element loop. See element_group.h for conventions.
 */
#include <anvil/element/element_group.h>
#include <anvil/element/hourglass.h>
#include <anvil/kinematics/rotation.h>
#include <anvil/utilities/input_error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>

#include <xsimd/xsimd.hpp>

namespace anvil::Element
{
  std::string to_string(const Integration i)
  {
    return i == Integration::one_point ? "one point" : "full";
  }

  std::string to_string(const HourglassType h)
  {
    switch (h)
      {
        case HourglassType::viscous:
          return "viscous";
        case HourglassType::stiffness:
          return "stiffness";
        default:
          return "none";
      }
  }

  namespace
  {
    // @sect3{Shape-function tables}
    //
    // Natural coordinates of the lexicographic vertices, and the
    // derivatives dN_I/dxi_a of the trilinear shape functions (seed
    // Eq. (40)) at the 8 Gauss points (index 0..7) and at the centroid
    // (index 8), where they reduce to Lambda_a / 8 (seed Eq. (43)).
    constexpr double sgn[8][3] = {{-1, -1, -1},
                                  {1, -1, -1},
                                  {-1, 1, -1},
                                  {1, 1, -1},
                                  {-1, -1, 1},
                                  {1, -1, 1},
                                  {-1, 1, 1},
                                  {1, 1, 1}};

    constexpr double gauss = 0.57735026918962576451; // 1/sqrt(3)

    /** Compile-time shape-function tables, so that the element loop's
        multiplications by +-1/8 and +-1 fold into additions. */
    struct Tables
    {
      double dN[9][8][3];
      double weight[9];
      /** Hourglass base vectors Gamma_j (seed Eq. (42)), lexicographic. */
      double Gamma[4][8];

      constexpr Tables()
        : dN()
        , weight()
        , Gamma()
      {
        for (unsigned int q = 0; q < 9; ++q)
          {
            double p[3] = {0, 0, 0};
            for (unsigned int a = 0; a < 3; ++a)
              p[a] = (q < 8 ? gauss * sgn[q][a] : 0.);
            weight[q] = (q < 8 ? 1. : 8.);
            for (unsigned int I = 0; I < 8; ++I)
              for (unsigned int a = 0; a < 3; ++a)
                {
                  double d = 0.125 * sgn[I][a];
                  for (unsigned int b = 0; b < 3; ++b)
                    if (b != a)
                      d *= 1. + sgn[I][b] * p[b];
                  dN[q][I][a] = d;
                }
          }
        for (unsigned int I = 0; I < 8; ++I)
          {
            Gamma[0][I] = sgn[I][0] * sgn[I][1];
            Gamma[1][I] = sgn[I][1] * sgn[I][2];
            Gamma[2][I] = sgn[I][0] * sgn[I][2];
            Gamma[3][I] = sgn[I][0] * sgn[I][1] * sgn[I][2];
          }
      }
    };

    constexpr Tables tables;

    // @sect3{Small 3x3 helpers}
    inline double det3(const double (&A)[3][3])
    {
      return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
             A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
             A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    }

    inline void inv3(const double (&A)[3][3], const double det, double (&B)[3][3])
    {
      const double r = 1. / det;
      B[0][0]        = r * (A[1][1] * A[2][2] - A[1][2] * A[2][1]);
      B[0][1]        = r * (A[0][2] * A[2][1] - A[0][1] * A[2][2]);
      B[0][2]        = r * (A[0][1] * A[1][2] - A[0][2] * A[1][1]);
      B[1][0]        = r * (A[1][2] * A[2][0] - A[1][0] * A[2][2]);
      B[1][1]        = r * (A[0][0] * A[2][2] - A[0][2] * A[2][0]);
      B[1][2]        = r * (A[0][2] * A[1][0] - A[0][0] * A[1][2]);
      B[2][0]        = r * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
      B[2][1]        = r * (A[0][1] * A[2][0] - A[0][0] * A[2][1]);
      B[2][2]        = r * (A[0][0] * A[1][1] - A[0][1] * A[1][0]);
    }

    /** Voigt [xx,yy,zz,xy,yz,xz] to full symmetric matrix. */
    inline void voigt_to_matrix(const double *s, double (&A)[3][3])
    {
      A[0][0] = s[0];
      A[1][1] = s[1];
      A[2][2] = s[2];
      A[0][1] = A[1][0] = s[3];
      A[1][2] = A[2][1] = s[4];
      A[0][2] = A[2][0] = s[5];
    }

    /** Double contraction of two symmetric tensors in Voigt storage. */
    inline double contract(const double *a, const double *b)
    {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] +
             2. * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
    }

    using Kinematics::rotate_stress;

    /** The derivatives at the 8 Gauss points transposed for the fully
        integrated batched loop: by_point[n][c][q] = dN_n/dxi_c at point q
        (lanes: points), by_node[q][c][n] the same (lanes: nodes). */
    struct PointTables
    {
      double by_point[8][3][8];
      double by_node[8][3][8];

      constexpr PointTables()
        : by_point()
        , by_node()
      {
        for (unsigned int q = 0; q < 8; ++q)
          for (unsigned int n = 0; n < 8; ++n)
            for (unsigned int c = 0; c < 3; ++c)
              {
                by_point[n][c][q] = tables.dN[q][n][c];
                by_node[q][c][n]  = tables.dN[q][n][c];
              }
      }
    };

    constexpr PointTables point_tables;

    /** B = A^-1 for W 3x3 matrices with determinants @p det, lane by lane
        (inv3()'s arithmetic). */
    template <unsigned int W>
    inline void inverse_batch(const double (&A)[3][3][W], const double *det, double (&B)[3][3][W])
    {
      for (unsigned int l = 0; l < W; ++l)
        {
          const double r = 1. / det[l];
          B[0][0][l] = r * (A[1][1][l] * A[2][2][l] - A[1][2][l] * A[2][1][l]);
          B[0][1][l] = r * (A[0][2][l] * A[2][1][l] - A[0][1][l] * A[2][2][l]);
          B[0][2][l] = r * (A[0][1][l] * A[1][2][l] - A[0][2][l] * A[1][1][l]);
          B[1][0][l] = r * (A[1][2][l] * A[2][0][l] - A[1][0][l] * A[2][2][l]);
          B[1][1][l] = r * (A[0][0][l] * A[2][2][l] - A[0][2][l] * A[2][0][l]);
          B[1][2][l] = r * (A[0][2][l] * A[1][0][l] - A[0][0][l] * A[1][2][l]);
          B[2][0][l] = r * (A[1][0][l] * A[2][1][l] - A[1][1][l] * A[2][0][l]);
          B[2][1][l] = r * (A[0][1][l] * A[2][0][l] - A[0][0][l] * A[2][1][l]);
          B[2][2][l] = r * (A[0][0][l] * A[1][1][l] - A[0][1][l] * A[1][0][l]);
        }
    }

    /** The mid-step Jacobian J^n - dt/2 dJ/dt at W points. */
    template <unsigned int W>
    inline void midstep_jacobian_batch(const double (&Jn)[3][3][W], const double (&Jd)[3][3][W],
                                       const double dt, double (&Jm)[3][3][W])
    {
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = 0; c < 3; ++c)
          for (unsigned int l = 0; l < W; ++l)
            Jm[a][c][l] = Jn[a][c][l] - 0.5 * dt * Jd[a][c][l];
    }

    /** The velocity gradient L = dJ/dt Jm^-1 at W points, its symmetric
        part D (xx, yy, zz, xy, yz, xz) and its spin (W_01, W_12, W_02). */
    template <unsigned int W>
    inline void deformation_rate_batch(const double (&Jd)[3][3][W], const double (&Jmi)[3][3][W],
                                       double (&D)[6][W], double (&spin)[3][W])
    {
      alignas(64) double L[3][3][W];
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          for (unsigned int l = 0; l < W; ++l)
            L[a][b][l] =
              Jd[a][0][l] * Jmi[0][b][l] + Jd[a][1][l] * Jmi[1][b][l] + Jd[a][2][l] * Jmi[2][b][l];
      for (unsigned int l = 0; l < W; ++l)
        {
          D[0][l]    = L[0][0][l];
          D[1][l]    = L[1][1][l];
          D[2][l]    = L[2][2][l];
          D[3][l]    = 0.5 * (L[0][1][l] + L[1][0][l]);
          D[4][l]    = 0.5 * (L[1][2][l] + L[2][1][l]);
          D[5][l]    = 0.5 * (L[0][2][l] + L[2][0][l]);
          spin[0][l] = 0.5 * (L[0][1][l] - L[1][0][l]);
          spin[1][l] = 0.5 * (L[1][2][l] - L[2][1][l]);
          spin[2][l] = 0.5 * (L[0][2][l] - L[2][0][l]);
        }
    }

    /** det A for W 3x3 matrices, lane by lane (det3()'s arithmetic). */
    template <unsigned int W>
    inline void determinant_batch(const double (&A)[3][3][W], double (&det)[W])
    {
      for (unsigned int l = 0; l < W; ++l)
        det[l] = A[0][0][l] * (A[1][1][l] * A[2][2][l] - A[1][2][l] * A[2][1][l]) -
                 A[0][1][l] * (A[1][0][l] * A[2][2][l] - A[1][2][l] * A[2][0][l]) +
                 A[0][2][l] * (A[1][0][l] * A[2][1][l] - A[1][1][l] * A[2][0][l]);
    }

    /** The faces of the lexicographic hexahedron, each in cyclic order. */
    constexpr unsigned int faces[6][4] = {
      {0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

    /** Square of the largest face area, |(x_c - x_a) x (x_d - x_b)|^2 / 4
        per face: with the volume, LS-DYNA's characteristic length V /
        A_max, which is the safer of the two measures for distorted
        elements. @p x returns coordinate a of vertex n. */
    template <typename Coordinate>
    inline double max_face_area2(const Coordinate &x)
    {
      double a2 = 0;
      for (const auto &f : faces)
        {
          double p[3], q[3];
          for (unsigned int a = 0; a < 3; ++a)
            {
              p[a] = x(f[2], a) - x(f[0], a);
              q[a] = x(f[3], a) - x(f[1], a);
            }
          const double c0 = p[1] * q[2] - p[2] * q[1], c1 = p[2] * q[0] - p[0] * q[2],
                       c2 = p[0] * q[1] - p[1] * q[0];
          a2 = std::max(a2, 0.25 * (c0 * c0 + c1 * c1 + c2 * c2));
        }
      return a2;
    }

    // @sect3{The element's Walsh basis}
    //
    // A trilinear field on the hexahedron is u(xi) = sum_m c_m psi_m(xi)
    // with the eight products psi_m of 1, xi, eta, zeta (m's bits say
    // which of xi, eta, zeta it contains), and the nodal values are u_n =
    // sum_m c_m psi_m(node n). At the centroid dN_I/dxi_c = sgn_Ic / 8
    // (seed Eq. (43)), so 8 dx_a/dxi_c = sum_I sgn_Ic x_Ia is the
    // coefficient with m = 2^c, and the hourglass sums sum_I Gamma_jI x_Ia
    // (seed Eq. (42)) are those with m = 3, 6, 5, 7. Both come from one
    // fast Walsh-Hadamard transform of the nodal values: 3 stages of 8
    // additions per component, against 8 x 7 multiply-adds term by term;
    // and the nodal forces, sum_c G_ac dN_Ic - sum_j r_aj Gamma_jI, are
    // the inverse transform of the same kind of coefficients.

    /** Walsh index of Gamma_j (seed Eq. (42)): xi eta, eta zeta, xi zeta, xi eta zeta. */
    constexpr unsigned int gamma_index[4] = {3, 6, 5, 7};

    /** The hourglass state (stiffness modes q_aj, resistance r_aj: 12
        values an element) is stored by batch (batch_major_entry()), so
        that the batched loop reads and writes a batch's state as twelve
        aligned lane vectors (a scalar gather of 96 values a batch before). */
    inline std::size_t hourglass_entry(const unsigned int e, const unsigned int k)
    {
      return batch_major_entry(e, k, 12);
    }

    /** The fast transform from @p in to @p out, per component and lane:
        forward, c_m = sum_n u_n psi_m(node n); inverse, u_n = sum_m c_m
        psi_m(node n). A stage on one bit (xi, then eta, then zeta) maps the
        pair without and with it, (lo, hi), to (lo + hi, hi - lo) forward
        and to (lo - hi, lo + hi) inverse. The lanes' loop has straight-line
        code, so it vectorises across them. */
    template <bool inverse, unsigned int W>
    inline void walsh_transform(const double (&in)[8][3][W], double (&out)[8][3][W])
    {
      const auto stage = [](const double lo, const double hi, double &a, double &b) {
        a = inverse ? lo - hi : lo + hi;
        b = inverse ? lo + hi : hi - lo;
      };
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int l = 0; l < W; ++l)
          {
            double p[8], q[8], r[8];
            for (unsigned int n = 0; n < 8; n += 2)
              stage(in[n][a][l], in[n + 1][a][l], p[n], p[n + 1]);
            for (const unsigned int n : {0u, 1u, 4u, 5u})
              stage(p[n], p[n + 2], q[n], q[n + 2]);
            for (unsigned int n = 0; n < 4; ++n)
              stage(q[n], q[n + 4], r[n], r[n + 4]);
            for (unsigned int n = 0; n < 8; ++n)
              out[n][a][l] = r[n];
          }
    }

    // Vectors of the compiler's generic vector extension (GCC, Clang): their
    // shuffles (__builtin_shufflevector) are lowered to the target's own
    // instructions (AVX-512's two-register permutes, AVX2's unpacks and lane
    // permutes, NEON's zips), so that the gather below is written once for
    // every instruction set. (Debian's xsimd 8 has no shuffle of two
    // registers that means the same on every instruction set.) A Vec4 is
    // loaded from any double; the others are stored aligned.
    typedef double        Vec4 __attribute__((vector_size(32), aligned(8)));
    typedef double        Vec8 __attribute__((vector_size(64)));
    typedef double        AlignedVec4 __attribute__((vector_size(32)));

    /** The doubles a vector register holds on this machine (8 with
        AVX-512, 4 with AVX2, 2 with SSE and NEON). */
    constexpr unsigned int register_doubles = xsimd::batch<double>::size;

    /** xe[n][a][l] = x[idx[n][l] + a]: the batch's nodal values, lanes
        innermost. A node's three components are consecutive: each
        (node, lane) is one load of four doubles (the node's and the next
        value, unused), and the loads of four or eight lanes are transposed
        into the three components' lane vectors in registers (24 scalar
        loads and their inserts per node otherwise). The fourth value read
        must exist: @p wide is false where the batch holds its group's
        last node (whose offset + 3 may be past the vector's end), and the
        batch is then gathered value by value. */
    template <unsigned int W>
    inline void gather_nodes(const double *x, const unsigned int (&idx)[8][W], double (&xe)[8][3][W],
                             const bool wide)
    {
      const auto load = [x](const unsigned int i) { return *reinterpret_cast<const Vec4 *>(x + i); };
      if constexpr (register_doubles >= 8 && W % 8 == 0)
        if (wide)
          {
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int l0 = 0; l0 < W; l0 += 8)
                {
                  // Lanes (2k, 2k + 1) side by side, [x y z . | x y z .];
                  // then the eight lanes' x and y, and their z.
                  Vec8 t[4];
                  for (unsigned int k = 0; k < 4; ++k)
                    t[k] = __builtin_shufflevector(load(idx[n][l0 + 2 * k]), load(idx[n][l0 + 2 * k + 1]),
                                                   0, 1, 2, 3, 4, 5, 6, 7);
                  const Vec8 xy03 = __builtin_shufflevector(t[0], t[1], 0, 4, 8, 12, 1, 5, 9, 13),
                             xy47 = __builtin_shufflevector(t[2], t[3], 0, 4, 8, 12, 1, 5, 9, 13),
                             z03  = __builtin_shufflevector(t[0], t[1], 2, 6, 10, 14, 2, 6, 10, 14),
                             z47  = __builtin_shufflevector(t[2], t[3], 2, 6, 10, 14, 2, 6, 10, 14);
                  *reinterpret_cast<Vec8 *>(&xe[n][0][l0]) =
                    __builtin_shufflevector(xy03, xy47, 0, 1, 2, 3, 8, 9, 10, 11);
                  *reinterpret_cast<Vec8 *>(&xe[n][1][l0]) =
                    __builtin_shufflevector(xy03, xy47, 4, 5, 6, 7, 12, 13, 14, 15);
                  *reinterpret_cast<Vec8 *>(&xe[n][2][l0]) = __builtin_shufflevector(z03, z47, 0, 1, 2, 3, 8, 9, 10, 11);
                }
            return;
          }
      if constexpr (W % 4 == 0)
        if (wide)
          {
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int l0 = 0; l0 < W; l0 += 4)
                {
                  // Within the halves of two lanes' loads: [x x' z z'] and
                  // [y y' . .]; then the halves joined.
                  const Vec4  r0 = load(idx[n][l0]), r1 = load(idx[n][l0 + 1]), r2 = load(idx[n][l0 + 2]),
                             r3 = load(idx[n][l0 + 3]);
                  const Vec4 xz01 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6),
                             xz23 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6),
                             y01  = __builtin_shufflevector(r0, r1, 1, 5, 3, 7),
                             y23  = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
                  *reinterpret_cast<AlignedVec4 *>(&xe[n][0][l0]) = __builtin_shufflevector(xz01, xz23, 0, 1, 4, 5);
                  *reinterpret_cast<AlignedVec4 *>(&xe[n][1][l0]) = __builtin_shufflevector(y01, y23, 0, 1, 4, 5);
                  *reinterpret_cast<AlignedVec4 *>(&xe[n][2][l0]) = __builtin_shufflevector(xz01, xz23, 2, 3, 6, 7);
                }
            return;
          }
      for (unsigned int n = 0; n < 8; ++n)
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int l = 0; l < W; ++l)
            xe[n][a][l] = x[idx[n][l] + a];
    }

    /** rows[k][l] = s[6 l + k] for the W elements whose Voigt stresses
        start at @p s, one after the other (a batch whose lanes are its own
        elements): four elements' 24 values are six loads of four, put in
        place by lane permutes and unpacks (the lanes' values one by one
        otherwise, which the vector loads of the rows then wait for). */
    template <unsigned int W>
    inline void load_voigt_rows(const double *s, double (&rows)[6][W])
    {
      static_assert(W % 4 == 0, "lanes in fours");
      for (unsigned int l0 = 0; l0 < W; l0 += 4)
        {
          const double *p = s + 6 * l0;
          Vec4          r[6];
          for (unsigned int i = 0; i < 6; ++i)
            r[i] = *reinterpret_cast<const Vec4 *>(p + 4 * i);
          // Elements a, b, c, d: u[0] = a0 a1 c0 c1, u[1] = a2 a3 c2 c3,
          // u[2] = a4 a5 c4 c5, u[3] = b0 b1 d0 d1, u[4] = b2 b3 d2 d3,
          // u[5] = b4 b5 d4 d5; then component k from u[k / 2], u[k / 2 + 3].
          const Vec4 u[6] = {__builtin_shufflevector(r[0], r[3], 0, 1, 4, 5),
                             __builtin_shufflevector(r[0], r[3], 2, 3, 6, 7),
                             __builtin_shufflevector(r[1], r[4], 0, 1, 4, 5),
                             __builtin_shufflevector(r[1], r[4], 2, 3, 6, 7),
                             __builtin_shufflevector(r[2], r[5], 0, 1, 4, 5),
                             __builtin_shufflevector(r[2], r[5], 2, 3, 6, 7)};
          for (unsigned int j = 0; j < 3; ++j)
            {
              *reinterpret_cast<AlignedVec4 *>(&rows[2 * j][l0]) = __builtin_shufflevector(u[j], u[j + 3], 0, 4, 2, 6);
              *reinterpret_cast<AlignedVec4 *>(&rows[2 * j + 1][l0]) =
                __builtin_shufflevector(u[j], u[j + 3], 1, 5, 3, 7);
            }
        }
    }

    /** The inverse of load_voigt_rows(): s[6 l + k] = rows[k][l]. */
    template <unsigned int W>
    inline void store_voigt_rows(const double (&rows)[6][W], double *s)
    {
      static_assert(W % 4 == 0, "lanes in fours");
      for (unsigned int l0 = 0; l0 < W; l0 += 4)
        {
          Vec4 u[6];
          for (unsigned int j = 0; j < 3; ++j)
            {
              const Vec4 even = *reinterpret_cast<const AlignedVec4 *>(&rows[2 * j][l0]),
                         odd  = *reinterpret_cast<const AlignedVec4 *>(&rows[2 * j + 1][l0]);
              u[j]            = __builtin_shufflevector(even, odd, 0, 4, 2, 6);
              u[j + 3]        = __builtin_shufflevector(even, odd, 1, 5, 3, 7);
            }
          double *p = s + 6 * l0;
          for (unsigned int i = 0; i < 3; ++i)
            {
              *reinterpret_cast<Vec4 *>(p + 4 * i)       = __builtin_shufflevector(u[2 * i], u[2 * i + 1], 0, 1, 4, 5);
              *reinterpret_cast<Vec4 *>(p + 4 * (i + 3)) = __builtin_shufflevector(u[2 * i], u[2 * i + 1], 2, 3, 6, 7);
            }
        }
    }

    /** x^(-1/3) for x between 1e-100 and 1e100 (a volume), with no call,
        branch or division, so that a loop over lanes vectorises: a first
        guess from the bits (minus a third of the exponent, a few per cent
        off), then four of Newton's steps r <- r (4 - x r^3) / 3, each
        squaring the relative error (3e-2, 2e-3, 7e-6, 1e-10, round-off).
        cbrt(x) = x r^2 and x^(2/3) = x r then agree with std::cbrt to
        1.0e-15 and 1.3e-15 (5 and 6 ulp; 10^7 samples over the range).
        The guess is made from the upper 32 bits (the exponent and 20 bits
        of the mantissa) as 32-bit integers: AVX2 converts those to and
        from doubles across lanes, but not 64-bit integers (AVX-512 does),
        and with the 64-bit guess GCC left this function's loops scalar on
        AVX2 machines. */
    inline double inverse_cube_root(const double x)
    {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      const std::int32_t upper = static_cast<std::int32_t>(bits >> 32);
      const std::int32_t guess = 0x553EF0FF - static_cast<std::int32_t>(static_cast<double>(upper) * (1. / 3.));
      bits                     = static_cast<std::uint64_t>(static_cast<std::uint32_t>(guess)) << 32;
      double r;
      std::memcpy(&r, &bits, sizeof r);
      // (r (4 - x r^3) / 3 as r (4/3 - (x/3) r^3): four dependent
      // operations a step instead of six.)
      const double third_x = x * (1. / 3.);
      for (unsigned int k = 0; k < 4; ++k)
        {
          const double r2 = r * r;
          r               = r * (4. / 3. - third_x * (r2 * r));
        }
      return r;
    }

    /** The Jacobian dX/dxi at point @p q of the shape-function tables (the
        8 Gauss points, 8: the centroid) of the hexahedron @p X. */
    inline void reference_jacobian(const double (&X)[8][3], const unsigned int q, double (&J)[3][3])
    {
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int c = 0; c < 3; ++c)
          J[a][c] = 0;
      for (unsigned int I = 0; I < 8; ++I)
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            J[a][c] += X[I][a] * tables.dN[q][I][c];
    }
  } // namespace


  void lumped_mass(const double (&X)[8][3], const double density, double (&mass)[8])
  {
    std::fill(mass, mass + 8, 0.);
    const double g = gauss;
    for (unsigned int q = 0; q < 8; ++q)
      {
        double J[3][3];
        reference_jacobian(X, q, J);
        const double jxw = det3(J);
        for (unsigned int I = 0; I < 8; ++I)
          {
            double N = 0.125;
            for (unsigned int a = 0; a < 3; ++a)
              N *= 1. + sgn[I][a] * g * sgn[q][a];
            mass[I] += density * N * jxw;
          }
      }
  }


  ElementGroup::ElementGroup(const MaterialModel::Interface &material,
                             const Formulation               formulation,
                             const Integration               integration,
                             const HourglassType             hourglass,
                             const double hourglass_coefficient)
    : material(material)
    , formulation(formulation)
    , integration(integration)
    , hourglass(integration == Integration::one_point ? hourglass :
                                                        HourglassType::none)
    , hourglass_coefficient(hourglass_coefficient)
    , n_qp(integration == Integration::one_point ? 1 : 8)
    , n_hist(material.n_history(formulation))
    , n_hot(std::min(material.n_hot_history(formulation), n_hist))
    , n_cold(n_hist - n_hot)
  {
    AssertThrow(n_hist <= MaterialModel::Interface::max_history,
                dealii::ExcMessage("a material's history exceeds Interface::max_history"));
  }


  void ElementGroup::set_bulk_viscosity(const double linear, const double quadratic)
  {
    bulk_linear                     = linear;
    bulk_quadratic                  = quadratic;
    const double s                  = std::sqrt(1. + linear * linear) - linear;
    bulk_dt_factor2_expansion       = s * s;
  }


  void ElementGroup::add_element(const std::array<unsigned int, 8> &node,
                                 const double (&X)[8][3],
                                 const unsigned int  cell,
                                 const bool          owned,
                                 const unsigned long id,
                                 const double        strength_factor)
  {
    strength_factors.push_back(strength_factor);
    const unsigned int e = cell_index.size();
    nodes.resize(std::max<std::size_t>(nodes.size(), (e / W + 1) * 8 * W));
    for (unsigned int n = 0; n < 8; ++n)
      nodes[(e / W) * 8 * W + n * W + e % W] = node[n];
    cell_index.push_back(cell);
    global_id.push_back(id == static_cast<unsigned long>(-1) ? cell : id);
    energy_weight.push_back(owned ? 1. : 0.);

    // Reference Jacobians at the element's points; the volume by full
    // Gauss quadrature (exact for the trilinear map).
    double volume = 0;
    for (unsigned int q = 0; q < 8; ++q)
      {
        double J[3][3];
        reference_jacobian(X, q, J);
        volume += det3(J);
      }
    reference_volume.push_back(volume);

    if (formulation == Formulation::total_lagrangian)
      for (unsigned int qq = 0; qq < n_qp; ++qq)
        {
          const unsigned int q       = (n_qp == 1 ? 8 : qq);
          double             J[3][3];
          reference_jacobian(X, q, J);
          const double d = det3(J);
          double       Ji[3][3];
          inv3(J, d, Ji);
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int c = 0; c < 3; ++c)
              jacobian_inverse_ref.push_back(Ji[a][c]);
          jxw_ref.push_back(d * tables.weight[q]);
        }
  }


  void ElementGroup::finalize()
  {
    const std::size_t n = cell_index.size();
    // The arrays add_element() grew one element at a time hold up to twice
    // their size: down to it (26 bytes an element on the column).
    for (auto *v : {&strength_factors, &energy_weight, &reference_volume, &jacobian_inverse_ref, &jxw_ref})
      v->shrink_to_fit();
    nodes.shrink_to_fit();
    // The batches the gather may read a fourth value past each node of
    // (gather_nodes()): all but those that hold the group's last node.
    const unsigned int last = nodes.empty() ? 0 : *std::max_element(nodes.begin(), nodes.end());
    batch_wide.assign(nodes.size() / (8 * W), 0);
    for (std::size_t b = 0; b < batch_wide.size(); ++b)
      batch_wide[b] = *std::max_element(&nodes[8 * W * b], &nodes[8 * W * (b + 1)]) < last;
    cell_index.shrink_to_fit();
    global_id.shrink_to_fit();
    stresses.assign(6 * n * n_qp, 0.);
    history.assign(batch_major_size(n * n_qp, n_hot), 0.);
    cold_history.assign(n_cold * n * n_qp, 0.);
    scratch_history.assign(n_hot * W, 0.);
    scratch_cold_history.assign(n_cold * W, 0.);
    if (n_hist > 0)
      for (std::size_t e = 0; e < n; ++e)
        {
          MaterialModel::PointData data;
          data.characteristic_length = std::cbrt(reference_volume[e]);
          data.strength_factor       = strength_factors[e];
          for (unsigned int q = 0; q < n_qp; ++q)
            {
              double  buffer[MaterialModel::Interface::max_history];
              double *h = point_history(e * n_qp + q, buffer);
              material.initialize_history(h, data);
              store_history(e * n_qp + q, h);
            }
        }
    strength_factors = std::vector<double>();
    if (hourglass == HourglassType::stiffness)
      hourglass_modes.assign(batch_major_size(n, 12), 0.);
    if (hourglass != HourglassType::none)
      hourglass_resistance.assign(batch_major_size(n, 12), 0.);
    internal_energy.assign(n, 0.);
    hourglass_energy.assign(n, 0.);
    shape_factor.assign(n, 1.);
    mass_factor.assign(n, 1.);
    if (bulk_viscosity())
      bulk_pressure.assign(n * n_qp, 0.);
    if (material.erodes())
      alive.assign(n, 1);
  }


  // An element's state as one record of doubles: whether it is intact,
  // its points' stresses and histories, its hourglass state, its energies,
  // its points' bulk viscosity pressures and its shape factor (the arrays
  // a group of its kind has).
  void ElementGroup::serialize(StateArchive &ar, const std::string &table)
  {
    ar &n_calls &refresh_shape;
    // (By the group's kind, not by its arrays, which are empty on a process
    // without elements of the group.)
    const bool         erodes      = material.erodes();
    const bool         modes       = hourglass == HourglassType::stiffness;
    const bool         resistance  = hourglass != HourglassType::none;
    const unsigned int record      = (erodes ? 1 : 0) + (6 + n_hist) * n_qp + (modes ? 12 : 0) +
                                (resistance ? 12 : 0) + 2 + (bulk_viscosity() ? n_qp : 0) + 1;
    std::vector<std::uint64_t> keys;
    std::vector<unsigned int>  elements;
    for (unsigned int e = 0; e < n_elements(); ++e)
      if (ar.is_loading() || element_is_owned(e))
        {
          keys.push_back(global_id[e]);
          elements.push_back(e);
        }
    const auto io_element = [&](const std::size_t item, RecordCursor &io) {
      const unsigned int e = elements[item];
      if (erodes)
        io(alive[e]);
      for (unsigned int q = 0; q < n_qp; ++q)
        {
          const std::size_t p = std::size_t(e) * n_qp + q;
          io(stresses, 6 * p, 6);
          for (unsigned int k = 0; k < n_hot; ++k)
            io(history[hot_entry(p, k)]);
          io(cold_history, n_cold * p, n_cold);
        }
      for (auto *v : {modes ? &hourglass_modes : nullptr, resistance ? &hourglass_resistance : nullptr})
        if (v != nullptr)
          for (unsigned int k = 0; k < 12; ++k)
            io((*v)[hourglass_entry(e, k)]);
      io(internal_energy[e]);
      io(hourglass_energy[e]);
      if (bulk_viscosity())
        io(bulk_pressure, std::size_t(e) * n_qp, n_qp);
      io(shape_factor[e]);
    };
    if (!ar.is_loading() || ar.element_transfer() == nullptr)
      {
        ar.keyed_items(table, keys, record, io_element);
        return;
      }

    // Loading onto a mesh refined or coarsened since the checkpoint
    // (doc/adaptivity.md, "Refinement during the run"): each new element's
    // record is made from its sources' records. A child takes its parent's
    // state at the parent's point in the child's octant (one-point: the
    // parent's), a coarsened parent at each point the mean of the child in
    // that point's octant (one-point: the children's mean by volume); the
    // energies split and add by volume; hourglass state starts anew.
    const ElementTransfer     &sources = *ar.element_transfer();
    std::vector<std::uint64_t> wanted;
    for (const auto key : keys)
      if (const auto s = sources.find(key); s != sources.end())
        for (const auto &source : s->second)
          wanted.push_back(source.id);
      else
        wanted.push_back(key);
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    std::vector<double> old_values;
    ar.keyed(table, wanted, record, old_values);
    const auto old_record = [&](const std::uint64_t id) {
      return old_values.data() + record * (std::lower_bound(wanted.begin(), wanted.end(), id) - wanted.begin());
    };
    const unsigned int first_point = erodes ? 1 : 0;
    const unsigned int per_point   = 6 + n_hist;
    const unsigned int after_points = first_point + per_point * n_qp;
    const unsigned int energies     = after_points + (modes ? 12 : 0) + (resistance ? 12 : 0);
    // (The elastic energy density of a point's stresses, with the
    // material's undamaged moduli: what averaging takes out.)
    const double K = material.bulk_modulus(), G = 0.75 * (material.wave_modulus() - K);
    const auto   elastic = [&](const double *sigma) {
      const double p  = (sigma[0] + sigma[1] + sigma[2]) / 3.;
      double       ss = 0;
      for (unsigned int d = 0; d < 3; ++d)
        ss += (sigma[d] - p) * (sigma[d] - p) + 2. * sigma[3 + d] * sigma[3 + d];
      return 0.5 * p * p / K + (G > 0 ? 0.25 * ss / G : 0.);
    };
    std::vector<double> values(record);
    for (std::size_t item = 0; item < keys.size(); ++item)
      {
        const auto s = sources.find(keys[item]);
        if (s == sources.end() || s->second.front().kind == ElementSource::same)
          std::copy_n(old_record(s == sources.end() ? keys[item] : s->second.front().id), record, values.begin());
        else
          {
            double old_elastic = 0;
            std::fill(values.begin(), values.end(), 0.);
            if (erodes)
              values[0] = 1;
            for (const auto &source : s->second)
              {
                const double *r = old_record(source.id);
                if (erodes)
                  values[0] = std::min(values[0], r[0]);
                for (unsigned int q = 0; q < n_qp; ++q)
                  {
                    // (Where the new element's point q takes from this
                    // source, from which of its points, with what weight.)
                    const auto add = [&](const unsigned int from, const double w) {
                      old_elastic += w * elastic(r + first_point + per_point * from) / n_qp;
                      for (unsigned int k = 0; k < per_point; ++k)
                        values[first_point + per_point * q + k] += w * r[first_point + per_point * from + k];
                      if (bulk_viscosity())
                        values[energies + 2 + q] += w * r[energies + 2 + from];
                    };
                    if (n_qp == 1)
                      add(0, source.intensive);
                    else if (source.kind == ElementSource::child)
                      add(source.octant, 1.);
                    else if (source.octant == q)
                      for (unsigned int from = 0; from < n_qp; ++from)
                        add(from, 1. / n_qp);
                  }
                values[energies] += source.extensive * r[energies];
                values[energies + 1] += source.extensive * r[energies + 1];
                values[record - 1] += source.intensive * r[record - 1];
              }
            // (What the element's geometry set at setup stays its own: a
            // child's crack band is its own length, so that the crack
            // opening kappa h of the parent is kept across its children.)
            for (const unsigned int k : material.geometric_history())
              for (unsigned int q = 0; q < n_qp; ++q)
                values[first_point + per_point * q + 6 + k] = history_variable(elements[item], q, k);
            double new_elastic = 0;
            for (unsigned int q = 0; q < n_qp; ++q)
              new_elastic += elastic(values.data() + first_point + per_point * q) / n_qp;
            const unsigned int e = elements[item];
            const double       change = reference_volume[e] * (new_elastic - old_elastic);
            values[energies] += change;
            if (element_is_owned(e))
              adapted_energy += change;
          }
        RecordCursor in(values.data(), false);
        io_element(item, in);
      }
    refresh_shape = true;
  }


  void ElementGroup::time_elements(const bool on)
  {
    const unsigned int n  = n_elements();
    const bool         ul = formulation == Formulation::updated_lagrangian;
    // (The updated Lagrangian loops are the batched ones, which time their
    // batches or elements; the total Lagrangian ones are timed whole.)
    timing_chunk = !on ? 0 : !ul ? std::max(1u, n) : integration == Integration::one_point ? W : 1;
    chunk_seconds.assign(on && n > 0 ? (n + timing_chunk - 1) / timing_chunk : 0, 0.);
  }


  double ElementGroup::element_seconds(const unsigned int e) const
  {
    if (timing_chunk == 0 || chunk_seconds.empty())
      return 0.;
    const unsigned int c     = e / timing_chunk;
    const unsigned int first = c * timing_chunk;
    return chunk_seconds[c] / std::min(timing_chunk, n_elements() - first);
  }


  double ElementGroup::measured_seconds() const
  {
    return std::accumulate(chunk_seconds.begin(), chunk_seconds.end(), 0.);
  }


  void ElementGroup::set_nodal_mass_ratio(const double *ratio)
  {
    for (unsigned int e = 0; e < mass_factor.size(); ++e)
      {
        double r = 1.;
        for (unsigned int n = 0; n < 8; ++n)
          r = std::min(r, ratio[node(e, n)]);
        mass_factor[e] = r;
      }
    refresh_shape = true;
  }


  const std::array<unsigned int, 8>
  ElementGroup::element_nodes(const unsigned int e) const
  {
    std::array<unsigned int, 8> n;
    for (unsigned int k = 0; k < 8; ++k)
      n[k] = node(e, k);
    return n;
  }


  double ElementGroup::memory_per_element() const
  {
    const double n = std::max<std::size_t>(1, cell_index.size());
    return (nodes.capacity() * sizeof(unsigned int) + batch_wide.capacity() +
            cell_index.capacity() * sizeof(unsigned int) +
            sizeof(double) *
              (reference_volume.capacity() + energy_weight.capacity() + jacobian_inverse_ref.capacity() +
               jxw_ref.capacity() + stresses.capacity() + history.capacity() +
               cold_history.capacity() +
               hourglass_modes.capacity() + hourglass_resistance.capacity() +
               internal_energy.capacity() + shape_factor.capacity() +
               hourglass_energy.capacity())) /
           n;
  }


  LoopResult ElementGroup::compute_internal_forces(const double *x,
                                                   const double *v,
                                                   const double  dt,
                                                   double       *force)
  {
    refresh_shape = (n_calls++ % shape_refresh_interval == 0);
    // (A group whose loop does not time its chunks is timed whole.)
    if (timing_chunk > 0 && formulation != Formulation::updated_lagrangian)
      {
        auto       mark = std::chrono::steady_clock::now();
        const auto r    = dispatch_loop(x, v, dt, force);
        tick(mark, 0);
        return r;
      }
    return dispatch_loop(x, v, dt, force);
  }


  LoopResult ElementGroup::dispatch_loop(const double *x, const double *v, const double dt, double *force)
  {
    // Dispatch once per group to a loop specialised at compile time. The
    // one-point updated Lagrangian path, the workhorse of impact analysis,
    // runs batched; the others element by element.
    const unsigned int n = n_elements();
    const bool         ul = (formulation == Formulation::updated_lagrangian);
    // Elements that can erode run batched too: an eroded element's lane
    // is masked (see batched_loop).
    if (integration == Integration::full)
      return ul ? (batch_points ? full_batched_loop(x, v, dt, force) :
                                  loop<Formulation::updated_lagrangian, Integration::full, HourglassType::none>(
                                    x, v, dt, force, 0, n)) :
                  loop<Formulation::total_lagrangian, Integration::full, HourglassType::none>(
                    x, v, dt, force, 0, n);
    switch (hourglass)
      {
        case HourglassType::viscous:
          return ul ?
                   batched_loop<HourglassType::viscous>(x, v, dt, force) :
                   ul ? loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::viscous>(
                          x, v, dt, force, 0, n) :
                      loop<Formulation::total_lagrangian, Integration::one_point, HourglassType::viscous>(
                        x, v, dt, force, 0, n);
        case HourglassType::stiffness:
          return ul ?
                   batched_loop<HourglassType::stiffness>(x, v, dt, force) :
                   ul ? loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::stiffness>(
                          x, v, dt, force, 0, n) :
                      loop<Formulation::total_lagrangian, Integration::one_point, HourglassType::stiffness>(
                        x, v, dt, force, 0, n);
        default:
          return ul ?
                   batched_loop<HourglassType::none>(x, v, dt, force) :
                   ul ? loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::none>(
                          x, v, dt, force, 0, n) :
                      loop<Formulation::total_lagrangian, Integration::one_point, HourglassType::none>(
                        x, v, dt, force, 0, n);
      }
  }


  LoopResult ElementGroup::compute_internal_forces_reference(const double *x,
                                                             const double *v,
                                                             const double  dt,
                                                             double       *force)
  {
    if (formulation == Formulation::updated_lagrangian && integration == Integration::full)
      {
        // loop(), point by point, not full_batched_loop().
        batch_points    = false;
        const auto r    = compute_internal_forces(x, v, dt, force);
        batch_points    = true;
        return r;
      }
    if (formulation != Formulation::updated_lagrangian || integration != Integration::one_point)
      return compute_internal_forces(x, v, dt, force);
    refresh_shape = (n_calls++ % shape_refresh_interval == 0);
    const unsigned int n = n_elements();
    switch (hourglass)
      {
        case HourglassType::viscous:
          return loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::viscous>(
            x, v, dt, force, 0, n);
        case HourglassType::stiffness:
          return loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::stiffness>(
            x, v, dt, force, 0, n);
        default:
          return loop<Formulation::updated_lagrangian, Integration::one_point, HourglassType::none>(
            x, v, dt, force, 0, n);
      }
  }


  // @sect3{The element loop}
  //
  // For every element: gather positions and velocities, and at each
  // integration point form the Jacobian J = dx/dxi of the current
  // configuration and its rate. In the updated Lagrangian formulation the
  // velocity gradient L = dv/dx (seed Eq. (4)) is evaluated on the
  // mid-step configuration x - dt v / 2, which makes the Hughes-Winget
  // rotation exact for rigid rotations; D and W follow from seed Eq. (5)
  // and the internal force is f = int B^T sigma dV (seed Eqs. (35), (38),
  // (39)). In the total Lagrangian formulation F = J J_0^{-1}, E from seed
  // Eq. (7), S from the material, and f = int B_0^T (F S) dV_0 (seed
  // Eq. (37)).
  template <Formulation F, Integration I, HourglassType H>
  LoopResult ElementGroup::loop(const double      *x,
                                const double      *v,
                                const double       dt,
                                double            *force,
                                const unsigned int begin,
                                const unsigned int end)
  {
    constexpr unsigned int nq  = (I == Integration::one_point ? 1 : 8);
    constexpr unsigned int q0  = (I == Integration::one_point ? 8 : 0);
    const double           rho0 = material.density();
    const double           M    = material.wave_modulus();
    LoopResult             result;
    double                 min_dt2 = 1e300;

    const bool can_erode       = !alive.empty();
    const bool rotate_history  = material.has_tensorial_history();
    const bool degrading       = material.degrades() && n_hist > 0;
    for (unsigned int e = begin; e < end; ++e)
      {
        if (can_erode && !alive[e])
          continue;
        bool                failed = false;
        const std::array<unsigned int, 8> en = element_nodes(e);
        double              xe[8][3], ve[8][3], fe[8][3] = {};
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            {
              xe[n][a] = x[en[n] + a];
              ve[n][a] = v[en[n] + a];
            }

        double e_int    = 0;
        double e_visc   = 0;
        double dt_bulk2 = 1; // bulk viscosity's factor on the squared stable step
        double dt_hourglass2 = 1e300; // the viscous hourglass damper's squared stable step
        double volume   = 0;
        double Jinv_c[3][3]; // centroid inverse Jacobian, for hourglass control
        double Jd_c[3][3];   // centroid velocity Jacobian, for hourglass control
        double max_grad2 = 0;

        for (unsigned int qq = 0; qq < nq; ++qq)
          {
            const unsigned int q = q0 + qq;
            const auto        &dN = tables.dN[q];
            double             Jn[3][3] = {}, Jd[3][3] = {};
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    Jn[a][c] += xe[n][a] * dN[n][c];
                    Jd[a][c] += ve[n][a] * dN[n][c];
                  }
            const double detn = det3(Jn);
            if (!(detn > 0))
              {
                if (result.inverted_element < 0)
                  result.inverted_element = e;
                continue;
              }
            double Ji[3][3];
            inv3(Jn, detn, Ji);
            // Characteristic length L_e = 2 / max_c |grad xi_c|: the
            // element's smallest height, V/A_max for a parallelepiped.
            double grad2 = 0;
            for (unsigned int c = 0; c < 3; ++c)
              grad2 = std::max(grad2, Ji[c][0] * Ji[c][0] + Ji[c][1] * Ji[c][1] + Ji[c][2] * Ji[c][2]);
            max_grad2 = std::max(max_grad2, grad2);
            double trD = 0; // volumetric rate over the last step, for bulk viscosity
            // Bulk viscosity at this point, density rho_q and weight jxw_now
            // of the current configuration: q, its work, its step factor.
            auto bulk_pressure_at = [&](const double rho_q, const double jxw_now) {
              double       f2;
              const double q = bulk_viscosity_pressure(
                trD, 2. / std::sqrt(grad2), rho_q, std::sqrt(M / rho_q), f2);
              dt_bulk2      = std::min(dt_bulk2, f2);
              double &q_old = bulk_pressure[e * nq + qq];
              e_visc += 0.5 * (q_old + q) * (-trD) * dt * jxw_now;
              q_old = q;
              return q;
            };
            volume += detn * tables.weight[q];

            double *sig = &stresses[6 * (e * nq + qq)];
            double  hst_buffer[MaterialModel::Interface::max_history];
            double *hst = point_history(e * nq + qq, hst_buffer);
            double  G[3][3]; // stress times inverse Jacobian transposed
            double  jxw;

            if constexpr (F == Formulation::updated_lagrangian)
              {
                jxw = detn * tables.weight[q];
                if (dt > 0)
                  {
                    double Jm[3][3];
                    for (unsigned int a = 0; a < 3; ++a)
                      for (unsigned int c = 0; c < 3; ++c)
                        Jm[a][c] = Jn[a][c] - 0.5 * dt * Jd[a][c];
                    double Jmi[3][3];
                    inv3(Jm, det3(Jm), Jmi);
                    double L[3][3];
                    for (unsigned int a = 0; a < 3; ++a)
                      for (unsigned int b = 0; b < 3; ++b)
                        L[a][b] = Jd[a][0] * Jmi[0][b] + Jd[a][1] * Jmi[1][b] +
                                  Jd[a][2] * Jmi[2][b];
                    const double D[6] = {L[0][0],
                                         L[1][1],
                                         L[2][2],
                                         0.5 * (L[0][1] + L[1][0]),
                                         0.5 * (L[1][2] + L[2][1]),
                                         0.5 * (L[0][2] + L[2][0])};
                    double       old[6];
                    std::copy(sig, sig + 6, old);
                    rotate_stress(0.5 * (L[0][1] - L[1][0]),
                                  0.5 * (L[1][2] - L[2][1]),
                                  0.5 * (L[0][2] - L[2][0]),
                                  dt,
                                  sig);
                    if (rotate_history)
                      material.rotate_history(0.5 * (L[0][1] - L[1][0]),
                                              0.5 * (L[1][2] - L[2][1]),
                                              0.5 * (L[0][2] - L[2][0]),
                                              dt,
                                              hst);
                    material.update_cauchy_stress(D, dt, sig, hst);
                    store_history(e * nq + qq, hst);
                    trD = D[0] + D[1] + D[2];
                    // Seed Eq. (25): rho dw/dt = sigma : D, mid-step stress.
                    double mid[6];
                    for (unsigned int k = 0; k < 6; ++k)
                      mid[k] = 0.5 * (old[k] + sig[k]);
                    e_int += contract(mid, D) * dt * jxw;
                  }
                // The stress of the forces: the material's, less the bulk
                // viscosity pressure.
                double sf[6];
                std::copy(sig, sig + 6, sf);
                if (bulk_viscosity())
                  {
                    const double q = bulk_pressure_at(rho0 * reference_volume[e] / (8. * detn), jxw);
                    for (unsigned int k = 0; k < 3; ++k)
                      sf[k] -= q;
                  }
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int c = 0; c < 3; ++c)
                    G[a][c] = sf[a == 0 ? 0 : (a == 1 ? 3 : 5)] * Ji[c][0] +
                              sf[a == 0 ? 3 : (a == 1 ? 1 : 4)] * Ji[c][1] +
                              sf[a == 0 ? 5 : (a == 1 ? 4 : 2)] * Ji[c][2];
              }
            else
              {
                const double *Jr = &jacobian_inverse_ref[9 * (e * nq + qq)];
                jxw              = jxw_ref[e * nq + qq];
                double Fm[9], Fd[9];
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int b = 0; b < 3; ++b)
                    {
                      Fm[3 * a + b] = Jn[a][0] * Jr[b] + Jn[a][1] * Jr[3 + b] +
                                      Jn[a][2] * Jr[6 + b];
                      Fd[3 * a + b] = Jd[a][0] * Jr[b] + Jd[a][1] * Jr[3 + b] +
                                      Jd[a][2] * Jr[6 + b];
                    }
                auto C = [&](unsigned int i, unsigned int j) {
                  return Fm[i] * Fm[j] + Fm[3 + i] * Fm[3 + j] +
                         Fm[6 + i] * Fm[6 + j];
                };
                const double E[6] = {0.5 * (C(0, 0) - 1.),
                                     0.5 * (C(1, 1) - 1.),
                                     0.5 * (C(2, 2) - 1.),
                                     0.5 * C(0, 1),
                                     0.5 * C(1, 2),
                                     0.5 * C(0, 2)};
                double       old[6];
                std::copy(sig, sig + 6, old);
                material.update_pk2_stress(Fm, E, dt, sig, hst);
                store_history(e * nq + qq, hst);
                if (dt > 0)
                  {
                    // Seed Eq. (22c): rho_0 dw/dt = S : dE/dt with
                    // dE/dt = sym(F^T dF/dt) on the mid-step F, which makes
                    // dt dE/dt the exact increment of E over the step.
                    double Fh[9];
                    for (unsigned int k = 0; k < 9; ++k)
                      Fh[k] = Fm[k] - 0.5 * dt * Fd[k];
                    auto Ed = [&](unsigned int i, unsigned int j) {
                      return 0.5 * (Fh[i] * Fd[j] + Fh[3 + i] * Fd[3 + j] +
                                    Fh[6 + i] * Fd[6 + j] + Fd[i] * Fh[j] +
                                    Fd[3 + i] * Fh[3 + j] + Fd[6 + i] * Fh[6 + j]);
                    };
                    const double Edot[6] = {
                      Ed(0, 0), Ed(1, 1), Ed(2, 2), Ed(0, 1), Ed(1, 2), Ed(0, 2)};
                    double mid[6];
                    for (unsigned int k = 0; k < 6; ++k)
                      mid[k] = 0.5 * (old[k] + sig[k]);
                    e_int += contract(mid, Edot) * dt * jxw;
                    if (bulk_viscosity())
                      {
                        // tr D = tr(dF/dt F^{-1}) on the mid-step F.
                        double Fh3[3][3], Fhi[3][3];
                        for (unsigned int a = 0; a < 3; ++a)
                          for (unsigned int b = 0; b < 3; ++b)
                            Fh3[a][b] = Fh[3 * a + b];
                        inv3(Fh3, det3(Fh3), Fhi);
                        for (unsigned int a = 0; a < 3; ++a)
                          for (unsigned int b = 0; b < 3; ++b)
                            trD += Fd[3 * a + b] * Fhi[b][a];
                      }
                  }
                // First Piola-Kirchhoff P = F S, then G = P J_0^{-T}.
                double Sm[3][3], P[3][3];
                voigt_to_matrix(sig, Sm);
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int b = 0; b < 3; ++b)
                    P[a][b] = Fm[3 * a] * Sm[0][b] + Fm[3 * a + 1] * Sm[1][b] +
                              Fm[3 * a + 2] * Sm[2][b];
                if (bulk_viscosity())
                  {
                    // The pressure q as a Cauchy stress: P -= q J F^{-T}.
                    double F3[3][3], Fi[3][3];
                    for (unsigned int a = 0; a < 3; ++a)
                      for (unsigned int b = 0; b < 3; ++b)
                        F3[a][b] = Fm[3 * a + b];
                    const double J = det3(F3);
                    inv3(F3, J, Fi);
                    const double q = bulk_pressure_at(rho0 / J, J * jxw);
                    for (unsigned int a = 0; a < 3; ++a)
                      for (unsigned int b = 0; b < 3; ++b)
                        P[a][b] -= q * J * Fi[b][a];
                  }
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int c = 0; c < 3; ++c)
                    G[a][c] = P[a][0] * Jr[3 * c] + P[a][1] * Jr[3 * c + 1] +
                              P[a][2] * Jr[3 * c + 2];
              }

            // Failure (ABAQUS's rule for solids): the element goes when any
            // of its integration points has failed.
            if (can_erode && material.point_failed(hst))
              failed = true;

            // f_Ia -= jxw * sum_c G_ac dN_I/dxi_c
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int a = 0; a < 3; ++a)
                fe[n][a] -= jxw * (G[a][0] * dN[n][0] + G[a][1] * dN[n][1] +
                                   G[a][2] * dN[n][2]);

            if constexpr (I == Integration::one_point)
              {
                std::copy(&Ji[0][0], &Ji[0][0] + 9, &Jinv_c[0][0]);
                std::copy(&Jd[0][0], &Jd[0][0] + 9, &Jd_c[0][0]);
              }
          }

        if (result.inverted_element == long(e))
          continue;

        // @sect4{Flanagan-Belytschko hourglass control}
        //
        // gamma_jI = Gamma_jI - (Gamma_jK x_Ka) b_Ia with b_I = dN_I/dx at
        // the centroid: orthogonal to every linear velocity field, so an
        // affine motion produces no hourglass force on any mesh. The
        // viscous force is seed Eq. (44) with alpha = Q rho V^(2/3) c / 4.
        if constexpr (H != HourglassType::none)
          {
            // The rates h_aj = v_Ia gamma_jI and, once the resistance r_aj
            // is known, the forces -r_aj gamma_jI: hourglass_rates() and
            // add_hourglass_forces() (include/anvil/element/hourglass.h).
            double t[4][3], h[3][4];
            hourglass_rates(tables.Gamma, xe, ve, Jinv_c, Jd_c, t, h);
            const double rho = rho0 * reference_volume[e] / volume;
            double       k;
            double       r[3][4];
            if constexpr (H == HourglassType::viscous)
              {
                k = viscous_hourglass_coefficient(rho, volume, M);
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int j = 0; j < 4; ++j)
                    r[a][j] = k * h[a][j];
                dt_hourglass2 = viscous_hourglass_step2(rho * volume, k, mass_factor[e]);
              }
            else
              {
                // A damaged material's hourglass stiffness follows its
                // elastic stiffness (secant: r = k (1 - d) q).
                k = 0.25 * hourglass_coefficient * M * std::cbrt(volume) *
                    (degrading ? stiffness_fraction(e * nq) : 1.);
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int j = 0; j < 4; ++j)
                    {
                      double &q = hourglass_modes[hourglass_entry(e, 4 * a + j)];
                      q += dt * h[a][j];
                      r[a][j] = k * q;
                    }
              }
            // Work of the hourglass forces over the last step by the
            // trapezoidal rule, (r^{n-1} + r^n)/2 . h^{n-1/2} dt: the same
            // rule by which the central difference scheme moves energy, so
            // the balance also closes for modes that flip sign every step.
            double power = 0;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int j = 0; j < 4; ++j)
                {
                  double &r_old = hourglass_resistance[hourglass_entry(e, 4 * a + j)];
                  power += 0.5 * (r_old + r[a][j]) * h[a][j];
                  r_old = r[a][j];
                }
            add_hourglass_forces(tables.Gamma, tables.dN[8], t, r, fe);
            hourglass_energy[e] += power * dt;
            result.hourglass_energy_increment += energy_weight[e] * power * dt;
          }

        internal_energy[e] += e_int;
        result.internal_energy_increment += energy_weight[e] * e_int;

        // @sect4{Erosion}
        //
        // A failed element stops carrying force from this step on; the
        // energy it holds (strain, plastic and hourglass work) leaves the
        // internal and hourglass energies for the eroded one, so the
        // balance still closes.
        if (failed)
          {
            erode(e, nq, result);
            continue;
          }

        // Stable time step of this element: L_e / c with the current
        // density rho_0 V_0 / V (seed Eq. (23)).
        // The smaller of 2 / max |grad xi| and V / A_max (seed section 3.6;
        // LS-DYNA's measure for solids); the ratio of the two squared, the
        // element's distortion, is refreshed every few cycles (see
        // shape_factor).
        min_dt2 = std::min(min_dt2, element_step2(e, xe, volume, max_grad2, dt_bulk2));
        min_dt2 = std::min(min_dt2, dt_hourglass2);
        result.viscous_energy_increment += energy_weight[e] * e_visc;

        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            force[en[n] + a] += fe[n][a];
      }
    result.critical_time_step = std::sqrt(min_dt2);
    return result;
  }


  // @sect3{The batched fully integrated loop}
  //
  // Updated Lagrangian, 2x2x2 Gauss points, no hourglass control: the
  // element's eight points are the lanes of a batch (the positions and
  // velocities of its nodes are shared by all of them), so that the
  // Jacobians, the velocity gradients, the stress rotation and the
  // material update vectorise across the points, and the nodal forces
  // across the nodes. The kinematics' arithmetic and the order of every sum
  // are those of loop<updated_lagrangian, full, none>, the reference (the
  // file is compiled without contraction to FMA); the material update is
  // the batched one, where the reference updates point by point.
  // tests/unit/fast_path compares the two: the same bits for an elastic
  // material without bulk viscosity (with it, round-off: its terms are
  // arranged to need one division a point, as in batched_loop()), 4e-12
  // of the history for cracking concrete. An element with
  // a point not positive (now or at mid-step) goes to loop(), which
  // reports it.
  LoopResult ElementGroup::full_batched_loop(const double *x,
                                             const double *v,
                                             const double  dt,
                                             double       *force)
  {
    constexpr unsigned int nq   = 8;
    static_assert(nq == W, "an element's points are one batch of the history");
    const double           rho0 = material.density();
    const double           M    = material.wave_modulus();
    LoopResult             result;
    double                 min_dt2   = 1e300;
    const bool             can_erode = !alive.empty();
    const bool             with_bulk_viscosity = bulk_viscosity();
    const double           b1 = bulk_linear, b2 = bulk_quadratic,
                           expansion_factor2 = bulk_dt_factor2_expansion;
    const unsigned int     n_el      = n_elements();
    const auto            &dNp       = point_tables.by_point;
    const auto            &dNn       = point_tables.by_node;
    // (With time_elements(): each element's time, clock to clock.)
    const bool timed = timing_chunk > 0;
    auto       mark  = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();

    for (unsigned int e = 0; e < n_el; ++e)
      {
        if (timed && e > 0)
          tick(mark, e - 1);
        if (can_erode && !alive[e])
          continue;
        const std::array<unsigned int, 8> en = element_nodes(e);
        double                            xe[8][3], ve[8][3];
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            {
              xe[n][a] = x[en[n] + a];
              ve[n][a] = v[en[n] + a];
            }

        // Jacobians of position and velocity at the points, one entry at a
        // time summed over the nodes in registers (summed node by node into
        // the arrays, every partial sum went through memory: a load and a
        // store per term; the order of the sums is the same).
        alignas(64) double Jn[3][3][W], Jd[3][3][W];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            {
              alignas(64) double jn[W] = {}, jd[W] = {};
              for (unsigned int n = 0; n < 8; ++n)
                for (unsigned int l = 0; l < W; ++l)
                  {
                    jn[l] += xe[n][a] * dNp[n][c][l];
                    jd[l] += ve[n][a] * dNp[n][c][l];
                  }
              for (unsigned int l = 0; l < W; ++l)
                {
                  Jn[a][c][l] = jn[l];
                  Jd[a][c][l] = jd[l];
                }
            }
        alignas(64) double detn[W], Jm[3][3][W], detm[W];
        determinant_batch(Jn, detn);
        bool inverted = false;
        for (unsigned int l = 0; l < W; ++l)
          inverted |= !(detn[l] > 0);
        if (dt > 0)
          {
            midstep_jacobian_batch(Jn, Jd, dt, Jm);
            determinant_batch(Jm, detm);
            for (unsigned int l = 0; l < W; ++l)
              inverted |= !(detm[l] > 0);
          }
        if (inverted)
          {
            ++reference_fallbacks;
            const LoopResult r =
              loop<Formulation::updated_lagrangian, Integration::full, HourglassType::none>(
                x, v, dt, force, e, e + 1);
            min_dt2 = std::min(min_dt2, r.critical_time_step * r.critical_time_step);
            result.add(r);
            continue;
          }
        alignas(64) double Ji[3][3][W];
        inverse_batch(Jn, detn, Ji);

        // The stress update of the eight points as one batch.
        double            *sig_e = &stresses[6 * e * nq];
        alignas(64) double sig[6][W], old[6][W], D[6][W] = {}, p_int[W] = {};
        for (unsigned int l = 0; l < W; ++l)
          for (unsigned int k = 0; k < 6; ++k)
            old[k][l] = sig[k][l] = sig_e[6 * l + k];
        if (dt > 0)
          {
            alignas(64) double Jmi[3][3][W], spin[3][W];
            inverse_batch(Jm, detm, Jmi);
            deformation_rate_batch(Jd, Jmi, D, spin);
            for (unsigned int l = 0; l < W; ++l)
              rotate_stress(spin[0][l], spin[1][l], spin[2][l], dt, sig[0][l], sig[1][l], sig[2][l],
                            sig[3][l], sig[4][l], sig[5][l]);
            // (nq = W: the element's points are one stored batch.)
            material.update_cauchy_stress_batch(D, spin, dt, sig,
                                                n_hist ? batch_history(std::size_t(e) * nq) :
                                                         MaterialModel::Interface::BatchHistory());
            // Seed Eq. (25) with the mid-step stress, per point.
            for (unsigned int l = 0; l < W; ++l)
              {
                double mid[6], d[6];
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    mid[k] = 0.5 * (old[k][l] + sig[k][l]);
                    d[k]   = D[k][l];
                  }
                p_int[l] = contract(mid, d) * dt * (detn[l] * tables.weight[l]);
              }
            for (unsigned int l = 0; l < W; ++l)
              for (unsigned int k = 0; k < 6; ++k)
                sig_e[6 * l + k] = sig[k][l];
          }

        // Characteristic length, bulk viscosity and the stress of the
        // forces, G_ac = sigma_ab dxi_c/dx_b, at each point.
        alignas(64) double grad2[W], sf[6][W];
        for (unsigned int l = 0; l < W; ++l)
          {
            grad2[l] = 0;
            for (unsigned int c = 0; c < 3; ++c)
              grad2[l] = std::max(grad2[l], Ji[c][0][l] * Ji[c][0][l] + Ji[c][1][l] * Ji[c][1][l] +
                                              Ji[c][2][l] * Ji[c][2][l]);
            for (unsigned int k = 0; k < 6; ++k)
              sf[k][l] = sig[k][l];
          }
        double e_int = 0, e_visc = 0, volume = 0, max_grad2 = 0, dt_bulk2 = 1;
        for (unsigned int l = 0; l < W; ++l)
          {
            e_int += p_int[l];
            volume += detn[l] * tables.weight[l];
            max_grad2 = std::max(max_grad2, grad2[l]);
          }
        if (with_bulk_viscosity)
          {
            // The pressure at each point across the lanes, from Z at the
            // point's density rho_0 V_0 / (8 det J) (one division a
            // point); then the work in point order.
            alignas(64) double qp[W], f2[W], trD[W];
            const double       m8 = rho0 * reference_volume[e] / 8.;
            for (unsigned int l = 0; l < W; ++l)
              {
                trD[l]         = D[0][l] + D[1][l] + D[2][l];
                const double Z = m8 / (detn[l] * grad2[l]);
                qp[l]          = bulk_viscosity_pressure_of_Z(trD[l], Z, M, b1, b2, expansion_factor2, f2[l]);
              }
            for (unsigned int l = 0; l < W; ++l)
              {
                dt_bulk2      = std::min(dt_bulk2, f2[l]);
                double &q_old = bulk_pressure[e * nq + l];
                e_visc += 0.5 * (q_old + qp[l]) * (-trD[l]) * dt * (detn[l] * tables.weight[l]);
                q_old = qp[l];
                for (unsigned int k = 0; k < 3; ++k)
                  sf[k][l] -= qp[l];
              }
          }
        alignas(64) double G[3][3][W];
        for (unsigned int c = 0; c < 3; ++c)
          for (unsigned int l = 0; l < W; ++l)
            {
              G[0][c][l] = sf[0][l] * Ji[c][0][l] + sf[3][l] * Ji[c][1][l] + sf[5][l] * Ji[c][2][l];
              G[1][c][l] = sf[3][l] * Ji[c][0][l] + sf[1][l] * Ji[c][1][l] + sf[4][l] * Ji[c][2][l];
              G[2][c][l] = sf[5][l] * Ji[c][0][l] + sf[4][l] * Ji[c][1][l] + sf[2][l] * Ji[c][2][l];
            }
        bool failed = false;
        if (can_erode)
          for (unsigned int l = 0; l < W; ++l)
            failed |= point_failed(e * nq + l);

        // f_Ia -= jxw sum_c G_ac dN_I/dxi_c, point after point (lanes:
        // nodes).
        alignas(64) double fe[3][8] = {};
        for (unsigned int q = 0; q < W; ++q)
          {
            const double jxw = detn[q] * tables.weight[q];
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int n = 0; n < 8; ++n)
                fe[a][n] -= jxw * (G[a][0][q] * dNn[q][0][n] + G[a][1][q] * dNn[q][1][n] +
                                   G[a][2][q] * dNn[q][2][n]);
          }

        internal_energy[e] += e_int;
        result.internal_energy_increment += energy_weight[e] * e_int;
        if (failed)
          {
            erode(e, nq, result);
            continue;
          }
        min_dt2 = std::min(min_dt2, element_step2(e, xe, volume, max_grad2, dt_bulk2));
        result.viscous_energy_increment += energy_weight[e] * e_visc;
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            force[en[n] + a] += fe[a][n];
      }
    if (timed && n_el > 0)
      tick(mark, n_el - 1);
    result.critical_time_step = std::sqrt(min_dt2);
    return result;
  }


  // The squared stable step of element @p e with nodal positions @p xe,
  // current volume @p volume, max_q max_c |grad xi_c|^2 @p max_grad2 and
  // the bulk viscosity's factor @p dt_bulk2 (loop() and
  // full_batched_loop()); refreshes its shape factor every few cycles.
  double ElementGroup::element_step2(const unsigned int e,
                                     const double (&xe)[8][3],
                                     const double volume,
                                     const double max_grad2,
                                     const double dt_bulk2)
  {
    const double rho_c = material.density() * reference_volume[e] / volume;
    if (refresh_shape)
      {
        const double A2 = max_face_area2([&](unsigned int n, unsigned int a) { return xe[n][a]; });
        shape_factor[e] = shape_factor_of(volume, A2, max_grad2, mass_factor[e]);
      }
    return element_step2_of(max_grad2, shape_factor[e], rho_c, material.wave_modulus(), dt_bulk2);
  }


  double ElementGroup::stable_step(const unsigned int e, const double (&X)[8][3]) const
  {
    // As loop() at dt = 0: the Jacobian at each point (the centroid for
    // one-point elements), the largest |grad xi|^2, the volume; then
    // element_step2()'s arithmetic and the damper's bound.
    const bool         one_point = integration == Integration::one_point;
    const unsigned int q0 = one_point ? 8 : 0, nq = one_point ? 1 : 8;
    double             volume = 0, max_grad2 = 0;
    for (unsigned int q = q0; q < q0 + nq; ++q)
      {
        double J[3][3];
        reference_jacobian(X, q, J);
        const double det = det3(J);
        if (!(det > 0))
          return 0.;
        double Ji[3][3];
        inv3(J, det, Ji);
        for (unsigned int c = 0; c < 3; ++c)
          max_grad2 = std::max(max_grad2, Ji[c][0] * Ji[c][0] + Ji[c][1] * Ji[c][1] + Ji[c][2] * Ji[c][2]);
        volume += det * tables.weight[q];
      }
    const double rho0 = material.density(), M = material.wave_modulus();
    const double rho  = rho0 * reference_volume[e] / volume;
    const double A2   = max_face_area2([&](unsigned int n, unsigned int a) { return X[n][a]; });
    double       dt_bulk2 = 1.;
    if (bulk_viscosity())
      bulk_viscosity_pressure(0., 2. / std::sqrt(max_grad2), rho, std::sqrt(M / rho), dt_bulk2);
    double dt2 = element_step2_of(max_grad2, shape_factor_of(volume, A2, max_grad2, mass_factor[e]), rho, M, dt_bulk2);
    if (hourglass == HourglassType::viscous)
      dt2 = std::min(dt2, viscous_hourglass_step2(rho * volume,
                                                  viscous_hourglass_coefficient(rho, volume, M), mass_factor[e]));
    return std::sqrt(dt2);
  }


  // A failed element's stresses go to zero and the energy it holds (strain,
  // plastic and hourglass work) moves from the internal and hourglass
  // energies to the eroded one.
  void ElementGroup::erode(const unsigned int e, const unsigned int nq, LoopResult &result)
  {
    alive[e] = 0;
    std::fill(&stresses[6 * e * nq], &stresses[6 * (e + 1) * nq], 0.);
    const double w = energy_weight[e];
    result.internal_energy_increment -= w * internal_energy[e];
    result.hourglass_energy_increment -= w * hourglass_energy[e];
    result.eroded_energy_increment += w * (internal_energy[e] + hourglass_energy[e]);
    result.eroded_elements.push_back(global_id[e]);
  }


  // @sect3{The batched one-point loop}
  //
  // The same mathematics as loop<updated_lagrangian, one_point, H> (the
  // reference; tests/unit compare the two), written for W = 8 elements at
  // a time with every quantity an array over the batch, so that each
  // statement becomes one SIMD operation. The last batch is padded by
  // repeating its last element in lanes that are never written back. Every
  // element goes through the same instructions whatever its lane, so the
  // results do not depend on how elements fall into batches (nor on the
  // partition).
  template <HourglassType H>
  LoopResult ElementGroup::batched_loop(const double *x,
                                        const double *v,
                                        const double  dt,
                                        double       *force)
  {
    const double           rho0 = material.density();
    const double           M    = material.wave_modulus();
    LoopResult             result;
    double                 min_dt2 = 1e300;
    const unsigned int     n_el    = n_elements();
    const bool             degrading = material.degrades() && n_hist > 0;
    const double           b1 = bulk_linear, b2 = bulk_quadratic,
                           expansion_factor2 = bulk_dt_factor2_expansion;
    const bool             can_erode = !alive.empty();
    const bool             with_bulk_viscosity = bulk_viscosity();
    // The constants of the stable steps: 4 / M of the element's (times
    // Z below), 1 / (64 Q^2 M) of the viscous hourglass damper's.
    const double four_over_M            = 4. / M;
    const double hourglass_step2_factor = 1. / (64. * hourglass_coefficient * hourglass_coefficient * M);
    // (With time_elements(): each batch's time, clock to clock.)
    const bool timed = timing_chunk > 0;
    auto       mark  = timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point();

    for (unsigned int e0 = 0; e0 < n_el; e0 += W)
      {
        if (timed && e0 > 0)
          tick(mark, e0 / W - 1);
        // The lanes: the batch's live elements; the padding of the last
        // batch and eroded elements repeat a live element of the batch and
        // are never written back (their history is a scratch copy), so an
        // element's result does not depend on its neighbours in the batch.
        const unsigned int n_valid = std::min(W, n_el - e0);
        unsigned int       el[W];
        bool               live[W];
        int                first_live = -1;
        for (unsigned int l = 0; l < n_valid; ++l)
          if (!can_erode || alive[e0 + l])
            {
              first_live = e0 + l;
              break;
            }
        if (first_live < 0)
          continue;
        // The next batch's element data, fetched while this one is
        // computed: the hardware's prefetchers follow a few of the loop's
        // streams only (doc/performance.md).
        if (e0 + W < n_el)
          {
            // (Entries [first, first + count) of an array, within it.)
            const auto fetch = [](const auto &array, const std::size_t first, const std::size_t count) {
              const char *p     = reinterpret_cast<const char *>(array.data() + first);
              const auto  bytes = std::min(count, array.size() - first) * sizeof(array[0]);
              for (std::size_t b = 0; b < bytes; b += 64)
                __builtin_prefetch(p + b);
            };
            const std::size_t next = e0 + W;
            fetch(nodes, 8 * next, 8 * W);
            fetch(stresses, 6 * next, 6 * W);
            if constexpr (H != HourglassType::none)
              fetch(hourglass_resistance, hourglass_entry(next, 0), 12 * W);
            // (Of the history only the hot values, which every step reads;
            // a material that reads the rest fetches it itself.)
            if (n_hist)
              fetch(history, hot_entry(next, 0), n_hot * W);
          }
        unsigned int last_live = first_live;
        bool         all_live  = true;
        for (unsigned int l = 0; l < W; ++l)
          {
            live[l] = l < n_valid && (!can_erode || alive[e0 + l]);
            if (live[l])
              last_live = e0 + l;
            el[l] = live[l] ? e0 + l : last_live;
            all_live = all_live && live[l];
          }

        // The lanes' nodes: the batch's node-major block (node()), with
        // the lanes that repeat another element's redirected.
        alignas(64) unsigned int idx[8][W];
        std::memcpy(idx, &nodes[8 * e0], sizeof idx);
        for (unsigned int l = 0; l < W; ++l)
          if (el[l] != e0 + l)
            for (unsigned int n = 0; n < 8; ++n)
              idx[n][l] = node(el[l], n);
        alignas(64) double xe[8][3][W], ve[8][3][W];
        gather_nodes(x, idx, xe, batch_wide[e0 / W] != 0);
        gather_nodes(v, idx, ve, batch_wide[e0 / W] != 0);

        // Positions and velocities in the element's Walsh basis; the
        // Jacobians of position and velocity at the centroid.
        alignas(64) double cx[8][3][W], cv[8][3][W];
        walsh_transform<false>(xe, cx);
        walsh_transform<false>(ve, cv);
        alignas(64) double Jn[3][3][W], Jd[3][3][W];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            for (unsigned int l = 0; l < W; ++l)
              {
                Jn[a][c][l] = 0.125 * cx[1u << c][a][l];
                Jd[a][c][l] = 0.125 * cv[1u << c][a][l];
              }
        alignas(64) double detn[W];
        determinant_batch(Jn, detn);
        bool inverted = false;
        for (unsigned int l = 0; l < W; ++l)
          inverted |= !(detn[l] > 0);
        if (inverted)
          {
            // Let the reference loop find and report the element.
            ++reference_fallbacks;
            const LoopResult r = loop<Formulation::updated_lagrangian, Integration::one_point, H>(
              x, v, dt, force, e0, e0 + n_valid);
            min_dt2 = std::min(min_dt2, r.critical_time_step * r.critical_time_step);
            result.add(r);
            continue;
          }

        alignas(64) double Ji[3][3][W];
        inverse_batch(Jn, detn, Ji);

        alignas(64) double sig[6][W], old[6][W];
        if (all_live)
          load_voigt_rows(&stresses[6 * e0], old);
        else
          for (unsigned int l = 0; l < W; ++l)
            for (unsigned int k = 0; k < 6; ++k)
              old[k][l] = stresses[6 * el[l] + k];
        std::memcpy(sig, old, sizeof sig);
        alignas(64) double e_int[W] = {};
        alignas(64) double trD[W]   = {};
        bool               failed[W] = {};

        if (dt > 0)
          {
            // Velocity gradient on the mid-step configuration: its
            // symmetric part D and its spin W_01, W_12, W_02.
            alignas(64) double Jm[3][3][W], Jmi[3][3][W], detm[W], D[6][W], spin[3][W];
            midstep_jacobian_batch(Jn, Jd, dt, Jm);
            determinant_batch(Jm, detm);
            inverse_batch(Jm, detm, Jmi);
            deformation_rate_batch(Jd, Jmi, D, spin);
            // Padding lanes work on a scratch copy of the history, so that
            // the repeated last element is updated once only.
            MaterialModel::Interface::BatchHistory hist;
            if (n_hist)
              {
                hist = batch_history(e0);
                for (unsigned int l = 0; l < W; ++l)
                  if (!live[l])
                    {
                      const std::size_t p = el[l];
                      hist.hot[l]    = scratch_history.data() + l;
                      hist.cold[l]   = scratch_cold_history.data() + n_cold * l;
                      hist.hot_batch = nullptr;
                      for (unsigned int k = 0; k < n_hot; ++k)
                        hist.hot_value(l, k) = history[hot_entry(p, k)];
                      std::copy_n(cold_history.data() + n_cold * p, n_cold, hist.cold[l]);
                    }
              }
            // The Hughes-Winget rotation of the stress across lanes (the
            // material rotates its own history).
            for (unsigned int l = 0; l < W; ++l)
              Kinematics::rotate_stress(spin[0][l], spin[1][l], spin[2][l], dt, sig[0][l],
                                        sig[1][l], sig[2][l], sig[3][l], sig[4][l], sig[5][l]);
            material.update_cauchy_stress_batch(D, spin, dt, sig, hist);
            // Failure (ABAQUS's rule for solids): the element goes when its
            // integration point has failed.
            if (can_erode)
              for (unsigned int l = 0; l < W; ++l)
                failed[l] = live[l] && point_failed(el[l]);
            for (unsigned int l = 0; l < W; ++l)
              trD[l] = D[0][l] + D[1][l] + D[2][l];
            for (unsigned int l = 0; l < W; ++l)
              {
                double p = 0;
                for (unsigned int k = 0; k < 3; ++k)
                  p += 0.5 * (old[k][l] + sig[k][l]) * D[k][l];
                for (unsigned int k = 3; k < 6; ++k)
                  p += (old[k][l] + sig[k][l]) * D[k][l];
                e_int[l] = p * dt * 8. * detn[l];
              }
          }

        // Per-element data of the lanes, gathered once so that the loops
        // below vectorise across them.
        alignas(64) double V0[W], shape[W], q_old[W], r_old[3][4][W];
        for (unsigned int l = 0; l < W; ++l)
          {
            V0[l]    = reference_volume[el[l]];
            shape[l] = shape_factor[el[l]];
            q_old[l] = with_bulk_viscosity ? bulk_pressure[el[l]] : 0.;
          }
        alignas(64) double q_modes[3][4][W], stiffness[W];
        // The batch's hourglass state (hourglass_entry()): a lane that
        // repeats another element reads the state of its own slot, and
        // keeps it; its results are never written back.
        // (e0 is a multiple of W, so lane l of entry 4 a + j is at hg(a, j)
        // + l.)
        const auto hg = [hg0 = hourglass_entry(e0, 0)](const unsigned int a, const unsigned int j) {
          return hg0 + W * (4 * a + j);
        };
        if constexpr (H != HourglassType::none)
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int j = 0; j < 4; ++j)
              for (unsigned int l = 0; l < W; ++l)
                r_old[a][j][l] = hourglass_resistance[hg(a, j) + l];
        if constexpr (H == HourglassType::stiffness)
          for (unsigned int l = 0; l < W; ++l)
            {
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int j = 0; j < 4; ++j)
                  q_modes[a][j][l] = hourglass_modes[hg(a, j) + l];
              stiffness[l] = degrading ? stiffness_fraction(el[l]) : 1.;
            }

        // max_c |grad xi_c|^2 per lane: the characteristic length.
        alignas(64) double g2[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            g2[l] = 0;
            for (unsigned int c = 0; c < 3; ++c)
              g2[l] = std::max(g2[l], Ji[c][0][l] * Ji[c][0][l] + Ji[c][1][l] * Ji[c][1][l] +
                                        Ji[c][2][l] * Ji[c][2][l]);
          }

        // Z = rho L^2 / 4 = m / (V |grad xi|^2), with L = 2 / |grad xi|
        // the characteristic length and m = rho_0 V_0 the element's mass:
        // the one quotient of both stable steps and the bulk viscosity.
        alignas(64) double Z[W];
        for (unsigned int l = 0; l < W; ++l)
          Z[l] = rho0 * V0[l] / (8. * detn[l] * g2[l]);

        // Bulk viscosity: the pressure q joins the normal stresses of the
        // forces (not the stored stress); its trapezoidal work.
        alignas(64) double qv[W] = {}, e_visc[W] = {}, dt_bulk2[W], dt_hourglass2[W];
        std::fill(dt_hourglass2, dt_hourglass2 + W, 1e300);
        std::fill(dt_bulk2, dt_bulk2 + W, 1.);
        if (with_bulk_viscosity)
          for (unsigned int l = 0; l < W; ++l)
            {
              // (One square root where there were three and three
              // divisions.)
              qv[l]     = bulk_viscosity_pressure_of_Z(trD[l], Z[l], M, b1, b2, expansion_factor2, dt_bulk2[l]);
              e_visc[l] = 0.5 * (q_old[l] + qv[l]) * (-trD[l]) * dt * 8. * detn[l];
            }
        // Internal force f_Ia -= V sigma_ab dxi_c/dx_b dN_I/dxi_c, together
        // with the hourglass force below.
        alignas(64) double G[3][3][W];
        for (unsigned int c = 0; c < 3; ++c)
          for (unsigned int l = 0; l < W; ++l)
            {
              const double V = 8. * detn[l];
              G[0][c][l] =
                -V * ((sig[0][l] - qv[l]) * Ji[c][0][l] + sig[3][l] * Ji[c][1][l] + sig[5][l] * Ji[c][2][l]);
              G[1][c][l] =
                -V * (sig[3][l] * Ji[c][0][l] + (sig[1][l] - qv[l]) * Ji[c][1][l] + sig[4][l] * Ji[c][2][l]);
              G[2][c][l] =
                -V * (sig[5][l] * Ji[c][0][l] + sig[4][l] * Ji[c][1][l] + (sig[2][l] - qv[l]) * Ji[c][2][l]);
            }
        alignas(64) double r[3][4][W] = {};
        alignas(64) double e_hg[W]    = {};
        if constexpr (H != HourglassType::none)
          {
            alignas(64) double t[4][3][W], h[3][4][W];
            for (unsigned int j = 0; j < 4; ++j)
              for (unsigned int l = 0; l < W; ++l)
                {
                  const double g[3]  = {cx[gamma_index[j]][0][l], cx[gamma_index[j]][1][l],
                                        cx[gamma_index[j]][2][l]};
                  const double vg[3] = {cv[gamma_index[j]][0][l], cv[gamma_index[j]][1][l],
                                        cv[gamma_index[j]][2][l]};
                  for (unsigned int c = 0; c < 3; ++c)
                    t[j][c][l] = g[0] * Ji[c][0][l] + g[1] * Ji[c][1][l] + g[2] * Ji[c][2][l];
                  for (unsigned int a = 0; a < 3; ++a)
                    h[a][j][l] = vg[a] - (t[j][0][l] * Jd[a][0][l] + t[j][1][l] * Jd[a][1][l] +
                                          t[j][2][l] * Jd[a][2][l]);
                }
            alignas(64) double k[W];
            for (unsigned int l = 0; l < W; ++l)
              {
                const double volume = 8. * detn[l];
                if constexpr (H == HourglassType::viscous)
                  {
                    // 0.25 Q rho V^(2/3) c with c = sqrt(M / rho) and rho V
                    // = m, the element's mass: 0.25 Q V^(-1/3) sqrt(M m V);
                    // the damper's squared step (m / 32 k)^2 f =
                    // m V^(-1/3) f / (64 Q^2 M) (viscous_hourglass_step2()),
                    // with no division.
                    const double mass = rho0 * V0[l], r = inverse_cube_root(volume);
                    k[l]             = 0.25 * hourglass_coefficient * r * std::sqrt(M * mass * volume);
                    dt_hourglass2[l] = mass * r * mass_factor[el[l]] * hourglass_step2_factor;
                  }
                else
                  {
                    const double r = inverse_cube_root(volume);
                    k[l]           = 0.25 * hourglass_coefficient * M * (volume * r * r) * stiffness[l];
                  }
              }
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int j = 0; j < 4; ++j)
                for (unsigned int l = 0; l < W; ++l)
                  {
                    if constexpr (H == HourglassType::viscous)
                      r[a][j][l] = k[l] * h[a][j][l];
                    else
                      {
                        const double q = q_modes[a][j][l] + dt * h[a][j][l];
                        r[a][j][l]     = k[l] * q;
                      }
                    e_hg[l] += 0.5 * (r_old[a][j][l] + r[a][j][l]) * h[a][j][l] * dt;
                  }
            // The hourglass part of G: + r_aj t_jc.
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int c = 0; c < 3; ++c)
                for (unsigned int l = 0; l < W; ++l)
                  G[a][c][l] += r[a][0][l] * t[0][c][l] + r[a][1][l] * t[1][c][l] +
                                r[a][2][l] * t[2][c][l] + r[a][3][l] * t[3][c][l];
            // Write back the hourglass state of the live lanes.
            // (The other lanes keep what their slots hold; a batch whose
            // lanes all live, nearly every one, stores whole rows.)
            if (all_live)
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int j = 0; j < 4; ++j)
                  for (unsigned int l = 0; l < W; ++l)
                    {
                      const std::size_t i = hg(a, j) + l;
                      if constexpr (H == HourglassType::stiffness)
                        hourglass_modes[i] = q_modes[a][j][l] + dt * h[a][j][l];
                      hourglass_resistance[i] = r[a][j][l];
                    }
            else
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int j = 0; j < 4; ++j)
                  for (unsigned int l = 0; l < W; ++l)
                    {
                      const std::size_t i = hg(a, j) + l;
                      if constexpr (H == HourglassType::stiffness)
                        hourglass_modes[i] = live[l] ? q_modes[a][j][l] + dt * h[a][j][l] : q_modes[a][j][l];
                      hourglass_resistance[i] = live[l] ? r[a][j][l] : r_old[a][j][l];
                    }
          }

        // The nodal forces from their Walsh coefficients: G_ac / 8 on
        // xi_c, -r_aj on Gamma_j.
        alignas(64) double fc[8][3][W], fe[8][3][W];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int l = 0; l < W; ++l)
            {
              fc[0][a][l] = 0;
              for (unsigned int c = 0; c < 3; ++c)
                fc[1u << c][a][l] = 0.125 * G[a][c][l];
              for (unsigned int j = 0; j < 4; ++j)
                fc[gamma_index[j]][a][l] = -r[a][j][l]; // zero without hourglass control
            }
        walsh_transform<true>(fc, fe);

        // Stable time step per lane: L_e = min(2 / max_c |grad xi_c|, V / A_max).
        // Distortion factor, refreshed every few cycles (shape_factor).
        if (refresh_shape)
          for (unsigned int l = 0; l < W; ++l)
            {
              const double V = 8. * detn[l];
              const double A2 = max_face_area2([&](unsigned int n, unsigned int a) { return xe[n][a][l]; });
              shape[l]        = shape_factor_of(V, A2, g2[l], mass_factor[el[l]]);
              if (live[l])
                shape_factor[el[l]] = shape[l];
            }
        // (4 / |grad xi|^2) shape (rho / M) = (4 / M) Z shape.
        alignas(64) double dt2[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            dt2[l] = four_over_M * Z[l] * shape[l] * dt_bulk2[l];
            dt2[l] = std::min(dt2[l], dt_hourglass2[l]);
          }

        // Write back and scatter the live lanes, in element order.
        bool any_failed = false;
        for (unsigned int l = 0; l < W; ++l)
          any_failed |= failed[l];
        if (all_live && !any_failed)
          {
            // A batch of its own elements, none failed (nearly every one):
            // the same as the lane-by-lane loop below, with the per-element
            // arrays written as rows and the sums over the elements in
            // element order, as there.
            store_voigt_rows(sig, &stresses[6 * e0]);
            for (unsigned int l = 0; l < W; ++l)
              {
                hourglass_energy[e0 + l] += e_hg[l];
                internal_energy[e0 + l] += e_int[l];
                min_dt2 = std::min(min_dt2, dt2[l]);
              }
            if (with_bulk_viscosity)
              std::memcpy(&bulk_pressure[e0], qv, sizeof qv);
            alignas(64) double w[W];
            std::memcpy(w, &energy_weight[e0], sizeof w);
            for (unsigned int l = 0; l < W; ++l)
              result.hourglass_energy_increment += w[l] * e_hg[l];
            for (unsigned int l = 0; l < W; ++l)
              result.internal_energy_increment += w[l] * e_int[l];
            if (with_bulk_viscosity)
              for (unsigned int l = 0; l < W; ++l)
                result.viscous_energy_increment += w[l] * e_visc[l];
            for (unsigned int l = 0; l < W; ++l)
              for (unsigned int n = 0; n < 8; ++n)
                for (unsigned int a = 0; a < 3; ++a)
                  force[idx[n][l] + a] += fe[n][a][l];
            continue;
          }
        for (unsigned int l = 0; l < W; ++l)
          {
            if (!live[l])
              continue;
            const unsigned int e = el[l];
            for (unsigned int k = 0; k < 6; ++k)
              stresses[6 * e + k] = sig[k][l];
            hourglass_energy[e] += e_hg[l];
            result.hourglass_energy_increment += energy_weight[e] * e_hg[l];
            internal_energy[e] += e_int[l];
            result.internal_energy_increment += energy_weight[e] * e_int[l];
            if (with_bulk_viscosity)
              bulk_pressure[e] = qv[l];
            if (failed[l])
              {
                // As in the reference loop: a failed element stops carrying
                // force from this step on, and the energy it holds moves to
                // the eroded energy.
                erode(e, 1, result);
                continue;
              }
            if (with_bulk_viscosity)
              result.viscous_energy_increment += energy_weight[e] * e_visc[l];
            min_dt2 = std::min(min_dt2, dt2[l]);
            for (unsigned int n = 0; n < 8; ++n)
              for (unsigned int a = 0; a < 3; ++a)
                force[idx[n][l] + a] += fe[n][a][l];
          }
      }
    if (timed && n_el > 0)
      tick(mark, (n_el - 1) / W);
    result.critical_time_step = std::sqrt(min_dt2);
    return result;
  }


  void ElementGroup::cauchy_stress(const unsigned int e,
                                   const double      *x,
                                   double            *sigma) const
  {
    std::fill(sigma, sigma + 6, 0.);
    for (unsigned int qq = 0; qq < n_qp; ++qq)
      {
        const double *s = stress(e, qq);
        if (formulation == Formulation::updated_lagrangian)
          {
            for (unsigned int k = 0; k < 6; ++k)
              sigma[k] += s[k] / n_qp;
            continue;
          }
        // sigma = F S F^T / det F
        const unsigned int q  = (n_qp == 1 ? 8 : qq);
        const double      *Jr = &jacobian_inverse_ref[9 * (e * n_qp + qq)];
        double             Jn[3][3] = {};
        for (unsigned int n = 0; n < 8; ++n)
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int c = 0; c < 3; ++c)
              Jn[a][c] += x[node(e, n) + a] * tables.dN[q][n][c];
        double Fm[3][3];
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            Fm[a][b] = Jn[a][0] * Jr[b] + Jn[a][1] * Jr[3 + b] +
                       Jn[a][2] * Jr[6 + b];
        const double J = det3(Fm);
        double       S[3][3], T[3][3];
        voigt_to_matrix(s, S);
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int b = 0; b < 3; ++b)
            T[a][b] = Fm[a][0] * S[0][b] + Fm[a][1] * S[1][b] + Fm[a][2] * S[2][b];
        auto c = [&](unsigned int i, unsigned int j) {
          return (T[i][0] * Fm[j][0] + T[i][1] * Fm[j][1] + T[i][2] * Fm[j][2]) / J;
        };
        sigma[0] += c(0, 0) / n_qp;
        sigma[1] += c(1, 1) / n_qp;
        sigma[2] += c(2, 2) / n_qp;
        sigma[3] += c(0, 1) / n_qp;
        sigma[4] += c(1, 2) / n_qp;
        sigma[5] += c(0, 2) / n_qp;
      }
  }
} // namespace anvil::Element
