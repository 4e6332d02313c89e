#pragma once
// Internal to the lattice family: reading and writing the fields of the lattice file format (nlohmann JSON).
// Every reader names the JSON path of what it refuses ("U.control: expected ...").
#include <nlohmann/json.hpp>

#include <cstdint>
#include <initializer_list>
#include <string>

#include "steady/core/frame.hpp"
#include "steady/core/similarity.hpp"
#include "steady/lattice/steady_brick_layout.hpp"

namespace steady::detail {

using json = nlohmann::json;

void refuse_unknown_keys(const json& obj, const std::string& path, std::initializer_list<const char*> allowed);
// The member `key` of an object; path is the object's own path ("" at the top level).
const json& member(const json& obj, const char* key, const std::string& path);
double as_number(const json& value, const std::string& path);
std::int64_t as_integer(const json& value, const std::string& path);
int as_int(const json& value, const std::string& path);
Vec3 as_vec3(const json& value, const std::string& path);
double number(const json& obj, const char* key, const std::string& path);
Vec3 vec3(const json& obj, const char* key, const std::string& path);
Vec3 vec3_or(const json& obj, const char* key, const std::string& path, const Vec3& fallback);
Frame read_frame(const json& value, const std::string& path);
// A similarity in any of the file format's forms; `allow_control` admits a direction's "control" field.
Similarity read_similarity(const json& value, const std::string& path, bool allow_control);
// A direction (similarity and control) at obj[key].
DirectionControl read_direction(const json& obj, const char* key, const std::string& path);

// The fields a steady brick is written with, in every layout built on one: "U", "V", "W" (directions with
// their control) and "placement" (optional when read).
struct SteadyFields {
  DirectionControl u, v, w;
  Similarity placement;
};
SteadyFields read_steady_fields(const json& obj, const std::string& path);
json write_steady_fields(const SteadyFields& fields);

json write_vec3(const Vec3& v);
// By its generator (exact), with a description for people.
json write_similarity(const Similarity& s);
json write_direction(const DirectionControl& d);

}  // namespace steady::detail
