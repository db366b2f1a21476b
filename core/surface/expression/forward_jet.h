// Forward-mode automatic differentiation for typed formulas: a "jet" is a value together with
// its first derivatives (Order >= 1) and second derivatives (Order >= 2) with respect to N
// inputs, and each operation of a formula maps the jets of its operands to the jet of its
// result by the chain rule. Evaluating a formula once on jets gives exact derivatives (to
// rounding) at the cost of a few multiply-adds per operation, where central differences need
// 7 (gradient) to 19 (Hessian) evaluations and lose half the digits.
//
// Second derivatives are symmetric, so only the upper triangle is kept, row by row:
// (0,0) (0,1) .. (0,N-1) (1,1) .. (N-1,N-1); hessian(i, j) reads either triangle.
//
// The operations work in place on the left operand because the formula tape is a stack
// machine: a binary operation replaces the lower of the top two entries.
#pragma once

#include <array>
#include <cmath>
#include <utility>

namespace dynamesh {

// Fixed-size storage for derivatives. Unlike std::array<double, 0> (one byte, copied along),
// the empty case takes no room; its operator[] is never called (the loops over it run zero
// times) but must exist for them to compile. Tag keeps a jet's two empty members distinct
// types, so that both can share the value's address.
template <int Size, int Tag>
struct JetSlots {
  double v[Size];
  double& operator[](int i) { return v[i]; }
  const double& operator[](int i) const { return v[i]; }
  void fill(double x) {
    for (double& d : v) d = x;
  }
  double* begin() { return v; }
  double* end() { return v + Size; }
  const double* begin() const { return v; }
  const double* end() const { return v + Size; }
};

template <int Tag>
struct JetSlots<0, Tag> {
  double& operator[](int) const { __builtin_unreachable(); }
  void fill(double) {}
};

template <int N, int Order>
struct ForwardJet {
  static_assert(N >= 0 && Order >= 0 && Order <= 2);
  static constexpr int kInputs = N;
  static constexpr int kOrder = Order;
  static constexpr int kGrad = Order >= 1 ? N : 0;
  static constexpr int kHess = Order >= 2 ? N * (N + 1) / 2 : 0;

  // No initialisers: the tape's evaluation stack is an uninitialised array of jets, and every
  // entry is written before it is read.
  double value;
  [[no_unique_address]] JetSlots<kGrad, 0> grad;
  [[no_unique_address]] JetSlots<kHess, 1> hess;

  // The setters write in place: building a temporary and copying it onto the stack makes the
  // copy's wide loads wait for the temporary's narrow stores (a store-forwarding stall that
  // cost more than the arithmetic).
  void set_constant(double c) {
    value = c;
    for (int i = 0; i < kGrad; ++i) grad[i] = 0.0;
    for (int k = 0; k < kHess; ++k) hess[k] = 0.0;
  }
  // Input i (i >= N: an input that is not differentiated, such as the time).
  void set_input(double v, int i) {
    value = v;
    for (int k = 0; k < kGrad; ++k) grad[k] = k == i ? 1.0 : 0.0;
    for (int k = 0; k < kHess; ++k) hess[k] = 0.0;
  }
  static ForwardJet constant(double c) {
    ForwardJet j;
    j.set_constant(c);
    return j;
  }

  static constexpr int hessian_index(int i, int j) {
    if (i > j) return hessian_index(j, i);
    return i * N - i * (i - 1) / 2 + (j - i);
  }
  double hessian(int i, int j) const { return hess[hessian_index(i, j)]; }
};

// The layout the tape's stack and its callers rely on: just the doubles.
static_assert(sizeof(ForwardJet<0, 0>) == sizeof(double));
static_assert(sizeof(ForwardJet<3, 1>) == 4 * sizeof(double));
static_assert(sizeof(ForwardJet<3, 2>) == 10 * sizeof(double));

namespace jet {

// The outer-product terms of the second-order chain rule, a_i b_j + b_i a_j, are walked in the
// same upper-triangle order as `hess`: f(k, i, j) for every entry k = (i, j), unrolled at
// compile time (as nested loops the compiler kept the loop overhead, which was most of the
// cost of a jet operation).
template <int N, bool kRow>
constexpr auto upper_indices() {
  std::array<int, N*(N + 1) / 2> index{};
  int k = 0;
  for (int i = 0; i < N; ++i)
    for (int j = i; j < N; ++j) index[k++] = kRow ? i : j;
  return index;
}

template <class J, class F, int... K>
inline void for_upper(F& f, std::integer_sequence<int, K...>) {
  constexpr auto rows = upper_indices<J::kInputs, true>();
  constexpr auto cols = upper_indices<J::kInputs, false>();
  (f(K, rows[K], cols[K]), ...);
}

template <class J, class F>
inline void for_upper(F&& f) {
  for_upper<J>(f, std::make_integer_sequence<int, J::kHess>{});
}

template <class J>
inline void add(J& a, const J& b) {
  a.value += b.value;
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] += b.grad[i];
  for (int k = 0; k < J::kHess; ++k) a.hess[k] += b.hess[k];
}

template <class J>
inline void sub(J& a, const J& b) {
  a.value -= b.value;
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] -= b.grad[i];
  for (int k = 0; k < J::kHess; ++k) a.hess[k] -= b.hess[k];
}

template <class J>
inline void negate(J& a) {
  a.value = -a.value;
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] = -a.grad[i];
  for (int k = 0; k < J::kHess; ++k) a.hess[k] = -a.hess[k];
}

// a *= c for a constant c (derivatives scale; the value is a.value * c as written).
template <class J>
inline void scale(J& a, double c) {
  a.value *= c;
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] *= c;
  for (int k = 0; k < J::kHess; ++k) a.hess[k] *= c;
}

// a /= c for a constant c (the value divided, as written; the derivatives times 1/c).
template <class J>
inline void divide(J& a, double c) {
  const double r = 1.0 / c;
  a.value /= c;
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] *= r;
  for (int k = 0; k < J::kHess; ++k) a.hess[k] *= r;
}

// (ab)'' = a b'' + b a'' + a' b'^T + b' a'^T.
template <class J>
inline void mul(J& a, const J& b) {
  if constexpr (J::kHess > 0)
    for_upper<J>([&](int k, int i, int j) {
      a.hess[k] =
          a.value * b.hess[k] + b.value * a.hess[k] + a.grad[i] * b.grad[j] + b.grad[i] * a.grad[j];
    });
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] = a.value * b.grad[i] + b.value * a.grad[i];
  a.value *= b.value;
}

// q = a / b, from a = q b: q' = (a' - q b') / b, q'' = (a'' - q b'' - q' b'^T - b' q'^T) / b.
// The derivatives multiply by 1/b, computed alongside q rather than after it (the value is
// the quotient itself, as muparser computes it).
template <class J>
inline void div(J& a, const J& b) {
  const double q = a.value / b.value;
  if constexpr (J::kGrad > 0) {
    const double r = 1.0 / b.value;
    for (int i = 0; i < J::kGrad; ++i) a.grad[i] = (a.grad[i] - q * b.grad[i]) * r;
    if constexpr (J::kHess > 0)
      for_upper<J>([&](int k, int i, int j) {
        a.hess[k] = (a.hess[k] - q * b.hess[k] - a.grad[i] * b.grad[j] - b.grad[i] * a.grad[j]) * r;
      });
  }
  a.value = q;
}

// f(a) given f, f' and f'' at a.value: (f o a)' = f' a', (f o a)'' = f' a'' + f'' a' a'^T.
struct Taylor {
  double f0, f1, f2;
};

// Where f' or f'' is infinite (sqrt at 0, asin at 1, x^p with p < 1 at 0) the plain rule gives
// inf * 0 = NaN for every input the argument does not depend on. A zero inner derivative is
// taken to give a zero term instead, which is the limit along the symmetric stencil of central
// differences; and at a point where the argument is stationary (every a' = 0: the tip of the
// cone sqrt(x^2 + y^2), the origin of |x|^0.5 ...) the derivatives are undefined and reported
// as zero, as the compiled sinc scene does at its own cone point.
inline double times_nonzero(double c, double d) {
  return d == 0.0 ? 0.0 : c * d;
}

template <class J>
inline void chain_singular(J& a, const Taylor& t) {
  bool stationary = true;
  for (int i = 0; i < J::kGrad; ++i) stationary = stationary && a.grad[i] == 0.0;
  if (stationary) {
    a.set_constant(t.f0);
    return;
  }
  if constexpr (J::kHess > 0)
    for_upper<J>([&](int k, int i, int j) {
      a.hess[k] = times_nonzero(t.f1, a.hess[k]) + times_nonzero(t.f2, a.grad[i] * a.grad[j]);
    });
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] = times_nonzero(t.f1, a.grad[i]);
  a.value = t.f0;
}

template <class J>
inline void chain(J& a, const Taylor& t) {
  if constexpr (J::kGrad > 0) {
    if (!std::isfinite(t.f1) || (J::kHess > 0 && !std::isfinite(t.f2))) {
      chain_singular(a, t);
      return;
    }
  }
  if constexpr (J::kHess > 0)
    for_upper<J>(
        [&](int k, int i, int j) { a.hess[k] = t.f1 * a.hess[k] + t.f2 * a.grad[i] * a.grad[j]; });
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] *= t.f1;
  a.value = t.f0;
}

// f(a, b) given f and its partial derivatives at (a.value, b.value):
//   f' = fa a' + fb b',
//   f'' = fa a'' + fb b'' + faa a' a'^T + fbb b' b'^T + fab (a' b'^T + b' a'^T).
struct Taylor2 {
  double f, fa, fb, faa, fab, fbb;
};

template <class J>
inline void chain2(J& a, const J& b, const Taylor2& t) {
  if constexpr (J::kHess > 0)
    for_upper<J>([&](int k, int i, int j) {
      a.hess[k] = t.fa * a.hess[k] + t.fb * b.hess[k] + t.faa * a.grad[i] * a.grad[j] +
                  t.fbb * b.grad[i] * b.grad[j] +
                  t.fab * (a.grad[i] * b.grad[j] + b.grad[i] * a.grad[j]);
    });
  for (int i = 0; i < J::kGrad; ++i) a.grad[i] = t.fa * a.grad[i] + t.fb * b.grad[i];
  a.value = t.f;
}

// True when b carries no derivative (a constant, or a formula of undifferentiated inputs).
template <class J>
inline bool is_constant(const J& b) {
  for (int i = 0; i < J::kGrad; ++i)
    if (b.grad[i] != 0.0) return false;
  for (int k = 0; k < J::kHess; ++k)
    if (b.hess[k] != 0.0) return false;
  return true;
}

}  // namespace jet

}  // namespace dynamesh
