// The 3MF Beam Lattice extension v1.2, written as XML into the 3MF package (a zip) with libzip. Debian's lib3mf
// 1.8.1 cannot write it: it puts a non-standard `clipping` attribute where the specification has `clippingmode`,
// never writes the representation mesh, and has no balls (namespace b2 of v1.2).
#include <zip.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "mesh/hub_tessellation.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/output_file.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/mesh/mesh_files.hpp"

namespace steady {

namespace {

constexpr const char* kContentTypes =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">"
    "<Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>"
    "<Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>"
    "</Types>\n";
constexpr const char* kRelationships =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
    "<Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
    "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>"
    "</Relationships>\n";
// Lone balls (no beam) are not balls of the lattice (a ball must sit at a beam's end): they are tessellated into
// the object's triangles at this fraction of their radius.
constexpr double kLoneBallTolerance = 1e-3;
// The time stamp of the package's entries (2020-01-01 00:00 UTC).
constexpr time_t kPackageTime = 1577836800;

// XML text built in one string (about 60 bytes per beam).
class Xml {
 public:
  std::string text;
  Xml& operator<<(const char* s) {
    text += s;
    return *this;
  }
  Xml& operator<<(const std::string& s) {
    text += s;
    return *this;
  }
  template <class T>
  Xml& number(T v) {  // shortest text that reads back to the same value
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof(buffer), v);
    text.append(buffer, r.ptr);
    return *this;
  }
  template <class T>  // double, float (meshes that ride along) or std::uint64_t (indices)
  Xml& attribute(const char* name, T v) {
    text += ' ';
    text += name;
    text += "=\"";
    number(v);
    text += '"';
    return *this;
  }
};

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

void check_unit(const std::string& unit) {
  for (const char* u : {"micron", "millimeter", "centimeter", "inch", "foot", "meter"})
    if (unit == u) return;
  fail_input("unit", "'" + unit + "' is not a 3MF unit (micron, millimeter, centimeter, inch, foot, meter)");
}

// A <vertex>: the lattice's own at full precision, meshes that ride along as the floats 3MF readers hold.
template <class Real>
void vertex(Xml& x, const Vec3& v) {
  x << "<vertex";
  x.attribute("x", static_cast<Real>(v.x));
  x.attribute("y", static_cast<Real>(v.y));
  x.attribute("z", static_cast<Real>(v.z));
  x << "/>\n";
}

void triangles(Xml& x, const std::vector<Triangle>& list) {
  for (const Triangle& t : list) {
    x << "<triangle";
    x.attribute("v1", std::uint64_t(t[0]));
    x.attribute("v2", std::uint64_t(t[1]));
    x.attribute("v3", std::uint64_t(t[2]));
    x << "/>\n";
  }
}

void mesh_object(Xml& x, std::uint64_t id, const std::string& name, const TriangleMesh& mesh) {
  x << "<object";
  x.attribute("id", id);
  x << " type=\"model\" name=\"" << escaped(name) << "\"><mesh><vertices>\n";
  for (const Vec3& v : mesh.vertices) vertex<float>(x, v);
  x << "</vertices><triangles>\n";
  triangles(x, mesh.triangles);
  x << "</triangles></mesh></object>\n";
}

void zip_package(const std::string& path, const std::string& model) {
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) throw std::runtime_error("3mf: cannot create '" + path + "' (libzip error " + std::to_string(error) + ")");
  auto add = [&](const char* name, const char* data, std::size_t size) {
    zip_source_t* source = zip_source_buffer(zip, data, size, 0);
    const zip_int64_t index = source ? zip_file_add(zip, name, source, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE) : -1;
    if (index < 0) {
      if (source) zip_source_free(source);
      const std::string why = zip_strerror(zip);
      zip_discard(zip);
      throw std::runtime_error("3mf: cannot add " + std::string(name) + ": " + why);
    }
    // Fast deflate: the XML compresses about 4:1 at level 1, and level 6 costs several times the time for ~10 %.
    zip_set_file_compression(zip, static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 1);
    // A fixed time stamp: the same lattice gives the same bytes, whenever it is written.
    zip_file_set_mtime(zip, static_cast<zip_uint64_t>(index), kPackageTime, 0);
  };
  add("[Content_Types].xml", kContentTypes, std::strlen(kContentTypes));
  add("_rels/.rels", kRelationships, std::strlen(kRelationships));
  add("3D/3dmodel.model", model.data(), model.size());
  if (zip_close(zip) != 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    throw std::runtime_error("3mf: writing '" + path + "' failed: " + why);
  }
}

}  // namespace

BeamLatticeStats write_3mf_beam_lattice(const FlatLattice& f, const std::string& path, const BeamLatticeOptions& options,
                                        Progress& progress) {
  check_output_path(path);
  check_unit(options.unit);
  if (f.ball_count() == 0) fail_input("lattice", "has no balls");
  if (options.clipping && options.clipping->triangles.empty()) fail_input("clipping", "the clipping mesh has no triangles");
  if (options.clipping && !mesh_edge_report(*options.clipping).closed_manifold())
    fail_input("clipping", "the clipping mesh is not closed (3MF clips by a closed mesh's inside)");
  progress.set_total(100);
  const std::vector<BeamFrustum> frustums = beam_frustums(f);
  std::vector<char> has_beam(f.ball_count(), 0);
  std::vector<std::int64_t> written;
  double min_length = INFINITY;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    // A beam one of whose end balls contains the other adds nothing to its larger ball: not written.
    if (!frustums[e].cone.has_lateral_surface()) continue;
    written.push_back(e);
    has_beam[f.beams[e].a] = has_beam[f.beams[e].b] = 1;
    min_length = std::min(min_length, frustums[e].cone.length);
  }
  progress.advance(5);
  BeamLatticeStats stats;
  Xml x;
  x.text.reserve(96 * (written.size() + f.balls.size()) + 4096);
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<model unit=\"" << options.unit << "\" xml:lang=\"en-US\" "
       "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" "
       "xmlns:b=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/2017/02\" "
       "xmlns:b2=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/balls/2020/07\" "
       "requiredextensions=\"b b2\">\n"
       "<metadata name=\"Application\">LatticeWorkbench</metadata>\n<resources>\n";
  std::uint64_t next_id = 1, representation_id = 0, clipping_id = 0;
  if (options.representation) mesh_object(x, representation_id = next_id++, options.name + " (representation)", *options.representation);
  if (options.clipping) mesh_object(x, clipping_id = next_id++, options.name + " (clipping)", *options.clipping);
  const std::uint64_t lattice_id = next_id++;
  x << "<object";
  x.attribute("id", lattice_id);
  x << " type=\"model\" name=\"" << escaped(options.name) << "\"><mesh><vertices>\n";
  for (const Ball& b : f.balls) vertex<double>(x, b.center);
  // Lone balls as triangles: their sphere's vertices follow the balls'.
  TriangleMesh lone;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if (has_beam[i]) continue;
    ++stats.lone_balls;
    const HubTemplate sphere = tessellate_clean_hub({}, kLoneBallTolerance);
    const auto base = static_cast<std::uint32_t>(f.ball_count() + lone.vertices.size());
    for (const Vec3& p : sphere.vertices) lone.vertices.push_back(f.balls[i].center + f.balls[i].radius * p);
    for (const Triangle& t : sphere.triangles) lone.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  for (const Vec3& v : lone.vertices) vertex<double>(x, v);
  x << "</vertices><triangles>\n";
  triangles(x, lone.triangles);
  x << "</triangles>\n";
  progress.advance(5);
  if (!written.empty()) {
    x << "<b:beamlattice";
    x.attribute("minlength", 0.5 * min_length);
    x.attribute("radius", f.beams[written[0]].ra);
    if (clipping_id) {
      x << " clippingmode=\"inside\"";
      x.attribute("clippingmesh", clipping_id);
    }
    if (representation_id) x.attribute("representationmesh", representation_id);
    x << " cap=\"sphere\" b2:ballmode=\"mixed\"";
    x.attribute("b2:ballradius", f.balls[f.beams[written[0]].a].radius);
    x << ">\n<b:beams>\n";
    Progress part(progress, 40, static_cast<std::int64_t>(written.size()) + 1);
    for (std::size_t k = 0; k < written.size(); ++k) {
      const FlatBeam& b = f.beams[written[k]];
      x << "<b:beam";
      x.attribute("v1", std::uint64_t(b.a));
      x.attribute("v2", std::uint64_t(b.b));
      x.attribute("r1", b.ra);
      x.attribute("r2", b.rb);
      x << "/>\n";
      if (k % 65536 == 0) part.advance(65536);
    }
    x << "</b:beams>\n<b2:balls>\n";
    for (std::int64_t i = 0; i < f.ball_count(); ++i) {
      if (!has_beam[i]) continue;
      ++stats.balls;
      x << "<b2:ball";
      x.attribute("vindex", std::uint64_t(i));
      x.attribute("r", f.balls[i].radius);
      x << "/>\n";
    }
    x << "</b2:balls>\n</b:beamlattice>\n";
  }
  x << "</mesh></object>\n</resources>\n<build><item";
  x.attribute("objectid", lattice_id);
  x << "/></build>\n</model>\n";
  stats.vertices = f.ball_count() + static_cast<std::int64_t>(lone.vertices.size());
  stats.beams = static_cast<std::int64_t>(written.size());
  PartialFile file(path, false);
  zip_package(file.temporary_path(), x.text);
  file.commit();
  progress.finish();
  std::FILE* written_file = std::fopen(path.c_str(), "rb");
  if (written_file) {
    std::fseek(written_file, 0, SEEK_END);
    stats.bytes = static_cast<std::uint64_t>(std::ftell(written_file));
    std::fclose(written_file);
  }
  return stats;
}

}  // namespace steady
