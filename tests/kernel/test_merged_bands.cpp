// Thin bands of cone merged into their stumps (brep/merged_bands.hpp), and the trim's retry that clips a cluster
// so: the crowded sweep's BCC at beam/node 1.0 (3 x 3 x 3 cells, nodes 0.35 of the neighbour distance) in a
// cylinder of radius 1.05 without a skin, whose one boundary cluster's Common came out empty in every layout,
// turned frame and fuzzy value, and the trim was refused (docs/brep.md, section 3).
#include <BRepAdaptor_Surface.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "brep/merged_bands.hpp"
#include "lattice_membership.hpp"
#include "lattice_test_shapes.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {
namespace {

FlatLattice dense_bcc() { return flatten(Lattice(test::preset_brick("BCC", 0.35, 1.0, {3, 3, 3}))); }

bool on_beam_surface(const TopoDS_Face& face) {
  const GeomAbs_SurfaceType type = BRepAdaptor_Surface(face, Standard_False).GetType();
  return type == GeomAbs_Cone || type == GeomAbs_Cylinder;
}

std::vector<TopoDS_Face> faces_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) faces.push_back(TopoDS::Face(x.Current()));
  return faces;
}

TEST(MergedBands, BandsMergeIntoTheirStumpsAndEveryOtherFaceStaysTheSame) {
  const TopoDS_Shape lattice = build_lattice_brep(dense_bcc()).shape;
  const std::vector<TopoDS_Face> before = faces_of(lattice);
  const MergedBands merged = merge_bands_into_stumps(before);
  // Every beam between two tight collars has one or two bands (a joint ring between them).
  EXPECT_GT(merged.merged, 50);
  EXPECT_EQ(merged.faces.size() + static_cast<std::size_t>(merged.merged), before.size());
  std::unordered_set<const void*> kept;
  for (const TopoDS_Face& face : merged.faces) kept.insert(face.TShape().get());
  for (const TopoDS_Face& face : before)
    if (!on_beam_surface(face)) EXPECT_TRUE(kept.count(face.TShape().get())) << "a sphere or disk face was rebuilt";
  const TopoDS_Shape solid = solids_from_faces(merged.faces);
  EXPECT_TRUE(is_valid(solid));
  EXPECT_NEAR(shape_volume(solid) / shape_volume(lattice), 1.0, 1e-12);
  // No band is left where a stump could take it, so a second pass merges nothing.
  EXPECT_EQ(merge_bands_into_stumps(merged.faces).merged, 0);
}

TEST(MergedBands, ACylinderAcrossThinBandsClipsTheClusterWithItsBandsMerged) {
  const FlatLattice f = dense_bcc();
  const double radius = 1.05, height = 4.5;
  const Vec3 base(1.25, 1.25, -1.0);
  const TopoDS_Shape body =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(base.x, base.y, base.z), gp_Dir(0, 0, 1)), radius, height).Shape();
  const TrimResult r = trim_lattice(f, body, TrimOptions{});
  EXPECT_TRUE(is_valid(r.part));
  EXPECT_EQ(r.stats.merged_clusters, 1);
  // The lattice lies within heights -0.5 and 3.5.
  const test::SampledVolume sampled =
      test::volume_in_upright_cylinder(f, base.x, base.y, radius, -0.5, 3.5, 200000, 3);
  EXPECT_NEAR(shape_volume(r.part), sampled.volume, 4 * sampled.sigma);
  std::printf("[ report ] BCC at beam/node 1.0 in the cylinder: volume %.5f, Monte Carlo %.5f +- %.5f; %lld "
              "clusters retried, %lld with their bands merged\n",
              shape_volume(r.part), sampled.volume, sampled.sigma, (long long)r.stats.retried_clusters,
              (long long)r.stats.merged_clusters);
}

}  // namespace
}  // namespace steady
