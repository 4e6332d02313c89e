#pragma once
// The exact union of overlapping hubs, for the integral properties of a lattice that is not clean.
//
// When hubs of different nodes overlap, the lattice is no longer the assembly of its hubs: the sum over hubs
// counts the shared regions more than once. Two ways to correct it, tried in this order:
// 1. Moved cuts, no Boolean. Most overlaps come from crowded hubs whose stumps meet beyond their beams'
//    mid-planes. Moving those beams' cuts past the hubs' collars (the B-rep's rule) makes all hubs disjoint
//    again, checked piece by piece; the correction is the moved hubs' exact properties (hub_properties) minus
//    their mid-plane ones.
//    A moved cut may lie inside its ball (the hub then ends at the cut disk); no moved disk may meet another
//    stump of its hub.
// 2. Otherwise the overlapping hubs fall into clusters (connected components of the "overlaps" relation); each
//    cluster's union is computed with OpenCASCADE (each hub fused from its ball and stump frustums, then the
//    hubs fused, integrated by BRepGProp to 1e-10 relative), and the properties become
//        sum over all hubs  +  sum over clusters of ( union of the cluster's hubs  -  sum of its hubs ),
//    the cluster's hubs measured as fused, so that a hub's own Fuse error cancels where it meets no other hub.
//    Hubs outside every cluster have disjoint interiors from everything else, so this is exact when the Fuse
//    is. A hub fused keeps its ball whole where hub_properties ends it at a cut inside the ball (a ball past its
//    beam's mid-plane): its spherical caps beyond those cuts are added to its exact properties
//    (caps_past_cuts.hpp) for the check below and taken back from the correction.
//    The Fuse is checked before it is trusted: each hub's solid against its exact volume (a crowded hub's
//    Fuse has come back valid and 8 % short), the union a valid solid with a volume between the largest hub's
//    and the sum, and the volume the hubs share (sum less union) within 5 standard errors of an estimate that
//    integrates along lines through where their pieces meet (shared_volume_sampling.hpp). Each Fuse is retried
//    (checked_fuse.hpp) until a result passes.
// Areas exclude the cut disks (between a hub and its neighbour across a beam's cut: inside the lattice).
#include <cstdint>
#include <vector>

#include "steady/lattice/hub.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/properties/hub_properties.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/properties/mass_moments.hpp"
#include "steady/core/progress.hpp"

namespace steady {

// The most hubs whose union is computed (the clusters' Booleans grow with them); beyond, properties() refuses.
constexpr std::int64_t kMaxUnionHubs = 2000;

struct HubUnionCorrection {
  MassMoments moments;            // to add to the sum over hubs; moments about `reference`
  std::int64_t moved_cuts = 0;    // beams whose cut moved past a crowded hub's collars (then no Boolean)
  std::int64_t moved_cut_hubs = 0;  // hubs with a moved cut
  std::int64_t clusters = 0;      // clusters of overlapping hubs fused (0 when moved cuts were enough)
  std::int64_t hubs = 0;          // hubs in them
  double volume_error = 0.0;      // BRepGProp's error estimate, relative to the clusters' volume
};

// `overlaps` must list every overlapping pair (HubOverlapReport::overlaps with overlap_count of them).
HubUnionCorrection hub_union_correction(const Lattice& lattice, const std::vector<HubOverlap>& overlaps,
                                        const Vec3& reference, const HubPropertiesOptions& options = {},
                                        Progress& progress = no_progress());

}  // namespace steady
