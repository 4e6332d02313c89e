#pragma once
// Internal to trimming: the phases trim_attempt() runs in order, each a function with an explicit result
// (docs/brep.md, section 3, says why each is the way it is):
//   bodies      the body, and with a skin the skin and its inner boundary               (trim_roles.cpp)
//   states      every hub inside, outside or crossing each boundary                        (trim_roles.cpp)
//   roles       which hubs are built whole, which are clipped, which beams are kept        (trim_roles.cpp)
//   cuts        where the beams between clipped hubs are cut, and the clusters they leave  (trim_cuts.cpp)
//   disks       the disks closing the clusters' cuts, and their fates in the Booleans     (trim_disks.cpp)
//   clip        each cluster's Common with the boundary, then the retry ladder            (trim_clip.cpp)
//   skin union  the clipped clusters glued to the skin, by holes or through the pores     (trim_skin_union.cpp)
//   assembly    every face into solids                                                    (trim.cpp)
#include <BRepAlgoAPI_BooleanOperation.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "brep/skin_holes.hpp"
#include "brep/brep_pieces.hpp"
#include "brep/foreign_groups.hpp"
#include "steady/brep/skin.hpp"
#include "steady/brep/solid_body.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/beam_frustum.hpp"

namespace steady::trim {

// ---- progress ----------------------------------------------------------------------------------------------

// Work units of one attempt: fixed shares first (the body, the skin, the hubs' pieces, each classification), then
// the rest in proportion to estimates of what is left, known once the roles are (WorkWeights).
class TrimBudget {
 public:
  explicit TrimBudget(Progress& progress);
  Progress& progress() { return progress_; }
  // Hands out a fixed share of the units.
  std::int64_t fixed(std::int64_t units);
  // Shares the units left in proportion to `total_weight`; rest(w) is then the share of weight w.
  void share_rest(std::int64_t total_weight) { rest_weight_ = total_weight; }
  std::int64_t rest(std::int64_t weight) const;

 private:
  Progress& progress_;
  std::int64_t fixed_ = 0;
  std::int64_t rest_weight_ = 1;
};

// ---- bodies, states, roles ---------------------------------------------------------------------------------

struct Bodies {
  SolidBody body;
  std::optional<Skin> skin;
  std::optional<SolidBody> inner;  // the skin's inner boundary, against which the lattice is trimmed
};
Bodies make_bodies(const TopoDS_Shape& body_shape, const TrimOptions& options, TrimBudget& budget);

// The pieces of a hub, each in a bounding ball: the node ball, and each half-beam from its exit circle to its cut.
// A hub is clear of a boundary when all its pieces are; and since the segment joining two nodes runs through their
// pieces (ball, half-beam, half-beam, ball), hubs clear of the boundary and joined by a beam lie on the same side.
struct Piece {
  Vec3 center{0.0};
  double radius = 0.0;
};
// Per ball (with the cuts in `frustums`).
std::vector<std::vector<Piece>> hub_pieces(const FlatLattice& f, const std::vector<BeamFrustum>& frustums,
                                           Progress& progress);

enum class HubState : char { Absent, Inside, Outside, Crossing };
struct HubStates {
  std::vector<HubState> outer;  // against the body
  std::vector<HubState> inner;  // against the inner boundary (the body's when there is no skin)
};
HubStates classify(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, const std::vector<char>& absorbed,
                   const Bodies& bodies, TrimStats& stats, TrimBudget& budget);

// How many of the lattice's hubs lie inside, outside and across the inner boundary (the body's without a skin).
// InvalidInput naming "body" when none meets the body.
struct HubCounts {
  std::int64_t inside = 0, outside = 0, crossing = 0;
};
HubCounts count_hubs(const HubStates& states);

struct HubRoles {
  std::vector<char> interior, band;  // per ball: built whole with no Boolean / clipped in a boundary cluster
  std::vector<char> beam_kept;       // per beam
  std::vector<char> band_beams, interior_beams;  // per beam: attached to a band / an interior hub
  std::vector<char> open_cuts;       // per beam between a band and an interior hub: glued at its cut
  std::vector<char> no_room;         // per beam: never cut (no room between its crowded hubs' collars, or it meets
                                     // an element of another node)
  ForeignContacts contacts;          // elements meeting foreign ones: their hubs are built in groups
  bool has_band = false;
};
// `no_room`: place_cuts_between_collars's beams with no room for a cut. Their two hubs are built together (tight
// collars, or one group of hubs), so an interior hub joined by one to a band hub joins the band. The hubs of a
// foreign contact are built in one group likewise (foreign_groups.hpp): they join the band together, and the beams
// in a contact are never cut.
// InvalidInput naming "body" (the lattice misses it), "policy" or "skin" (nothing is kept).
HubRoles assign_roles(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, const HubStates& states,
                      const std::vector<char>& no_room, ForeignContacts contacts, const TrimOptions& options,
                      bool has_skin, TrimStats& stats);

// The estimates of what follows the roles, relative to building one element (docs/brep.md).
struct WorkWeights {
  std::int64_t band_hubs = 0, band_elements = 0, interior_elements = 0, band_band_beams = 0;
  std::int64_t split = 0, build_band = 0, build_interior = 0, boolean = 0, skin_union = 0, verify = 0, assemble = 0;
  std::int64_t total() const { return split + build_band + build_interior + boolean + skin_union + verify + assemble; }
};
WorkWeights work_weights(const FlatLattice& f, const HubRoles& roles, const TrimOptions& options, bool unite);

// ---- cuts and clusters ---------------------------------------------------------------------------------------

// A hub's bounding ball may come this close (relative to the body's size) to the boundary and still count as
// clear of it: far below any feature, far above the exact distance's own accuracy.
constexpr double kClearanceRelative = 1e-9;

struct CutPlan {
  const SolidBody* boundary = nullptr;  // what the clusters are clipped at (policy Clip), or null
  std::vector<char> split;              // per beam between band hubs: cut into two sides, one per cluster
  std::vector<char> moved;              // per beam: its cut left the middle
  std::vector<std::int64_t> cluster_root;  // per ball: the representative of its cluster
  std::vector<double> cut_fractions;    // per beam: where its cut lies (BeamFrustum::cut_fraction)
};
// Moves cuts in `frustums` where halfway is not clear of the boundary (never within a `known` collar).
CutPlan place_cuts(const FlatLattice& f, const HubRoles& roles, const Bodies& bodies, const TrimOptions& options,
                   std::vector<BeamFrustum>& frustums, TrimStats& stats, Progress& progress,
                   const KnownCollars& known = {});

struct Clusters {
  std::vector<std::vector<TopoDS_Face>> faces;  // per cluster
  std::unordered_map<std::int64_t, int> index;  // cluster root -> cluster
  int of_ball(const CutPlan& plan, std::int64_t ball) const { return index.at(plan.cluster_root[ball]); }
};
Clusters group_clusters(const BrepPieces& band, const CutPlan& plan);

// ---- the disks at the clusters' cuts -------------------------------------------------------------------------

enum class Fate : char { Present, Deleted, Modified };

// The disks that close the clusters' cuts toward interior hubs and between split band hubs: removed after the
// Booleans to glue the pieces again. Each lies clear of the boundary, so its fate in a Boolean is known before
// the Boolean runs (expected); a disk that met another fate shows the Boolean went wrong.
class CutDisks {
 public:
  struct Disk {
    const CutCap* cap = nullptr;
    int cluster = 0;
    int layout = 0;       // 0: the first layout of the spheres; 1: the other one (for clusters that failed)
    bool active = true;   // the disk of the layout its cluster uses
    Fate fate = Fate::Present;
    int changed_by = -2;  // the cluster whose Boolean changed its fate, or -1 for the final one
    bool expected_present = true;
  };

  // The disks of one layout of the clusters' pieces (its caps on split or open cuts). `active`: per cluster, or
  // null for all. Expected fates: toward an interior hub it stays; between two band hubs it stays when its
  // center is inside the boundary the clusters are clipped at (`expected_by_beam` when given: as another layout).
  void add(const BrepPieces& pieces, int layout, const std::unordered_map<const void*, int>& cluster_of_face,
           const HubRoles& roles, const CutPlan& plan, const std::vector<char>* active,
           const std::vector<BeamFrustum>& frustums);
  bool contains(const TopoDS_Shape& face) const { return index_.count(face.TShape().get()) > 0; }
  void use_layout(int cluster, int layout);
  void reset_fates(const std::vector<char>* among = nullptr);  // of every disk, or of the clusters `among` marks

  // Records the fates a Boolean gave the disks of `cluster` (-1: the final Boolean, over every cluster, or those
  // `among` marks). `frame`: where the Boolean saw its arguments (a turned frame).
  void track(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int cluster,
             const TopLoc_Location& frame = TopLoc_Location(), const std::vector<char>* among = nullptr);
  // A cluster's Common is right when its disks of `layout` met their expected fate and its faces close up by
  // themselves with the faces it produced valid.
  bool cluster_result_ok(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int cluster, int layout,
                         const TopLoc_Location& frame = TopLoc_Location()) const;
  // After every Boolean: the active disks untouched (or deleted, for split cuts), the two sides of each split cut
  // with one fate. An error message, or empty.
  std::string check_fates(const HubRoles& roles, const CutPlan& plan, std::size_t cluster_count) const;

 private:
  std::vector<Disk> disks_;
  std::unordered_map<const void*, std::size_t> index_;
};

// ---- clipping the clusters -----------------------------------------------------------------------------------

struct ClusterClips {
  const TopoDS_Shape* tool = nullptr;  // what the clusters are clipped with, or null (no Boolean)
  std::string tool_text;               // its BREP text: each Boolean reads its own copy
  const char* what = "";
  std::vector<TopoDS_Shape> results;    // per cluster: clipped
  std::vector<TopoDS_Shape> unclipped;  // per cluster: its pieces, of the layout that was clipped
  std::vector<char> failed;             // per cluster: the first Common failed (retried)
  // Per cluster: one of its balls has its centre inside the tool, clear of the boundary, so its Common cannot be
  // empty. OpenCASCADE's Common of a dense cluster with a cylinder has returned nothing, and reported success.
  std::vector<char> cannot_be_empty;
  std::vector<std::vector<CutFace>> cut_faces;  // per cluster, with a skin: its faces on the inner boundary
  std::vector<char> as_holes;           // per cluster: those cut faces can be holes in the skin
  // Per cluster, with a skin: it reaches an edge, seam or vertex of the inner boundary (within its hubs' bounding
  // pieces), so its cut faces cannot be holes, and such clusters hold most of the band (otherwise none is marked):
  // it is united with the skin through the pores' Cut (skin union), unclipped, and its Common is not run (results
  // holds the unclipped solid).
  std::vector<char> on_rim;
};

struct ClipContext {
  const FlatLattice& f;
  const std::vector<BeamFrustum>& frustums;
  const TrimOptions& options;
  const Bodies& bodies;
  const HubRoles& roles;
  const CutPlan& plan;
  const Clusters& clusters;
  const BrepPieces& band;
  bool unite = false;  // the clusters are united with a skin afterwards
};

// Each cluster's Common with the boundary, in parallel; the failed ones are marked for the retries.
ClusterClips clip_clusters(const ClipContext& c, CutDisks& disks, Progress& progress);
// The failed clusters again, through clip_retries(): their spheres laid out the other way (built here, sharing the
// cut circles in `cuts`), turned frames, fuzzy values. `second_layout` keeps the other layout's pieces alive.
void retry_failed_clusters(const ClipContext& c, SeamPreference seams, CutEdges& cuts, ClusterClips& clips,
                           CutDisks& disks, BrepPieces& second_layout, TrimStats& stats, Progress& progress);

// The rim clusters' Commons (those on_rim marks, whose Cut through the pores failed its checks), with the retries;
// on_rim is cleared. `second_layout` keeps their other layout's pieces alive.
void clip_rim_clusters(const ClipContext& c, SeamPreference seams, CutEdges& cuts, ClusterClips& clips,
                       CutDisks& disks, BrepPieces& second_layout, TrimStats& stats, Progress& progress);

// ---- the union with the skin, and the faces kept -------------------------------------------------------------

struct UnionContext {
  const ClipContext& clip;
  const ClusterClips& clips;
  CutDisks& disks;
  const std::vector<TopoDS_Face>& interior_faces;  // the part's faces outside the band
  Progress& progress;                              // the union's and the checks' share
  std::int64_t union_weight = 0, verify_weight = 0;
  // Runs the rim clusters' Commons (clip_rim_clusters), when their Cut through the pores failed.
  std::function<void()> clip_rim_clusters;
};

// The faces the band contributes, united with the skin where there is one; an error message, or empty.
// Clip with a skin: by holes in the skin's inner faces where the clusters' cut faces can be holes; for the others
// (on its rims) one Cut of the inner body when they were marked on_rim, else their Commons glued by a Fuse (and
// those too after a failed Cut); through the pores for all should that go wrong. Whole with a skin: through the
// pores. No skin: the clipped clusters' faces.
std::string band_faces(UnionContext& u, std::vector<TopoDS_Face>& kept, TrimStats& stats);

// ---- policy Bridge --------------------------------------------------------------------------------------------

// The bridged lattice (plan_bridges, steady/brep/bridges.hpp) trimmed with policy Clip, with the bridge counts.
TrimResult trim_with_bridges(const FlatLattice& f, const TopoDS_Shape& body, const TrimOptions& options,
                             Progress& progress);

// ---- helpers shared by the phases ----------------------------------------------------------------------------

TopoDS_Shape compound_of(const std::vector<TopoDS_Shape>& shapes);
// A copy of a shape read back from its BREP text (each Boolean gets its own: see trim_clip.cpp).
TopoDS_Shape text_copy(const TopoDS_Shape& shape);
// One Boolean, non-destructive (the arguments' untouched sub-shapes come out as the very same shapes), parallel;
// std::runtime_error naming `what` when OpenCASCADE fails; Cancelled when the progress is.
TopoDS_Shape run_boolean(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& a, const TopoDS_Shape& b,
                         const char* what, Progress& progress);
// The same for a boundary cluster: a failure is one more reason to try again (nothing returned), not an error.
std::optional<TopoDS_Shape> try_boolean(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& a, const TopoDS_Shape& b,
                                        const char* what, Progress& progress);
// Edges of two sets of faces that one face uses once: where the faces do not close up (seams and degenerate
// edges do not count). `open_faces`: where given, the faces with such an edge.
std::int64_t free_edges(const std::vector<TopoDS_Face>& a, const std::vector<TopoDS_Face>& b,
                        std::vector<TopoDS_Shape>* open_faces = nullptr);
// The TShapes of a shape's faces (fates are decided by presence in a result).
std::unordered_set<const void*> face_set(const TopoDS_Shape& shape);
// Developers' diagnostics through TrimOptions::report, when set.
void report(const TrimOptions& options, const std::string& message);

}  // namespace steady::trim
