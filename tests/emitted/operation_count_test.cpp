// The costs each header records (kOrbitCosts: additions, multiplications, negations and stencil
// values read, per orbit and path) are what its code executes: every orbit function runs once per
// path with a number type that counts its operations, and the counts must match exactly.
#include <gtest/gtest.h>

#include <set>

#include "emitted/biquadratic.hpp"
#include "emitted/fcc6_bernstein.hpp"
#include "emitted/m12_horner.hpp"
#include "emitted/m7_bernstein.hpp"
#include "emitted/m7_horner.hpp"
#include "emitted/m7_monomial.hpp"
#include "emitted/zp.hpp"
#include "emitted/zp_monomial.hpp"
#include "generated/cart7.hpp"
#include "generated/fcc6.hpp"
#include "generated/m12.hpp"
#include "generated/m7.hpp"
#include "generated/m8.hpp"
#include "generated/tricubic.hpp"

namespace {

// A number that counts the arithmetic done with it. A stencil value remembers its index, so the
// distinct values an evaluation reads are counted too.
struct Tally {
  long adds = 0, muls = 0, negs = 0;
  std::set<int> loads;
};
Tally tally;

struct Counted {
  double value = 0;
  int load = -1;  // k for the stencil value v[k]
  Counted() = default;
  explicit Counted(double v, int k = -1) : value(v), load(k) {}
};

Counted read(const Counted& a) {
  if (a.load >= 0) tally.loads.insert(a.load);
  return Counted(a.value);
}
Counted operator+(const Counted& a, const Counted& b) {
  ++tally.adds;
  return Counted(read(a).value + read(b).value);
}
Counted operator-(const Counted& a, const Counted& b) {
  ++tally.adds;
  return Counted(read(a).value - read(b).value);
}
Counted operator*(const Counted& a, const Counted& b) {
  ++tally.muls;
  return Counted(read(a).value * read(b).value);
}
// No registry filter's code negates (docs/design.md §15), but a header that does must count it.
[[maybe_unused]] Counted operator-(const Counted& a) {
  ++tally.negs;
  return Counted(-read(a).value);
}

template <class Traits, int Order>
void check_path(const long (&costs)[3][5], int orbit, const char* name) {
  tally = {};
  Counted v[Traits::kStencilSize], x[Traits::kDimension], d[Traits::kDimension * 4];
  for (int k = 0; k < Traits::kStencilSize; ++k) v[k] = Counted(k + 1.0, k);
  for (int i = 0; i < Traits::kDimension; ++i) x[i] = Counted(0.25 + i);
  const Counted value = Traits::template orbit<Order>(orbit, v, x, d);
  // A result that is a stencil value itself is read without arithmetic.
  read(value);
  for (const Counted& di : d) read(di);
  const long* expected = costs[Order];
  EXPECT_EQ(tally.adds, expected[0]) << name << " orbit " << orbit << " order " << Order;
  EXPECT_EQ(tally.muls, expected[1]) << name << " orbit " << orbit << " order " << Order;
  EXPECT_EQ(tally.negs, expected[2]) << name << " orbit " << orbit << " order " << Order;
  EXPECT_EQ(static_cast<long>(tally.loads.size()), expected[3])
      << name << " orbit " << orbit << " order " << Order;
}

template <class Traits, class Costs>
void check_header(const Costs& costs, const char* name) {
  for (int o = 0; o < Traits::kOrbitCount; ++o) {
    check_path<Traits, 0>(costs[o], o, name);
    check_path<Traits, 1>(costs[o], o, name);
    check_path<Traits, 2>(costs[o], o, name);
  }
}

#define BOXGEN_COUNT_TEST(NS)                                                             \
  TEST(EmittedOperationCounts, NS) {                                                      \
    check_header<boxgen::generated::NS::Traits>(boxgen::generated::NS::kOrbitCosts, #NS); \
  }

BOXGEN_COUNT_TEST(m7)
BOXGEN_COUNT_TEST(m8)
BOXGEN_COUNT_TEST(m12)
BOXGEN_COUNT_TEST(fcc6)
BOXGEN_COUNT_TEST(tricubic)
BOXGEN_COUNT_TEST(cart7)
BOXGEN_COUNT_TEST(m7_horner)
BOXGEN_COUNT_TEST(m7_bernstein)
BOXGEN_COUNT_TEST(m7_monomial)
BOXGEN_COUNT_TEST(m12_horner)
BOXGEN_COUNT_TEST(fcc6_bernstein)
BOXGEN_COUNT_TEST(zp)
BOXGEN_COUNT_TEST(zp_monomial)
BOXGEN_COUNT_TEST(biquadratic)

// The costliest orbit's value + gradient + Hessian is the header's kHessianOperations.
TEST(EmittedOperationCounts, SummaryIsTheCostliestOrbit) {
  const auto& c = boxgen::generated::fcc6::kOrbitCosts;
  const long worst = std::max(c[0][2][0] + c[0][2][1], c[1][2][0] + c[1][2][1]);
  EXPECT_EQ(boxgen::generated::fcc6::kHessianOperations, worst);
}

}  // namespace
