// Wavefront OBJ: one object, "v x y z" lines then "f a b c" lines (1-based), coordinates to double precision.
#include <charconv>

#include "steady/core/output_file.hpp"
#include "steady/mesh/mesh_files.hpp"

namespace steady {

void write_obj(const TriangleMesh& mesh, const std::string& path, const std::string& name) {
  PartialFile file(path);
  std::string text = "# written by LatticeWorkbench\no " + name + "\n";
  char number[32];
  auto append = [&](auto value) {
    const auto r = std::to_chars(number, number + sizeof(number), value);
    text.append(number, r.ptr);
  };
  auto flush = [&](bool force) {
    if (force || text.size() > (1u << 22)) {
      file.write(text);
      text.clear();
    }
  };
  for (const Vec3& v : mesh.vertices) {
    text += "v ";
    append(v.x);
    text += ' ';
    append(v.y);
    text += ' ';
    append(v.z);
    text += '\n';
    flush(false);
  }
  for (const Triangle& t : mesh.triangles) {
    text += "f ";
    append(t[0] + 1ull);
    text += ' ';
    append(t[1] + 1ull);
    text += ' ';
    append(t[2] + 1ull);
    text += '\n';
    flush(false);
  }
  flush(true);
  file.commit();
}

}  // namespace steady
