#pragma once
// Pieces of a lattice built separately and glued: a beam whose ball is not built ends at its cut (halfway
// between its exit planes), either closed by a planar disk or left open on a circle edge shared through CutEdges
// with the piece on the other side. Trimming uses this to run Booleans on boundary hubs only.
#include <Geom_Circle.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "steady/brep/brep_builder.hpp"
#include "steady/core/progress.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

// Which part of a lattice to build.
struct ForeignContacts;

struct BrepSelection {
  std::vector<char> balls;  // per ball: build its sphere (absorbed balls are never built)
  std::vector<char> beams;  // per beam: build it; a built beam whose ball is not built stops at its cut
  std::vector<char> split;      // per beam (or empty): build it as two halves meeting at its cut, even when both
                                // its balls are built (each half closed by its own disk, or open)
  std::vector<char> open_cuts;  // per beam (or empty): leave its cut open, for gluing; other cuts get a disk
  std::vector<double> cut_fractions;  // per beam (or empty: halfway): where its cut lies, BeamFrustum::cut_fraction
  SeamPreference seams = SeamPreference::FewestCrossings;  // where spherical faces put their seams
  // Whole beams too short for their hubs' collars: tight collars, then hubs built as one (brep_builder.cpp). The
  // trim's band has them too: such beams are never cut there, their hubs share a cluster (assign_roles), and the
  // thin bands of cone between a stump's envelope and a tight collar, which the Booleans may fail to split, are
  // caught by the clusters' checks and the check of the assembled part (part_check.hpp).
  bool crowded_fallbacks = true;
  // Elements meeting foreign ones (foreign_groups.hpp): their hubs are built in groups. Null: the lattice is
  // clean but for crowded hubs (the caller checked).
  const ForeignContacts* foreign = nullptr;
  static BrepSelection everything(const FlatLattice& lattice);
};

// The circle at a beam's cut, shared by the pieces built on either side of it: its edges run between its vertices
// (one or two: where the seams of the two sides' conical faces meet it).
struct CutCircle {
  Handle(Geom_Circle) curve;            // normal along the beam (from its ball a to its ball b)
  std::vector<double> params;           // vertex parameters, sorted, within [params[0], params[0] + 2 pi)
  std::vector<TopoDS_Vertex> vertices;  // one per parameter
  std::vector<TopoDS_Edge> edges;       // edges[k] from params[k] to params[k + 1] (the last one wraps)
};
using CutEdges = std::unordered_map<std::int64_t, CutCircle>;

// A disk closing a beam's cut: side 0 closes the piece on the beam's `a` side, side 1 the `b` side.
struct CutCap {
  std::int64_t beam = -1;
  int side = 0;
  TopoDS_Face face;
};

struct BrepPieces {
  std::vector<TopoDS_Face> faces;         // every face, oriented outward
  std::vector<std::int64_t> face_owner;   // per face: the ball whose hub it belongs to
  std::vector<CutCap> caps;
  BrepBuildStats stats;
};

// Builds the selected part. Cut edges found in `cut_edges` are reused; new ones are added to it (only when the
// build succeeds: Cancelled or an error leaves it as it was).
BrepPieces build_brep_pieces(const FlatLattice& lattice, const BrepSelection& selection, CutEdges& cut_edges,
                             Progress& progress = no_progress());

// Where the stumps of a ball's hub start when it is built with the beams `beams` says (per beam): per incident
// beam, the axial distance from the ball's center to its first circle (the exit circle on a clean hub, the collar
// on a crowded one), NaN for beams not built. A beam's cut must lie beyond the circles at both its ends.
std::vector<double> stump_starts(const FlatLattice& lattice, const std::vector<BeamFrustum>& frustums,
                                 const std::vector<char>& beams, std::int64_t ball);

// A crowded hub's collar that came out beyond its beam's cut: the core's Fuse needed collars farther out than the
// ones the cut was placed for (build_hub_core's fallbacks, e.g. tangent exit caps with a taper). Says where, so
// that the trim can place its cuts again knowing that collar.
struct CollarPastCut : std::runtime_error {
  struct End {
    std::int64_t beam;
    int end;        // 0 at the beam's ball a, 1 at ball b
    double collar;  // the collar's distance from its ball's centre
  };
  CollarPastCut(const std::string& what, std::vector<End> found) : std::runtime_error(what), ends(std::move(found)) {}
  std::vector<End> ends;  // every one the build found
};

// Collars known from a build (CollarPastCut), per beam end (2 * beam + end): where the stump starts at least.
using KnownCollars = std::map<std::int64_t, double>;

// Moves the cut of every beam whose halfway cut lies within a crowded hub's collar (thick beams between crowded
// hubs) to halfway between its two hubs' stump starts, with the whole lattice's hubs (each distinct shape's
// collars computed once; `known` ones farther out where a build found them so). Beams too short for both collars
// keep their cut: returned, per beam, as 1 (no room for a cut between the two collars; the build gives their hubs
// tight collars, or builds them as one).
std::vector<char> place_cuts_between_collars(const FlatLattice& lattice, std::vector<BeamFrustum>& frustums,
                                             const KnownCollars& known = {});

}  // namespace steady
