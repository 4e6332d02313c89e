#pragma once
// Slices for printers that take layers: each layer a bitmap (and its contours), computed from the elements that
// cross that layer, not by a point query per pixel.
//
// An element meets the layer's plane in a convex region (a ball in a disk, a beam, the convex hull of its two end
// balls, in a region bounded by circle and conic arcs). Along each pixel row that region is one interval, found in
// closed form: the row's line against the two end balls and against the beam's cone between its tangent planes
// (a quadratic inequality), united. The pixels whose centers fall in the interval are set. Elements are sorted by
// their lowest point, so each layer visits only those that reach it.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "steady/core/progress.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

struct SliceOptions {
  double layer_height = 0.05;  // model units, > 0; layer k is the plane z = box_min.z + (k + 1/2) layer_height
  double pixel_size = 0.05;    // model units, > 0; pixel (i, j) has its center at box_min + ((i, j) + 1/2) pixel
  // The region sliced: the lattice's bounding box grown by one pixel when left empty (min > max).
  Vec3 box_min{1.0}, box_max{0.0};
};

class LatticeSlicer {
 public:
  // InvalidInput naming "layer_height", "pixel_size" or "box" for values that are not finite and positive, or a
  // box that is empty; ResourceLimit for a layer bitmap beyond the memory budget.
  LatticeSlicer(const FlatLattice& lattice, const SliceOptions& options);

  std::int64_t layer_count() const { return layers_; }
  std::int64_t width() const { return width_; }
  std::int64_t height() const { return height_; }
  double layer_z(std::int64_t layer) const;
  const Vec3& origin() const { return min_; }

  // Layer k as width x height bytes, row after row from the box's lowest y (1: inside the lattice, 0: outside).
  // Returns how many elements met the layer.
  std::int64_t rasterize(std::int64_t layer, std::vector<std::uint8_t>& pixels) const;

  // The layer's cross-sections as SVG: a circle per ball, a polygon per beam through the exact ends of its
  // interval on every pixel row (the union of the filled shapes is the layer).
  std::string svg(std::int64_t layer) const;

 private:
  struct Element {
    double z_min, z_max;
    std::int64_t index;  // ball index, or ball_count + beam index
  };
  void elements_at(double z, std::vector<const Element*>& out) const;

  const FlatLattice& lattice_;
  Vec3 min_{0.0};
  double layer_height_ = 0.0, pixel_ = 0.0;
  std::int64_t width_ = 0, height_ = 0, layers_ = 0;
  std::vector<Element> elements_;  // sorted by z_min
  double tallest_ = 0.0;           // largest z_max - z_min
};

struct SliceStats {
  std::int64_t layers = 0, width = 0, height = 0;
  std::int64_t element_layers = 0;  // (element, layer) pairs rasterised
  double raster_seconds = 0.0;      // computing the bitmaps
  double write_seconds = 0.0;       // encoding and writing the files
};

// Writes every layer into `directory` (which must exist) as layer_00000.png, ... (1-bit grayscale PNG, white =
// solid) and, with svg, layer_00000.svg too; files are written beside their names and renamed when complete, and
// an error or a cancel removes the layers already written (a stack is complete or absent).
SliceStats write_slices(const FlatLattice& lattice, const SliceOptions& options, const std::string& directory,
                        bool svg = false, Progress& progress = no_progress());

// One bitmap as a 1-bit grayscale PNG (zlib), rows from the top of the image: row 0 of the file is the bitmap's
// last row, so that +y points up in the picture as in the model.
void write_png(const std::string& path, const std::vector<std::uint8_t>& pixels, std::int64_t width, std::int64_t height);

}  // namespace steady
