// Slices against their slow, obviously right twin: point membership at every pixel center (the RangeFinder's
// contains, itself tested against brute force). They must agree on every pixel of every layer, for balls, beams
// of every taper, the hull model and crowded hubs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "sample_lattices.hpp"
#include "test_lattices.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/slices.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/query/queries.hpp"

namespace steady {
namespace {

namespace fs = std::filesystem;

// Pixels where the slice and contains() disagree, over `layers` layers spread over the height.
std::int64_t disagreements(const Lattice& lattice, double pixel, int layers, std::int64_t* inked = nullptr) {
  const FlatLattice f = flatten(lattice);
  SliceOptions options;
  options.pixel_size = pixel;
  options.layer_height = pixel;
  const LatticeSlicer slicer(f, options);
  const LatticeQuery query(lattice);
  const LatticeSource source(query);
  std::int64_t differ = 0;
  for (int l = 0; l < layers; ++l) {
    const std::int64_t k = (2 * l + 1) * slicer.layer_count() / (2 * layers);
    std::vector<std::uint8_t> pixels;
    slicer.rasterize(k, pixels);
    std::vector<double> points;
    for (std::int64_t j = 0; j < slicer.height(); ++j)
      for (std::int64_t i = 0; i < slicer.width(); ++i)
        points.insert(points.end(), {slicer.origin().x + (i + 0.5) * pixel, slicer.origin().y + (j + 0.5) * pixel,
                                     slicer.layer_z(k)});
    std::vector<std::uint8_t> inside(pixels.size());
    contains(source, points.data(), inside.size(), inside.data());
    for (std::size_t p = 0; p < pixels.size(); ++p) {
      differ += (pixels[p] != 0) != (inside[p] != 0);
      if (inked) *inked += pixels[p];
    }
  }
  return differ;
}

TEST(Slices, AgreeWithPointMembershipOnEveryPixel) {
  std::int64_t inked = 0;
  for (const std::string& name : preset_names()) {
    for (double beam : {0.0, 0.1, 0.24}) {
      SCOPED_TRACE(name + " beam " + std::to_string(beam));
      EXPECT_EQ(disagreements(preset_lattice(name, {2, 2, 2}, 2.0, 0.3, beam), 0.02, 5, &inked), 0);
    }
  }
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 4; ++trial) {  // tapered beams, steps of every kind
    SCOPED_TRACE("strut " + std::to_string(trial));
    EXPECT_EQ(disagreements(test::strut_lattice(rng, test::StepKind(trial), {3, 3, 2}, 0.25), 0.01, 4, &inked), 0);
  }
  EXPECT_GT(inked, 100000);  // the layers are not empty
}

TEST(Slices, PngAndSvgFilesForEveryLayer) {
  const FlatLattice f = flatten(preset_lattice("octet", {1, 1, 1}, 2.0, 0.3, 0.2));
  const fs::path dir = fs::temp_directory_path() / "steady_slices";
  fs::remove_all(dir);
  fs::create_directories(dir);
  SliceOptions options;
  options.layer_height = 0.1;
  options.pixel_size = 0.02;
  const SliceStats stats = write_slices(f, options, dir.string(), true);
  EXPECT_GT(stats.layers, 20);
  std::int64_t png = 0, svg = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    png += e.path().extension() == ".png";
    svg += e.path().extension() == ".svg";
    EXPECT_NE(e.path().extension(), ".partial");
  }
  EXPECT_EQ(png, stats.layers);
  EXPECT_EQ(svg, stats.layers);
  // Every SVG is well-formed XML (xmllint, an independent parser).
  EXPECT_EQ(std::system(("xmllint --noout " + (dir / "layer_00010.svg").string()).c_str()), 0);
  std::ifstream in(dir / "layer_00010.png", std::ios::binary);
  char signature[8];
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  fs::remove_all(dir);
}

TEST(Slices, BadInputNamesTheParameter) {
  const FlatLattice f = flatten(preset_lattice("cubic", {1, 1, 1}, 2.0, 0.3, 0.1));
  for (double bad : {0.0, -1.0, std::nan("")}) {
    SliceOptions a;
    a.layer_height = bad;
    EXPECT_THROW(LatticeSlicer(f, a), InvalidInput);
    SliceOptions b;
    b.pixel_size = bad;
    EXPECT_THROW(LatticeSlicer(f, b), InvalidInput);
  }
  SliceOptions tiny;
  tiny.pixel_size = 1e-9;
  EXPECT_THROW(LatticeSlicer(f, tiny), ResourceLimit);
  EXPECT_THROW(write_slices(f, {}, "/no/such/directory"), InvalidInput);
}

}  // namespace
}  // namespace steady
