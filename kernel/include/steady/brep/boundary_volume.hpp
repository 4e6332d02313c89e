#pragma once
// The volume of a B-rep solid by the divergence theorem, each face's share integrated on its (u, v) domain by
// Green's theorem: a line integral along the face's (u, v) curves of an integral across u, both by Gauss-Legendre
// quadrature on short panels (to about 1e-12 relative on spheres, cones, cylinders and planes). Slower than
// OpenCASCADE's BRepGProp, and independent of it: its adaptive rule (shape_volume) is off by up to 2e-5 on parts
// trimmed by a skin's inner wall (faces of a cylinder with many holes bounded by intersection curves), too coarse
// to tell whether two parts add up to a third to 1e-6.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>

namespace steady {

// The signed volume enclosed by the shape's faces (as oriented in it); throws InvalidInput naming `what` when a
// face has an edge without a (u, v) curve.
double boundary_volume(const TopoDS_Shape& shape, const char* what = "shape");

// One face's share of that volume (the flux of (x - origin) / 3 through it, as it is oriented), additive over faces
// for one origin: NaN when an edge has no (u, v) curve on it.
double face_volume_share(const TopoDS_Face& face, const gp_Pnt& origin);

}  // namespace steady
