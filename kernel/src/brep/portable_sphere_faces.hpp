#pragma once
// Sphere faces whose loops cross the sphere's seam, rebuilt on a frame whose seam and poles clear every loop.
//
// OpenCASCADE's sphere has a seam (the half great circle u = 0 from pole to pole). Where a loop of a face runs across
// it, OpenCASCADE keeps the loop as arcs of the face's outer wire, split at the seam. A STEP file stores no seam: the
// reader rebuilds the face from its loops, makes such a loop a closed hole across the periodic boundary, and finds
// it crossing the seam it adds ("intersecting wires"). The builder lays its own hubs out without such loops
// (sphere_layout.hpp, hub_core.cpp), but a Boolean (a hub clipped by the body or its skin's inner wall, a split)
// keeps the frame of its input, wherever the cut runs. The same face on another frame of the same sphere is the
// same surface: only the (u, v) curves of its edges change, the 3D geometry and the topology around it do not.
#include <BRepTools_ReShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <string>

namespace steady {

// Whether a sphere face holds a chain of edges across its seam: leaving the seam on one side and coming back to
// the same side at another latitude (a hole laid across the periodic boundary). A chain around a pole leaves on
// one side and comes back on the other, which readers keep.
bool has_chain_across_seam(const TopoDS_Face& face);

struct PortableSphereFaces {
  std::int64_t reseated = 0;  // faces rebuilt on a portable frame (recorded in the ReShape); of those, the ones
  std::int64_t seam_through_loops = 0;  // whose seam crosses loops around its poles (no room between the loops)
  std::int64_t kept = 0;      // faces with such a chain left as they were, and why (the first reason)
  std::string kept_reason;
};

// Records in `reshape` (which must consider locations) a portable twin of every sphere face of `shape` that has a
// chain across its seam: the same surface on a frame whose seam and poles stay clear of all its loops, its edges
// (the same edges, shared with the neighbouring faces) given (u, v) curves on that frame. A twin is recorded only
// when it checks out: valid, no chain across its seam, the same region of the sphere (256 points classified
// alike). Otherwise the face is kept and counted.
PortableSphereFaces reseat_sphere_faces(const TopoDS_Shape& shape, BRepTools_ReShape& reshape);

}  // namespace steady
