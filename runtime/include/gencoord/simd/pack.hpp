// SPDX-License-Identifier: BSD-3-Clause
// Pack<N>: N doubles that every arithmetic operation treats at once, a Scalar for the
// generated kernels (straight-line code templated on Scalar), so that one call evaluates N
// states, one per lane.
//
// The lanes are a GCC/Clang vector (vector_size), which the compiler maps onto the widest
// registers the target has: N = 4 is one AVX2 register where the build enables AVX2
// (-mavx2, or -march=native on such a machine), two SSE2 registers otherwise. +, -, *, / are
// IEEE operations lane by lane, as in scalar code. sin, cos, exp, log and (glibc 2.35 on) tanh
// come from glibc's vector math library (libmvec: 4 lanes per AVX2 call, 2 per SSE call;
// within 4 ulp of the correctly rounded result, as its manual states), elsewhere lane by lane
// from std::; sqrt, abs and the other functions lane by lane (the compiler vectorizes sqrt and
// abs).
// Users link libmvec (-lmvec) where GENCOORD_HAVE_LIBMVEC is 1; cmake/simd.cmake does it.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include <Eigen/Core>

#if defined(__x86_64__) && defined(__GLIBC__) && !defined(GENCOORD_NO_LIBMVEC)
#include <immintrin.h>
#define GENCOORD_HAVE_LIBMVEC 1
// libmvec's 2-lane (SSE) and 4-lane (AVX2) variants of FUNCTION
#if defined(__AVX2__)
#define GENCOORD_LIBMVEC_DECLARE(FUNCTION) \
  __m128d _ZGVbN2v_##FUNCTION(__m128d);    \
  __m256d _ZGVdN4v_##FUNCTION(__m256d);
#else
#define GENCOORD_LIBMVEC_DECLARE(FUNCTION) __m128d _ZGVbN2v_##FUNCTION(__m128d);
#endif
extern "C" {
GENCOORD_LIBMVEC_DECLARE(sin)
GENCOORD_LIBMVEC_DECLARE(cos)
GENCOORD_LIBMVEC_DECLARE(exp)
GENCOORD_LIBMVEC_DECLARE(log)
#if __GLIBC_PREREQ(2, 35)  // the release that added tanh to libmvec
#define GENCOORD_HAVE_LIBMVEC_TANH 1
GENCOORD_LIBMVEC_DECLARE(tanh)
#endif
}
#undef GENCOORD_LIBMVEC_DECLARE
#else
#define GENCOORD_HAVE_LIBMVEC 0
#endif
#ifndef GENCOORD_HAVE_LIBMVEC_TANH
#define GENCOORD_HAVE_LIBMVEC_TANH 0
#endif

namespace gencoord {

/// The lanes a batch uses by default: 4 (one AVX2 register, or two SSE2 ones).
inline constexpr int kSimdLanes = 4;

namespace detail {
// the vector type of N doubles (an attribute on a dependent alias would be dropped)
template <int N>
struct LaneVector;
template <>
struct LaneVector<2> {
  typedef double type __attribute__((vector_size(16)));
};
template <>
struct LaneVector<4> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct LaneVector<8> {
  typedef double type __attribute__((vector_size(64)));
};
}  // namespace detail

/// N doubles, one per lane. A comparison holds when it holds in every lane: the generated
/// LDL^T's `if (!(d > 0)) return false` then gives up on the whole pack when one lane's pivot
/// is not positive, and batch_qddot_simd() computes each lane again by the scalar path.
template <int N>
struct Pack {
  static_assert(N == 2 || N == 4 || N == 8, "gencoord: Pack<N> takes N = 2, 4 or 8 lanes");
  using Lanes = typename detail::LaneVector<N>::type;
  Lanes lanes;

  Pack() = default;
  Pack(double x) : lanes(x - Lanes{}) {}  // NOLINT: every lane x, as Scalar(x) reads
  explicit Pack(Lanes l) : lanes(l) {}

  /// The pack of values[0 .. N - 1].
  static Pack load(const double* values) {
    Pack p;
    std::memcpy(&p.lanes, values, sizeof p.lanes);
    return p;
  }
  /// The pack whose lane k is lane(k).
  template <class Lane>
  static Pack generate(const Lane& lane) {
    double values[N];
    for (int k = 0; k < N; ++k) values[k] = lane(k);
    return load(values);
  }

  double operator[](int k) const { return lanes[k]; }

  Pack& operator+=(const Pack& b) { return lanes += b.lanes, *this; }
  Pack& operator-=(const Pack& b) { return lanes -= b.lanes, *this; }
  Pack& operator*=(const Pack& b) { return lanes *= b.lanes, *this; }
  Pack& operator/=(const Pack& b) { return lanes /= b.lanes, *this; }
  Pack operator-() const { return Pack(-lanes); }
  Pack operator+() const { return *this; }
  friend Pack operator+(Pack a, const Pack& b) { return a += b; }
  friend Pack operator-(Pack a, const Pack& b) { return a -= b; }
  friend Pack operator*(Pack a, const Pack& b) { return a *= b; }
  friend Pack operator/(Pack a, const Pack& b) { return a /= b; }

  friend bool operator<(const Pack& a, const Pack& b) { return all(a.lanes < b.lanes); }
  friend bool operator>(const Pack& a, const Pack& b) { return all(a.lanes > b.lanes); }
  friend bool operator<=(const Pack& a, const Pack& b) { return all(a.lanes <= b.lanes); }
  friend bool operator>=(const Pack& a, const Pack& b) { return all(a.lanes >= b.lanes); }
  friend bool operator==(const Pack& a, const Pack& b) { return all(a.lanes == b.lanes); }
  friend bool operator!=(const Pack& a, const Pack& b) { return !(a == b); }

 private:
  // a lane comparison's result: -1 (all bits set) where it holds, 0 elsewhere
  template <class Mask>
  static bool all(const Mask& mask) {
    for (int k = 0; k < N; ++k)
      if (!mask[k]) return false;
    return true;
  }
};

namespace detail {

template <int N, class F>
Pack<N> lane_by_lane(const Pack<N>& x, F f) {
  return Pack<N>::generate([&](int k) { return f(x.lanes[k]); });
}

#if GENCOORD_HAVE_LIBMVEC
// a function of every lane through libmvec, `Two` and `Four` its 2- and 4-lane variants
template <int N, class Two, class Four>
Pack<N> vector_math(const Pack<N>& x, Two two, [[maybe_unused]] Four four) {
  Pack<N> out;
#if defined(__AVX2__)
  if constexpr (N % 4 == 0) {
    for (int k = 0; k < N; k += 4) {
      const __m256d r = four(_mm256_loadu_pd(reinterpret_cast<const double*>(&x.lanes) + k));
      _mm256_storeu_pd(reinterpret_cast<double*>(&out.lanes) + k, r);
    }
    return out;
  }
#endif
  for (int k = 0; k < N; k += 2) {
    const __m128d r = two(_mm_loadu_pd(reinterpret_cast<const double*>(&x.lanes) + k));
    _mm_storeu_pd(reinterpret_cast<double*>(&out.lanes) + k, r);
  }
  return out;
}
#endif

}  // namespace detail

// FUNCTION of every lane: GENCOORD_PACK_LANE_FUNCTION lane by lane from std::FUNCTION,
// GENCOORD_PACK_VECTOR_FUNCTION through libmvec where it is at hand
#define GENCOORD_PACK_LANE_FUNCTION(FUNCTION)                                  \
  template <int N>                                                             \
  Pack<N> FUNCTION(const Pack<N>& x) {                                         \
    return detail::lane_by_lane(x, [](double a) { return std::FUNCTION(a); }); \
  }
#if GENCOORD_HAVE_LIBMVEC
#if defined(__AVX2__)
#define GENCOORD_LIBMVEC_FOUR_LANES(FUNCTION) _ZGVdN4v_##FUNCTION
#else
#define GENCOORD_LIBMVEC_FOUR_LANES(FUNCTION) nullptr
#endif
#define GENCOORD_PACK_VECTOR_FUNCTION(FUNCTION)                                                \
  template <int N>                                                                             \
  Pack<N> FUNCTION(const Pack<N>& x) {                                                         \
    return detail::vector_math(x, _ZGVbN2v_##FUNCTION, GENCOORD_LIBMVEC_FOUR_LANES(FUNCTION)); \
  }
#else
#define GENCOORD_PACK_VECTOR_FUNCTION(FUNCTION) GENCOORD_PACK_LANE_FUNCTION(FUNCTION)
#endif

GENCOORD_PACK_VECTOR_FUNCTION(sin)
GENCOORD_PACK_VECTOR_FUNCTION(cos)
GENCOORD_PACK_VECTOR_FUNCTION(exp)
GENCOORD_PACK_VECTOR_FUNCTION(log)
#if GENCOORD_HAVE_LIBMVEC_TANH
GENCOORD_PACK_VECTOR_FUNCTION(tanh)
#else
GENCOORD_PACK_LANE_FUNCTION(tanh)
#endif
#undef GENCOORD_PACK_VECTOR_FUNCTION
#undef GENCOORD_PACK_LANE_FUNCTION
#undef GENCOORD_LIBMVEC_FOUR_LANES

template <int N>
Pack<N> sqrt(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::sqrt(a); });
}

template <int N>
Pack<N> abs(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::abs(a); });
}

// The other functions a generated kernel may call (gencoord/cxx/printer.py's MATH_FUNCTIONS),
// lane by lane.
template <int N>
Pack<N> tan(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::tan(a); });
}
template <int N>
Pack<N> asin(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::asin(a); });
}
template <int N>
Pack<N> acos(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::acos(a); });
}
template <int N>
Pack<N> atan(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::atan(a); });
}
template <int N>
Pack<N> sinh(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::sinh(a); });
}
template <int N>
Pack<N> cosh(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::cosh(a); });
}
template <int N>
Pack<N> cbrt(const Pack<N>& x) {
  return detail::lane_by_lane(x, [](double a) { return std::cbrt(a); });
}
template <int N>
Pack<N> atan2(const Pack<N>& a, const Pack<N>& b) {
  return Pack<N>::generate([&](int k) { return std::atan2(a.lanes[k], b.lanes[k]); });
}
template <int N>
Pack<N> pow(const Pack<N>& a, const Pack<N>& b) {
  return Pack<N>::generate([&](int k) { return std::pow(a.lanes[k], b.lanes[k]); });
}

}  // namespace gencoord

/// A Pack's limits are a double's in every lane (the generated LDL^T fills a failed solve
/// with quiet_NaN()).
template <int N>
class std::numeric_limits<gencoord::Pack<N>> : public std::numeric_limits<double> {
 public:
  static gencoord::Pack<N> quiet_NaN() { return std::numeric_limits<double>::quiet_NaN(); }
  static gencoord::Pack<N> infinity() { return std::numeric_limits<double>::infinity(); }
  static gencoord::Pack<N> epsilon() { return std::numeric_limits<double>::epsilon(); }
  static gencoord::Pack<N> max() { return std::numeric_limits<double>::max(); }
  static gencoord::Pack<N> min() { return std::numeric_limits<double>::min(); }
  static gencoord::Pack<N> lowest() { return std::numeric_limits<double>::lowest(); }
};

namespace Eigen {

/// Eigen's view of a Pack: a real scalar whose operations cost a double's.
template <int N>
struct NumTraits<gencoord::Pack<N>> : NumTraits<double> {
  using Real = gencoord::Pack<N>;
  using NonInteger = gencoord::Pack<N>;
  using Nested = gencoord::Pack<N>;
  using Literal = gencoord::Pack<N>;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 0 };
};

}  // namespace Eigen
