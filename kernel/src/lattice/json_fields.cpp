// JSON fields of the lattice file format, read with the path of each field in every refusal.
#include "lattice/json_fields.hpp"

#include <cstdint>
#include <set>

#include "steady/core/errors.hpp"

namespace steady::detail {

void refuse_unknown_keys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
  if (!obj.is_object()) fail_input(path.empty() ? "file" : path, "expected an object");
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
  if (value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX))
    fail_input(path, "integer out of range");
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

DirectionControl read_direction(const json& obj, const char* key, const std::string& path) {
  const json& value = member(obj, key, path);
  const std::string at = path.empty() ? key : path + "." + key;
  DirectionControl d;
  d.similarity = read_similarity(value, at, true);
  if (value.contains("control")) {
    const json& c = value["control"];
    const std::string where = at + ".control";
    if (!c.is_string()) fail_input(where, "expected \"incremental\" or \"cumulative\"");
    const std::string s = c.get<std::string>();
    if (s == "incremental") d.control = StepControl::Incremental;
    else if (s == "cumulative") d.control = StepControl::Cumulative;
    else fail_input(where, "expected \"incremental\" or \"cumulative\" (got \"" + s + "\")");
  }
  return d;
}

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

SteadyFields read_steady_fields(const json& obj, const std::string& path) {
  const std::string placement_path = path.empty() ? "placement" : path + ".placement";
  return {read_direction(obj, "U", path), read_direction(obj, "V", path), read_direction(obj, "W", path),
          obj.contains("placement") ? read_similarity(obj["placement"], placement_path, false) : Similarity::identity()};
}

json write_steady_fields(const SteadyFields& f) {
  return {{"U", write_direction(f.u)}, {"V", write_direction(f.v)}, {"W", write_direction(f.w)},
          {"placement", write_similarity(f.placement)}};
}

}  // namespace steady::detail
