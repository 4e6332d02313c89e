#pragma once
// The mesh family: lattices straight to triangle meshes, and the printer files (STL, OBJ, 3MF, 3MF beam
// lattices), slices for layer printers. No OpenCASCADE: link steady_mesh (CGAL, lib3mf and libzip are its private dependencies).
#include "steady/steady.hpp"

#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/mesh_files.hpp"
#include "steady/mesh/slices.hpp"
#include "steady/mesh/threemf_reader.hpp"
#include "steady/mesh/triangle_mesh.hpp"
#include "steady/mesh/trimmed_mesh.hpp"
