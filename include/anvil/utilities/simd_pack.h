/**
 * @file
 * A few vector registers as one value, for code whose time is the latency
 * of a long chain of dependent operations (a return mapping's Newton
 * steps, exp and log): every operation of a Pack is that operation on each
 * of its R registers in turn, so that R independent chains are in flight
 * at once instead of one. The operations are xsimd's, register by
 * register; a lane's result is the same whatever R is and whatever the
 * other lanes hold.
 */
#ifndef ANVIL_UTILITIES_SIMD_PACK_H
#define ANVIL_UTILITIES_SIMD_PACK_H

#include <xsimd/xsimd.hpp>

namespace anvil::Simd
{
  using Register = xsimd::batch<double>;
  using RegisterMask = xsimd::batch_bool<double>;

  /** Lanes of one register (8 with AVX-512, 4 with AVX2, 2 with SSE2 and NEON). */
  constexpr unsigned int register_lanes = Register::size;

  template <unsigned int R>
  struct Mask
  {
    RegisterMask m[R];
  };

  template <unsigned int R>
  struct Pack
  {
    static constexpr unsigned int lanes = R * register_lanes;
    Register                      v[R];

    Pack() = default;
    Pack(const double a)
    {
      for (unsigned int r = 0; r < R; ++r)
        v[r] = Register(a);
    }
    /** Lanes p[0] ... p[lanes - 1] (any alignment). */
    static Pack load(const double *p)
    {
      Pack x;
      for (unsigned int r = 0; r < R; ++r)
        x.v[r] = Register::load_unaligned(p + r * register_lanes);
      return x;
    }
    void store(double *p) const
    {
      for (unsigned int r = 0; r < R; ++r)
        v[r].store_unaligned(p + r * register_lanes);
    }
  };

#define ANVIL_PACK_BINARY(OP, RESULT, TYPE, EXPR)                                   \
  template <unsigned int R>                                                         \
  inline RESULT<R> OP(const TYPE<R> &a, const TYPE<R> &b)                           \
  {                                                                                 \
    RESULT<R> x;                                                                    \
    for (unsigned int r = 0; r < R; ++r)                                            \
      x.EXPR;                                                                       \
    return x;                                                                       \
  }

  ANVIL_PACK_BINARY(operator+, Pack, Pack, v[r] = a.v[r] + b.v[r])
  ANVIL_PACK_BINARY(operator-, Pack, Pack, v[r] = a.v[r] - b.v[r])
  ANVIL_PACK_BINARY(operator*, Pack, Pack, v[r] = a.v[r] * b.v[r])
  ANVIL_PACK_BINARY(operator/, Pack, Pack, v[r] = a.v[r] / b.v[r])
  ANVIL_PACK_BINARY(min, Pack, Pack, v[r] = xsimd::min(a.v[r], b.v[r]))
  ANVIL_PACK_BINARY(max, Pack, Pack, v[r] = xsimd::max(a.v[r], b.v[r]))
  ANVIL_PACK_BINARY(operator>, Mask, Pack, m[r] = a.v[r] > b.v[r])
  ANVIL_PACK_BINARY(operator<, Mask, Pack, m[r] = a.v[r] < b.v[r])
  ANVIL_PACK_BINARY(operator<=, Mask, Pack, m[r] = a.v[r] <= b.v[r])
  ANVIL_PACK_BINARY(operator==, Mask, Pack, m[r] = a.v[r] == b.v[r])
  ANVIL_PACK_BINARY(operator!=, Mask, Pack, m[r] = a.v[r] != b.v[r])
  ANVIL_PACK_BINARY(operator&&, Mask, Mask, m[r] = a.m[r] && b.m[r])
  ANVIL_PACK_BINARY(operator||, Mask, Mask, m[r] = a.m[r] || b.m[r])
  ANVIL_PACK_BINARY(operator==, Mask, Mask, m[r] = a.m[r] == b.m[r])
#undef ANVIL_PACK_BINARY

#define ANVIL_PACK_UNARY(OP, RESULT, TYPE, EXPR)                                    \
  template <unsigned int R>                                                         \
  inline RESULT<R> OP(const TYPE<R> &a)                                             \
  {                                                                                 \
    RESULT<R> x;                                                                    \
    for (unsigned int r = 0; r < R; ++r)                                            \
      x.EXPR;                                                                       \
    return x;                                                                       \
  }

  ANVIL_PACK_UNARY(operator-, Pack, Pack, v[r] = -a.v[r])
  ANVIL_PACK_UNARY(abs, Pack, Pack, v[r] = xsimd::abs(a.v[r]))
  ANVIL_PACK_UNARY(sqrt, Pack, Pack, v[r] = xsimd::sqrt(a.v[r]))
  ANVIL_PACK_UNARY(exp, Pack, Pack, v[r] = xsimd::exp(a.v[r]))
  ANVIL_PACK_UNARY(log, Pack, Pack, v[r] = xsimd::log(a.v[r]))
  ANVIL_PACK_UNARY(operator!, Mask, Mask, m[r] = !a.m[r])
#undef ANVIL_PACK_UNARY

  // A number beside a Pack is the same number in every lane (a broadcast,
  // which AVX-512 folds into the operation): constants cost no register.
#define ANVIL_PACK_SCALAR(OP, RESULT, EXPR_LEFT, EXPR_RIGHT)                        \
  template <unsigned int R>                                                         \
  inline RESULT<R> OP(const Pack<R> &a, const double b)                             \
  {                                                                                 \
    RESULT<R> x;                                                                    \
    const Register c(b);                                                            \
    for (unsigned int r = 0; r < R; ++r)                                            \
      x.EXPR_LEFT;                                                                  \
    return x;                                                                       \
  }                                                                                 \
  template <unsigned int R>                                                         \
  inline RESULT<R> OP(const double b, const Pack<R> &a)                             \
  {                                                                                 \
    RESULT<R> x;                                                                    \
    const Register c(b);                                                            \
    for (unsigned int r = 0; r < R; ++r)                                            \
      x.EXPR_RIGHT;                                                                 \
    return x;                                                                       \
  }

  ANVIL_PACK_SCALAR(operator+, Pack, v[r] = a.v[r] + c, v[r] = c + a.v[r])
  ANVIL_PACK_SCALAR(operator-, Pack, v[r] = a.v[r] - c, v[r] = c - a.v[r])
  ANVIL_PACK_SCALAR(operator*, Pack, v[r] = a.v[r] * c, v[r] = c * a.v[r])
  ANVIL_PACK_SCALAR(operator/, Pack, v[r] = a.v[r] / c, v[r] = c / a.v[r])
  ANVIL_PACK_SCALAR(min, Pack, v[r] = xsimd::min(a.v[r], c), v[r] = xsimd::min(c, a.v[r]))
  ANVIL_PACK_SCALAR(max, Pack, v[r] = xsimd::max(a.v[r], c), v[r] = xsimd::max(c, a.v[r]))
  ANVIL_PACK_SCALAR(operator>, Mask, m[r] = a.v[r] > c, m[r] = c > a.v[r])
  ANVIL_PACK_SCALAR(operator<, Mask, m[r] = a.v[r] < c, m[r] = c < a.v[r])
  ANVIL_PACK_SCALAR(operator<=, Mask, m[r] = a.v[r] <= c, m[r] = c <= a.v[r])
  ANVIL_PACK_SCALAR(operator!=, Mask, m[r] = a.v[r] != c, m[r] = c != a.v[r])
  ANVIL_PACK_SCALAR(operator==, Mask, m[r] = a.v[r] == c, m[r] = c == a.v[r])
#undef ANVIL_PACK_SCALAR

  template <unsigned int R>
  inline Pack<R> select(const Mask<R> &c, const Pack<R> &a, const Pack<R> &b)
  {
    Pack<R> x;
    for (unsigned int r = 0; r < R; ++r)
      x.v[r] = xsimd::select(c.m[r], a.v[r], b.v[r]);
    return x;
  }

  template <unsigned int R>
  inline Pack<R> select(const Mask<R> &c, const Pack<R> &a, const double b)
  {
    Pack<R>        x;
    const Register k(b);
    for (unsigned int r = 0; r < R; ++r)
      x.v[r] = xsimd::select(c.m[r], a.v[r], k);
    return x;
  }

  template <unsigned int R>
  inline Pack<R> select(const Mask<R> &c, const double a, const Pack<R> &b)
  {
    Pack<R>        x;
    const Register k(a);
    for (unsigned int r = 0; r < R; ++r)
      x.v[r] = xsimd::select(c.m[r], k, b.v[r]);
    return x;
  }

  /** Whether any lane of the pack is set. */
  template <unsigned int R>
  inline bool any(const Mask<R> &c)
  {
    RegisterMask a = c.m[0];
    for (unsigned int r = 1; r < R; ++r)
      a = a || c.m[r];
    return xsimd::any(a);
  }

  /** Whether every lane is. */
  template <unsigned int R>
  inline bool all(const Mask<R> &c)
  {
    RegisterMask a = c.m[0];
    for (unsigned int r = 1; r < R; ++r)
      a = a && c.m[r];
    return xsimd::all(a);
  }
} // namespace anvil::Simd

#endif
