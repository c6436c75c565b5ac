// The fine cell complex on unit squares cut by diagonals, where the cells are drawn by hand.
#include "generator/cell_complex.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "generator/knot_normals.h"
#include "generator/simplex_integral.h"

namespace boxgen::generator {
namespace {

std::set<RatVec> vertex_set(const FineCell& c) { return {c.vertices.begin(), c.vertices.end()}; }

TEST(CellComplex, OneDiagonalCutsTheSquareIntoTwoTriangles) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}}, 2);
  const auto cells = split_cube(normals, {0, 0});
  ASSERT_EQ(cells.size(), 2u);
  std::set<std::set<RatVec>> got{vertex_set(cells[0]), vertex_set(cells[1])};
  EXPECT_EQ(got, (std::set<std::set<RatVec>>{{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {0, 1}, {1, 1}}}));
  for (const auto& c : cells) EXPECT_TRUE(off_integer_planes(normals, c.interior));
}

TEST(CellComplex, TwoDiagonalsMeetAtTheCentre) {
  const auto normals = arrangement_normals({{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, 2);
  const auto cells = split_cube(normals, {3, -2});
  ASSERT_EQ(cells.size(), 4u);
  Rational area = 0;
  for (const auto& c : cells) {
    EXPECT_EQ(c.vertices.size(), 3u);
    EXPECT_TRUE(vertex_set(c).count({Rational(7) / 2, Rational(-3) / 2}))
        << "every triangle has the centre";
    area = area + simplex_volume(c.vertices);
  }
  EXPECT_EQ(area, 1);
}

TEST(KnotComplexCells, FindsEveryCellByItsKeyAndTilesTheHexagon) {
  // The hat function's directions (1,0), (0,1), (1,1): its support is the hexagon of area
  // |det(e1,e2)| + |det(e1,d)| + |det(e2,d)| = 3, cut by x = 1, y = 1 and x = y.
  const KnotComplex complex(knot_planes({{1, 0}, {0, 1}, {1, 1}}, 2), {0, 0}, {2, 2});
  Rational area = 0;
  for (std::size_t i = 0; i < complex.cells().size(); ++i) {
    EXPECT_EQ(complex.find(complex.cells()[i].key), static_cast<int>(i));
    for (const auto& simplex : triangulate(complex.cells()[i], complex))
      area = area + simplex_volume(simplex);
  }
  EXPECT_EQ(complex.cells().size(), 6u);
  EXPECT_EQ(area, 3);
  EXPECT_EQ(complex.locate({Rational(19) / 10, Rational(1) / 10}),
            -1);  // in the box, outside the hexagon
  EXPECT_GE(complex.locate({Rational(1) / 3, Rational(1) / 7}), 0);
}

// split_cubes translates the cells of one cube: the same cells, keys, vertices and interior
// points, in the same order, as splitting every cube (2-D with long normals, and 3-D).
TEST(CellComplex, SplitCubesEqualsSplittingEachCube) {
  for (const auto& [columns, n] :
       {std::make_pair(IntColumns{{20, 1}, {1, 20}, {7, 5}, {-9, 4}}, 2),
        std::make_pair(IntColumns{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, 0, 0}},
                       3)}) {
    const auto normals = arrangement_normals(columns, n);
    const std::vector<IntVec> corners =
        n == 2 ? std::vector<IntVec>{{0, 0}, {3, -2}, {-7, 11}}
               : std::vector<IntVec>{{0, 0, 0}, {1, -1, 2}, {-3, 0, 5}};
    std::vector<FineCell> each;
    for (const auto& c : corners)
      for (auto& cell : split_cube(normals, c)) each.push_back(std::move(cell));
    const std::vector<FineCell> translated = split_cubes(normals, corners);
    ASSERT_EQ(translated.size(), each.size());
    for (size_t i = 0; i < each.size(); ++i) {
      EXPECT_EQ(translated[i].key, each[i].key) << i;
      EXPECT_EQ(translated[i].vertices, each[i].vertices) << i;
      EXPECT_EQ(translated[i].interior, each[i].interior) << i;
    }
  }
  EXPECT_TRUE(split_cubes(arrangement_normals({{1, 0}, {0, 1}}, 2), {}).empty());
}

TEST(CellComplex, AffineRankAndTriangulation) {
  EXPECT_EQ(affine_rank({{0, 0}}), 0);
  EXPECT_EQ(affine_rank({{0, 0}, {1, 1}, {2, 2}}), 1);
  EXPECT_EQ(affine_rank({{0, 0}, {1, 1}, {2, 3}}), 2);
  EXPECT_EQ(affine_rank({{0, 0}, {0, 0}, {2, 3}}), 1);  // a repeated first point
  // 3-D: the first points repeated or collinear, then the plane, then a point off it.
  const Rational h = Rational(1) / 2;
  EXPECT_EQ(affine_rank({{1, 1, 1}, {1, 1, 1}}), 0);
  EXPECT_EQ(affine_rank({{0, 0, 0}, {h, h, h}, {2, 2, 2}}), 1);
  EXPECT_EQ(affine_rank({{0, 0, 0}, {1, 2, 3}, {2, 4, 6}, {1, 0, 0}, {2, 2, 3}}), 2);
  EXPECT_EQ(affine_rank({{0, 0, 0}, {1, 2, 3}, {2, 4, 6}, {1, 0, 0}, {2, 2, 3}, {0, 0, h}}), 3);
  EXPECT_EQ(affine_rank({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), 2);
  // More than three coordinates take row elimination.
  EXPECT_EQ(affine_rank({{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}}), 2);
  EXPECT_EQ(affine_rank({{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 1}}), 3);
  const std::vector<RatVec> square{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const std::vector<Plane> sides{{{1, 0}, 0}, {{1, 0}, 1}, {{0, 1}, 0}, {{0, 1}, 1}};
  const auto simplices = triangulate_polytope(square, sides);
  ASSERT_EQ(simplices.size(), 2u);
  EXPECT_EQ(simplex_volume(simplices[0]) + simplex_volume(simplices[1]), 1);
}

}  // namespace
}  // namespace boxgen::generator
