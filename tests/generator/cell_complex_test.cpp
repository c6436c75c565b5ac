// The fine cell complex on unit squares cut by diagonals, where the cells are drawn by hand.
#include "generator/cell_complex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "generator/knot_normals.h"
#include "generator/simplex_integral.h"

namespace boxgen {
namespace {

std::set<RatVec> vertex_set(const FineCell& c) { return {c.vertices.begin(), c.vertices.end()}; }

TEST(CellComplex, OneDiagonalCutsTheSquareIntoTwoTriangles) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}}, 2);
  const auto cells = CellComplex::split_cube(normals, {0, 0});
  ASSERT_EQ(cells.size(), 2u);
  std::set<std::set<RatVec>> got{vertex_set(cells[0]), vertex_set(cells[1])};
  EXPECT_EQ(got, (std::set<std::set<RatVec>>{{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {0, 1}, {1, 1}}}));
  for (const auto& c : cells) EXPECT_TRUE(off_integer_planes(normals, c.interior));
}

TEST(CellComplex, TwoDiagonalsMeetAtTheCentre) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, 2);
  const auto cells = CellComplex::split_cube(normals, {3, -2});
  ASSERT_EQ(cells.size(), 4u);
  Rational area = 0;
  for (const auto& c : cells) {
    EXPECT_EQ(c.vertices.size(), 3u);
    EXPECT_TRUE(vertex_set(c).count({Rational(7) / 2, Rational(-3) / 2})) << "every triangle has the centre";
    area = area + simplex_volume(c.vertices);
  }
  EXPECT_EQ(area, 1);
}

TEST(CellComplex, FindsEveryCellByItsKey) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}}, 2);
  const CellComplex complex(normals, {0, 0}, {2, 2});
  ASSERT_EQ(complex.cells().size(), 8u);  // four squares, two triangles each
  for (std::size_t i = 0; i < complex.cells().size(); ++i)
    EXPECT_EQ(complex.find(complex.cells()[i].key), static_cast<int>(i));
  EXPECT_EQ(complex.find(floor_key(normals, {Rational(5) / 2, Rational(1) / 3})), -1);  // outside
}

TEST(CellComplex, AffineRankAndTriangulation) {
  EXPECT_EQ(affine_rank({{0, 0}}), 0);
  EXPECT_EQ(affine_rank({{0, 0}, {1, 1}, {2, 2}}), 1);
  EXPECT_EQ(affine_rank({{0, 0}, {1, 1}, {2, 3}}), 2);
  const std::vector<RatVec> square{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const std::vector<Plane> sides{{{1, 0}, 0}, {{1, 0}, 1}, {{0, 1}, 0}, {{0, 1}, 1}};
  const auto simplices = triangulate_polytope(square, sides);
  ASSERT_EQ(simplices.size(), 2u);
  EXPECT_EQ(simplex_volume(simplices[0]) + simplex_volume(simplices[1]), 1);
}

}  // namespace
}  // namespace boxgen
