#include "formats/json/BlenderExport.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "formats/common/QuadCorners.hpp"
#include "formats/common/UnitVector.hpp"
#include "formats/json/ReferencedFiles.hpp"
#include "scene/Limits.hpp"
#include "util/Text.hpp"

namespace rt {

namespace fs = std::filesystem;

namespace {

// Blender's defaults where an exporter left a value out: its default
// camera (50 mm lens, 36 x 24 mm sensor), render size, point light power
// and world colour, and the Principled BSDF's base colour and roughness.
constexpr double kDefaultFocalLengthMm = 50.0;
constexpr double kDefaultSensorWidthMm = 36.0;
constexpr double kDefaultSensorHeightMm = 24.0;
constexpr uint32_t kDefaultWidth = 1920;
constexpr uint32_t kDefaultHeight = 1080;
constexpr float kDefaultLightWatts = 1000.0f;
constexpr float kWorldGrey = 0.050876f;
constexpr float kDefaultBaseColor = 0.8f;
constexpr float kDefaultRoughness = 0.5f;
// Blinn-Phong weight of the highlight where a file gives only a roughness
// (the coursework readers' textbook 0.2).
constexpr float kDefaultKs = 0.2f;

// ------------------------------------------------------------- recognition

// A list of Blender objects, one of them a camera ({"type": "CAMERA", ...}).
bool listsBlenderCamera(const Json* objects) {
  return objects && objects->is_array() &&
         std::any_of(objects->begin(), objects->end(), [](const Json& object) {
           const Json* type = findKey(object, "type");
           return type && type->is_string() && *type == "CAMERA";
         });
}

// Objects grouped by Blender type: {"CAMERA": {"PERSP": ...}} or
// {"Camera": {"Perspective": [...]}} (kailen-hargenrader).
bool groupsByBlenderType(const Json& document) {
  for (const char* key : {"CAMERA", "Camera", "MESH", "Mesh", "LIGHT", "Light"}) {
    const Json* group = findKey(document, key);
    if (group && group->is_object() && !group->contains("location")) return true;
  }
  return false;
}

// ------------------------------------------------------------------ values

// Three numbers of an object by key: {"x", "y", "z"} or {"roll", "pitch", "yaw"}.
glm::dvec3 readKeyedTriple(const JsonNode& node, const char* first, const char* second,
                           const char* third) {
  JsonObject object = node.object();
  const glm::dvec3 v(object.required(first).number(), object.required(second).number(),
                     object.required(third).number());
  object.reportUnknownKeys();
  return v;
}

// [x, y, z] or {"x", "y", "z"}.
glm::dvec3 readVector(const JsonNode& node) {
  if (!node.raw().is_object()) return node.point();
  return readKeyedTriple(node, "x", "y", "z");
}

// Euler angles in radians: [x, y, z], {"x", "y", "z"} or {"roll", "pitch", "yaw"}.
glm::dvec3 readEuler(const JsonNode& node) {
  if (!node.raw().is_object() || !node.raw().contains("roll")) return readVector(node);
  return readKeyedTriple(node, "roll", "pitch", "yaw");
}

// One number (uniform) or three.
glm::dvec3 readScale(const JsonNode& node) {
  if (node.raw().is_number()) return glm::dvec3(node.number());
  return readVector(node);
}

// [r, g, b] (a fourth number, alpha, unused). Whole numbers above 1 are
// 8-bit values (James-h-1969's base_colour).
glm::vec3 readColorArray(const JsonNode& node) {
  const std::vector<JsonNode> channels = node.array();
  if (channels.size() != 3 && channels.size() != 4) {
    node.fail("expected 3 colour channels (or 4 with alpha), got " +
              std::to_string(channels.size()));
  }
  glm::vec3 rgb;
  bool eightBit = false;
  for (int i = 0; i < 3; ++i) {
    rgb[i] = channels[i].nonNegativeFloat();
    eightBit = eightBit || (rgb[i] > 1.0f && channels[i].raw().is_number_integer());
  }
  if (channels.size() == 4) channels[3].floatValue();  // alpha: checked, unused
  return eightBit ? rgb / 255.0f : rgb;
}

// readColorArray's forms, {"r", "g", "b"} or {"type": "RGB", "value": [...]}.
glm::vec3 readColor(const JsonNode& node) {
  if (!node.raw().is_object()) return readColorArray(node);
  JsonObject color = node.object();
  glm::vec3 rgb;
  if (color.has("value")) {
    color.optional("type");
    rgb = readColorArray(color.required("value"));
  } else {
    rgb = glm::vec3(color.required("r").nonNegativeFloat(), color.required("g").nonNegativeFloat(),
                    color.required("b").nonNegativeFloat());
    color.optional("a");
  }
  color.reportUnknownKeys();
  return rgb;
}

// ----------------------------------------------------------------- records

enum class Kind { Camera, Light, Sphere, Cube, Plane, Cylinder, Metaball };

const char* kindName(Kind kind) {
  switch (kind) {
    case Kind::Camera: return "camera";
    case Kind::Light: return "light";
    case Kind::Sphere: return "sphere";
    case Kind::Cube: return "cube";
    case Kind::Plane: return "plane";
    case Kind::Cylinder: return "cylinder";
    case Kind::Metaball: return "metaball";
  }
  return "object";
}

// A Blender mesh's kind from a name such as "Cube.001", "SPHERE" or "UV Sphere".
std::optional<Kind> meshKindNamed(std::string name) {
  name = lowercase(std::move(name));
  if (const size_t dot = name.find('.'); dot != std::string::npos) name.resize(dot);
  name.erase(std::remove(name.begin(), name.end(), ' '), name.end());
  if (name.rfind("cube", 0) == 0 || name == "box") return Kind::Cube;
  if (name.find("sphere") != std::string::npos || name == "ball") return Kind::Sphere;
  if (name.rfind("plane", 0) == 0 || name == "quad" || name == "floor") return Kind::Plane;
  if (name.rfind("cylinder", 0) == 0) return Kind::Cylinder;
  return std::nullopt;
}

struct Record {
  Kind kind;
  JsonNode node;
};

// The kind of one element of an `objects` list or a bare list:
// {"type": "CAMERA" | "LIGHT" | "MESH" | "META" | "Cube" | ...}, a mesh's
// kind from its `shape` key, a sub-object (`sphere`, `cube`, `plane`:
// DDTTYYSS) or its name.
std::optional<Kind> objectKind(const Json& object) {
  const Json* type = findKey(object, "type");
  const std::string written = type && type->is_string() ? lowercase(type->get<std::string>()) : "";
  if (written == "camera") return Kind::Camera;
  if (written == "light" || written == "lamp") return Kind::Light;
  if (written == "meta") return Kind::Metaball;
  if (written != "mesh") return meshKindNamed(written);
  if (const Json* shape = findKey(object, "shape"); shape && shape->is_string()) {
    return meshKindNamed(shape->get<std::string>());
  }
  for (Kind kind : {Kind::Sphere, Kind::Cube, Kind::Plane, Kind::Cylinder}) {
    if (const Json* detail = findKey(object, kindName(kind)); detail && detail->is_object()) {
      return kind;
    }
  }
  const Json* name = findKey(object, "name");
  return name && name->is_string() ? meshKindNamed(name->get<std::string>()) : std::nullopt;
}

void addObjectList(const JsonNode& list, std::vector<Record>& out) {
  for (const JsonNode& element : list.array()) {
    if (!element.raw().is_object()) element.fail("expected a Blender object");
    if (const std::optional<Kind> kind = objectKind(element.raw())) {
      out.push_back({*kind, element});
    } else {
      const Json* type = findKey(element.raw(), "type");
      element.warn("a Blender object of type " + (type ? type->dump() : std::string("(none)")) +
                   " this renderer does not read: left out");
    }
  }
}

// The records of one kind: a list, or an object of records keyed by id.
void addRecords(const JsonNode& node, Kind kind, std::vector<Record>& out) {
  if (node.raw().is_array()) {
    for (const JsonNode& element : node.array()) out.push_back({kind, element});
    return;
  }
  const std::string base = node.path();
  for (const auto& [id, value] : node.raw().items()) {
    out.push_back({kind, JsonNode(value, base + "." + id, node.diagnostics())});
  }
  node.object();  // checks that it is an object
}

// {"CAMERA": {"PERSP": {...}}, "LIGHT": {"POINT": ...}, "MESH": {"Cube": ...}}:
// the second level names the camera, light or mesh kind.
void addGroupedRecords(JsonObject& top, std::vector<Record>& out) {
  for (const char* key : {"CAMERA", "Camera", "LIGHT", "Light", "MESH", "Mesh"}) {
    const std::optional<JsonNode> group = top.optional(key);
    if (!group) continue;
    const bool meshes = lowercase(key) == "mesh";
    const Kind groupKind = lowercase(key) == "camera" ? Kind::Camera : Kind::Light;
    JsonObject kinds = group->object();
    for (const auto& [name, value] : group->raw().items()) {
      const JsonNode members = *kinds.optional(name);
      const std::string written = lowercase(name);
      if (!meshes) {
        if (written != "persp" && written != "perspective" && written != "point") {
          members.warn("read as a perspective camera or a point light");
        }
        addRecords(members, groupKind, out);
      } else if (const std::optional<Kind> kind = meshKindNamed(name)) {
        addRecords(members, *kind, out);
      } else {
        members.warn("a mesh this renderer does not read: left out");
      }
    }
  }
}

// Every record of the document, in file order within each layout.
std::vector<Record> collectRecords(const JsonNode& root, JsonObject* top) {
  std::vector<Record> records;
  if (!top) {
    addObjectList(root, records);
    return records;
  }
  std::optional<JsonObject> properties;
  if (const std::optional<JsonNode> node = top->optional("properties")) properties = node->object();
  JsonObject& lists = properties ? *properties : *top;
  const std::pair<const char*, Kind> listKeys[] = {
      {"cameras", Kind::Camera},    {"point_lights", Kind::Light}, {"lights", Kind::Light},
      {"spheres", Kind::Sphere},    {"cubes", Kind::Cube},         {"planes", Kind::Plane},
      {"cylinders", Kind::Cylinder}};
  for (const auto& [key, kind] : listKeys) {
    if (const std::optional<JsonNode> list = lists.optional(key)) addRecords(*list, kind, records);
  }
  if (const std::optional<JsonNode> camera = top->optional("camera")) {
    records.push_back({Kind::Camera, *camera});
  }
  if (const std::optional<JsonNode> objects = top->optional("objects")) {
    addObjectList(*objects, records);
  }
  addGroupedRecords(*top, records);
  if (properties) properties->reportUnknownKeys();
  return records;
}

// One record's keys, looked up in the record and then in the sub-object
// some exporters put the kind's own values in (`camera_properties`,
// DDTTYYSS's `camera`, `light`, `cube`, `sphere`, `plane`).
class RecordFields {
 public:
  explicit RecordFields(const Record& record)
      : main_(record.node.object()), path_(record.node.path()) {
    const char* detailKeys[] = {"camera_properties", kindName(record.kind)};
    for (const char* key : detailKeys) {
      const Json* detail = findKey(record.node.raw(), key);
      if (detail && detail->is_object()) {
        detail_ = main_.required(key).object();
        detail_->ignore({"clip_start", "clip_end"});
        break;
      }
    }
    if (const std::optional<JsonNode> name = main_.optionalOneOf({"name"})) label_ = name->string();
    // What the record is, already decided by collectRecords; ids and
    // Blender's clipping and shift have no effect on the image here.
    main_.ignore({"type", "shape", "id", "clip_start", "clip_end", "rotation_mode"});
  }

  std::optional<JsonNode> find(std::initializer_list<std::string_view> keys) {
    if (std::optional<JsonNode> node = main_.optionalOneOf(keys)) return node;
    return detail_ ? detail_->optionalOneOf(keys) : std::nullopt;
  }
  void ignore(std::initializer_list<std::string_view> keys) {
    main_.ignore(keys);
    if (detail_) detail_->ignore(keys);
  }
  void warnIgnored(std::string_view key, std::string_view why) {
    main_.ignoreWithWarning(key, why);
    if (detail_) detail_->ignoreWithWarning(key, why);
  }
  void finish() {
    main_.reportUnknownKeys();
    if (detail_) detail_->reportUnknownKeys();
  }
  void warn(std::string_view what) const { main_.diagnostics().warn(path_, what); }
  [[noreturn]] void fail(std::string_view what) const { main_.fail(what); }
  const std::string& path() const { return path_; }
  const std::string& label() const { return label_; }

 private:
  JsonObject main_;
  std::optional<JsonObject> detail_;
  std::string path_;
  std::string label_;
};

// --------------------------------------------------------------- placement

// Blender's XYZ Euler rotation: x first, then y, then z, about world axes.
glm::dmat4 eulerRotation(const glm::dvec3& radians) {
  return glm::rotate(glm::dmat4(1.0), radians.z, {0, 0, 1}) *
         glm::rotate(glm::dmat4(1.0), radians.y, {0, 1, 0}) *
         glm::rotate(glm::dmat4(1.0), radians.x, {1, 0, 0});
}

std::optional<JsonNode> findPosition(RecordFields& fields) {
  return fields.find({"location", "translation", "position"});
}
std::optional<JsonNode> findRotation(RecordFields& fields) {
  return fields.find({"rotation", "rotation_euler", "rotation_euler_rad", "rotation_euler_radians",
                      "rotationEuler", "rotation_euler_xyz_radians"});
}
std::optional<JsonNode> findScale(RecordFields& fields) {
  return fields.find({"scale", "scale_1d", "uniform_scale"});
}

// Translation x rotation x scale of a Blender object; what is missing is
// Blender's identity.
struct Placement {
  glm::dvec3 translation{0.0};
  glm::dmat4 rotation{1.0};
  glm::dvec3 scale{1.0};
  glm::dmat4 matrix() const {
    return glm::translate(glm::dmat4(1.0), translation) * rotation *
           glm::scale(glm::dmat4(1.0), scale);
  }
};

Placement readPlacement(RecordFields& fields) {
  Placement placement;
  if (std::optional<JsonNode> at = findPosition(fields)) placement.translation = readVector(*at);
  if (std::optional<JsonNode> turn = findRotation(fields)) {
    placement.rotation = eulerRotation(readEuler(*turn));
  }
  if (std::optional<JsonNode> size = findScale(fields)) placement.scale = readScale(*size);
  fields.ignore({"uniform_scale"});  // DDTTYYSS: the mean of the scale beside it
  fields.ignore({"rotationQuat", "rotation_quaternion"});  // the same turn as the Euler angles
  return placement;
}

bool isUniform(const glm::dvec3& scale) {
  const double largest = std::max({std::abs(scale.x), std::abs(scale.y), std::abs(scale.z)});
  return std::abs(std::abs(scale.x) - largest) <= 1e-6 * largest &&
         std::abs(std::abs(scale.y) - largest) <= 1e-6 * largest &&
         std::abs(std::abs(scale.z) - largest) <= 1e-6 * largest;
}

// ---------------------------------------------------------------- the scene

class BlenderSceneReader {
 public:
  BlenderSceneReader(const fs::path& file, Diagnostics& diagnostics)
      : sceneDir_(absoluteFolderOf(file)), diagnostics_(diagnostics) {}

  Scene read(const JsonNode& root) {
    scene_.backgroundColor = glm::vec3(kWorldGrey);
    std::optional<JsonObject> top;
    if (root.raw().is_object()) top = root.object();
    std::optional<JsonObject> render;
    if (top) {
      if (std::optional<JsonNode> node = top->optional("render")) render = node->object();
      top->ignore({"scene_name", "scene", "notes", "frame"});
    }
    const std::vector<Record> records = collectRecords(root, top ? &*top : nullptr);
    bool cameraRead = false;
    for (const Record& record : records) {
      if (record.kind == Kind::Camera) {
        if (cameraRead) {
          diagnostics_.warn(record.node.path(), "another camera: not used (the first one is)");
          continue;
        }
        readCamera(record, render ? &*render : nullptr);
        cameraRead = true;
      } else if (record.kind == Kind::Light) {
        readLight(record);
      } else {
        readShape(record);
      }
    }
    if (!cameraRead) useDefaultCamera();
    if (scene_.pointLights.empty() && scene_.areaLights.empty()) {
      diagnostics_.warn("", "no lights: only the world colour shows");
    }
    if (render) render->reportUnknownKeys();
    if (top) top->reportUnknownKeys();
    return std::move(scene_);
  }

 private:
  // ------------------------------------------------------------- camera

  // Blender's startup scene's camera, where a file has none
  // (kailen-hargenrader's exports of lights or planes alone).
  void useDefaultCamera() {
    diagnostics_.warn("", "no camera: Blender's default camera (at 7.36, -6.93, 4.96, 50 mm)");
    Camera& camera = scene_.camera;
    camera.position = {7.3589, -6.9258, 4.9583};
    const glm::dmat4 turn = eulerRotation(glm::radians(glm::dvec3(63.559, 0.0, 46.692)));
    camera.forward = glm::vec3(turn * glm::dvec4(0, 0, -1, 0));
    camera.up = glm::vec3(turn * glm::dvec4(0, 1, 0, 0));
    camera.width = kDefaultWidth;
    camera.height = kDefaultHeight;
    camera.fovYDegrees =
        verticalFovDegrees(kDefaultFocalLengthMm, kDefaultSensorWidthMm, kDefaultSensorHeightMm,
                           "auto", kDefaultWidth, kDefaultHeight);
  }

  // Blender's sensor fit: AUTO fits the sensor width to the image's longer
  // side, HORIZONTAL to its width, VERTICAL the sensor height to its height.
  static float verticalFovDegrees(double focal, double sensorWidth, double sensorHeight,
                                  const std::string& fit, uint32_t width, uint32_t height) {
    const double aspect = double(height) / double(width);
    const bool vertical = fit == "vertical" || (fit == "auto" && height > width);
    const double sensor = fit == "vertical" ? sensorHeight : sensorWidth;
    const double halfTan = sensor / (2.0 * focal);
    const double verticalHalfTan = vertical ? halfTan : halfTan * aspect;
    return static_cast<float>(glm::degrees(2.0 * std::atan(verticalHalfTan)));
  }

  static std::optional<glm::uvec2> readResolution(RecordFields& fields) {
    const std::optional<JsonNode> node =
        fields.find({"film_resolution", "resolution", "resolution_px", "filmResolution", "film"});
    if (!node) return std::nullopt;
    if (node->raw().is_object()) {
      JsonObject size = node->object();
      const std::optional<JsonNode> w = size.optionalOneOf({"x", "width"});
      const std::optional<JsonNode> h = size.optionalOneOf({"y", "height"});
      if (!w || !h) node->fail("expected {\"x\", \"y\"} or {\"width\", \"height\"}");
      size.reportUnknownKeys();
      return glm::uvec2(w->integer(1, kMaxImageSide), h->integer(1, kMaxImageSide));
    }
    const std::vector<JsonNode> sides = node->array();
    if (sides.size() != 2) node->fail("expected [width, height]");
    return glm::uvec2(sides[0].integer(1, kMaxImageSide), sides[1].integer(1, kMaxImageSide));
  }

  // A top-level {"render": {"resolution_x", "resolution_y", "resolution_percentage"}}.
  static std::optional<glm::uvec2> readRenderResolution(JsonObject& render) {
    const std::optional<JsonNode> w = render.optional("resolution_x");
    const std::optional<JsonNode> h = render.optional("resolution_y");
    if (!w || !h) return std::nullopt;
    double percent = 100.0;
    if (std::optional<JsonNode> p = render.optional("resolution_percentage")) {
      percent = p->floatInRange(1.0f, 10000.0f);
    }
    const auto side = [&](const JsonNode& n) {
      const double pixels = std::round(double(n.integer(1, kMaxImageSide)) * percent / 100.0);
      return static_cast<uint32_t>(std::clamp(pixels, 1.0, double(kMaxImageSide)));
    };
    return glm::uvec2(side(*w), side(*h));
  }

  static double positiveNumber(RecordFields& fields, std::initializer_list<std::string_view> keys,
                               double fallback) {
    const std::optional<JsonNode> node = fields.find(keys);
    return node ? node->positiveFloat() : fallback;
  }

  void readCamera(const Record& record, JsonObject* render) {
    RecordFields fields(record);
    Camera& camera = scene_.camera;
    const Placement placement = readPlacement(fields);
    camera.position = placement.translation;
    // A Blender camera looks down its local -z with local +y up.
    glm::vec3 forward = glm::vec3(placement.rotation * glm::dvec4(0, 0, -1, 0));
    glm::vec3 up = glm::vec3(placement.rotation * glm::dvec4(0, 1, 0, 0));
    const bool turned = placement.rotation != glm::dmat4(1.0);
    if (std::optional<JsonNode> gaze =
            fields.find({"gaze_vector", "gaze", "gaze_vector_direction", "direction", "gaze_dir_ws",
                         "gaze_direction"})) {
      forward = glm::vec3(readVector(*gaze));
      if (!normalizeInPlace(forward)) gaze->fail("the gaze vector has no direction");
      if (!turned) up = {0, 0, 1};  // Blender's world up
    }
    if (std::optional<JsonNode> upNode = fields.find({"up_vector", "up", "up_ws"})) {
      up = glm::vec3(readVector(*upNode));
    }
    // Hand-written files in y-up style (Anna1021) look down -z with no up.
    if (glm::length(glm::cross(forward, up)) < 1e-4f * glm::length(up)) up = {0, 1, 0};
    camera.forward = forward;
    camera.up = up;
    std::optional<glm::uvec2> size = readResolution(fields);
    if (!size && render) size = readRenderResolution(*render);
    if (!size) {
      fields.warn("no film resolution: Blender's default 1920 x 1080");
      size = glm::uvec2(kDefaultWidth, kDefaultHeight);
    }
    camera.width = size->x;
    camera.height = size->y;
    const double focal =
        positiveNumber(fields, {"focal_length", "focal_length_mm", "focalLengthMM", "lens"},
                       kDefaultFocalLengthMm);
    double sensorWidth = kDefaultSensorWidthMm, sensorHeight = kDefaultSensorHeightMm;
    if (std::optional<JsonNode> sensor = fields.find({"sensor"})) {
      JsonObject both = sensor->object();
      sensorWidth = both.required("width").positiveFloat();
      sensorHeight = both.required("height").positiveFloat();
      both.reportUnknownKeys();
    }
    sensorWidth =
        positiveNumber(fields, {"sensor_width", "sensor_width_mm", "sensorWidthMM"}, sensorWidth);
    sensorHeight = positiveNumber(fields, {"sensor_height", "sensor_height_mm", "sensorHeightMM"},
                                  sensorHeight);
    std::string fit = "auto";
    if (std::optional<JsonNode> node = fields.find({"sensor_fit"})) fit = lowercase(node->string());
    camera.fovYDegrees =
        verticalFovDegrees(focal, sensorWidth, sensorHeight, fit, camera.width, camera.height);
    if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 179.0f)) {
      fields.fail("the focal length and sensor give no usable field of view");
    }
    if (std::optional<JsonNode> lens = fields.find({"lens_type", "camera_type"});
        lens && lowercase(lens->string()) != "persp") {
      lens->warn("read as a perspective camera");
    }
    for (const char* shift : {"shift_x", "shift_y"}) {
      if (std::optional<JsonNode> node = fields.find({shift}); node && node->number() != 0.0) {
        node->warn("lens shift is not read: the image is centred");
      }
    }
    // Image right is Blender's: local +x, forward x up (the physical conventions').
    fields.ignore(
        {"right_ws", "pixel_aspect", "resolution_percentage", "material_base_color_rgb", "scale"});
    fields.finish();
  }

  // -------------------------------------------------------------- lights

  // Blender's light power P in watts is a radiant intensity of P / (4 pi)
  // W/sr; under the physical conventions an intensity I lights like I / 4
  // W/sr (README "Conventions"), so I = P / pi. `id`/`is` (James-h-1969's
  // later exporter) are already P / (4 pi).
  void readLight(const Record& record) {
    RecordFields fields(record);
    PointLight light;
    const std::optional<JsonNode> position = findPosition(fields);
    if (!position) fields.fail("missing 'location'");
    light.position = readVector(*position);
    glm::vec3 color(1.0f);
    if (std::optional<JsonNode> node = fields.find({"color", "colour"})) color = readColor(*node);
    const std::optional<JsonNode> diffuse = fields.find({"id"});
    const std::optional<JsonNode> specular = fields.find({"is"});
    if (diffuse && specular && diffuse->raw().is_number()) {
      light.diffuseIntensity = color * (4.0f * diffuse->nonNegativeFloat());
      light.specularIntensity = color * (4.0f * specular->nonNegativeFloat());
    } else {
      float watts = kDefaultLightWatts;
      if (std::optional<JsonNode> power = fields.find(
              {"radiant_intensity", "radiantIntensity", "intensity", "power", "energy", "watts"})) {
        watts = power->nonNegativeFloat();
      } else {
        fields.warn("no light power: Blender's default 1000 W");
      }
      light.diffuseIntensity = light.specularIntensity = color * (watts / glm::pi<float>());
    }
    if (std::optional<JsonNode> kind = fields.find({"kind", "light_type"});
        kind && lowercase(kind->string()) != "point") {
      kind->warn("read as a point light");
    }
    fields.ignore({"rotation_euler_radians", "rotation", "scale", "material_base_color_rgb"});
    const std::optional<JsonNode> radius = fields.find({"radius", "shadow_soft_size"});
    fields.finish();
    if (radius && radius->nonNegativeFloat() > 0.0f) {
      addSphereLight(light, radius->positiveFloat(), fields.label());
    } else {
      scene_.pointLights.push_back(light);
    }
  }

  // A point light with a radius (Blender's soft shadows): a spherical area
  // light of the same power.
  void addSphereLight(const PointLight& point, float radius, const std::string& label) {
    AreaLight light;
    light.shape =
        addEmitterShape(scene_, Sphere{point.position, radius}, label.empty() ? "light" : label);
    light.diffuseIntensity = point.diffuseIntensity;
    light.specularIntensity = point.specularIntensity;
    scene_.areaLights.push_back(light);
  }

  // ------------------------------------------------------------ materials

  uint32_t addMaterial(Material material) {
    scene_.materials.push_back(std::move(material));
    return static_cast<uint32_t>(scene_.materials.size() - 1);
  }

  // Roughness r as a Blinn-Phong exponent: 2 / a^2 - 2 with a = r^2, the
  // exponent whose lobe is about as wide as a Beckmann lobe of that width.
  static float exponentOfRoughness(float roughness) {
    const float alpha = std::max(roughness * roughness, 0.01f);
    return std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
  }

  void readTexture(const JsonNode& node, Material& out) {
    if (node.raw().is_null() || node.raw() == "") return;
    if (node.raw().is_object()) {
      JsonObject texture = node.object();
      texture.optional("type");
      const JsonNode path = *texture.optionalOneOf({"path", "absolute_path", "file"});
      texture.reportUnknownKeys();
      readTextureFile(path, sceneDir_, out, scene_);
      return;
    }
    readTextureFile(node, sceneDir_, out, scene_);
  }

  // A material's keys, in its `material` object or (Omur1ce's
  // `material_base_color_rgb`, Zhuohao's `base_color` and `texture`) on the
  // shape itself.
  Material readMaterial(RecordFields& shape) {
    Material out;
    out.diffuseColor = glm::vec3(kDefaultBaseColor);
    out.kd = 1.0f;
    out.ks = kDefaultKs;
    out.specularExponent = exponentOfRoughness(kDefaultRoughness);
    std::optional<JsonObject> material;
    if (std::optional<JsonNode> node = shape.find({"material"}); node && !node->raw().is_null()) {
      material = node->object();
    }
    auto find = [&](std::initializer_list<std::string_view> keys) {
      std::optional<JsonNode> node = material ? material->optionalOneOf(keys) : std::nullopt;
      return node ? node : shape.find(keys);
    };
    bool colored = false;
    if (std::optional<JsonNode> base =
            find({"diffuse_color", "diffuse", "base_color", "base_colour", "baseColor",
                  "material_base_color_rgb", "color", "colour"})) {
      if (base->raw().is_object() && base->raw().contains("path")) {
        readTexture(*base, out);  // kailen's {"type": "ImageTexture", "path"}
      } else if (!base->raw().is_null()) {
        out.diffuseColor = readColor(*base);
        colored = true;
      }
    }
    if (std::optional<JsonNode> kd = find({"kd", "k_diffuse"})) {
      if (kd->raw().is_number()) {
        out.kd = kd->nonNegativeFloat();
      } else {
        out.diffuseColor = readColor(*kd);  // Omur1ce: kd is the colour
        colored = true;
      }
    }
    readSpecular(find, out);
    if (std::optional<JsonNode> mirror = find({"reflectivity", "reflectance"})) {
      out.reflectivity = mirror->floatInRange(0.0f, 1.0f);
    }
    if (std::optional<JsonNode> clear =
            find({"transparency", "transparancy", "transmissive", "transmission"})) {
      out.transmission = clear->floatInRange(0.0f, 1.0f);
    } else if (std::optional<JsonNode> alpha = find({"alpha"})) {
      out.transmission = 1.0f - alpha->floatInRange(0.0f, 1.0f);
    }
    if (std::optional<JsonNode> ior = find({"ior", "refractive_index", "refractiveIndex"})) {
      out.ior = ior->positiveFloat();
    }
    if (std::optional<JsonNode> texture = find({"texture", "texture_file", "texture_path"})) {
      readTexture(*texture, out);
    }
    // A texture multiplies the colour where both are given (James-h-1969).
    out.textureTintedByColor = colored;
    if (material) {
      material->ignore({"k_ambient", "ka", "uv_scale", "uv_offset", "name"});
      material->ignoreWithWarning("metallic", "no metal model here: read as a dielectric");
      material->reportUnknownKeys();
    }
    shape.ignore({"uv_scale", "uv_offset"});
    return out;
  }

  template <typename Find>
  static void readSpecular(Find& find, Material& out) {
    bool weighted = false;
    if (std::optional<JsonNode> ks = find({"ks", "k_specular"})) {
      if (ks->raw().is_number()) {
        out.ks = ks->nonNegativeFloat();
        weighted = true;
      } else {
        out.specularColor = readColor(*ks);  // Omur1ce: ks is the colour
        out.ks = 1.0f;
      }
    }
    if (std::optional<JsonNode> color = find({"specular_color", "specular"})) {
      out.specularColor = readColor(*color);
      if (!weighted) out.ks = 1.0f;
    }
    if (std::optional<JsonNode> exponent = find({"shininess", "specular_exponent", "exponent"})) {
      out.specularExponent = std::max(exponent->nonNegativeFloat(), 1.0f);
    } else if (std::optional<JsonNode> roughness = find({"roughness"})) {
      out.specularExponent = exponentOfRoughness(roughness->floatInRange(0.0f, 1.0f));
    }
  }

  // --------------------------------------------------------------- shapes

  void readShape(const Record& record) {
    RecordFields fields(record);
    Shape shape;
    shape.geometry = readGeometry(record.kind, fields);
    shape.material = addMaterial(readMaterial(fields));
    shape.label = fields.label();
    shape.origin = record.node.path();
    if (std::optional<JsonNode> velocity = fields.find({"velocity"})) {
      velocity->warn("motion blur is not read: the shape is drawn where it starts");
    }
    fields.finish();
    scene_.shapes.push_back(std::move(shape));
  }

  Geometry readGeometry(Kind kind, RecordFields& fields) {
    switch (kind) {
      case Kind::Sphere:
      case Kind::Metaball: return readSphere(kind, fields);
      case Kind::Cube: return MeshInstance{cubeMesh(), readPlacement(fields).matrix()};
      case Kind::Plane: return readPlane(fields);
      case Kind::Cylinder: return readCylinder(fields);
      case Kind::Camera:
      case Kind::Light: break;
    }
    fields.fail("not a shape");
  }

  // A UV sphere of radius `radius` or 1 x scale; a non-uniform scale makes
  // it an ellipsoid, drawn as a mesh.
  Geometry readSphere(Kind kind, RecordFields& fields) {
    if (kind == Kind::Metaball) fields.warn("a metaball: drawn as a sphere of radius 1 x scale");
    if (std::optional<JsonNode> radius = fields.find({"radius"})) {
      const Placement placement = readPlacement(fields);
      return Sphere{placement.translation, radius->positiveFloat()};
    }
    const Placement placement = readPlacement(fields);
    if (isUniform(placement.scale)) {
      const auto radius = static_cast<float>(std::abs(placement.scale.x));
      if (!(radius > 0.0f)) fields.fail("a sphere of scale 0");
      return Sphere{placement.translation, radius};
    }
    return MeshInstance{sphereMesh(), placement.matrix()};
  }

  // Four corners, around the plane or in Blender's vertex order (-,-),
  // (+,-), (-,+), (+,+); or Blender's plane, 2 x 2 in its xy, placed.
  Geometry readPlane(RecordFields& fields) {
    if (std::optional<JsonNode> corners = fields.find({"corners", "corners_world", "corners_ws"})) {
      const std::vector<JsonNode> points = corners->array();
      if (points.size() != 4) {
        corners->fail("expected 4 corners, got " + std::to_string(points.size()));
      }
      Quad quad{readVector(points[0]), readVector(points[1]), readVector(points[2]),
                readVector(points[3])};
      fields.ignore({"location", "translation", "rotation", "rotation_euler_radians", "scale",
                     "rotation_euler_rad", "normal"});
      return cornersAroundTheQuad(quad);
    }
    const glm::dmat4 placed = readPlacement(fields).matrix();
    auto corner = [&](double x, double y) { return WorldPoint(placed * glm::dvec4(x, y, 0, 1)); };
    return Quad{corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1)};
  }

  // Blender's cylinder: radius 1 and depth 2 along its local z, placed;
  // `radius` and `length`/`depth` (kailen-hargenrader) where given.
  Cylinder readCylinder(RecordFields& fields) {
    const Placement placement = readPlacement(fields);
    Cylinder cylinder;
    cylinder.center = placement.translation;
    cylinder.axis = glm::normalize(glm::vec3(placement.rotation * glm::dvec4(0, 0, 1, 0)));
    const double sx = std::abs(placement.scale.x), sy = std::abs(placement.scale.y);
    if (std::abs(sx - sy) > 1e-3 * std::max(sx, sy)) {
      fields.warn("an elliptic cylinder: drawn round, with the mean of its x and y scales");
    }
    cylinder.radius = static_cast<float>(0.5 * (sx + sy));
    cylinder.halfHeight = static_cast<float>(std::abs(placement.scale.z));
    if (std::optional<JsonNode> radius = fields.find({"radius"}))
      cylinder.radius = radius->positiveFloat();
    if (std::optional<JsonNode> length = fields.find({"length", "depth", "height"})) {
      cylinder.halfHeight = 0.5f * length->positiveFloat();
    }
    if (!(cylinder.radius > 0.0f && cylinder.halfHeight > 0.0f))
      fields.fail("a cylinder of size 0");
    return cylinder;
  }

  // Blender's default cube, [-1, 1]^3, each face with the whole texture.
  uint32_t cubeMesh() {
    if (cube_) return *cube_;
    TriangleMesh mesh;
    for (int axis = 0; axis < 3; ++axis) {
      for (float side : {-1.0f, 1.0f}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const auto first = static_cast<uint32_t>(mesh.positions.size());
        for (glm::vec2 corner :
             {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
          glm::vec3 p(0.0f);
          p[axis] = side;
          p[u] = 2.0f * corner.x - 1.0f;
          p[v] = 2.0f * corner.y - 1.0f;
          mesh.positions.push_back(p);
          mesh.uvs.push_back(corner);
        }
        mesh.faces.emplace_back(first, first + 1, first + 2);
        mesh.faces.emplace_back(first, first + 2, first + 3);
      }
    }
    cube_ = addMesh(std::move(mesh));
    return *cube_;
  }

  // A unit UV sphere for ellipsoids, with smooth normals and Blender's UVs.
  uint32_t sphereMesh() {
    if (sphere_) return *sphere_;
    constexpr uint32_t kSegments = 64, kRings = 32;
    TriangleMesh mesh;
    for (uint32_t ring = 0; ring <= kRings; ++ring) {
      const float theta = glm::pi<float>() * float(ring) / kRings;
      for (uint32_t segment = 0; segment <= kSegments; ++segment) {
        const float phi = 2.0f * glm::pi<float>() * float(segment) / kSegments;
        const glm::vec3 p(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
        mesh.positions.push_back(p);
        mesh.normals.push_back(p);
        mesh.uvs.emplace_back(float(segment) / kSegments, 1.0f - float(ring) / kRings);
      }
    }
    for (uint32_t ring = 0; ring < kRings; ++ring) {
      for (uint32_t segment = 0; segment < kSegments; ++segment) {
        const uint32_t a = ring * (kSegments + 1) + segment, b = a + kSegments + 1;
        if (ring > 0) mesh.faces.emplace_back(a, b, a + 1);
        if (ring + 1 < kRings) mesh.faces.emplace_back(a + 1, b, b + 1);
      }
    }
    sphere_ = addMesh(std::move(mesh));
    return *sphere_;
  }

  uint32_t addMesh(TriangleMesh mesh) {
    scene_.meshes.push_back(std::move(mesh));
    return static_cast<uint32_t>(scene_.meshes.size() - 1);
  }

  fs::path sceneDir_;
  Diagnostics& diagnostics_;
  Scene scene_;
  std::optional<uint32_t> cube_, sphere_;
};

}  // namespace

bool looksLikeBlenderExport(const Json& document) {
  if (listsBlenderCamera(&document)) return true;
  if (!document.is_object()) return false;
  if (groupsByBlenderType(document)) return true;
  const Json* camera = findKey(document, "camera");
  if (!camera) {
    const Json* properties = findKey(document, "properties");
    return document.contains("cameras") || listsBlenderCamera(findKey(document, "objects")) ||
           (properties && properties->is_object() && properties->contains("cameras"));
  }
  return camera->is_object() && camera->contains("location") && !camera->contains("position") &&
         (camera->contains("gaze") || camera->contains("gaze_vector"));
}

Scene readBlenderExport(const Json& document, const fs::path& file, Diagnostics& diagnostics) {
  const JsonNode root(document, "", diagnostics);
  Scene scene = BlenderSceneReader(file, diagnostics).read(root);
  scene.sourcePath = file;
  scene.fileKind = "a Blender scene export (JSON)";
  setConventions(scene, Conventions::Physical,
                 "a Blender scene export: Blender's units (light power in watts, inverse-square "
                 "falloff)");
  return scene;
}

}  // namespace rt
