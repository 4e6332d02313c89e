#include "steady/lattice/lattice_io.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "lattice/json_fields.hpp"
#include "lattice/layout_registry.hpp"
#include "steady/core/errors.hpp"

namespace steady {
namespace {

using json = nlohmann::json;
using namespace detail;

json parse(const std::string& text) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double range
    throw InvalidInput(std::string("file: not valid JSON (") + e.what() + ")");
  }
}

}  // namespace

std::string similarity_to_json(const Similarity& s) { return write_similarity(s).dump(2); }

Similarity similarity_from_json(const std::string& text) { return read_similarity(parse(text), "similarity", false); }

std::string lattice_to_json(const Lattice& lattice, int indent) {
  if (indent < -1 || indent > kMaxJsonIndent)
    fail_input("indent", "must be -1 (one line) to " + std::to_string(kMaxJsonIndent) + " (got " +
                             std::to_string(indent) + ")");
  const LatticeDefinition& d = lattice.definition();
  json j;
  j["format"] = kLatticeFormatName;
  j["version"] = kLatticeFormatVersion;
  json nodes = json::array();
  for (const TemplateNode& n : d.nodes) nodes.push_back({{"center", write_vec3(n.center)}, {"radius", n.radius}});
  j["nodes"] = nodes;
  json beams = json::array();
  for (const BeamPattern& b : d.beams) {
    json jb = {{"from", b.from}, {"offset", json::array({b.di, b.dj, b.dk})}, {"to", b.to}};
    if (b.has_radii()) jb["radii"] = json::array({*b.from_radius, *b.to_radius});
    beams.push_back(jb);
  }
  j["beams"] = beams;
  const Counts& c = lattice.counts();
  j["counts"] = json::array({c.u, c.v, c.w});
  const Layout& layout = lattice.layout();
  json l = layout_codec(layout.kind(), "layout.kind").write(layout);
  l["kind"] = layout.kind();
  j["layout"] = l;
  json omitted = json::array();
  for (const NodeId& id : d.omitted) omitted.push_back(json::array({id.i, id.j, id.k, id.n}));
  j["omitted"] = omitted;
  return j.dump(indent);
}

namespace {

std::vector<TemplateNode> read_nodes(const json& j) {
  std::vector<TemplateNode> out;
  const json& nodes = member(j, "nodes", "");
  if (!nodes.is_array()) fail_input("nodes", "expected an array");
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const std::string path = "nodes[" + std::to_string(n) + "]";
    refuse_unknown_keys(nodes[n], path, {"center", "radius"});
    out.push_back({vec3(nodes[n], "center", path), number(nodes[n], "radius", path)});
  }
  return out;
}

std::vector<BeamPattern> read_beams(const json& j) {
  std::vector<BeamPattern> out;
  const json& beams = member(j, "beams", "");
  if (!beams.is_array()) fail_input("beams", "expected an array");
  for (std::size_t p = 0; p < beams.size(); ++p) {
    const std::string path = "beams[" + std::to_string(p) + "]";
    const json& b = beams[p];
    refuse_unknown_keys(b, path, {"from", "offset", "to", "radii"});
    BeamPattern bp;
    bp.from = as_int(member(b, "from", path), path + ".from");
    bp.to = as_int(member(b, "to", path), path + ".to");
    const json& off = member(b, "offset", path);
    if (!off.is_array() || off.size() != 3) fail_input(path + ".offset", "expected an array of 3 integers");
    bp.di = as_int(off[0], path + ".offset[0]");
    bp.dj = as_int(off[1], path + ".offset[1]");
    bp.dk = as_int(off[2], path + ".offset[2]");
    if (b.contains("radii")) {
      const json& r = b["radii"];
      if (!r.is_array() || r.size() != 2) fail_input(path + ".radii", "expected an array of 2 numbers");
      bp.from_radius = as_number(r[0], path + ".radii[0]");
      bp.to_radius = as_number(r[1], path + ".radii[1]");
    }
    out.push_back(bp);
  }
  return out;
}

Counts read_counts(const json& j) {
  const json& counts = member(j, "counts", "");
  if (!counts.is_array() || counts.size() != 3) fail_input("counts", "expected an array of 3 integers");
  return {as_integer(counts[0], "counts.u"), as_integer(counts[1], "counts.v"), as_integer(counts[2], "counts.w")};
}

std::vector<NodeId> read_omitted(const json& j) {
  std::vector<NodeId> out;
  if (!j.contains("omitted")) return out;
  const json& om = j["omitted"];
  if (!om.is_array()) fail_input("omitted", "expected an array of [i, j, k, n]");
  for (std::size_t q = 0; q < om.size(); ++q) {
    const std::string path = "omitted[" + std::to_string(q) + "]";
    if (!om[q].is_array() || om[q].size() != 4) fail_input(path, "expected [i, j, k, n]");
    out.push_back({as_integer(om[q][0], path), as_integer(om[q][1], path), as_integer(om[q][2], path),
                   as_int(om[q][3], path)});
  }
  return out;
}

// Version 2: the layout in its own section, {"kind": ..., fields of that kind}.
LayoutPtr read_layout(const json& j, const Counts& counts) {
  const json& l = member(j, "layout", "");
  if (!l.is_object()) fail_input("layout", "expected an object with a \"kind\"");
  const json& kind = member(l, "kind", "layout");
  if (!kind.is_string()) fail_input("layout.kind", "expected a string");
  return layout_codec(kind.get<std::string>(), "layout.kind").read(l, counts, "layout");
}

}  // namespace

Lattice lattice_from_json(const std::string& text) {
  const json j = parse(text);
  if (!j.is_object()) fail_input("file", "expected a JSON object at the top level");
  const json& format = member(j, "format", "");
  if (!format.is_string() || format.get<std::string>() != kLatticeFormatName)
    fail_input("format", std::string("expected \"") + kLatticeFormatName + "\"");
  const std::int64_t version = as_integer(member(j, "version", ""), "version");
  if (version != 1 && version != kLatticeFormatVersion)
    fail_input("version", "unsupported version " + std::to_string(version) + " (this build reads versions 1 to " +
                              std::to_string(kLatticeFormatVersion) + ")");
  // Version 1 had the steady brick's fields at the top level; version 2 has a layout section.
  if (version == 1)
    refuse_unknown_keys(j, "", {"format", "version", "units", "name", "nodes", "beams", "counts", "U", "V", "W",
                                "placement", "omitted"});
  else
    refuse_unknown_keys(j, "", {"format", "version", "units", "name", "nodes", "beams", "counts", "layout", "omitted"});

  LatticeDefinition d;
  d.nodes = read_nodes(j);
  d.beams = read_beams(j);
  const Counts counts = read_counts(j);
  if (version == 1) {
    const SteadyFields f = read_steady_fields(j, "");
    d.layout = SteadyBrickLayout::make(counts, f.u, f.v, f.w, f.placement);
  } else {
    d.layout = read_layout(j, counts);
  }
  d.omitted = read_omitted(j);
  return Lattice(std::move(d));
}

}  // namespace steady
