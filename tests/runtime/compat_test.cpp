// The old names of runtime/compat.h still compile and mean what they meant: each is the one API
// under another name (docs/runtime.md maps them). Oracle: the same computation through the new
// names, which must agree exactly.
#include "runtime/compat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "generated/m7.hpp"
#include "runtime/test_functions.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::runtime {
namespace {

TEST(Compat, FilterIsTheRegistrysBccFilters) {
  EXPECT_EQ(SplineFilter(Filter::M7), SplineFilter::parse("m7"));
  EXPECT_EQ(SplineFilter(Filter::M12).name(), "m12");
  EXPECT_EQ(parse_filter("m8"), Filter::M8);
  EXPECT_STREQ(filter_name(Filter::M8), "m8");
  EXPECT_THROW((void)parse_filter("fcc6"), std::invalid_argument);
  for (const Filter f : {Filter::M7, Filter::M8, Filter::M12})
    for (const PrefilterChoice q :
         {PrefilterChoice::None, PrefilterChoice::Q1, PrefilterChoice::Q2}) {
      EXPECT_EQ(required_margin(f, q), SplineFilter(f).required_margin(q));
      EXPECT_EQ(prefilter_taps(f, q), SplineFilter(f).prefilter(q));
    }
  EXPECT_EQ(stencil_reach(Filter::M7).hi, SplineFilter::parse("m7").reach().hi);
}

TEST(Compat, BccVolumeCodeRunsOnTheOneApi) {
  const BccVolume<double> samples =
      sample_cube<double>(cubic, 9, required_margin(Filter::M7, PrefilterChoice::Q1));
  const BccVolume<double> volume =
      prefilter(samples, prefilter_taps(Filter::M7, PrefilterChoice::Q1));
  const Reconstructor<double> old_way(volume, Filter::M7);
  const SplineFilter m7 = SplineFilter::parse("m7");
  LatticeVolume<double> v = sample_lattice<double>(
      cubic, cube_lattice_grid(CosetLattice::bcc(), 9, m7.required_margin(PrefilterChoice::Q1)));
  v = prefilter(v, m7.prefilter(PrefilterChoice::Q1));
  ASSERT_EQ(v.sample_count(), volume.sample_count());
  EXPECT_TRUE(std::equal(v.samples().begin(), v.samples().end(), volume.samples().begin()));
  const Reconstructor<double> new_way(v, m7);
  const LatticeReconstructor<generated::m7::Traits, double> emitted(v);
  for (const Vec3& p : {Vec3{0.1, -0.2, 0.3}, Vec3{-0.7, 0.65, 0.9}}) {
    EXPECT_EQ(old_way.value(p), new_way.value(p));
    EXPECT_EQ(emitted.value(p), new_way.value(p));
  }
  EXPECT_TRUE(BccVolume<double>::is_lattice_point(1, -1, 3));
  EXPECT_FALSE(BccVolume<double>::is_lattice_point(1, 0, 3));
  const BccGrid grid = cube_grid(5, 2);
  EXPECT_EQ(grid.h, 0.25);
  EXPECT_EQ(prefilter_margin(prefilter_taps(Filter::M7, PrefilterChoice::Q2)), 1);
}

TEST(Compat, BccVolumesConvertWithoutChange) {
  BccVolume<float> bcc({3, 2, 2}, 0.25, {1, 2, 3});
  for (std::size_t s = 0; s < bcc.sample_count(); ++s)
    bcc.samples()[s] = static_cast<float>(s) * 0.5f;
  const BccVolume<float> copy = bcc;
  LatticeVolume<float> l = to_lattice_volume(std::move(bcc));
  EXPECT_EQ(l.lattice(), CosetLattice::bcc());
  const BccVolume<float> back = to_bcc_volume(std::move(l));
  EXPECT_TRUE(std::equal(back.samples().begin(), back.samples().end(), copy.samples().begin(),
                         copy.samples().end()));
  EXPECT_EQ(back.origin(), copy.origin());
  EXPECT_THROW(
      (void)to_bcc_volume(LatticeVolume<float>(CosetLattice::fcc(), {1, 1, 1}, 1, {0, 0, 0})),
      std::invalid_argument);
}

class CompatNrrd : public test::ScratchDirectoryTest {
 protected:
  CompatNrrd() : ScratchDirectoryTest("boxgen-compat") {}
};

TEST_F(CompatNrrd, BccFilesReadAndWriteAsBefore) {
  const BccVolume<double> v = sample_cube<double>(cubic, 4, 1);
  write_bcc_nrrd(dir_ / "v.nrrd", v);
  const BccVolume<double> back = read_bcc_nrrd<double>(dir_ / "v.nrrd");
  EXPECT_EQ(std::memcmp(back.samples().data(), v.samples().data(), v.samples().size_bytes()), 0);
  write_lattice_nrrd(dir_ / "f.nrrd",
                     LatticeVolume<double>(CosetLattice::fcc(), {2, 2, 2}, 1, {0, 0, 0}));
  EXPECT_THROW((void)read_bcc_nrrd<double>(dir_ / "f.nrrd"), NrrdError);
}

}  // namespace
}  // namespace boxgen::runtime
