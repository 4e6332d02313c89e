#pragma once
// The brep family: exact B-rep lattices, trimming into bodies, skins, STEP and BREP files (OpenCASCADE).
// Link steady_brep.
#include "steady/steady.hpp"

#include "steady/brep/body_filter.hpp"
#include "steady/brep/boundary_volume.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/brep/connector_step.hpp"
#include "steady/brep/connectors.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/lattice_part.hpp"
#include "steady/brep/skin.hpp"
#include "steady/brep/solid_body.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/trim.hpp"
