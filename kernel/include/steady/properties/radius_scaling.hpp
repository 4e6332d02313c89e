#pragma once
// Density targeting: the radius scale (every node radius and beam radius multiplied by it, positions kept)
// at which the lattice reaches a target volume, relative density or mass.
//
// The volume is monotone in the radius scale (balls and beam hulls only grow, the mid-plane cuts stay), so a
// bracketing root finder (Brent's method on log volume against log scale, which is nearly linear since the
// volume grows like scale^2 to scale^3) converges in a handful of evaluations. Each evaluation is the exact
// closed form of lattice_properties, reduced to volume and precomputed once: the distinct ball, beam and hub
// shapes with the total weight of their similar copies (sum of scale^3 over the copies, in closed form).
#include <cstdint>
#include <memory>

#include "steady/properties/hub_properties.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// The lattice with every node radius and beam radius multiplied by `scale` (> 0).
Lattice with_radius_scale(const Lattice& lattice, double scale);

// The lattice's exact volume as a function of the radius scale.
class RadiusScaledVolume {
 public:
  explicit RadiusScaledVolume(const Lattice& lattice, const HubPropertiesOptions& hub = {});
  ~RadiusScaledVolume();
  RadiusScaledVolume(RadiusScaledVolume&&) noexcept;
  double operator()(double scale) const;
  // Balls and beams only: equal to the volume wherever no hub's stumps overlap.
  double without_overlaps(double scale) const;
  // Whether some hub's stumps overlap (so that the overlap corrections are not zero) at this scale.
  bool overlaps_at(double scale) const;
  // Above this scale some node ball would cross a beam's mid-plane (the lattice cannot be clean).
  double max_scale() const;
  std::size_t beam_shapes() const;
  std::size_t hub_shapes() const;

 private:
  struct Model;
  std::unique_ptr<Model> model_;
};

struct RadiusScaleOptions {
  double relative_tolerance = 1e-10;  // on the volume
  bool check_clean = true;            // check the scaled lattice at the solution (refuse if not clean)
  HubPropertiesOptions hub;
};

struct RadiusScaleSolution {
  double scale = 1.0;
  double volume = 0.0;        // of the scaled lattice
  int evaluations = 0;        // of the volume
  bool clean_verified = false;
};

// Throws InvalidInput naming the target when it cannot be reached by a clean lattice.
RadiusScaleSolution radius_scale_for_volume(const Lattice& lattice, double target_volume,
                                            const RadiusScaleOptions& options = {});
// relative_density = lattice volume / envelope volume (of a body, or cell_envelope_volume()).
RadiusScaleSolution radius_scale_for_density(const Lattice& lattice, double relative_density, double envelope_volume,
                                             const RadiusScaleOptions& options = {});
RadiusScaleSolution radius_scale_for_mass(const Lattice& lattice, double mass, double density,
                                          const RadiusScaleOptions& options = {});

// The volume of the lattice's cells: each group's template cell (the parallelepiped spanned at the template
// nodes' centroid o by U(o) - o, V(o) - o, W(o) - o) mapped by the group's similarity, summed in closed form.
// For a translational lattice this is exactly counts x cell volume; for bent or graded lattices it is the
// natural envelope of the groups. Throws InvalidInput when the three steps span no volume (for example an
// identity step of a direction with count 1): give the envelope of a body instead.
double cell_envelope_volume(const Lattice& lattice);

}  // namespace steady
