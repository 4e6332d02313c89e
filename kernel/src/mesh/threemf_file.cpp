// Core 3MF through lib3mf's C interface (Debian's lib3mf 1.8.1), and reading any 3MF back with it.
#include <Model/COM/NMR_DLLInterfaces.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "steady/core/errors.hpp"
#include "steady/core/output_file.hpp"
#include "steady/mesh/mesh_files.hpp"
#include "steady/mesh/threemf_reader.hpp"

namespace steady {

namespace {

// One lib3mf object, released when it goes out of scope.
struct Handle3mf {
  NMR::PLib3MFBase* p = nullptr;
  Handle3mf() = default;
  Handle3mf(const Handle3mf&) = delete;
  Handle3mf& operator=(const Handle3mf&) = delete;
  ~Handle3mf() {
    if (p) NMR::lib3mf_release(p);
  }
};

void check(LIB3MFRESULT result, NMR::PLib3MFBase* instance, const std::string& what) {
  if (result == LIB3MF_OK) return;
  std::string message = "lib3mf: " + what + " failed";
  DWORD code = 0;
  LPCSTR text = nullptr;
  if (instance && NMR::lib3mf_getlasterror(instance, &code, &text) == LIB3MF_OK && text) message += std::string(": ") + text;
  throw std::runtime_error(message);
}

DWORD unit_code(const std::string& unit) {
  static const std::map<std::string, DWORD> codes = {
      {"micron", NMR::MODELUNIT_MICROMETER}, {"millimeter", NMR::MODELUNIT_MILLIMETER},
      {"centimeter", NMR::MODELUNIT_CENTIMETER}, {"inch", NMR::MODELUNIT_INCH},
      {"foot", NMR::MODELUNIT_FOOT}, {"meter", NMR::MODELUNIT_METER}};
  const auto it = codes.find(unit);
  if (it == codes.end())
    fail_input("unit", "'" + unit + "' is not a 3MF unit (micron, millimeter, centimeter, inch, foot, meter)");
  return it->second;
}

// A UUID of the production extension drawn from the mesh (FNV-1a over its name, vertices as written and
// triangles) and `which` (build, object, item), in the RFC 9562 custom form (version 8): lib3mf drew them at random,
// so two writes of one mesh differed.
std::string content_uuid(const std::string& name, const std::vector<NMR::MODELMESHVERTEX>& vertices,
                         const std::vector<NMR::MODELMESHTRIANGLE>& triangles, int which) {
  std::uint64_t h[2] = {1469598103934665603ULL ^ static_cast<std::uint64_t>(which), 0x9e3779b97f4a7c15ULL};
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      h[0] = (h[0] ^ c[i]) * 1099511628211ULL;
      h[1] = (h[1] ^ c[i] ^ (h[0] >> 29)) * 1099511628211ULL;
    }
  };
  mix(name.data(), name.size());
  mix(vertices.data(), vertices.size() * sizeof(NMR::MODELMESHVERTEX));
  mix(triangles.data(), triangles.size() * sizeof(NMR::MODELMESHTRIANGLE));
  h[0] = (h[0] & ~0xF000ULL) | 0x8000ULL;                      // version 8
  h[1] = (h[1] & 0x3FFFFFFFFFFFFFFFULL) | 0x8000000000000000ULL;  // variant 10
  char text[40];
  std::snprintf(text, sizeof text, "%08x-%04x-%04x-%04x-%012llx", static_cast<unsigned>(h[0] >> 32),
                static_cast<unsigned>((h[0] >> 16) & 0xFFFF), static_cast<unsigned>(h[0] & 0xFFFF),
                static_cast<unsigned>(h[1] >> 48), static_cast<unsigned long long>(h[1] & 0xFFFFFFFFFFFFULL));
  return text;
}

}  // namespace

void write_3mf(const TriangleMesh& mesh, const std::string& path, const ThreeMfOptions& options) {
  const DWORD unit = unit_code(options.unit);
  if (mesh.triangles.empty()) fail_input("mesh", "has no triangles");
  PartialFile file(path, false);
  Handle3mf model, object, item, writer;
  check(NMR::lib3mf_createmodel(&model.p), nullptr, "creating a model");
  check(NMR::lib3mf_model_setunit(model.p, unit), model.p, "setting the unit");
  check(NMR::lib3mf_model_addmeshobject(model.p, &object.p), model.p, "adding a mesh object");
  check(NMR::lib3mf_object_setnameutf8(object.p, options.name.c_str()), object.p, "naming the object");
  std::vector<NMR::MODELMESHVERTEX> vertices(mesh.vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[i].m_fPosition[k] = static_cast<float>(mesh.vertices[i][k]);
  std::vector<NMR::MODELMESHTRIANGLE> triangles(mesh.triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) triangles[i].m_nIndices[k] = mesh.triangles[i][k];
  check(NMR::lib3mf_meshobject_setgeometry(object.p, vertices.data(), static_cast<DWORD>(vertices.size()),
                                           triangles.data(), static_cast<DWORD>(triangles.size())),
        object.p, "setting the mesh");
  check(NMR::lib3mf_model_addbuilditem(model.p, object.p, nullptr, &item.p), model.p, "adding the build item");
  check(NMR::lib3mf_model_setbuilduuidutf8(model.p, content_uuid(options.name, vertices, triangles, 0).c_str()),
        model.p, "setting the build's UUID");
  check(NMR::lib3mf_object_setuuidutf8(object.p, content_uuid(options.name, vertices, triangles, 1).c_str()),
        object.p, "setting the object's UUID");
  check(NMR::lib3mf_builditem_setuuidutf8(item.p, content_uuid(options.name, vertices, triangles, 2).c_str()),
        item.p, "setting the build item's UUID");
  check(NMR::lib3mf_model_querywriter(model.p, "3mf", &writer.p), model.p, "getting a 3MF writer");
  check(NMR::lib3mf_writer_writetofileutf8(writer.p, file.temporary_path().c_str()), writer.p,
        "writing '" + path + "'");
  file.commit();
}

ThreeMfContents read_3mf(const std::string& path) {
  Handle3mf model, reader, objects;
  check(NMR::lib3mf_createmodel(&model.p), nullptr, "creating a model");
  check(NMR::lib3mf_model_queryreader(model.p, "3mf", &reader.p), model.p, "getting a 3MF reader");
  check(NMR::lib3mf_reader_readfromfileutf8(reader.p, path.c_str()), reader.p, "reading '" + path + "'");
  ThreeMfContents out;
  DWORD warnings = 0;
  check(NMR::lib3mf_reader_getwarningcount(reader.p, &warnings), reader.p, "counting warnings");
  for (DWORD w = 0; w < warnings; ++w) {
    DWORD code = 0;
    ULONG needed = 0;
    std::vector<wchar_t> text(1024, L'\0');
    if (NMR::lib3mf_reader_getwarning(reader.p, w, &code, text.data(), static_cast<ULONG>(text.size()), &needed) != LIB3MF_OK)
      continue;
    std::string message;
    for (const wchar_t* c = text.data(); *c; ++c) message += *c < 128 ? static_cast<char>(*c) : '?';
    out.warnings.push_back(message + " (code " + std::to_string(code) + ")");
  }
  DWORD unit = 0;
  check(NMR::lib3mf_model_getunit(model.p, &unit), model.p, "reading the unit");
  static const char* units[] = {"micron", "millimeter", "centimeter", "inch", "foot", "meter"};
  out.unit = unit < 6 ? units[unit] : "?";
  check(NMR::lib3mf_model_getmeshobjects(model.p, &objects.p), model.p, "listing mesh objects");
  for (;;) {
    BOOL more = false;
    check(NMR::lib3mf_resourceiterator_movenext(objects.p, &more), objects.p, "listing mesh objects");
    if (!more) break;
    Handle3mf object;
    check(NMR::lib3mf_resourceiterator_getcurrent(objects.p, &object.p), objects.p, "getting a mesh object");
    ThreeMfObject o;
    DWORD id = 0;
    check(NMR::lib3mf_resource_getresourceid(object.p, &id), object.p, "reading an id");
    o.id = id;
    ULONG needed = 0;
    check(NMR::lib3mf_object_getnameutf8(object.p, nullptr, 0, &needed), object.p, "reading a name");
    std::string name(needed + 1, '\0');
    check(NMR::lib3mf_object_getnameutf8(object.p, name.data(), needed + 1, &needed), object.p, "reading a name");
    o.name = name.c_str();
    DWORD nv = 0, nt = 0, nb = 0;
    check(NMR::lib3mf_meshobject_getvertexcount(object.p, &nv), object.p, "counting vertices");
    check(NMR::lib3mf_meshobject_gettrianglecount(object.p, &nt), object.p, "counting triangles");
    check(NMR::lib3mf_meshobject_getbeamcount(object.p, &nb), object.p, "counting beams");
    std::vector<NMR::MODELMESHVERTEX> vertices(nv);
    std::vector<NMR::MODELMESHTRIANGLE> triangles(nt);
    if (nv) check(NMR::lib3mf_meshobject_getvertices(object.p, vertices.data(), nv, nullptr), object.p, "reading vertices");
    if (nt)
      check(NMR::lib3mf_meshobject_gettriangleindices(object.p, triangles.data(), nt, nullptr), object.p,
            "reading triangles");
    for (const auto& v : vertices) o.mesh.vertices.emplace_back(v.m_fPosition[0], v.m_fPosition[1], v.m_fPosition[2]);
    for (const auto& t : triangles) o.mesh.triangles.push_back({t.m_nIndices[0], t.m_nIndices[1], t.m_nIndices[2]});
    for (DWORD b = 0; b < nb; ++b) {
      NMR::MODELMESHBEAM beam;
      check(NMR::lib3mf_meshobject_getbeam(object.p, b, &beam), object.p, "reading a beam");
      o.beams.push_back({beam.m_nIndices[0], beam.m_nIndices[1], beam.m_dRadius[0], beam.m_dRadius[1]});
    }
    if (nb) {
      check(NMR::lib3mf_meshobject_getbeamlattice_minlength(object.p, &o.min_length), object.p, "reading minlength");
      check(NMR::lib3mf_meshobject_getbeamlattice_radius(object.p, &o.default_radius), object.p, "reading radius");
    }
    out.objects.push_back(std::move(o));
  }
  return out;
}

}  // namespace steady
