// Exact conversion between the generator's dense polynomials (poly.h, CLN rationals) and GiNaC
// expressions (docs/design.md §12). GiNaC's numbers are CLN numbers, so nothing is rounded in
// either direction; the hot loops stay on Poly and GiNaC is used at the edges, for printing.
#pragma once
#include <ginac/ginac.h>

#include <vector>

#include "generator/poly.h"

namespace boxgen::generator {

// The coordinate symbols x, y (and z): one set per process, so that expressions built by
// different callers compare and parse against the same symbols.
const std::vector<GiNaC::symbol>& coordinate_symbols(int n);

GiNaC::numeric to_numeric(const Rational& r);
// Throws InputError unless the number is rational.
Rational to_rational(const GiNaC::numeric& n);

// sum over the monomials of p of coefficient * x^a y^b z^c, in the given symbols.
GiNaC::ex to_ex(const Poly& p, const std::vector<GiNaC::symbol>& vars);
GiNaC::ex to_ex(const Poly& p);  // in coordinate_symbols(p.vars())
// The polynomial of an expression in `vars` with rational coefficients (expanded first).
// Throws InputError if it is not one: another symbol, a non-rational number, a negative power.
Poly to_poly(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& vars);

}  // namespace boxgen::generator
