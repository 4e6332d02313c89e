#include "steady/mesh/slices.hpp"

#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/output_file.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Interval {
  double lo = kInfinity, hi = -kInfinity;
  bool empty() const { return !(lo <= hi); }
  void unite(const Interval& o) {
    if (o.empty()) return;
    lo = std::min(lo, o.lo);
    hi = std::max(hi, o.hi);
  }
  Interval clipped(double a, double b) const { return {std::max(lo, a), std::min(hi, b)}; }
};

// The row's line p(s) = (s, y, z) against a ball.
Interval line_ball(const Vec3& c, double r, double y, double z) {
  const double dy = y - c.y, dz = z - c.z, h = r * r - dy * dy - dz * dz;
  if (h < 0.0) return {};
  const double w = std::sqrt(h);
  return {c.x - w, c.x + w};
}

// The row's line against the beam's cone between its two tangent planes, where the cone's radius is positive:
// with q = p - a, axial x = q.u and radial rho^2 = |q|^2 - x^2, the region is x in [ra sin, L + rb sin] and
// rho cos <= ra - x sin, i.e. Q(s) = (ra - x sin)^2 - cos^2 rho^2 >= 0 (a quadratic in s). Inside the slab the
// region is convex, so {Q >= 0} meets it in one interval.
Interval line_cone(const BeamCone& cone, double y, double z) {
  const Vec3 q0 = Vec3(0.0, y, z) - cone.a;
  const Vec3& u = cone.axis;
  const double x0 = glm::dot(q0, u), ux = u.x, sn = cone.sin_phi, cs = cone.cos_phi;
  const double xa = cone.ra * sn, xb = cone.length + cone.rb * sn;
  Interval slab{-kInfinity, kInfinity};
  if (std::abs(ux) > 1e-300) {
    const double s1 = (xa - x0) / ux, s2 = (xb - x0) / ux;
    slab = {std::min(s1, s2), std::max(s1, s2)};
  } else if (x0 < xa || x0 > xb) {
    return {};
  }
  const double k = cone.ra - x0 * sn, kx = -ux * sn, c2 = cs * cs;
  const double A = kx * kx - c2 * (1.0 - ux * ux);
  const double B = 2.0 * (k * kx - c2 * (q0.x - x0 * ux));
  const double C = k * k - c2 * (glm::dot(q0, q0) - x0 * x0);
  const double scale = std::abs(A) + std::abs(B) + std::abs(C);
  if (std::abs(A) <= 1e-14 * scale) {  // linear: B s + C >= 0
    if (std::abs(B) <= 1e-300) return C >= 0.0 ? slab : Interval{};
    const double root = -C / B;
    return (B > 0.0 ? Interval{root, kInfinity} : Interval{-kInfinity, root}).clipped(slab.lo, slab.hi);
  }
  const double disc = B * B - 4.0 * A * C;
  if (disc < 0.0) return A > 0.0 ? slab : Interval{};
  const double sq = std::sqrt(disc);
  // Roots without cancellation.
  const double t = -0.5 * (B + (B >= 0.0 ? sq : -sq));
  double r1 = t / A, r2 = t != 0.0 ? C / t : r1;
  if (r1 > r2) std::swap(r1, r2);
  if (A < 0.0) return Interval{r1, r2}.clipped(slab.lo, slab.hi);
  Interval out;
  out.unite(Interval{-kInfinity, r1}.clipped(slab.lo, slab.hi));
  out.unite(Interval{r2, kInfinity}.clipped(slab.lo, slab.hi));
  return out;
}

std::string g(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void require_length(double v, const char* field) {
  if (!std::isfinite(v) || v <= 0.0) fail_input(field, "must be a finite length > 0 (got " + g(v) + ")");
}

}  // namespace

LatticeSlicer::LatticeSlicer(const FlatLattice& lattice, const SliceOptions& options) : lattice_(lattice) {
  require_length(options.pixel_size, "pixel_size");
  require_length(options.layer_height, "layer_height");
  layer_height_ = options.layer_height;
  pixel_ = options.pixel_size;
  Vec3 lo(kInfinity), hi(-kInfinity);
  const std::int64_t balls = lattice.ball_count();
  elements_.reserve(balls + lattice.beam_count());
  for (std::int64_t i = 0; i < balls; ++i) {
    const Ball& b = lattice.balls[i];
    lo = glm::min(lo, b.center - b.radius);
    hi = glm::max(hi, b.center + b.radius);
    elements_.push_back({b.center.z - b.radius, b.center.z + b.radius, i});
  }
  for (std::int64_t e = 0; e < lattice.beam_count(); ++e) {
    const FlatBeam& b = lattice.beams[e];
    const Vec3 &a = lattice.balls[b.a].center, &c = lattice.balls[b.b].center;
    elements_.push_back({std::min(a.z - b.ra, c.z - b.rb), std::max(a.z + b.ra, c.z + b.rb), balls + e});
  }
  if (options.box_min.x <= options.box_max.x && options.box_min.y <= options.box_max.y &&
      options.box_min.z <= options.box_max.z) {
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(options.box_min[k]) || !std::isfinite(options.box_max[k])) fail_input("box", "must be finite");
    min_ = options.box_min;
    hi = options.box_max;
  } else {
    if (elements_.empty()) fail_input("lattice", "has no balls to slice");
    min_ = lo - pixel_;
    hi = hi + pixel_;
  }
  width_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi.x - min_.x) / pixel_)));
  height_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi.y - min_.y) / pixel_)));
  layers_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi.z - min_.z) / layer_height_)));
  if (static_cast<double>(width_) * static_cast<double>(height_) > 4e9)
    throw ResourceLimit("slices: a layer of " + std::to_string(width_) + " x " + std::to_string(height_) +
                        " pixels is too large: use a larger pixel_size");
  require_memory(static_cast<std::uint64_t>(width_ * height_), "slices: a layer bitmap of " + std::to_string(width_) + " x " +
                 std::to_string(height_) + " pixels", "use a larger pixel_size");
  std::sort(elements_.begin(), elements_.end(), [](const Element& a, const Element& b) { return a.z_min < b.z_min; });
  for (const Element& e : elements_) tallest_ = std::max(tallest_, e.z_max - e.z_min);
}

double LatticeSlicer::layer_z(std::int64_t layer) const { return min_.z + (static_cast<double>(layer) + 0.5) * layer_height_; }

void LatticeSlicer::elements_at(double z, std::vector<const Element*>& out) const {
  out.clear();
  auto first = std::lower_bound(elements_.begin(), elements_.end(), z - tallest_,
                                [](const Element& e, double v) { return e.z_min < v; });
  for (auto it = first; it != elements_.end() && it->z_min <= z; ++it)
    if (it->z_max >= z) out.push_back(&*it);
}

std::int64_t LatticeSlicer::rasterize(std::int64_t layer, std::vector<std::uint8_t>& pixels) const {
  pixels.assign(static_cast<std::size_t>(width_ * height_), 0);
  const double z = layer_z(layer);
  std::vector<const Element*> crossing;
  elements_at(z, crossing);
  const std::int64_t balls = lattice_.ball_count();
  auto fill_row = [&](std::int64_t row, const Interval& span) {
    if (span.empty()) return;
    const std::int64_t i0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil((span.lo - min_.x) / pixel_ - 0.5)));
    const std::int64_t i1 =
        std::min<std::int64_t>(width_ - 1, static_cast<std::int64_t>(std::floor((span.hi - min_.x) / pixel_ - 0.5)));
    if (i1 >= i0) std::fill(pixels.begin() + row * width_ + i0, pixels.begin() + row * width_ + i1 + 1, 1);
  };
  auto rows = [&](double y_lo, double y_hi, auto&& span_at) {
    const std::int64_t j0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil((y_lo - min_.y) / pixel_ - 0.5)));
    const std::int64_t j1 =
        std::min<std::int64_t>(height_ - 1, static_cast<std::int64_t>(std::floor((y_hi - min_.y) / pixel_ - 0.5)));
    for (std::int64_t j = j0; j <= j1; ++j) fill_row(j, span_at(min_.y + (static_cast<double>(j) + 0.5) * pixel_));
  };
  for (const Element* e : crossing) {
    if (e->index < balls) {
      const Ball& b = lattice_.balls[e->index];
      const double rho = std::sqrt(std::max(0.0, b.radius * b.radius - (z - b.center.z) * (z - b.center.z)));
      rows(b.center.y - rho, b.center.y + rho, [&](double y) { return line_ball(b.center, b.radius, y, z); });
      continue;
    }
    const FlatBeam& fb = lattice_.beams[e->index - balls];
    const Ball a{lattice_.balls[fb.a].center, fb.ra}, b{lattice_.balls[fb.b].center, fb.rb};
    const BeamCone cone = beam_cone(a, b);
    const bool lateral = cone.has_lateral_surface();
    rows(std::min(a.center.y - a.radius, b.center.y - b.radius), std::max(a.center.y + a.radius, b.center.y + b.radius),
         [&](double y) {
           Interval span = line_ball(a.center, a.radius, y, z);
           span.unite(line_ball(b.center, b.radius, y, z));
           if (lateral) span.unite(line_cone(cone, y, z));
           return span;
         });
  }
  return static_cast<std::int64_t>(crossing.size());
}

std::string LatticeSlicer::svg(std::int64_t layer) const {
  const double z = layer_z(layer);
  std::vector<const Element*> crossing;
  elements_at(z, crossing);
  std::ostringstream os;
  os.precision(9);
  const double w = static_cast<double>(width_) * pixel_, h = static_cast<double>(height_) * pixel_;
  // Model units, +y up: the group flips the SVG's downward y.
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w
     << "mm\" height=\"" << h << "mm\" viewBox=\"" << min_.x << ' ' << -(min_.y + h) << ' ' << w << ' ' << h
     << "\">\n<g transform=\"scale(1,-1)\" fill=\"black\" stroke=\"none\">\n";
  const std::int64_t balls = lattice_.ball_count();
  for (const Element* e : crossing) {
    if (e->index < balls) {
      const Ball& b = lattice_.balls[e->index];
      const double rho = std::sqrt(std::max(0.0, b.radius * b.radius - (z - b.center.z) * (z - b.center.z)));
      os << "<circle cx=\"" << b.center.x << "\" cy=\"" << b.center.y << "\" r=\"" << rho << "\"/>\n";
      continue;
    }
    const FlatBeam& fb = lattice_.beams[e->index - balls];
    const Ball a{lattice_.balls[fb.a].center, fb.ra}, b{lattice_.balls[fb.b].center, fb.rb};
    const BeamCone cone = beam_cone(a, b);
    std::vector<std::pair<double, Interval>> spans;
    const double y0 = std::min(a.center.y - a.radius, b.center.y - b.radius);
    const double y1 = std::max(a.center.y + a.radius, b.center.y + b.radius);
    const int steps = std::max(8, static_cast<int>(std::ceil((y1 - y0) / pixel_)));
    for (int k = 0; k <= steps; ++k) {
      const double y = y0 + (y1 - y0) * k / steps;
      Interval span = line_ball(a.center, a.radius, y, z);
      span.unite(line_ball(b.center, b.radius, y, z));
      if (cone.has_lateral_surface()) span.unite(line_cone(cone, y, z));
      if (!span.empty()) spans.emplace_back(y, span);
    }
    if (spans.size() < 2) continue;
    os << "<polygon points=\"";
    for (const auto& [y, s] : spans) os << s.lo << ',' << y << ' ';
    for (auto it = spans.rbegin(); it != spans.rend(); ++it) os << it->second.hi << ',' << it->first << ' ';
    os << "\"/>\n";
  }
  os << "</g>\n</svg>\n";
  return os.str();
}

void write_png(const std::string& path, const std::vector<std::uint8_t>& pixels, std::int64_t width, std::int64_t height) {
  PartialFile file(path);
  const std::size_t row_bytes = 1 + static_cast<std::size_t>((width + 7) / 8);
  std::vector<std::uint8_t> raw(row_bytes * static_cast<std::size_t>(height), 0);
  for (std::int64_t r = 0; r < height; ++r) {
    const std::uint8_t* src = pixels.data() + (height - 1 - r) * width;  // top row first: +y up
    std::uint8_t* dst = raw.data() + r * row_bytes + 1;                 // filter byte 0 (none)
    for (std::int64_t i = 0; i < width; ++i)
      if (src[i]) dst[i >> 3] |= static_cast<std::uint8_t>(0x80u >> (i & 7));
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), static_cast<uLong>(raw.size()), 1) != Z_OK)
    throw std::runtime_error("png: compressing a layer failed");
  auto chunk = [&](const char* type, const std::uint8_t* data, std::size_t size) {
    const std::uint8_t length[4] = {static_cast<std::uint8_t>(size >> 24), static_cast<std::uint8_t>(size >> 16),
                                    static_cast<std::uint8_t>(size >> 8), static_cast<std::uint8_t>(size)};
    file.write(length, 4);
    file.write(type, 4);
    if (size) file.write(data, size);
    uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(type), 4);
    if (size) crc = crc32(crc, data, static_cast<uInt>(size));
    const std::uint8_t c[4] = {static_cast<std::uint8_t>(crc >> 24), static_cast<std::uint8_t>(crc >> 16),
                               static_cast<std::uint8_t>(crc >> 8), static_cast<std::uint8_t>(crc)};
    file.write(c, 4);
  };
  static const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  file.write(signature, 8);
  const auto w = static_cast<std::uint32_t>(width), h = static_cast<std::uint32_t>(height);
  const std::uint8_t header[13] = {static_cast<std::uint8_t>(w >> 24), static_cast<std::uint8_t>(w >> 16),
                                   static_cast<std::uint8_t>(w >> 8),  static_cast<std::uint8_t>(w),
                                   static_cast<std::uint8_t>(h >> 24), static_cast<std::uint8_t>(h >> 16),
                                   static_cast<std::uint8_t>(h >> 8),  static_cast<std::uint8_t>(h),
                                   1 /* bit depth */, 0 /* grayscale */, 0, 0, 0};
  chunk("IHDR", header, sizeof(header));
  chunk("IDAT", packed.data(), packed_size);
  chunk("IEND", nullptr, 0);
  file.commit();
}

SliceStats write_slices(const FlatLattice& lattice, const SliceOptions& options, const std::string& directory,
                        bool svg, Progress& progress) {
  check_output_path(directory);
  const LatticeSlicer slicer(lattice, options);
  SliceStats stats;
  stats.layers = slicer.layer_count();
  stats.width = slicer.width();
  stats.height = slicer.height();
  progress.set_total(stats.layers);
  std::atomic<std::int64_t> element_layers{0};
  std::atomic<std::int64_t> raster_ns{0}, write_ns{0};
  auto name = [&](std::int64_t k, const char* extension) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "/layer_%05lld.%s", static_cast<long long>(k), extension);
    return directory + buffer;
  };
  // A stack is complete or absent: on an error or a cancel, the layers already written are removed again.
  std::vector<char> written(static_cast<std::size_t>(stats.layers), 0);
  try {
    tbb::parallel_for(std::int64_t(0), stats.layers, [&](std::int64_t k) {
      progress.check();
      std::vector<std::uint8_t> pixels;
      const auto t0 = std::chrono::steady_clock::now();
      element_layers += slicer.rasterize(k, pixels);
      const auto t1 = std::chrono::steady_clock::now();
      write_png(name(k, "png"), pixels, slicer.width(), slicer.height());
      if (svg) {
        PartialFile file(name(k, "svg"));
        file.write(slicer.svg(k));
        file.commit();
      }
      const auto t2 = std::chrono::steady_clock::now();
      written[k] = 1;
      raster_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count();
      write_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(t2 - t1).count();
      progress.advance();
    });
  } catch (...) {
    for (std::int64_t k = 0; k < stats.layers; ++k)
      if (written[k]) {
        std::remove(name(k, "png").c_str());
        if (svg) std::remove(name(k, "svg").c_str());
      }
    throw;
  }
  stats.element_layers = element_layers;
  stats.raster_seconds = raster_ns * 1e-9;  // summed over the threads
  stats.write_seconds = write_ns * 1e-9;
  progress.finish();
  return stats;
}

}  // namespace steady
