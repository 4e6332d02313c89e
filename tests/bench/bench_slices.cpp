// Slices of the bent, twisted and tapered 100^3 lattice (3 million beams) at 50 um pixels, against the baseline a
// voxelizer would use: one point-membership query per pixel (the RangeFinder's contains), on the same layers,
// measured in one run. Prints megapixels per second of both, the ratio, and PNG writing apart.
#include <cstdio>
#include <filesystem>
#include <random>

#include <tbb/parallel_for.h>

#include "bench_common.hpp"
#include "bench_lattices.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/mesh/slices.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/query/queries.hpp"

using namespace steady;

int main(int argc, char** argv) {
  const bool long_run = bench::long_run(argc, argv);
  const std::int64_t n = long_run ? 100 : 40;
  const Lattice lattice = bench::bent_twisted_tapered(n);
  const FlatLattice f = flatten(lattice);
  SliceOptions options;
  options.layer_height = 0.05;
  options.pixel_size = 0.05;
  const LatticeSlicer slicer(f, options);
  std::printf("bent, twisted, tapered %lld^3: %lld balls, %lld beams; layers %lld of %lld x %lld pixels (50 um)\n",
              static_cast<long long>(n), static_cast<long long>(f.ball_count()), static_cast<long long>(f.beam_count()),
              static_cast<long long>(slicer.layer_count()), static_cast<long long>(slicer.width()),
              static_cast<long long>(slicer.height()));
  // Layers spread over the height; two threads, one layer each at a time, as write_slices runs them.
  const int sample = 16;
  std::vector<std::int64_t> layers;
  for (int k = 0; k < sample; ++k) layers.push_back((2 * k + 1) * slicer.layer_count() / (2 * sample));
  std::vector<std::vector<std::uint8_t>> images(layers.size());
  std::int64_t element_layers = 0;
  const double ours = bench::seconds_of([&] {
    tbb::parallel_for(std::size_t(0), layers.size(), [&](std::size_t i) { slicer.rasterize(layers[i], images[i]); });
  });
  for (std::size_t i = 0; i < layers.size(); ++i) {
    std::vector<std::uint8_t> tmp;
    element_layers += slicer.rasterize(layers[i], tmp);
  }
  const double megapixels = static_cast<double>(slicer.width() * slicer.height()) * layers.size() / 1e6;
  // Baseline: contains() at every pixel center of a band of rows in the same layers (it is slow: a band suffices
  // for its rate), and every answer compared with the bitmap.
  const LatticeQuery query(lattice);
  const LatticeSource source(query);
  const std::int64_t band = std::min<std::int64_t>(slicer.height(), 40);
  std::vector<double> points;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const double z = slicer.layer_z(layers[i]);
    for (std::int64_t j = slicer.height() / 2; j < slicer.height() / 2 + band; ++j)
      for (std::int64_t x = 0; x < slicer.width(); ++x)
        points.insert(points.end(), {slicer.origin().x + (x + 0.5) * options.pixel_size,
                                     slicer.origin().y + (j + 0.5) * options.pixel_size, z});
  }
  std::vector<std::uint8_t> inside(points.size() / 3);
  const double naive = bench::seconds_of([&] { contains(source, points.data(), inside.size(), inside.data()); });
  std::int64_t differ = 0, k = 0;
  for (std::size_t i = 0; i < layers.size(); ++i)
    for (std::int64_t j = slicer.height() / 2; j < slicer.height() / 2 + band; ++j)
      for (std::int64_t x = 0; x < slicer.width(); ++x, ++k) differ += (images[i][j * slicer.width() + x] != 0) != (inside[k] != 0);
  const double naive_rate = inside.size() / 1e6 / naive;
  std::printf("  slices:      %.1f Mpixel in %.3f s = %.0f Mpixel/s (%lld element-layers)\n", megapixels, ours,
              megapixels / ours, static_cast<long long>(element_layers));
  std::printf("  per pixel:   contains() at %zu pixel centers: %.2f s = %.2f Mpixel/s; %lld of them differ from the "
              "slices\n", inside.size(), naive, naive_rate, static_cast<long long>(differ));
  std::printf("  ratio: %.0fx the point queries\n", (megapixels / ours) / naive_rate);
  // PNG encoding and writing of the same layers.
  const std::string dir = (std::filesystem::temp_directory_path() / "bench_slices").string();
  std::filesystem::create_directories(dir);
  const double png = bench::seconds_of([&] {
    tbb::parallel_for(std::size_t(0), layers.size(), [&](std::size_t i) {
      write_png(dir + "/layer_" + std::to_string(i) + ".png", images[i], slicer.width(), slicer.height());
    });
  });
  std::uintmax_t bytes = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) bytes += e.file_size();
  std::filesystem::remove_all(dir);
  std::printf("  PNG (1 bit): %.3f s for %zu layers, %.0f KB each; slices and PNG together %.0f Mpixel/s\n", png,
              layers.size(), bytes / 1e3 / layers.size(), megapixels / (ours + png));
  if (!long_run) std::printf("  (the 100^3 lattice with --long)\n");
  return differ == 0 ? 0 : 1;
}
