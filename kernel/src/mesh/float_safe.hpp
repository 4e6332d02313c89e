#pragma once
// Meshes that survive 32-bit floats. STL and 3MF store vertices as floats; the band's Boolean, rounded to double,
// can leave edges far below a float's resolution (a lattice vertex within 1e-8 of the wall it is cut at), which a
// reader would weld into flat triangles and non-manifold edges. So the band is rounded to floats here, once, and
// repaired with exact predicates on the rounded points, and every writer gets the mesh it checked.
#include <cstdint>
#include <string>

#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

// `p` rounded to the nearest 32-bit floats, as a double.
Vec3 float_rounded(const Vec3& p);

// Rounds every vertex of `mesh` to floats, without repair (for parts whose edges are far above a float's resolution).
void round_to_floats(TriangleMesh& mesh);

// The band (a Boolean's result: a 2-manifold, open or closed) with its vertices rounded to floats, its edges shorter
// than 16 floats' resolution collapsed, then, where rounded triangles intersect, the shortest edges of those that
// are needles collapsed when shorter than `needle_limit` (no border vertex ever moves); the triangles that rounding
// made degenerate removed, and no self-intersection (CGAL's exact predicates on the rounded points). Returns the
// number of triangles removed; std::runtime_error naming `what` if a degeneracy cannot be removed or the rounded band
// intersects itself.
std::int64_t make_float_safe(TriangleMesh& band, const std::string& what, double needle_limit = 0.0);

}  // namespace steady
