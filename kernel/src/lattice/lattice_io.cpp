#include "steady/lattice/lattice_io.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "steady/core/errors.hpp"

namespace steady {
namespace {

using json = nlohmann::json;

// ---- reading, every accessor names the JSON path it reads --------------------------------------------

void refuse_unknown_keys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
  const std::set<std::string> ok(allowed.begin(), allowed.end());
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (!ok.count(it.key())) fail_input(path.empty() ? it.key() : path + "." + it.key(), "unknown field");
}

const json& member(const json& obj, const char* key, const std::string& path) {
  const std::string where = path.empty() ? key : path + "." + key;
  if (!obj.is_object()) fail_input(path.empty() ? "file" : path, "expected an object");
  auto it = obj.find(key);
  if (it == obj.end()) fail_input(where, "missing field");
  return *it;
}

double as_number(const json& value, const std::string& path) {
  if (!value.is_number()) fail_input(path, "expected a number");
  const double x = value.get<double>();
  require_finite(x, path);
  return x;
}

std::int64_t as_integer(const json& value, const std::string& path) {
  if (!value.is_number_integer()) fail_input(path, "expected an integer");
  return value.get<std::int64_t>();
}

int as_int(const json& value, const std::string& path) {
  const std::int64_t x = as_integer(value, path);
  if (x < -2147483647 || x > 2147483647) fail_input(path, "integer out of range");
  return static_cast<int>(x);
}

Vec3 as_vec3(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) fail_input(path, "expected an array of 3 numbers");
  return {as_number(value[0], path + "[0]"), as_number(value[1], path + "[1]"), as_number(value[2], path + "[2]")};
}

double number(const json& obj, const char* key, const std::string& path) {
  return as_number(member(obj, key, path), path + "." + key);
}
Vec3 vec3(const json& obj, const char* key, const std::string& path) {
  return as_vec3(member(obj, key, path), path + "." + key);
}
Vec3 vec3_or(const json& obj, const char* key, const std::string& path, const Vec3& fallback) {
  return obj.contains(key) ? vec3(obj, key, path) : fallback;
}

Frame read_frame(const json& value, const std::string& path) {
  refuse_unknown_keys(value, path, {"origin", "x", "y", "z"});
  Frame f{vec3(value, "origin", path), vec3(value, "x", path), vec3(value, "y", path), vec3(value, "z", path)};
  validate_frame(f, path.c_str());
  return f;
}

Similarity read_similarity(const json& value, const std::string& path, bool allow_control) {
  if (!value.is_object()) fail_input(path, "expected an object describing a similarity");
  const json& type_value = member(value, "type", path);
  if (!type_value.is_string()) fail_input(path + ".type", "expected a string");
  const std::string type = type_value.get<std::string>();
  auto allowed = [&](std::initializer_list<const char*> keys) {
    std::vector<const char*> all(keys);
    all.push_back("type");
    all.push_back("description");  // written for people, ignored when read
    if (allow_control) all.push_back("control");
    const std::set<std::string> ok(all.begin(), all.end());
    for (auto it = value.begin(); it != value.end(); ++it)
      if (!ok.count(it.key())) fail_input(path + "." + it.key(), "unknown field for a similarity of type '" + type + "'");
  };
  try {
    if (type == "generator") {
      allowed({"log_scale", "rotation_vector", "velocity"});
      return Similarity::from_generator(number(value, "log_scale", path), vec3(value, "rotation_vector", path),
                                        vec3(value, "velocity", path));
    }
    if (type == "identity") {
      allowed({});
      return Similarity::identity();
    }
    if (type == "translation") {
      allowed({"vector"});
      return Similarity::translation(vec3(value, "vector", path));
    }
    if (type == "rotation") {
      allowed({"angle", "axis", "point"});
      return Similarity::rotation(number(value, "angle", path), vec3(value, "axis", path),
                                  vec3_or(value, "point", path, Vec3(0.0)));
    }
    if (type == "screw") {
      allowed({"angle", "axis", "point", "distance"});
      return Similarity::screw(number(value, "angle", path), vec3(value, "axis", path),
                               vec3_or(value, "point", path, Vec3(0.0)), number(value, "distance", path));
    }
    if (type == "dilation") {
      allowed({"scale", "center"});
      return Similarity::dilation(number(value, "scale", path), vec3_or(value, "center", path, Vec3(0.0)));
    }
    if (type == "swirl") {
      allowed({"angle", "axis", "center", "scale"});
      return Similarity::swirl(number(value, "angle", path), vec3(value, "axis", path),
                               vec3_or(value, "center", path, Vec3(0.0)), number(value, "scale", path));
    }
    if (type == "frames") {
      allowed({"from", "to"});
      return Similarity::from_frames(read_frame(member(value, "from", path), path + ".from"),
                                     read_frame(member(value, "to", path), path + ".to"));
    }
  } catch (const InvalidInput& e) {
    const std::string msg = e.what();
    if (msg.rfind(path, 0) == 0) throw;  // already names the path
    throw InvalidInput(path + ": " + msg);
  }
  fail_input(path + ".type", "unknown similarity type '" + type +
                                 "' (expected generator, identity, translation, rotation, screw, dilation, swirl or frames)");
}

DirectionControl read_direction(const json& obj, const char* key) {
  const json& value = member(obj, key, "");
  DirectionControl d;
  d.similarity = read_similarity(value, key, true);
  if (value.contains("control")) {
    const json& c = value["control"];
    const std::string where = std::string(key) + ".control";
    if (!c.is_string()) fail_input(where, "expected \"incremental\" or \"cumulative\"");
    const std::string s = c.get<std::string>();
    if (s == "incremental") d.control = StepControl::Incremental;
    else if (s == "cumulative") d.control = StepControl::Cumulative;
    else fail_input(where, "expected \"incremental\" or \"cumulative\" (got \"" + s + "\")");
  }
  return d;
}

// ---- writing -----------------------------------------------------------------------------------------

json write_vec3(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

json write_similarity(const Similarity& s) {
  json j;
  j["type"] = "generator";
  j["log_scale"] = s.log_scale();
  j["rotation_vector"] = write_vec3(s.rotation_vector());
  j["velocity"] = write_vec3(s.velocity());
  j["description"] = s.describe();
  return j;
}

json write_direction(const DirectionControl& d) {
  json j = write_similarity(d.similarity);
  j["control"] = d.control == StepControl::Cumulative ? "cumulative" : "incremental";
  return j;
}

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
  j["counts"] = json::array({d.counts.u, d.counts.v, d.counts.w});
  j["U"] = write_direction(d.u);
  j["V"] = write_direction(d.v);
  j["W"] = write_direction(d.w);
  j["placement"] = write_similarity(d.placement);
  json omitted = json::array();
  for (const NodeId& id : d.omitted) omitted.push_back(json::array({id.i, id.j, id.k, id.n}));
  j["omitted"] = omitted;
  return j.dump(indent);
}

Lattice lattice_from_json(const std::string& text) {
  const json j = parse(text);
  if (!j.is_object()) fail_input("file", "expected a JSON object at the top level");
  refuse_unknown_keys(j, "", {"format", "version", "units", "name", "nodes", "beams", "counts", "U", "V", "W",
                              "placement", "omitted"});
  const json& format = member(j, "format", "");
  if (!format.is_string() || format.get<std::string>() != kLatticeFormatName)
    fail_input("format", std::string("expected \"") + kLatticeFormatName + "\"");
  const std::int64_t version = as_integer(member(j, "version", ""), "version");
  if (version != kLatticeFormatVersion)
    fail_input("version", "unsupported version " + std::to_string(version) + " (this build reads version " +
                              std::to_string(kLatticeFormatVersion) + ")");

  LatticeDefinition d;
  const json& nodes = member(j, "nodes", "");
  if (!nodes.is_array()) fail_input("nodes", "expected an array");
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const std::string path = "nodes[" + std::to_string(n) + "]";
    refuse_unknown_keys(nodes[n], path, {"center", "radius"});
    d.nodes.push_back({vec3(nodes[n], "center", path), number(nodes[n], "radius", path)});
  }
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
    d.beams.push_back(bp);
  }
  const json& counts = member(j, "counts", "");
  if (!counts.is_array() || counts.size() != 3) fail_input("counts", "expected an array of 3 integers");
  d.counts = {as_integer(counts[0], "counts.u"), as_integer(counts[1], "counts.v"), as_integer(counts[2], "counts.w")};
  d.u = read_direction(j, "U");
  d.v = read_direction(j, "V");
  d.w = read_direction(j, "W");
  if (j.contains("placement")) d.placement = read_similarity(j["placement"], "placement", false);
  if (j.contains("omitted")) {
    const json& om = j["omitted"];
    if (!om.is_array()) fail_input("omitted", "expected an array of [i, j, k, n]");
    for (std::size_t q = 0; q < om.size(); ++q) {
      const std::string path = "omitted[" + std::to_string(q) + "]";
      if (!om[q].is_array() || om[q].size() != 4) fail_input(path, "expected [i, j, k, n]");
      d.omitted.push_back({as_integer(om[q][0], path), as_integer(om[q][1], path), as_integer(om[q][2], path),
                           as_int(om[q][3], path)});
    }
  }
  return Lattice(std::move(d));
}

}  // namespace steady
