// Binary STL: an 80-byte header, a 32-bit triangle count, then 50 bytes per triangle (normal, three corners as
// 32-bit floats, a 16-bit attribute), little-endian.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

#include "mesh/mesh_plan.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/output_file.hpp"
#include "steady/mesh/mesh_files.hpp"

namespace steady {

namespace {

constexpr std::size_t kRecordBytes = 50;
// Triangles computed and written at a time by the streamed writer: 4 MB buffers.
constexpr std::size_t kChunkTriangles = 1 << 16;

void put_record(char* out, const Vec3& a, const Vec3& b, const Vec3& c) {
  const glm::vec3 fa(a), fb(b), fc(c);
  glm::vec3 n = glm::cross(fb - fa, fc - fa);
  const float length = glm::length(n);
  n = length > 0.0f ? n / length : glm::vec3(0.0f);
  const float values[12] = {n.x, n.y, n.z, fa.x, fa.y, fa.z, fb.x, fb.y, fb.z, fc.x, fc.y, fc.z};
  std::memcpy(out, values, sizeof(values));
  out[48] = out[49] = 0;
}

void write_header(PartialFile& file, const std::string& name, std::uint64_t triangles) {
  if (triangles > 0xffffffffull)
    throw ResourceLimit("stl: " + std::to_string(triangles) +
                        " triangles exceed the 2^32 a binary STL can count: use a larger tolerance");
  char header[80] = {};
  const std::string text = "binary STL " + name;
  std::memcpy(header, text.data(), std::min<std::size_t>(text.size(), sizeof(header)));
  file.write(header, sizeof(header));
  const std::uint32_t count = static_cast<std::uint32_t>(triangles);
  file.write(&count, sizeof(count));
}

}  // namespace

void write_stl(const TriangleMesh& mesh, const std::string& path, const std::string& name) {
  PartialFile file(path);
  write_header(file, name, mesh.triangles.size());
  std::vector<char> buffer;
  for (std::size_t first = 0; first < mesh.triangles.size(); first += kChunkTriangles) {
    const std::size_t n = std::min(kChunkTriangles, mesh.triangles.size() - first);
    buffer.resize(n * kRecordBytes);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      const Triangle& t = mesh.triangles[first + i];
      put_record(buffer.data() + i * kRecordBytes, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    });
    file.write(buffer.data(), buffer.size());
  }
  file.commit();
}

TriangleMesh read_stl(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_input("path", "cannot read '" + path + "'");
  char header[80];
  std::uint32_t count = 0;
  in.read(header, sizeof(header));
  in.read(reinterpret_cast<char*>(&count), sizeof(count));
  in.seekg(0, std::ios::end);
  if (!in || static_cast<std::uint64_t>(in.tellg()) != 84 + static_cast<std::uint64_t>(count) * kRecordBytes)
    fail_input("path", "'" + path + "' is not a binary STL (its size does not match its triangle count)");
  in.seekg(84);
  TriangleMesh mesh;
  std::map<std::array<float, 3>, std::uint32_t> index;
  char record[kRecordBytes];
  for (std::uint32_t i = 0; i < count; ++i) {
    in.read(record, kRecordBytes);
    float v[12];
    std::memcpy(v, record, sizeof(v));
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      const std::array<float, 3> p{v[3 + 3 * k], v[4 + 3 * k], v[5 + 3 * k]};
      const auto [it, fresh] = index.emplace(p, static_cast<std::uint32_t>(mesh.vertices.size()));
      if (fresh) mesh.vertices.emplace_back(p[0], p[1], p[2]);
      t[k] = it->second;
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

LatticeMeshStats write_lattice_stl(const FlatLattice& lattice, const MeshOptions& options, const std::string& path,
                                   const std::string& name, Progress& progress) {
  check_output_path(path);
  progress.set_total(100);
  MeshPlan plan;
  {
    Progress part(progress, 30);
    plan = plan_lattice_mesh(lattice, options, part);
  }
  PartialFile file(path);
  write_header(file, name, plan.triangle_count);
  Progress part(progress, 70, static_cast<std::int64_t>(plan.triangle_count) + 1);
  std::vector<char> buffer;
  // Hubs, then strips, in runs of about kChunkTriangles triangles: each run computed in parallel, then written.
  auto run = [&](std::size_t count, auto first_triangle, auto fill) {
    std::size_t begin = 0;
    while (begin < count) {
      std::size_t end = begin;
      while (end < count && first_triangle(end + 1) - first_triangle(begin) <= kChunkTriangles) ++end;
      if (end == begin) ++end;
      const std::uint64_t base = first_triangle(begin);
      buffer.resize((first_triangle(end) - base) * kRecordBytes);
      tbb::parallel_for(begin, end, [&](std::size_t i) { fill(i, buffer.data() + (first_triangle(i) - base) * kRecordBytes); });
      file.write(buffer.data(), buffer.size());
      part.advance(static_cast<std::int64_t>(first_triangle(end) - base));
      begin = end;
    }
  };
  const std::size_t hubs = plan.hubs.size();
  const std::vector<MeshGroup>& groups = plan.groups.groups;
  auto group_first = [&](std::size_t g) { return g < groups.size() ? groups[g].first_triangle : plan.beam_first_triangle[0]; };
  auto hub_first = [&](std::size_t h) { return h < hubs ? plan.hubs[h].first_triangle : group_first(0); };
  run(hubs, hub_first, [&](std::size_t h, char* out) {
    if (plan.groups.of_hub[h] >= 0) return;  // in its group's mesh
    const HubTemplate& t = plan.templates[plan.hubs[h].templ];
    std::vector<Vec3> v(t.vertices.size());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = placed_vertex(plan, h, static_cast<std::uint32_t>(k));
    for (const Triangle& tri : t.triangles) {
      put_record(out, v[tri[0]], v[tri[1]], v[tri[2]]);
      out += kRecordBytes;
    }
  });
  run(groups.size(), group_first, [&](std::size_t g, char* out) {
    const TriangleMesh& m = groups[g].mesh;
    for (const Triangle& tri : m.triangles) {
      put_record(out, m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]]);
      out += kRecordBytes;
    }
  });
  auto beam_first = [&](std::size_t e) { return plan.beam_first_triangle[e]; };
  run(static_cast<std::size_t>(lattice.beam_count()), beam_first, [&](std::size_t e, char* out) {
    const std::size_t n = plan.beam_first_triangle[e + 1] - plan.beam_first_triangle[e];
    if (n == 0) return;
    std::vector<std::array<Vec3, 3>> corners(n);
    place_strip_corners(plan, static_cast<std::int64_t>(e), corners.data());
    for (const auto& c : corners) {
      put_record(out, c[0], c[1], c[2]);
      out += kRecordBytes;
    }
  });
  file.commit();
  progress.finish();
  return plan.stats;
}

}  // namespace steady
