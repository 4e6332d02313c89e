#pragma once
// Any 3MF file read back by lib3mf (an independent reader: the tests compare what we write with what it sees).
#include <cstdint>
#include <string>
#include <vector>

#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

struct ThreeMfBeam {
  std::uint32_t v1 = 0, v2 = 0;
  double r1 = 0.0, r2 = 0.0;
};

struct ThreeMfObject {
  std::uint32_t id = 0;
  std::string name;
  TriangleMesh mesh;  // 32-bit float coordinates, as stored
  std::vector<ThreeMfBeam> beams;
  double min_length = 0.0, default_radius = 0.0;
};

struct ThreeMfContents {
  std::string unit;
  std::vector<ThreeMfObject> objects;
  std::vector<std::string> warnings;  // what lib3mf reported while reading
};

// std::runtime_error with lib3mf's message when it cannot read the file.
ThreeMfContents read_3mf(const std::string& path);

}  // namespace steady
