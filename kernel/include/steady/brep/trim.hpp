#pragma once
// Trimming a lattice into a CAD body, with an optional skin. Classification first, Booleans only where needed.
//
// Every hub (a ball with its half-beams up to the beams' cuts) has a bounding ball. Against the body's boundary
// it is inside, outside or crossing: a triangulation of the boundary bounds the distance quickly, the exact
// distance (BRepExtrema) decides the hubs near it, and the inside/outside state spreads along beams from one
// exact point classification per connected region. Then:
//   policy Clip  - inside hubs are kept whole (Boolean-free B-rep), outside hubs dropped, and only the crossing
//                  hubs, closed by disks at their cuts toward kept hubs, meet the body in one Common; the result
//                  is glued to the rest along the circles of those disks (the disks are removed);
//   policy Whole - only hubs entirely inside are kept, never cut (no Boolean at all);
//   policy Bridge - the hubs Whole keeps, and from each that lost a neighbour a bridge beam to the nearest point of
//                  the wall, clipped there (steady/brep/bridges.hpp: the bridged lattice is trimmed with Clip).
// Dangling beams (joining a kept hub to a dropped one) are kept as stumps closed at their cut, or removed.
// With a skin of thickness t, the part is skin(t) united with the lattice trimmed to the inner offset: hubs are
// classified against the inner boundary, and only the hubs crossing it take part in the union with the skin.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <functional>
#include <string>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/core/progress.hpp"

namespace steady {

enum class TrimPolicy { Clip, Whole, Bridge };
enum class DanglingBeams { Keep, Remove };

TrimPolicy trim_policy_from_string(const std::string& name);        // "clip" | "whole" | "bridge"
DanglingBeams dangling_from_string(const std::string& name);        // "keep" | "remove"

struct TrimOptions {
  TrimPolicy policy = TrimPolicy::Clip;
  DanglingBeams dangling = DanglingBeams::Keep;
  double skin = 0.0;          // wall thickness; 0: no skin
  bool unite_skin = true;     // false: return the skin and the trimmed lattice as separate shapes
  bool verify_booleans = true;  // check the Booleans' output with BRepCheck (an error instead of a bad solid)
  bool move_cuts = true;  // cut beams between crossing hubs off their middle where that keeps the hubs in
                          // separate clusters (false: only halfway, for comparisons)
  bool rim_cut = true;  // with a skin, unite the clusters on the inner boundary's rims with it by one Cut when they
                        // hold most of the band (false: clip them and glue them by a Fuse, for comparisons)
  // Diagnostics as they happen, for the developers (how long the hubs took, why an attempt failed, why the union
  // went through the pores); none when empty. Python: brep(..., log=print).
  std::function<void(const std::string&)> report;
  // Where a cluster that fails every clip attempt (both layouts and the tool), and faces a union leaves open, are
  // written as BREP for study; empty: not written.
  std::string dump_directory;
};

struct TrimStats {
  std::int64_t inside_hubs = 0, outside_hubs = 0, crossing_hubs = 0;
  std::int64_t exact_distance_tests = 0;  // hubs the triangulation could not decide
  std::int64_t removed_beams = 0;         // dangling beams removed
  std::int64_t band_clusters = 0;         // independent Booleans the crossing hubs were split into
  std::int64_t moved_cuts = 0;            // beams between crossing hubs cut off their middle, where the
                                          // boundary leaves room, to keep their hubs in separate clusters
  std::int64_t retried_clusters = 0;      // clusters whose first Common failed, clipped by a retry; of those:
  std::int64_t relaid_clusters = 0;       //   with their spheres laid out the other way
  std::int64_t turned_clusters = 0;       //   in a turned frame
  std::int64_t fuzzy_clusters = 0;        //   with a fuzzy Common (1e-4 or 1e-3 of their size)
  std::int64_t merged_clusters = 0;       //   with their thin bands of cone merged into the stumps beside them
  std::int64_t holed_clusters = 0;        // with a skin: clusters glued to it by holes in its inner faces, no
                                          // Boolean; the others:
  std::int64_t rim_clusters = 0;          //   on the inner boundary's edges, seams or poles: clipped and glued to
                                          //   the skin by a Fuse, or, where they hold most of the band, united
                                          //   with it by one Cut of the inner body (through the pores)
  std::int64_t rim_clusters_unclipped = 0;  //   of those, found before their Common (which was not run)
  std::string rim_cut_reason;             // why that Cut failed its checks, when it did: the rim clusters were then
                                          // clipped one by one and glued to the skin by a Fuse
  std::int64_t core_hubs = 0, distinct_cores = 0, fused_cores = 0, tight_cores = 0;  // crowded hubs built from cores, and the cores built
  std::int64_t hub_groups = 0, grouped_hubs = 0;  // crowded hubs joined by too short beams, built as one
  std::int64_t foreign_groups = 0, foreign_hubs = 0;  // hubs meeting elements of other nodes, built as one
  std::int64_t joined_band_hubs = 0;      // hubs clipped with the band all the same, joined to it by a beam with
                                          // no room for a cut between their collars: inside hubs, and (clipping,
                                          // dangling beams kept) dropped ones for the Boolean to remove
  // With the skin apart (!unite_skin): pieces of the trimmed lattice holding no hub built whole (ends of beams and
  // hubs cut at the inner wall, touching only the skin), given to the skin part, and their volume.
  std::int64_t skin_pieces = 0;
  double skin_pieces_volume = 0.0;
  // Of those pieces, the lenses of beams whose axis runs outside the inner wall while their cone dips through it
  // (grazing_beams.hpp), split off the lattice for the skin; and why they were not, when the split failed its checks
  // or the skin's glued Fuse with them did (then the lenses stay in the lattice).
  std::int64_t grazing_pieces = 0;
  std::string grazing_kept_reason;
  double grazing_seconds = 0.0;
  // Sphere faces left with a loop across the seam by a Boolean, rebuilt on a frame whose seam clears their loops
  // (portable_sphere_faces.hpp: STEP readers find them invalid otherwise); those kept as they were, and why.
  std::int64_t reseated_sphere_faces = 0, kept_straddling_faces = 0;
  std::string kept_straddling_reason;
  double reseat_seconds = 0.0;
  // Edges a Boolean left loose (tolerance above 2e-7: walking-line approximations of where two quadrics
  // meet),
  // retraced onto the exact curve (retraced_edges.hpp); the loosest edge of those before and after.
  std::int64_t loose_edges = 0, retraced_edges = 0;
  // Intersection edges (loose or not) given curves with the angle around a beam or ball as their parameter: exact to
  // 1e-8 in a few spans, where a walking line keeps many (retraced_edges.hpp; issue 14: compact files).
  std::int64_t refitted_edges = 0;
  double loosest_edge_before = 0.0, loosest_edge_after = 0.0, retrace_seconds = 0.0;
  bool relaid_out = false;                // the first attempt failed as a whole; a later one (every cut halfway,
                                          // or the spheres laid out the other way) made the part
  std::string relaid_reason;              //   why the earlier attempts failed
  // Policy Bridge (then the other counts are of the bridged lattice's trim, but inside/outside/crossing of the
  // lattice's own hubs): hubs kept whole, those of them that lost a neighbour, bridges made, of those the ones
  // rerouted (toward the nearest wall point they would meet another kept element; another route was clear),
  // bridges refused because every route tried would meet another kept element (their hubs stay unbridged, named
  // through `report`), bridges whose hub had several nearest points on the wall (the first taken).
  std::int64_t kept_hubs = 0, lost_neighbour_hubs = 0, bridges = 0, rerouted_bridges = 0, blocked_bridges = 0,
               ambiguous_bridges = 0;
  std::int64_t faces = 0;
  double volume = 0.0;  // of the part (shape_volume), filled by lattice_part_brep
  double classify_seconds = 0.0, build_seconds = 0.0, boolean_seconds = 0.0, assemble_seconds = 0.0;
  double union_seconds = 0.0;      // of boolean_seconds, the union with the skin
  bool union_through_pores = false;  // the union with the skin failed its checks: united through the pores
  std::string pores_reason;          //   what the check found
};

struct TrimResult {
  TopoDS_Shape part;     // the result: trimmed lattice, united with the skin when there is one and unite_skin
  TopoDS_Shape lattice;  // when !unite_skin: the lattice trimmed to the inner offset, without its loose pieces
  TopoDS_Shape skin;     // the skin, when there is one (when !unite_skin: with the lattice's loose pieces)
  TrimStats stats;
};

// Throws InvalidInput naming "body" (not one closed valid solid; the lattice misses it), "skin" (negative,
// too thick) or "policy" (nothing left after trimming). Reports to `progress` through the skin, the classification,
// the building of the pieces, the Booleans (cluster by cluster, and inside OpenCASCADE's own loops) and the final
// assembly; throws Cancelled soon after it is cancelled (the inputs are never changed, so nothing needs undoing).
TrimResult trim_lattice(const FlatLattice& lattice, const TopoDS_Shape& body, const TrimOptions& options,
                        Progress& progress = no_progress());

}  // namespace steady
