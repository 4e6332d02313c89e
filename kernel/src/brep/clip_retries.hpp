#pragma once
// How a boundary cluster whose Common with the body failed is clipped again (trim.cpp). OpenCASCADE's failures
// there depend on
// - how the spheres are parametrized (where a seam or pole sits relative to the body's surface: a sphere face with
//   a self-intersecting wire, measured): `layout` 1 builds the cluster with its seams and poles elsewhere;
// - the floating-point path of the intersections: `frame` k > 0 runs the Boolean on both arguments turned by a
//   fixed rotation (a location, undone on the result), the same geometry computed another way (measured: a
//   cluster of a tilted cylinder whose Common came out empty in both layouts came out right, exactly, in every
//   turned frame tried);
// - near-tangent contact: where the body's surface passes within about 1e-4 of a hub's size from one of its
//   circles, OpenCASCADE cannot close the section loops (measured: 8e-5 on a hub of radius 0.25, the Common came
//   out empty in every layout and frame); a `fuzzy` value, relative to the cluster's size, merges them. The edges
//   it makes keep a tolerance of that size, so the exact attempts come first and the smaller value before the larger;
// - thin bands of cone between two crowded hubs' collars, which the section with a curved body can miss (the BCC at
//   beam/node 1.0 in a cylinder: the Common came out empty in every layout, frame and fuzzy value): `merged` clips
//   the cluster with its bands merged into their stumps (merged_bands.hpp), after the exact attempts without.
#include <TopLoc_Location.hxx>
#include <gp_Pnt.hxx>

#include <vector>

namespace steady {

struct ClipAttempt {
  int layout;    // 0: the spheres' first layout, 1: the other one
  int frame;     // turned_frame(frame, ...)
  double fuzzy;  // OpenCASCADE's fuzzy value relative to the cluster's size; 0 for an exact Boolean
  bool merged = false;  // the cluster's thin bands of cone merged into their stumps first
};

// Every attempt in the order they are tried, the first pass (layout 0, frame 0, exact) included.
const std::vector<ClipAttempt>& clip_retries();

// Frame k: a fixed rotation about `center` (the cluster's), as a location; frame 0 is the identity. A shape moved
// by it and a Boolean's result moved back by its inverse come out with the very same sub-shapes where untouched.
TopLoc_Location turned_frame(int k, const gp_Pnt& center);

}  // namespace steady
