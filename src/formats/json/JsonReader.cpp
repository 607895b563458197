#include "formats/json/JsonReader.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "util/Error.hpp"

namespace rt {

namespace {

std::string describeType(const Json& value) {
  if (value.is_array()) return "an array of " + std::to_string(value.size());
  return value.type_name();
}

}  // namespace

const Json* findKey(const Json& object, std::string_view key) {
  if (!object.is_object()) return nullptr;
  const auto found = object.find(key);
  return found == object.end() ? nullptr : &*found;
}

std::string formatNumber(double value) {
  if (std::isfinite(value) && std::trunc(value) == value && std::fabs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

void JsonNode::failType(std::string_view expected) const {
  fail("expected " + std::string(expected) + ", got " + describeType(raw()));
}

double JsonNode::number() const {
  if (!raw().is_number()) failType("a number");
  const double value = raw().get<double>();
  if (!std::isfinite(value)) fail("expected a finite number");
  return value;
}

float JsonNode::floatValue() const {
  const double value = number();
  if (std::fabs(value) > std::numeric_limits<float>::max()) {
    fail("number " + formatNumber(value) + " is out of range");
  }
  return static_cast<float>(value);
}

float JsonNode::positiveFloat() const {
  const float value = floatValue();
  if (!(value > 0.0f)) fail("must be positive, got " + formatNumber(value));
  return value;
}

float JsonNode::nonNegativeFloat() const {
  const float value = floatValue();
  if (value < 0.0f) fail("must not be negative, got " + formatNumber(value));
  return value;
}

float JsonNode::floatInRange(float low, float high) const {
  const float value = floatValue();
  if (value < low || value > high) {
    fail("must be between " + formatNumber(low) + " and " + formatNumber(high) + ", got " +
         formatNumber(value));
  }
  return value;
}

int64_t JsonNode::integer() const {
  if (!raw().is_number()) failType("an integer");
  const double value = number();
  if (std::trunc(value) != value) fail("expected an integer, got " + formatNumber(value));
  // Beyond 2^53 doubles skip integers; no count in a scene file gets near that.
  constexpr double kLargestExact = 9007199254740992.0;
  if (std::fabs(value) > kLargestExact) fail("integer " + formatNumber(value) + " is out of range");
  return static_cast<int64_t>(value);
}

int64_t JsonNode::integer(int64_t low, int64_t high) const {
  const int64_t value = integer();
  if (value < low || value > high) {
    fail("must be between " + std::to_string(low) + " and " + std::to_string(high) + ", got " +
         std::to_string(value));
  }
  return value;
}

bool JsonNode::boolean() const {
  if (raw().is_boolean()) return raw().get<bool>();
  if (raw().is_number_integer()) {
    const auto value = raw().get<int64_t>();
    if (value == 0 || value == 1) return value == 1;
  }
  // Seanst98's "isGlass": "true": its author's parser compared strings.
  if (raw().is_string() && (raw() == "true" || raw() == "false")) return raw() == "true";
  failType("a boolean (true/false)");
}

std::string JsonNode::string() const {
  if (!raw().is_string()) failType("a string");
  return raw().get<std::string>();
}

std::string JsonNode::nonEmptyString() const {
  std::string text = string();
  if (text.empty()) fail("must not be an empty string");
  return text;
}

glm::vec3 JsonNode::vec3() const {
  if (!raw().is_array() || raw().size() != 3) failType("an array of 3 numbers");
  const std::vector<JsonNode> items = array();
  return {items[0].floatValue(), items[1].floatValue(), items[2].floatValue()};
}

glm::dvec3 JsonNode::point() const {
  if (!raw().is_array() || raw().size() != 3) failType("an array of 3 numbers");
  const std::vector<JsonNode> items = array();
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) {
    items[i].floatValue();  // the range check: relative to the camera it becomes a float
    out[i] = items[i].number();
  }
  return out;
}

glm::vec3 JsonNode::nonNegativeVec3() const {
  const glm::vec3 value = vec3();
  const std::vector<JsonNode> items = array();
  for (int i = 0; i < 3; ++i) {
    if (value[i] < 0.0f) items[i].fail("must not be negative, got " + formatNumber(value[i]));
  }
  return value;
}

std::vector<JsonNode> JsonNode::array() const {
  if (!raw().is_array()) failType("an array");
  std::vector<JsonNode> items;
  items.reserve(raw().size());
  for (size_t i = 0; i < raw().size(); ++i) {
    items.emplace_back(raw()[i], path_ + "[" + std::to_string(i) + "]", *diagnostics_);
  }
  return items;
}

JsonObject JsonNode::object() const {
  if (!raw().is_object()) failType("an object");
  return JsonObject(*this);
}

std::string JsonObject::childPath(std::string_view key) const {
  if (path().empty()) return std::string(key);
  return path() + "." + std::string(key);
}

bool JsonObject::has(std::string_view key) const { return node_.raw().contains(key); }

const Json* JsonObject::peek(std::string_view key) const {
  const auto found = node_.raw().find(key);
  return found == node_.raw().end() ? nullptr : &*found;
}

namespace {

// A value short enough to show in `raytracer check`: a scalar or a short
// list of scalars, else nothing (objects and meshes are shown by their keys).
std::optional<std::string> shownValue(const Json& value) {
  constexpr size_t kLongest = 60;
  if (value.is_object()) return std::nullopt;
  if (value.is_array()) {
    if (value.size() > 4) return std::nullopt;
    for (const Json& item : value) {
      if (item.is_structured()) return std::nullopt;
    }
  }
  std::string text = value.dump();
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "...";
  return text;
}

}  // namespace

std::optional<JsonNode> JsonObject::optional(std::string_view key) {
  const auto found = node_.raw().find(key);
  if (found == node_.raw().end()) return std::nullopt;
  if (read_.emplace(key).second) {
    if (std::optional<std::string> shown = shownValue(*found)) {
      diagnostics().noteRead(childPath(key), *shown);
    }
  }
  return JsonNode(*found, childPath(key), diagnostics());
}

JsonNode JsonObject::required(std::string_view key) {
  std::optional<JsonNode> node = optional(key);
  if (!node) diagnostics().fail(childPath(key), "missing required key");
  return *node;
}

std::optional<JsonNode> JsonObject::optionalOneOf(std::initializer_list<std::string_view> keys) {
  std::optional<JsonNode> chosen;
  for (std::string_view key : keys) {
    std::optional<JsonNode> node = optional(key);
    if (!node) continue;
    if (chosen) {
      node->fail("conflicts with '" + chosen->path() + "': give only one of these aliases");
    }
    chosen = std::move(node);
  }
  return chosen;
}

void JsonObject::ignore(std::initializer_list<std::string_view> keys) {
  for (std::string_view key : keys) {
    if (has(key)) read_.emplace(key);
  }
}

void JsonObject::ignoreWithWarning(std::string_view key, std::string_view why) {
  if (!has(key)) return;
  read_.emplace(key);
  diagnostics().warn(childPath(key), why);
}

// JSON has no comments; students write them as keys ("_comment": "floor",
// "//": "...", "comment"), which no renderer reads.
namespace {
bool isCommentKey(std::string_view key) {
  return key.starts_with('_') || key.starts_with("//") || key == "comment" || key == "comments";
}
}  // namespace

void JsonObject::reportUnknownKeys() {
  for (const auto& [key, value] : node_.raw().items()) {
    if (!read_.contains(key) && !isCommentKey(key)) {
      diagnostics().warn(childPath(key), "unknown key '" + key + "' ignored");
    }
  }
}

}  // namespace rt
