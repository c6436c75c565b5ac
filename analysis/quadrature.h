// Quadrature of a smooth function over the Voronoi cell (design.md 9: "integrate over N with a
// high-order rule"). Two independent rules, so each checks the other:
//  - simplex fan: the cell split into simplices with apex 0 over its (triangulated) faces, each
//    mapped from the unit cube by the collapsed (Duffy) map with Gauss-Legendre in every variable;
//  - iterated: Gauss-Legendre in x, then y, then z with the limits of each slice computed from the
//    half-spaces and the slice's vertices as breakpoints, so every 1-D integrand is smooth on each
//    piece (what Matlab's triplequad does adaptively, here with exact breakpoints).
// The integrand psi_hat^2 is entire, so both converge exponentially in the order.
#pragma once
#include <functional>
#include <vector>

#include "analysis/dual_lattice.h"

namespace boxgen::analysis {

using Integrand = std::function<double(const Vec&)>;

// Nodes and weights of the order-k Gauss-Legendre rule on [0, 1].
struct GaussRule {
  std::vector<double> nodes, weights;
};
GaussRule gauss_legendre(int order);

double integrate_simplex_fan(const VoronoiCell& cell, const Integrand& f, int order);
double integrate_iterated(const VoronoiCell& cell, const Integrand& f, int order);

}  // namespace boxgen::analysis
