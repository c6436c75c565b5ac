// Lazy, exact derivation of a box spline (docs/design.md §5) or of its truncated power by
// directional integration, one column at a time, cell by cell.
//
// Level k uses the first k columns. On a cell C of level k+1 the function is
//   F_{k+1}(x) = integral over t of F_k(x - t xi), t in [0, 1] (box spline) or [0, inf) (truncated
//   power).
// At a generic interior point p of C the path p - t xi crosses level-k planes at parameters
// t_j(x) = (nu.x - c)/(nu.xi), affine in x; between crossings F_k is one polynomial P, so
//   F_{k+1}(x) = sum_j (G_{j-1} - G_j)(x, t_j(x)) [+ G_last(x, 1) on a segment],
// with G(x, t) = integral_0^t P(x - s xi) ds. The expression is exact on all of C.
// Cells are memoised by (level, key); the composed jump terms by the pair of cells they join.
// The unit-segment levels are keyed on the true knot planes of their columns (KnotPlanes), so
// the work follows the pieces of each M_k, not the length of the columns.
#pragma once
#include <memory>
#include <unordered_map>
#include <vector>

#include "generator/cell_key.h"
#include "generator/int_linalg.h"
#include "generator/knot_normals.h"
#include "generator/poly.h"

namespace boxgen::generator {

enum class IntegrationPath { UnitSegment, Ray };

class LevelIntegrator {
 public:
  // `columns`: the first n must form a basis. For Ray, all columns must lie in an open half-space.
  LevelIntegrator(IntColumns columns, int n, IntegrationPath path);

  // The top-level polynomial on the cell containing p (p must lie on no plane of the top level).
  const Poly& top(const RatVec& p);
  CellKey top_key(const RatVec& p) const { return key(static_cast<int>(levels_.size()) - 1, p); }
  // The same when the caller has the key of p already (computed in integers, say).
  const Poly& top(const CellKey& key, const RatVec& p);
  const KnotPlanes& top_planes() const { return levels_.back().planes; }

 private:
  struct Cell {
    Poly poly;
    std::vector<Poly>
        integrated;  // G_e: G(x, t) = sum_e t^e G_e(x) along the next level's direction
    bool has_integrated = false;
  };
  struct PairHash {
    std::size_t operator()(const std::pair<CellKey, CellKey>& p) const noexcept {
      return CellKeyHash{}(p.first) * 31u + CellKeyHash{}(p.second);
    }
  };
  struct Level {
    KnotPlanes planes;  // for Ray only the normals count (the arrangement is central)
    std::unordered_map<CellKey, Cell, CellKeyHash> cells;
    std::unordered_map<std::pair<CellKey, CellKey>, Poly, PairHash> jumps;
  };

  CellKey key(int level, const RatVec& p) const;
  Cell& cell(int level, const RatVec& p);
  // The cell with this key; `point` gives a point inside it, called only to derive a new cell.
  template <typename Point>
  Cell& cell(int level, const CellKey& k, Point point) {
    auto& cells = levels_[level].cells;
    if (auto it = cells.find(k); it != cells.end()) return it->second;
    Poly poly = derive(level, point());
    auto [it, inserted] = cells.emplace(k, Cell{});
    it->second.poly = std::move(poly);
    return it->second;
  }
  Poly derive(int level, RatVec p);
  Poly base(const RatVec& p) const;
  const std::vector<Poly>& integrated(int level, Cell& c);
  const Poly& jump(int level, const CellKey& a, Cell& ca, const CellKey& b, Cell& cb,
                   const RatVec& tau);
  RatVec perturbed(int level, const RatVec& p, int attempt) const;

  int n_;
  IntColumns columns_;
  IntegrationPath path_;
  std::vector<Level> levels_;  // levels_[i] has n + i columns
  RatMatrix basis_inverse_;
  Rational base_value_;
};

}  // namespace boxgen::generator
