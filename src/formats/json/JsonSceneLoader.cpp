#include "formats/json/JsonSceneLoader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <memory>
#include <system_error>

#include "formats/SceneFile.hpp"
#include "formats/common/FileBytes.hpp"
#include "formats/common/JsonSyntax.hpp"
#include "formats/common/MessageText.hpp"
#include "formats/common/ModelFraming.hpp"
#include "formats/common/QuadCorners.hpp"
#include "formats/common/SceneTextures.hpp"
#include "formats/common/UnitVector.hpp"
#include "formats/gltf/GltfLoader.hpp"
#include "formats/json/BlenderExport.hpp"
#include "formats/json/JsonReader.hpp"
#include "formats/json/NamedMaterials.hpp"
#include "formats/json/ReferencedFiles.hpp"
#include "formats/obj/ObjLoader.hpp"
#include "formats/ply/PlyLoader.hpp"
#include "scene/Limits.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

namespace rt {

namespace fs = std::filesystem;

namespace {

// Family B files may omit nbounces.
constexpr uint32_t kDefaultBounces = 4;
// |sin| of the angle below which up and forward give no usable image plane.
constexpr float kParallelTolerance = 1e-4f;

// The 2019 family-A file has no position/lookat/up. Its spheres sit at
// z = 0.4 and 0.7 in front of the origin, so look down +z with y up.
constexpr glm::dvec3 kDefaultPosition{0.0, 0.0, 0.0};
constexpr glm::vec3 kDefaultForward{0.0f, 0.0f, 1.0f};
constexpr glm::vec3 kDefaultUp{0.0f, 1.0f, 0.0f};

// What shape reading needs besides the JSON itself.
struct ShapeContext {
  fs::path sceneDir;  // absolute folder of the scene file, for texture and mesh paths
  RenderMode mode;
  std::map<fs::path, uint32_t> plyMeshes;  // Scene::meshes index of each PLY file read
  NamedMaterials namedMaterials;           // a `materials` list's, by name (isaacery)
};

// ---------------------------------------------------------------- JSON text

// Some students' parsers skip // and /* */ comments, which JSON lacks: such
// a file is read with a warning. Any other syntax error is reported as the
// plain JSON parse sees it.
Json parseJson(std::string_view text, const std::string& file, Diagnostics& diagnostics) {
  return withJsonSyntaxErrors(file, text, [&] {
    try {
      return Json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error&) {
      Json withComments = Json::parse(text.begin(), text.end(), nullptr, false, true);
      if (withComments.is_discarded()) throw;
      diagnostics.warn("", "comments (// or /* */) are not JSON; skipped");
      return withComments;
    }
  });
}

// Camera keys that say where it looks; without any, chooseDefaultView decides.
constexpr std::array<const char*, 6> kViewKeys = {"lookat", "lookAt",  "look_at",
                                                  "target", "camView", "cameraToWorld"};

// ---------------------------------------------------------- family detection

bool anyElement(const Json* array, bool (*predicate)(const Json&)) {
  return array && array->is_array() && std::any_of(array->begin(), array->end(), predicate);
}

// TsFreddie's renderer (metallic/transmit/roughness materials) lit its
// scenes with the textbook conventions: no falloff, per-channel Blinn-Phong,
// no ambient; its reference renders in ../shared match only that reading.
bool isTsFreddieMaterial(const Json& material) {
  return findKey(material, "metallic") || findKey(material, "transmit") ||
         findKey(material, "roughness");
}

bool hasTsFreddieMaterial(const Json& shape) {
  const Json* material = findKey(shape, "material");
  return material && isTsFreddieMaterial(*material);
}

bool isFamilyBShape(const Json& shape) {
  const Json* type = findKey(shape, "type");
  if (type && *type == "cylinder") return true;
  const Json* material = findKey(shape, "material");
  return material && (findKey(*material, "specularcolor") || findKey(*material, "isreflective") ||
                      findKey(*material, "isrefractive"));
}

bool hasIntensity(const Json& light) { return findKey(light, "intensity") != nullptr; }

struct ChosenConventions {
  Conventions conventions;
  std::string reason;
};

// The conventions a file asks for with `conventions`, else those of the
// family its keys belong to:
//  - family B ("Rendering", 2023-24): a top-level `rendermode`; a camera
//    `lookAt` (without family A's `up`), `upVector` or `exposure` (family A
//    writes `lookat` and `up` and has no exposure); or lights with `intensity` beside family-B
//    shape keys (a cylinder, material `specularcolor`/`isreflective`/`isrefractive`). `intensity`
//    alone decides nothing: the family-A 2019 file uses it too;
//  - TsFreddie's renderer (`intensity` lights beside metallic/transmit/
//    roughness materials): textbook;
//  - everything else is family A ("Path of Light").
// Which keys are read does not depend on the choice.
ChosenConventions chooseConventions(JsonObject& top, const Json& root) {
  if (const std::optional<JsonNode> named = top.optional("conventions")) {
    const std::string name = named->string();
    const std::optional<Conventions> conventions = conventionsNamed(name);
    if (!conventions) {
      named->fail("unknown conventions '" + name +
                  "' (expected \"coursework-a\", \"coursework-b\", \"textbook\" or \"physical\")");
    }
    return {*conventions, "the scene's 'conventions' key"};
  }
  if (findKey(root, "rendermode")) return {Conventions::CourseworkB, "family B key 'rendermode'"};
  if (const Json* camera = findKey(root, "camera")) {
    for (const char* key : {"lookAt", "upVector", "exposure"}) {
      // nizqleo's files pair `lookAt` with family A's `up`, and its renders
      // put image right along forward x up, as family A does.
      if (findKey(*camera, key) && !(std::string_view(key) == "lookAt" && findKey(*camera, "up"))) {
        return {Conventions::CourseworkB, std::string("family B key 'camera.") + key + "'"};
      }
    }
  }
  if (const Json* scene = findKey(root, "scene")) {
    const Json* shapes = findKey(*scene, "shapes");
    if (anyElement(findKey(*scene, "lightsources"), hasIntensity)) {
      if (anyElement(shapes, hasTsFreddieMaterial)) {
        return {Conventions::Textbook,
                "TsFreddie's materials (metallic/transmit/roughness) with 'intensity' lights"};
      }
      if (anyElement(shapes, isFamilyBShape)) {
        return {Conventions::CourseworkB,
                "'intensity' lights with family B shapes (cylinder or family B material keys)"};
      }
    }
  }
  return {Conventions::CourseworkA, "no family B key (family A, Path of Light)"};
}

// The first of `keys` present; when none is, a warning that `taken` is used.
std::optional<JsonNode> optionalOrDefault(JsonObject& object,
                                          std::initializer_list<std::string_view> keys,
                                          std::string_view taken) {
  std::optional<JsonNode> node = object.optionalOneOf(keys);
  if (!node) {
    object.diagnostics().warn(object.childPath(*keys.begin()),
                              "missing; taken as " + std::string(taken));
  }
  return node;
}

// ----------------------------------------------------------------- settings

// Settings of the students' own renderers: accepted so their files load; no effect here.
void ignoreRendererKeys(JsonObject& object) {
  object.ignore({"bvh", "BVH", "use_bvh", "useBVH", "output", "FramesNum"});
}

// Render mode spellings (any case).
RenderMode readRenderMode(JsonObject& top) {
  const std::optional<JsonNode> node =
      top.optionalOneOf({"rendermode", "render_mode", "renderMode"});
  if (!node) return top.has("path_sample_num") ? RenderMode::PathTracer : RenderMode::Phong;
  const std::string mode = lowercase(node->string());
  if (mode == "binary") return RenderMode::Binary;
  if (mode == "phong" || mode == "whitted" || mode == "blinnphong" || mode == "blinn-phong") {
    return RenderMode::Phong;
  }
  for (const char* name : {"pathtracer", "pathtracing", "path", "pathtrace", "pathtraced",
                           "path_tracer", "path_tracing", "path-tracer", "path-tracing"}) {
    if (mode == name) return RenderMode::PathTracer;
  }
  node->fail("unknown rendermode '" + node->string() +
             "' (expected \"binary\", \"phong\" or \"pathtracer\")");
}

uint32_t readBounces(JsonObject& top) {
  const std::optional<JsonNode> node = top.optional("nbounces");
  return node ? static_cast<uint32_t>(node->integer(0, kMaxBounces)) : kDefaultBounces;
}

// The mixed mode's second depth (the seed report's "distributed ray bounce"):
// sampled diffuse bounces on top of the Whitted tree. The path tracer
// counts every bounce against nbounces instead.
uint32_t readDistributedBounces(JsonObject& top, RenderMode mode) {
  const std::optional<JsonNode> node =
      top.optionalOneOf({"distributedbounces", "ndistributedbounces", "distributed_bounces"});
  if (!node) return 0;
  const auto bounces = static_cast<uint32_t>(node->integer(0, kMaxBounces));
  if (mode == RenderMode::PathTracer && bounces > 0) {
    node->warn("ignored: the path tracer's paths are nbounces long");
  }
  return bounces;
}

float readIndirectClamp(JsonObject& top) {
  const std::optional<JsonNode> node = top.optionalOneOf({"clampindirect", "clamp_indirect"});
  return node ? node->nonNegativeFloat() : 0.0f;
}

SamplerKind parseSampler(const JsonNode& node) {
  const std::string name = node.string();
  if (std::optional<SamplerKind> kind = samplerKindNamed(name)) return *kind;
  node.fail("unknown sampler '" + name + "' (expected \"random\", \"jittered\" or \"sobol\")");
}

uint32_t parseSampleCount(const JsonNode& node) {
  return static_cast<uint32_t>(node.integer(1, kMaxSamplesPerPixel));
}

// Students put sampling keys at the top level or in the camera. Either place is
// fine; both is fine only when they agree.
template <typename Parse>
auto readFromEither(const std::optional<JsonNode>& first, const std::optional<JsonNode>& second,
                    Parse parse) -> std::optional<decltype(parse(*first))> {
  if (!first && !second) return std::nullopt;
  if (!first) return parse(*second);
  const auto value = parse(*first);
  if (second && parse(*second) != value) {
    second->fail("conflicts with '" + first->path() + "': give the setting once");
  }
  return value;
}

// The sampler's key: `sampler` | `method`, or `sampling` where it names one
// (Seanst98: "jittering"; a number there, as Zspirates96 writes, is not).
std::optional<JsonNode> samplerKey(JsonObject& object) {
  const Json* sampling = object.peek("sampling");
  if (sampling && sampling->is_string() && !object.has("sampler") && !object.has("method")) {
    return object.optional("sampling");
  }
  return object.optionalOneOf({"sampler", "method"});
}

// Returns whether the file names a sampler.
bool readSampling(JsonObject& top, JsonObject& camera, RenderSettings& settings) {
  const auto samplesAt = [](JsonObject& object) {
    // `camera samples`: Trenza1ore; `sample_number`: IrwinChay; `samplesize`: Vergilc.
    return object.optionalOneOf({"nsamples", "samples", "spp", "pixel_sample_num",
                                 "samples_per_pixel", "camera samples", "sample_number",
                                 "samplesize"});
  };
  std::optional<SamplerKind> sampler =
      readFromEither(samplerKey(top), samplerKey(camera), parseSampler);
  if (const std::optional<JsonNode> random = top.optional("random"); random && !sampler) {
    if (random->boolean()) sampler = SamplerKind::Random;  // nizqleo: "random": 1
  }
  if (sampler) settings.sampler = *sampler;
  settings.samplerGiven = sampler.has_value();
  const auto adaptiveAt = [](JsonObject& object) { return object.optional("adaptive"); };
  const auto readBoolean = [](const JsonNode& node) { return node.boolean(); };
  if (const auto adaptive = readFromEither(adaptiveAt(top), adaptiveAt(camera), readBoolean)) {
    settings.adaptive = *adaptive;
  }
  if (const auto samples = readFromEither(samplesAt(top), samplesAt(camera), parseSampleCount)) {
    settings.samplesPerPixel = *samples;
  }
  // nizqleo's path tracer: path_sample_num paths for each of pixel_sample_num samples.
  if (const std::optional<JsonNode> paths = top.optional("path_sample_num")) {
    const uint64_t total = uint64_t{std::max(settings.samplesPerPixel, 1u)} *
                           static_cast<uint64_t>(paths->integer(1, kMaxSamplesPerPixel));
    settings.samplesPerPixel =
        static_cast<uint32_t>(std::min<uint64_t>(total, kMaxSamplesPerPixel));
    paths->warn("read as " + std::to_string(settings.samplesPerPixel) +
                " samples per pixel (pixel_sample_num times path_sample_num)");
  }
  return sampler.has_value();
}

// nizqleo's top-level `scale`: its tone map writes each linear value times
// `scale`, clamped to 255, where the others write it times 255 ("I increased
// the scale in tone mapping", for its darker path-traced scenes): an exposure
// of scale / 255.
void readOutputScale(JsonObject& top, Camera& camera) {
  const std::optional<JsonNode> scale = top.optional("scale");
  if (!scale) return;
  const float exposure = scale->positiveFloat() / 255.0f;
  if (exposure == 1.0f) return;
  camera.exposure *= exposure;
  scale->warn("read as an exposure of " + formatNumber(exposure) +
              " (scale / 255: the 0-255 output is the linear value times scale)");
}

// Switches of the students' renderers (Kierandon's `use_*`) that do not
// change what the image converges to here: light importance sampling (this
// renderer always samples lights directly) and its sample bounds. A denoiser
// or blur would change it: asked for, it is a warning.
void readRendererSwitches(JsonObject& top) {
  top.ignore({"use_importance_sampling", "importance_sampling_min_samples",
              "importance_sampling_max_samples", "use_shadow_rays"});
  for (const char* key : {"use_denoiser", "use_gaussian_blur"}) {
    const std::optional<JsonNode> node = top.optional(key);
    if (node && node->boolean()) node->warn("ignored: the image is the render itself, unfiltered");
  }
}

// `use_stratified_sampling` (Kierandon): jittered when true, random when
// false, unless the file names a sampler.
void readStratifiedSwitch(JsonObject& top, RenderSettings& settings) {
  // use_jitter_sample: IrwinChay.
  const std::optional<JsonNode> node =
      top.optionalOneOf({"use_stratified_sampling", "use_jitter_sample"});
  if (!node) return;
  const bool stratified = node->boolean();
  if (settings.samplerGiven) return;
  settings.sampler = stratified ? SamplerKind::Jittered : SamplerKind::Random;
  settings.samplerGiven = true;
}

// Tone curve spellings, in the camera (constancefr: "tone_mapping": "aces")
// or at the top level; `use_tone_mapping: true` (Kierandon, whose renderer
// applies Reinhard's curve) where no curve is named.
ToneCurve parseToneCurve(const JsonNode& node) {
  const std::string name = node.string();
  if (const std::optional<ToneCurve> curve = toneCurveNamed(name)) return *curve;
  node.warn("unknown tone curve '" + name +
            "': clamped (known: \"clamp\", \"reinhard\", \"aces\")");
  return ToneCurve::Clamp;
}

ToneCurve readToneCurve(JsonObject& top, JsonObject& camera) {
  const auto curveAt = [](JsonObject& object) {
    return object.optionalOneOf(
        {"tone_mapping", "tonemapping", "toneMapping", "tonemap", "tone_mapper", "tonemapper"});
  };
  const std::optional<JsonNode> toggle = top.optional("use_tone_mapping");
  if (const auto curve = readFromEither(curveAt(top), curveAt(camera), parseToneCurve)) {
    if (toggle && !toggle->boolean()) return ToneCurve::Clamp;
    return *curve;
  }
  return toggle && toggle->boolean() ? ToneCurve::Reinhard : ToneCurve::Clamp;
}

// ------------------------------------------------------------------- camera

glm::vec3 unitVector(const JsonNode& node) {
  glm::vec3 value = node.vec3();
  if (!normalizeInPlace(value)) node.fail("must be a non-zero, finite vector");
  return value;
}

// Family A `lookat` is a view direction, family B `lookAt` a target point
// (both verified against the official renders; see README).
glm::vec3 readForward(JsonObject& camera, const WorldPoint& position) {
  // Beside the textbook's `lookfrom`, `lookat` is the point looked at.
  const bool textbook = camera.has("lookfrom");
  const std::optional<JsonNode> direction =
      textbook ? std::nullopt : camera.optionalOneOf({"lookat", "camView"});
  const std::optional<JsonNode> target =
      textbook ? camera.optionalOneOf({"lookat", "lookAt", "target"})
               : camera.optionalOneOf({"lookAt", "look_at", "target"});
  if (direction && target) {
    target->fail(
        "conflicts with 'camera.lookat': lookat is a view direction, lookAt a target point");
  }
  if (direction && direction->vec3() == glm::vec3(0.0f) && position != WorldPoint(0.0)) {
    // Some family-A students wrote `lookat` as the point looked at (the origin).
    direction->warn("a zero view direction: read as the point looked at");
    glm::vec3 offset(glm::normalize(-position));
    normalizeInPlace(offset);
    return offset;
  }
  if (direction) return unitVector(*direction);
  if (!target) return kDefaultForward;
  // In double precision: a camera 1e-3 from its target 1e6 from the origin
  // keeps its view direction.
  const glm::dvec3 towards = target->point() - position;
  glm::vec3 offset(towards / glm::length(towards));
  if (!(glm::length(towards) > 0.0) || !normalizeInPlace(offset)) {
    target->fail("target point must differ from the camera position by a finite offset");
  }
  return offset;
}

// `up` is kept as given (the ray builder orthogonalises it) but must span an
// image plane with the view direction.
glm::vec3 readUp(JsonObject& camera, glm::vec3 forward) {
  const std::optional<JsonNode> node =
      camera.optionalOneOf({"up", "upVector", "up_vector", "vup", "camAxis"});
  const glm::vec3 up = node ? node->vec3() : kDefaultUp;
  const std::string path = node ? node->path() : camera.childPath("up");
  glm::vec3 direction = up;
  if (!normalizeInPlace(direction)) {
    camera.diagnostics().fail(path, "must be a non-zero, finite vector");
  }
  if (glm::length(glm::cross(forward, direction)) < kParallelTolerance) {
    camera.diagnostics().fail(path, node ? "is parallel to the view direction"
                                         : "missing, and the default up (0, 1, 0) is parallel "
                                           "to the view direction");
  }
  return up;
}

// Camera type spellings (any case): a thin lens by many names.
CameraType readCameraType(const JsonNode& node) {
  const std::string type = lowercase(node.string());
  if (type == "pinhole" || type == "perspective") return CameraType::Pinhole;
  for (const char* name : {"thinlens", "thinlen", "thin_lens", "thin-lens", "lens", "aperture",
                           "finite-aperture", "finite_aperture", "finiteaperture"}) {
    if (type == name) return CameraType::ThinLens;
  }
  node.fail("unknown camera type '" + node.string() + "' (expected \"pinhole\" or \"thinlens\")");
}

uint32_t readImageSide(const JsonNode& node) {
  return static_cast<uint32_t>(node.integer(1, kMaxImageSide));
}

float readFov(const JsonNode& node) {
  const float degrees = node.floatValue();
  if (!(degrees > 0.0f && degrees < 180.0f)) {
    node.fail("must be between 0 and 180 degrees (exclusive), got " + formatNumber(degrees));
  }
  return degrees;
}

// Thin-lens keys as the students spelled them.
struct LensKeys {
  std::optional<JsonNode> aperture;        // lens diameter, or a fraction of f with f and d
  std::optional<JsonNode> lensRadius;      // lens radius
  std::optional<JsonNode> focusDistance;   // distance to the plane in focus
  std::optional<JsonNode> focalLength;     // seed report: f
  std::optional<JsonNode> sensorDistance;  // seed report: lens-to-sensor distance d
};

std::optional<JsonNode> readFocusDistanceKey(JsonObject& camera) {
  return camera.optionalOneOf({"focusdistance", "focus_dist", "focalDistance", "focal_length",
                               "focus_distance", "focalLength", "focusDistance", "focus"});
}

LensKeys readLensKeys(JsonObject& camera) {
  LensKeys keys;
  // `size`: TsFreddie's files
  keys.aperture =
      camera.optionalOneOf({"aperture", "size", "aperture_size", "apertureSize", "diameter"});
  keys.lensRadius = camera.optionalOneOf({"lensRadius", "lensradius", "lens_radius", "radius"});
  if (keys.aperture && keys.lensRadius) {
    keys.lensRadius->fail(
        "conflicts with 'camera.aperture': give the lens diameter (aperture) or its radius "
        "(lensRadius)");
  }
  keys.focusDistance = readFocusDistanceKey(camera);
  if (!keys.aperture && !keys.lensRadius && camera.has("ap") && !camera.has("d")) {
    // Seanst98: `ap` the lens diameter, `f` the distance to the plane in
    // focus (its camera aims each lens ray at origin + f * direction).
    keys.aperture = camera.optional("ap");
    if (!keys.focusDistance) keys.focusDistance = camera.optional("f");
    return keys;
  }
  keys.focalLength = camera.optionalOneOf({"f", "focal"});
  keys.sensorDistance = camera.optional("d");
  return keys;
}

// The seed report's lens: focal length f and lens-to-sensor distance d fix the
// focus distance by the thin lens equation 1/f = 1/d + 1/focus, and `aperture`
// is the lens diameter as a fraction of f (0.0625 for f/16).
void applySeedReportLens(const LensKeys& keys, JsonObject& camera, Camera& out) {
  if (!keys.focalLength) {
    camera.diagnostics().fail(
        camera.childPath("f"),
        "missing: the lens-to-sensor distance 'd' needs the focal length 'f'");
  }
  if (!keys.sensorDistance) {
    camera.diagnostics().warn(camera.childPath("d"),
                              "missing: the focal length 'f' needs the lens-to-sensor distance "
                              "'d'; rendered as a pinhole");
    return;
  }
  if (keys.focusDistance) {
    keys.focusDistance->fail("conflicts with 'f' and 'd', which already fix the focus distance");
  }
  const float focal = keys.focalLength->positiveFloat();
  const float sensor = keys.sensorDistance->positiveFloat();
  if (!(sensor > focal)) {
    keys.sensorDistance->fail("must be greater than the focal length f = " + formatNumber(focal) +
                              " for the lens to focus");
  }
  out.focusDistance = focal * sensor / (sensor - focal);
  if (keys.aperture) out.apertureRadius = keys.aperture->nonNegativeFloat() * focal / 2.0f;
  if (keys.lensRadius) out.apertureRadius = keys.lensRadius->nonNegativeFloat();
}

void applyDirectLens(const LensKeys& keys, JsonObject& camera, Camera& out) {
  if (keys.aperture) out.apertureRadius = keys.aperture->nonNegativeFloat() / 2.0f;
  if (keys.lensRadius) out.apertureRadius = keys.lensRadius->nonNegativeFloat();
  if (keys.focusDistance) {
    out.focusDistance = keys.focusDistance->positiveFloat();
  } else if (out.apertureRadius > 0.0f) {
    camera.diagnostics().warn(camera.childPath("focusdistance"),
                              "missing: a thin lens needs a focus distance (focusdistance, "
                              "focus_dist, focalDistance or focal_length); rendered as a pinhole");
    out.apertureRadius = 0.0f;
  }
}

void readThinLens(JsonObject& camera, Camera& out) {
  const LensKeys keys = readLensKeys(camera);
  if (keys.focalLength || keys.sensorDistance) {
    applySeedReportLens(keys, camera, out);
  } else {
    applyDirectLens(keys, camera, out);
  }
  if (out.apertureRadius > 0.0f) return;
  // A lens without an aperture images like a pinhole; render it as one.
  out.type = CameraType::Pinhole;
  if (!keys.aperture && !keys.lensRadius) {
    camera.diagnostics().warn(camera.childPath("type"),
                              "thinlens camera without 'aperture' or 'lensRadius' renders as a "
                              "pinhole");
  }
}

void warnLensKeysOnPinhole(JsonObject& camera) {
  for (const char* key :
       {"aperture", "size", "aperture_size", "apertureSize", "lensRadius", "lensradius",
        "lens_radius", "focusdistance", "focus_dist", "focalDistance", "focal_length",
        "focus_distance", "focalLength", "focusDistance", "f", "focal", "d", "diameter", "ap"}) {
    camera.ignoreWithWarning(
        key, std::string("thin lens key '") + key + "' ignored: the camera type is \"pinhole\"");
  }
}

// Camera keys students leave out.
constexpr uint32_t kDefaultWidth = 800;
constexpr uint32_t kDefaultHeight = 600;
constexpr float kDefaultFovDegrees = 45.0f;

bool hasLensKeys(const JsonObject& camera) {
  for (const char* key : {"aperture", "aperture_size", "lensRadius", "lensradius", "lens_radius"}) {
    if (camera.has(key)) return true;
  }
  return false;
}

// A camera animated through keyframes (bartMn: `position0`..`positionN`,
// `movement0`.. frame ranges between them, a top-level `FramesNum`): the
// still is its first frame, at position0, which is said once.
std::optional<JsonNode> readKeyframedPosition(JsonObject& camera) {
  std::optional<JsonNode> first = camera.optional("position0");
  if (!first) return std::nullopt;
  size_t keys = 1;
  // The later key positions must be points too; the frame ranges are not read.
  while (const std::optional<JsonNode> key = camera.optional("position" + std::to_string(keys))) {
    key->point();
    ++keys;
  }
  for (size_t i = 0; camera.has("movement" + std::to_string(i)); ++i) {
    camera.ignore({"movement" + std::to_string(i)});
  }
  first->warn("an animated camera of " + std::to_string(keys) +
              " key positions: rendered as its first frame, at position0");
  return first;
}

// isaacery's `cameraToWorld`: 16 numbers, a 4x4 matrix row by row that
// takes camera space (looking down -z, y up) to the world.
void readCameraMatrix(const JsonNode& node, Camera& out) {
  const std::vector<JsonNode> numbers = node.array();
  if (numbers.size() != 16) {
    node.fail("expected 16 numbers (a 4x4 matrix, row by row), got " +
              std::to_string(numbers.size()));
  }
  const auto at = [&](int row, int column) { return numbers[size_t(row * 4 + column)].number(); };
  out.position = {at(0, 3), at(1, 3), at(2, 3)};
  out.forward = -glm::vec3(float(at(0, 2)), float(at(1, 2)), float(at(2, 2)));
  out.up = glm::vec3(float(at(0, 1)), float(at(1, 1)), float(at(2, 1)));
  if (!normalizeInPlace(out.forward) ||
      glm::length(glm::cross(out.forward, out.up)) < kParallelTolerance * glm::length(out.up)) {
    node.fail("its rotation gives no view direction and up");
  }
}

Camera readCamera(JsonObject& camera) {
  Camera out;
  if (const std::optional<JsonNode> type = camera.optional("type")) {
    out.type = readCameraType(*type);
  } else {
    out.type = hasLensKeys(camera) ? CameraType::ThinLens : CameraType::Pinhole;
    camera.diagnostics().warn(camera.childPath("type"),
                              out.type == CameraType::ThinLens
                                  ? "missing; taken as \"thinlens\" (the camera has lens keys)"
                                  : "missing; taken as \"pinhole\"");
  }
  const auto side = [&](const char* key, uint32_t fallback) {
    const std::optional<JsonNode> node = optionalOrDefault(camera, {key}, std::to_string(fallback));
    return node ? readImageSide(*node) : fallback;
  };
  out.width = side("width", kDefaultWidth);
  out.height = side("height", kDefaultHeight);
  const std::optional<JsonNode> fov =
      optionalOrDefault(camera, {"fov", "field_of_view", "fieldOfView"}, "45 degrees");
  out.fovYDegrees = fov ? readFov(*fov) : kDefaultFovDegrees;
  if (const std::optional<JsonNode> matrix = camera.optional("cameraToWorld")) {
    readCameraMatrix(*matrix, out);
  } else {
    // lookfrom/lookat/vup: the textbook's camera (sukriti27); camPos/camView/camAxis: acs107102.
    std::optional<JsonNode> position = camera.optionalOneOf({"position", "lookfrom", "camPos"});
    if (!position) position = readKeyframedPosition(camera);
    out.position = position ? position->point() : kDefaultPosition;
    out.forward = readForward(camera, out.position);
    out.up = readUp(camera, out.forward);
  }
  if (const std::optional<JsonNode> exposure = camera.optional("exposure")) {
    out.exposure = exposure->positiveFloat();
  }
  if (out.type == CameraType::ThinLens) {
    readThinLens(camera, out);
  } else {
    warnLensKeysOnPinhole(camera);
  }
  return out;
}

// Shapes (defined below) that an area light may write inline as its surface.
Sphere readSphere(JsonObject& shape);
Quad readQuad(JsonObject& shape);
Triangle readTriangle(JsonObject& shape);
std::string shapeType(const JsonNode& typeNode);

// ------------------------------------------------------------------ corners

// Corner spellings: v0..v3 (official), point1..point4 (nizqleo), c1..c4.
constexpr std::array<std::array<const char*, 4>, 4> kCornerKeys = {{
    {"v0", "v1", "v2", "v3"},
    {"point1", "point2", "point3", "point4"},
    {"c1", "c2", "c3", "c4"},
    {"v1", "v2", "v3", "v4"},  // numbered from 1 (sukriti27)
}};

// The corners of the first spelling whose first key is present: `lowest`
// required, up to `highest`; nullopt when no spelling is used.
std::optional<std::vector<WorldPoint>> readNamedCorners(JsonObject& object, size_t lowest,
                                                        size_t highest) {
  for (const auto& keys : kCornerKeys) {
    if (!object.has(keys[0])) continue;
    std::vector<WorldPoint> corners;
    for (size_t i = 0; i < highest; ++i) {
      if (i < lowest) {
        corners.push_back(object.required(keys[i]).point());
      } else if (const std::optional<JsonNode> node = object.optional(keys[i])) {
        corners.push_back(node->point());
      }
    }
    return corners;
  }
  return std::nullopt;
}

// Some students list a quad's corners row by row (v0 v1 / v2 v3) rather than
// around it: then v1 and v3 lie on the same side of the diagonal v0-v2, and
// the quad would be a bow tie. Read such corners as v0 v1 v3 v2.
Quad cyclicQuad(const Quad& q, const JsonObject& shape) {
  if (!isBowTie(q)) return q;
  shape.diagnostics().warn(shape.path(),
                           "quad corners given row by row, not around the quad: read in the "
                           "order 0 1 3 2");
  return cornersAroundTheQuad(q);
}

// ------------------------------------------------------------------- lights

bool isAreaLightType(const std::string& written) {
  const std::string type = lowercase(written);
  return type.find("area") != std::string::npos || type == "rectlight" || type == "quadlight" ||
         type == "spherelight";  // Ninteedo: a sphere of `radius` at `position`
}

// The ambient term a file asks for (a scene key, or a light of type
// "ambient"): that colour times each hit's diffuse colour. `where` is the
// key it came from.
void setAmbientLight(const glm::vec3& ambient, const JsonNode& where, Scene& scene) {
  if (scene.settings.mode == RenderMode::PathTracer) {
    where.warn("ignored: the path tracer has no ambient term");
    return;
  }
  scene.ambientLight = ambient;
}

struct LightIntensity {
  glm::vec3 diffuse{1.0f};
  glm::vec3 specular{1.0f};
};

// A light intensity: an RGB triple, or one number for white light (as some
// students write it).
glm::vec3 intensityOf(const JsonNode& node) {
  if (node.raw().is_number()) return glm::vec3(node.nonNegativeFloat());
  return node.nonNegativeVec3();
}

// `intensity` (2019 and family B) sets both terms; family A gives `is`
// (specular) and `id` (diffuse) separately.
LightIntensity readIntensity(JsonObject& light) {
  const std::optional<JsonNode> intensity = light.optional("intensity");
  const std::optional<JsonNode> specular = light.optional("is");
  const std::optional<JsonNode> diffuse = light.optional("id");
  if (intensity) {
    if (specular && diffuse && intensity->raw().is_number()) {  // Knhwong: a scale on is/id
      intensity->warn("read as a factor on 'is' and 'id'");
      const float scale = intensity->nonNegativeFloat();
      return {scale * intensityOf(*diffuse), scale * intensityOf(*specular)};
    }
    if (specular || diffuse) {
      (specular ? specular : diffuse)->fail("conflicts with 'intensity': give intensity or is/id");
    }
    glm::vec3 both = intensityOf(*intensity);
    if (const std::optional<JsonNode> colour = light.optionalOneOf({"color", "colour"})) {
      both *= colour->nonNegativeVec3();  // a scalar intensity of a coloured light
    }
    return {both, both};
  }
  if (!specular && !diffuse) {
    light.diagnostics().fail(light.childPath("intensity"),
                             "missing: a light needs 'intensity', or both 'is' and 'id'");
  }
  LightIntensity out;
  out.specular = intensityOf(light.required("is"));
  out.diffuse = intensityOf(light.required("id"));
  return out;
}

PointLight readPointLight(JsonObject& light) {
  PointLight out;
  out.position = light.required("position").point();
  const LightIntensity intensity = readIntensity(light);
  out.diffuseIntensity = intensity.diffuse;
  out.specularIntensity = intensity.specular;
  return out;
}

// Shadow rays per shading point; the students wrote `samples` or `nsamples`.
uint32_t readLightSamples(JsonObject& light) {
  const std::optional<JsonNode> node =
      light.optionalOneOf({"samples", "nsamples", "num_samples", "samplesize"});
  return node ? static_cast<uint32_t>(node->integer(1, int64_t{kMaxLightSamples})) : 1u;
}

// Every random dimension draws from the scene's one sampler; a light's own
// `method`/`sampler` is honoured only when the scene names none.
void readLightSampler(JsonObject& light, std::optional<SamplerKind>& lightSampler) {
  const std::optional<JsonNode> node = light.optionalOneOf({"method", "sampler"});
  if (!node) return;
  const SamplerKind kind = parseSampler(*node);
  if (lightSampler && *lightSampler != kind) {
    node->warn("ignored: another light asks for a different sampler, the first one is used");
    return;
  }
  lightSampler = kind;
}

// The quad with corner `corner` and edges `u`, `v`.
Quad parallelogram(const WorldPoint& corner, const glm::dvec3& u, const glm::dvec3& v) {
  return {corner, corner + u, corner + u + v, corner + v};
}

// The quad with edges `u`, `v` centred on `center`.
Quad centredParallelogram(const WorldPoint& center, const glm::dvec3& u, const glm::dvec3& v) {
  return parallelogram(center - 0.5 * (u + v), u, v);
}

// A rectangle centred on `position` facing `normal`, `width` (or `w`) by
// `height` (or `h`) (1 when not given), its width along the horizontal
// (the world x-z plane) where it can be.
Quad facingRectangle(JsonObject& light, const WorldPoint& position, glm::vec3 normal) {
  const std::optional<JsonNode> width = light.optionalOneOf({"width", "w"});
  const std::optional<JsonNode> height = light.optionalOneOf({"height", "h"});
  const float w = width ? width->positiveFloat() : 1.0f;
  const float h = height ? height->positiveFloat() : 1.0f;
  glm::vec3 across = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), normal);
  if (!normalizeInPlace(across)) across = glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::dvec3 u(across * w);
  const glm::dvec3 v(glm::normalize(glm::cross(normal, across)) * h);
  return centredParallelogram(position, u, v);
}

// Trenza1ore's `size`: [a, b], half the extents along x and z of a
// horizontal rectangle centred on the position, facing down, as its
// author's AreaLight samples it. [a, b, c] is a box there (points sampled in
// its volume): its horizontal middle, x by z, with a warning.
Quad horizontalRectangle(const JsonNode& size, const WorldPoint& position) {
  const std::vector<JsonNode> extents = size.array();
  if (extents.size() != 2 && extents.size() != 3) {
    size.fail("expected a number, or 2 or 3 half extents, got an array of " +
              std::to_string(extents.size()));
  }
  const double x = extents[0].positiveFloat();
  const double z = extents.back().positiveFloat();
  if (extents.size() == 3) {
    extents[1].nonNegativeFloat();
    size.warn("a box of light: read as its horizontal rectangle, x by z at the position's height");
  }
  return centredParallelogram(position, {2.0 * x, 0.0, 0.0}, {0.0, 0.0, 2.0 * z});
}

// The emitting surface of an area light written with its own geometry:
//   v0 v1 v2 [v3]        a triangle or a planar quad (julie-o, PFNK);
//   position u v [width height]
//                        a parallelogram centred on position with edges u
//                        and v (with width/height: unit directions scaled);
//   position radius      a sphere;
//   position size        a sphere of diameter size (TsFreddie), or, with
//                        size [a, b], a horizontal rectangle (Trenza1ore).
Geometry readAreaLightGeometry(JsonObject& light) {
  if (const auto c = readNamedCorners(light, 3, 4)) {
    if (c->size() == 4) return cyclicQuad({(*c)[0], (*c)[1], (*c)[2], (*c)[3]}, light);
    return Triangle{(*c)[0], (*c)[1], (*c)[2]};
  }
  if (light.has("e0") || light.has("e1")) {  // a corner and its two edges
    return parallelogram(light.required("p").point(), light.required("e0").point(),
                         light.required("e1").point());
  }
  const WorldPoint position = light.required("position").point();
  if (const std::optional<JsonNode> normal = light.optional("normal")) {
    return facingRectangle(light, position, unitVector(*normal));
  }
  if (light.has("u_axis")) {  // david14higgins: the half edges
    const glm::dvec3 u = 2.0 * light.required("u_axis").point();
    const glm::dvec3 v = 2.0 * light.required("v_axis").point();
    return centredParallelogram(position, u, v);
  }
  if (light.has("u") || light.has("v")) {
    glm::dvec3 u = light.required("u").point();
    glm::dvec3 v = light.required("v").point();
    const std::optional<JsonNode> width = light.optional("width");
    const std::optional<JsonNode> height = light.optional("height");
    // A zero edge stays zero: the light has no area (readAreaLight).
    if (width && u != glm::dvec3(0.0)) u = glm::normalize(u) * double(width->positiveFloat());
    if (height && v != glm::dvec3(0.0)) v = glm::normalize(v) * double(height->positiveFloat());
    return centredParallelogram(position, u, v);
  }
  if (const std::optional<JsonNode> radius = light.optionalOneOf({"radius", "areaRadius"})) {
    return Sphere{position, radius->positiveFloat()};
  }
  if (const std::optional<JsonNode> size = light.optional("size")) {
    if (size->raw().is_array()) return horizontalRectangle(*size, position);
    return Sphere{position, size->positiveFloat() / 2.0f};
  }
  light.diagnostics().fail(light.childPath("shape"),
                           "missing: an area light needs its surface: v0..v3, position with u "
                           "and v, position with radius or size, or the id of a shape");
}

// A light source in the file, kept until the shapes are read (area lights
// may name a shape by its id).
struct PendingAreaLight {
  AreaLight light;
  std::optional<Geometry> geometry;  // its own surface, or
  std::optional<JsonNode> shapeId;   // the id of the shape that emits
};

struct LightList {
  std::vector<PendingAreaLight> areaLights;
  std::optional<SamplerKind> sampler;  // asked for by the lights themselves
};

// An area light's surface written inline ("shape": {"type": "sphere", ...}).
Geometry readLightSurface(JsonObject& surface) {
  const JsonNode typeNode = surface.required("type");
  const std::string type = shapeType(typeNode);
  if (type == "sphere") return readSphere(surface);
  if (type == "plane") return readQuad(surface);
  if (type == "triangle") return readTriangle(surface);
  typeNode.fail("an area light's surface must be a sphere, plane or triangle");
}

// A point inside a shape: the centre of an analytic one, the mean vertex of
// a mesh (looked up in `meshes`).
WorldPoint geometryCenter(const Geometry& geometry, const std::vector<TriangleMesh>& meshes) {
  return std::visit(
      [&](const auto& g) -> WorldPoint {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, Sphere> || std::is_same_v<T, Cylinder>) return g.center;
        if constexpr (std::is_same_v<T, Triangle>) return (g.v0 + g.v1 + g.v2) / 3.0;
        if constexpr (std::is_same_v<T, Quad>) return (g.v0 + g.v1 + g.v2 + g.v3) / 4.0;
        if constexpr (std::is_same_v<T, MeshInstance>) {
          const TriangleMesh& mesh = meshes.at(g.mesh);
          glm::dvec3 sum(0.0);
          for (const glm::vec3& p : mesh.positions) sum += glm::dvec3(p);
          const glm::dvec3 mean =
              sum / static_cast<double>(std::max<size_t>(1, mesh.positions.size()));
          return WorldPoint(g.objectToWorld * glm::dvec4(mean, 1.0));
        }
      },
      geometry);
}

void readAreaLight(JsonObject& light, Scene& scene, LightList& lights) {
  PendingAreaLight pending;
  const LightIntensity intensity = readIntensity(light);
  pending.light.diffuseIntensity = intensity.diffuse;
  pending.light.specularIntensity = intensity.specular;
  pending.light.samples = readLightSamples(light);
  if (const std::optional<JsonNode> profile = light.optional("emission")) {
    const std::string name = profile->string();
    if (name == "isotropic") {
      pending.light.profile = EmissionProfile::Isotropic;
    } else if (name == "lambertian" || name == "diffuse") {
      pending.light.profile = EmissionProfile::Lambertian;
    } else {
      profile->fail("unknown emission '" + name + "' (expected \"isotropic\" or \"lambertian\")");
    }
  }
  readLightSampler(light, lights.sampler);
  pending.shapeId = light.optionalOneOf({"shape", "shapeid", "shapeId", "shape_id"});
  if (pending.shapeId && pending.shapeId->raw().is_object()) {  // the surface written inline
    JsonObject surface = pending.shapeId->object();
    pending.geometry = readLightSurface(surface);
    surface.reportUnknownKeys();
    pending.shapeId.reset();
  } else if (!pending.shapeId) {
    pending.geometry = readAreaLightGeometry(light);
    if (!(surfaceArea(*pending.geometry, {}) > 0.0f)) {
      // JinBa1's v [0, 0, 0]: its author's renderer samples a segment.
      light.diagnostics().warn(light.path(),
                               "an area light without area (an edge of length 0): read as a "
                               "point light at its centre");
      scene.pointLights.push_back(
          {geometryCenter(*pending.geometry, {}), intensity.diffuse, intensity.specular});
      return;
    }
  }
  lights.areaLights.push_back(std::move(pending));
}

// Whether an area light names its surface in any of the ways readAreaLight
// knows; students also wrote area lights as a position alone.
bool hasAreaLightSurface(const JsonObject& light) {
  for (const char* key : {"v0", "point1", "c1", "e0", "u", "u_axis", "normal", "radius",
                          "areaRadius", "size", "shape", "shapeid", "shapeId", "shape_id"}) {
    if (light.has(key)) return true;
  }
  return false;
}

void readLight(const JsonNode& node, Scene& scene, LightList& lights) {
  JsonObject light = node.object();
  if (!light.has("type")) {
    light.diagnostics().warn(light.childPath("type"), "missing; taken as \"pointlight\"");
    scene.pointLights.push_back(readPointLight(light));
    light.reportUnknownKeys();
    return;
  }
  const JsonNode typeNode = light.required("type");
  const std::string type = typeNode.string();
  if (isAreaLightType(type) && !hasAreaLightSurface(light)) {
    typeNode.warn("an area light without a surface (position only): read as a point light");
    scene.pointLights.push_back(readPointLight(light));
  } else if (isAreaLightType(type)) {
    readAreaLight(light, scene, lights);
  } else if (lowercase(type) == "pointlight" || lowercase(type) == "point" ||
             lowercase(type) == "point_light") {
    scene.pointLights.push_back(readPointLight(light));
  } else if (lowercase(type) == "ambient" || lowercase(type) == "ambientlight") {
    // Trenza1ore: the ambient term as a light source.
    setAmbientLight(readIntensity(light).diffuse, typeNode, scene);
  } else {
    typeNode.fail("unknown light type '" + type + "' (expected \"pointlight\" or \"arealight\")");
  }
  light.reportUnknownKeys();
}

// ---------------------------------------------------------------- materials

// TsFreddie's files may name a texture ("checkerboard") where a weight belongs.
std::optional<JsonNode> withoutTextureWeight(std::optional<JsonNode> node) {
  if (node && node->raw().is_string()) {
    node->warn("ignored: a texture as a weight is not supported");
    return std::nullopt;
  }
  return node;
}

// One of two alias keys, the second of which may be a texture name (ignored).
std::optional<JsonNode> weightOrAlias(JsonObject& material, const char* key, const char* alias) {
  std::optional<JsonNode> node = material.optional(key);
  std::optional<JsonNode> other = withoutTextureWeight(material.optional(alias));
  if (node && other)
    other->fail("conflicts with '" + node->path() + "': give only one of these aliases");
  return node ? node : other;
}

// Family A: `kr` (TsFreddie: `metallic`). Family B: `reflectivity`, which
// counts only when `isreflective` is true.
float readReflectivity(JsonObject& material) {
  const std::optional<JsonNode> kr = weightOrAlias(material, "kr", "metallic");
  const std::optional<JsonNode> isReflective = material.optional("isreflective");
  const std::optional<JsonNode> reflectivity = material.optional("reflectivity");
  if (kr && (isReflective || reflectivity)) {
    kr->fail("conflicts with 'isreflective'/'reflectivity': give one mirror weight");
  }
  if (kr) return kr->floatInRange(0.0f, 1.0f);
  const float weight = reflectivity ? reflectivity->floatInRange(0.0f, 1.0f) : 1.0f;
  if (isReflective) return isReflective->boolean() ? weight : 0.0f;
  if (reflectivity) reflectivity->warn("ignored: it only applies with \"isreflective\": true");
  return 0.0f;
}

// Family A: `kt` weight. Family B: `isrefractive` transmits what the mirror
// weight (already read into `out`) leaves.
void readRefraction(JsonObject& material, Material& out) {
  const std::optional<JsonNode> kt = weightOrAlias(material, "kt", "transmit");
  const std::optional<JsonNode> isRefractive =
      material.optionalOneOf({"isrefractive", "isGlass", "isglass"});  // isGlass: Seanst98
  if (kt && isRefractive) kt->fail("conflicts with 'isrefractive': give one transmission weight");
  if (kt) out.transmission = kt->floatInRange(0.0f, 1.0f);
  if (isRefractive) out.transmission = isRefractive->boolean() ? 1.0f - out.reflectivity : 0.0f;
  if (const std::optional<JsonNode> ior =
          material.optionalOneOf({"eta", "ior", "refractiveIndex", "refractiveindex"})) {
    // Basemism writes 0 where nothing refracts: no index is needed there.
    if (out.transmission == 0.0f && ior->raw().is_number() && ior->number() == 0.0) {
      ior->warn("an index of 0 on a surface that does not refract: read as 1");
      return;
    }
    out.ior = ior->positiveFloat();
  }
}

// A texture described rather than named by file (jayp97: {"type":
// "checkerboard", "color1", "color2", "scale"}); other kinds are drawn with
// the missing-texture squares.
void readProceduralTexture(JsonObject texture, Material& out, Scene& scene) {
  const std::optional<JsonNode> type = texture.optional("type");
  if (type && lowercase(type->string()) == "checkerboard") {
    const glm::vec3 even = texture.required("color1").nonNegativeVec3();
    const glm::vec3 odd = texture.required("color2").nonNegativeVec3();
    const std::optional<JsonNode> scale = texture.optional("scale");
    const auto squares = static_cast<uint32_t>(scale ? scale->floatInRange(1.0f, 64.0f) : 8.0f);
    out.texture = "checkerboard";
    out.diffuseTexture = addCheckerTexture(scene, even, odd, squares);
    texture.reportUnknownKeys();
    return;
  }
  texture.diagnostics().warn(texture.path(),
                             "a procedural texture this renderer does not know; drawn with the "
                             "missing-texture squares");
  texture.ignore({"type"});
  out.texture = "missing texture";
  out.diffuseTexture = addMissingTexture(scene);
}

// Material keys students leave out: the usual textbook values, with a warning.
constexpr float kDefaultKs = 0.2f;
constexpr float kDefaultKd = 0.8f;
constexpr float kDefaultSpecularExponent = 10.0f;

// Where a texture file is named: in the material, or on the shape itself
// beside its material (bartMn).
enum class TextureKeys { Material, Shape };

// `diffuse` is nizqleo's, `texturefile` Nebula1253's, `textureFilename`
// david14higgins'.
std::optional<JsonNode> textureKey(JsonObject& object, TextureKeys where) {
  if (where == TextureKeys::Shape) {
    return object.optionalOneOf({"texture", "texturefile", "textureFilename", "tPath"});
  }
  return object.optionalOneOf({"tPath", "texture", "texture_file", "texturepath", "texturefile",
                               "textureFilename", "texture_filename", "diffuse"});
}

// The texture `object` names, into `out`: a file, a procedural object or
// "checkerboard"; a missing file is a warning and the missing-texture
// squares. `hasTexture: false` (david14higgins) turns it off.
void readTextureKeys(JsonObject& object, TextureKeys where, const fs::path& sceneDir, Material& out,
                     Scene& scene) {
  if (const std::optional<JsonNode> toggle = object.optional("hasTexture");
      toggle && !toggle->boolean()) {
    textureKey(object, where);  // read, and left unused
    return;
  }
  if (const std::optional<JsonNode> empty = object.optional("texture");
      empty && empty->raw() == "") {
    empty->warn("empty: no texture");
    return;
  }
  const std::optional<JsonNode> texture = textureKey(object, where);
  if (!texture) return;
  if (texture->raw().is_object()) {
    readProceduralTexture(texture->object(), out, scene);
  } else if (texture->raw() == "checkerboard") {
    out.texture = "checkerboard";
    out.diffuseTexture = addCheckerboard(scene);
  } else {
    readTextureFile(*texture, sceneDir, out, scene);
  }
}

Material readMaterial(JsonObject& material, const fs::path& sceneDir, Scene& scene) {
  Material out;
  const auto weight = [&](std::initializer_list<std::string_view> keys, float fallback) {
    const std::optional<JsonNode> node = optionalOrDefault(material, keys, formatNumber(fallback));
    return node ? node->nonNegativeFloat() : fallback;
  };
  out.ks = weight({"ks"}, kDefaultKs);
  out.kd = weight({"kd"}, kDefaultKd);
  out.specularExponent = weight({"specularexponent"}, kDefaultSpecularExponent);
  const std::optional<JsonNode> diffuse =
      optionalOrDefault(material, {"diffusecolor"}, "white (1, 1, 1)");
  out.diffuseColor = diffuse ? diffuse->nonNegativeVec3() : glm::vec3(1.0f);
  if (const std::optional<JsonNode> specular = material.optional("specularcolor")) {
    out.specularColor = specular->nonNegativeVec3();
  }
  out.reflectivity = readReflectivity(material);
  readRefraction(material, out);
  readTextureKeys(material, TextureKeys::Material, sceneDir, out, scene);
  // The coursework's texture sizes do not match the real images; the image file decides.
  material.ignore({"tWidth", "tHeight"});
  material.ignoreWithWarning("roughness", "'roughness' ignored: mirror reflection is sharp");
  material.ignoreWithWarning("ka", "'ka' ignored: there is no ambient term");
  material.reportUnknownKeys();
  return out;
}

// A material given by its kind, as path tracers in the style of "Ray
// Tracing in One Weekend" write it (Kierandon): {"type": "diffuse" |
// "lambertian", "albedo"}, {"type": "metal", "albedo"}, {"type":
// "dielectric", "ior"}, {"type": "emissive", "colour", "intensity"}.
// Mapped onto the Blinn-Phong material; an emissive one also makes its shape
// an area light of radiance colour * intensity (`emission`).
Material readKindMaterial(JsonObject& material, const std::string& kind,
                          std::optional<glm::vec3>& emission) {
  Material out;
  out.ks = 0.0f;
  const std::optional<JsonNode> albedo = material.optionalOneOf({"albedo", "colour", "color"});
  const glm::vec3 colour = albedo ? albedo->nonNegativeVec3() : glm::vec3(1.0f);
  if (kind == "diffuse" || kind == "lambertian") {
    out.diffuseColor = colour;
  } else if (kind == "metal") {
    // Mirrors reflect untinted here: the mean of the albedo is reflected.
    out.kd = 0.0f;
    out.reflectivity = std::min((colour.x + colour.y + colour.z) / 3.0f, 1.0f);
    if (albedo && (colour.x != colour.y || colour.y != colour.z)) {
      albedo->warn("a metal's tint is not drawn: it reflects the mean of its albedo, untinted");
    }
    material.ignoreWithWarning("fuzz", "'fuzz' ignored: mirror reflection is sharp");
  } else if (kind == "dielectric") {
    out.kd = 0.0f;
    out.transmission = 1.0f;
    if (const std::optional<JsonNode> ior =
            material.optionalOneOf({"ior", "eta", "refractiveindex"})) {
      out.ior = ior->positiveFloat();
    }
  } else {  // emissive
    out.kd = 0.0f;
    const std::optional<JsonNode> strength = material.optional("intensity");
    emission = colour * (strength ? strength->nonNegativeFloat() : 1.0f);
  }
  material.ignoreWithWarning("roughness", "'roughness' ignored: mirror reflection is sharp");
  material.reportUnknownKeys();
  return out;
}

// The material kinds readKindMaterial knows, or nullopt.
std::optional<std::string> materialKind(const JsonObject& material) {
  const Json* type = material.peek("type");
  if (type == nullptr || !type->is_string()) return std::nullopt;
  const std::string kind = lowercase(type->get<std::string>());
  for (const char* known : {"diffuse", "lambertian", "metal", "dielectric", "emissive"}) {
    if (kind == known) return kind;
  }
  return std::nullopt;
}

// Shapes without a material are normal in binary mode (only hit/miss is drawn).
uint32_t addShapeMaterial(JsonObject& shape, const ShapeContext& context, Scene& scene,
                          std::optional<glm::vec3>& emission) {
  Material material;
  if (const Json* name = shape.peek("material"); name && name->is_string()) {
    return namedMaterial(shape.required("material"), context.namedMaterials);
  }
  if (const std::optional<JsonNode> node = shape.optional("material")) {
    JsonObject object = node->object();
    if (const std::optional<std::string> kind = materialKind(object)) {
      object.required("type");  // read: it names the kind
      material = readKindMaterial(object, *kind, emission);
    } else {
      material = readMaterial(object, context.sceneDir, scene);
    }
  } else if (context.mode != RenderMode::Binary) {
    shape.diagnostics().warn(shape.childPath("material"), "missing; the default material is used");
  }
  if (material.texture.empty()) {
    readTextureKeys(shape, TextureKeys::Shape, context.sceneDir, material, scene);
  }
  scene.materials.push_back(std::move(material));
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

// For shapes that cannot emit (a material given to a whole model file).
uint32_t addShapeMaterial(JsonObject& shape, const ShapeContext& context, Scene& scene) {
  std::optional<glm::vec3> emission;
  const uint32_t material = addShapeMaterial(shape, context, scene, emission);
  if (emission) {
    shape.diagnostics().warn(shape.childPath("material"),
                             "an emissive material on a model file: drawn, but not as a light");
  }
  return material;
}

// ------------------------------------------------------------------- shapes

Sphere readSphere(JsonObject& shape) {
  return {shape.required("center").point(), shape.required("radius").positiveFloat()};
}

// Corners as a `vertices` array (TsFreddie's files) instead of v0, v1, ...
std::optional<std::vector<WorldPoint>> readCornerArray(JsonObject& shape, size_t lowest,
                                                       size_t highest) {
  const std::optional<JsonNode> node = shape.optionalOneOf({"vertices", "points"});
  if (!node) return std::nullopt;
  std::vector<WorldPoint> corners;
  for (const JsonNode& corner : node->array()) corners.push_back(corner.point());
  if (corners.size() < lowest || corners.size() > highest) {
    node->fail("expected " + std::to_string(lowest) +
               (lowest == highest ? "" : " or " + std::to_string(highest)) + " vertices, got " +
               std::to_string(corners.size()));
  }
  return corners;
}

// An axis-aligned rectangle by two opposite corners (Kierandon's
// "rectangle": corner1, corner2, equal in one coordinate).
Quad readCornerRectangle(JsonObject& shape) {
  const JsonNode second = shape.required("corner2");
  const WorldPoint a = shape.required("corner1").point();
  const WorldPoint b = second.point();
  int flat = -1;
  for (int axis = 0; axis < 3; ++axis) {
    if (a[axis] == b[axis]) flat = axis;
  }
  if (flat < 0) second.fail("must equal corner1 in one coordinate (an axis-aligned rectangle)");
  const int u = (flat + 1) % 3;
  WorldPoint c1 = a;
  c1[u] = b[u];
  WorldPoint c3 = b;
  c3[u] = a[u];
  return {a, c1, b, c3};
}

// Four corners in cyclic order; three (v0 and its two neighbours, as
// TsFreddie writes planes) span a parallelogram.
Quad readQuad(JsonObject& shape) {
  if (shape.has("corner1")) return readCornerRectangle(shape);
  std::optional<std::vector<WorldPoint>> corners = readCornerArray(shape, 3, 4);
  if (!corners) corners = readNamedCorners(shape, 4, 4);
  if (!corners) shape.diagnostics().fail(shape.childPath("v0"), "missing required key");
  const std::vector<WorldPoint>& c = *corners;
  if (c.size() == 4) return cyclicQuad({c[0], c[1], c[2], c[3]}, shape);
  return {c[0], c[1], c[1] + c[2] - c[0], c[2]};
}

Triangle readTriangle(JsonObject& shape) {
  std::optional<std::vector<WorldPoint>> corners = readCornerArray(shape, 3, 3);
  if (!corners) corners = readNamedCorners(shape, 3, 3);
  if (!corners) shape.diagnostics().fail(shape.childPath("v0"), "missing required key");
  return {(*corners)[0], (*corners)[1], (*corners)[2]};
}

// Family B `height` is the half-length: the caps are at center +- axis * height.
Cylinder readCylinder(JsonObject& shape) {
  return {shape.required("center").point(), unitVector(shape.required("axis")),
          shape.required("radius").positiveFloat(), shape.required("height").positiveFloat()};
}

uint32_t readVertexIndex(const JsonNode& node, size_t vertexCount) {
  const int64_t index = node.integer();
  if (index < 0 || static_cast<uint64_t>(index) >= vertexCount) {
    node.fail("vertex index " + std::to_string(index) + " is out of range (the mesh has " +
              std::to_string(vertexCount) + " vertices)");
  }
  return static_cast<uint32_t>(index);
}

// Polygons with more than three corners become a triangle fan around the
// first corner, which is right for the convex faces the files contain.
void appendFace(const JsonNode& face, TriangleMesh& mesh) {
  const std::vector<JsonNode> corners = face.array();
  if (corners.size() < 3) {
    face.fail("a face needs at least 3 vertex indices, got " + std::to_string(corners.size()));
  }
  std::vector<uint32_t> indices;
  for (const JsonNode& corner : corners) {
    indices.push_back(readVertexIndex(corner, mesh.positions.size()));
  }
  for (size_t i = 1; i + 1 < indices.size(); ++i) {
    mesh.faces.emplace_back(indices[0], indices[i], indices[i + 1]);
  }
}

// Vertices without faces (Seanst98): a triangle strip, triangle i from
// vertices i, i + 1, i + 2 in that order, as its author's TriMesh makes them.
void readTriangleStrip(JsonObject& shape, TriangleMesh& mesh) {
  const auto count = static_cast<uint32_t>(mesh.positions.size());
  if (count < 3) {
    shape.diagnostics().fail(shape.childPath("faces"),
                             "missing, and fewer than 3 vertices make no triangle strip");
  }
  for (uint32_t i = 0; i + 2 < count; ++i) mesh.faces.emplace_back(i, i + 1, i + 2);
}

// Faces as lists of corners ("faces"/"tris"), or as a flat index list with
// a corner count per face (sukriti27: faceindex + vertexindex; Zspirates96:
// numVerticesOnEachFace + verticesOnEachFace, with "faces" their number).
void readFaces(JsonObject& shape, TriangleMesh& mesh) {
  const std::optional<JsonNode> counts =
      shape.optionalOneOf({"faceindex", "numVerticesOnEachFace"});
  if (counts) {
    const std::optional<JsonNode> flat = shape.optionalOneOf({"vertexindex", "verticesOnEachFace"});
    if (!flat) shape.diagnostics().fail(shape.childPath("vertexindex"), "missing required key");
    shape.ignore({"faces"});
    const std::vector<JsonNode> indices = flat->array();
    size_t next = 0;
    for (const JsonNode& count : counts->array()) {
      const auto corners = static_cast<size_t>(count.integer(3, 1 << 20));
      if (next + corners > indices.size())
        flat->fail("has fewer indices than the face counts need");
      std::vector<uint32_t> face;
      for (size_t c = 0; c < corners; ++c) {
        face.push_back(readVertexIndex(indices[next + c], mesh.positions.size()));
      }
      for (size_t c = 1; c + 1 < face.size(); ++c)
        mesh.faces.emplace_back(face[0], face[c], face[c + 1]);
      next += corners;
    }
    if (mesh.faces.empty()) counts->fail("must list at least one face");
    return;
  }
  const std::optional<JsonNode> faces = shape.optionalOneOf({"faces", "tris"});
  if (!faces) {
    readTriangleStrip(shape, mesh);
    return;
  }
  for (const JsonNode& face : faces->array()) appendFace(face, mesh);
  if (mesh.faces.empty()) faces->fail("must list at least one face");
}

// Inline vertices are world positions. The mesh keeps them relative to its
// first vertex (floats are fine near the mesh) and its instance carries
// that vertex in double precision, so a mesh far from the origin keeps its shape.
struct InlineMesh {
  TriangleMesh mesh;
  WorldPoint origin{0.0};
};

void setWorldPositions(const std::vector<WorldPoint>& points, InlineMesh& out) {
  out.origin = points.front();
  for (const WorldPoint& p : points) out.mesh.positions.emplace_back(p - out.origin);
}

// Vergilc's numbered keys: "vertex": N with v0..v(N-1), "face": M with f0..f(M-1).
void readNumberedMesh(JsonObject& shape, InlineMesh& out) {
  constexpr int64_t kMostNumbered = 1 << 16;
  const int64_t vertices = shape.required("vertex").integer(1, kMostNumbered);
  std::vector<WorldPoint> points;
  for (int64_t i = 0; i < vertices; ++i) {
    points.push_back(shape.required("v" + std::to_string(i)).point());
  }
  setWorldPositions(points, out);
  const int64_t faces = shape.required("face").integer(1, kMostNumbered);
  for (int64_t i = 0; i < faces; ++i) {
    appendFace(shape.required("f" + std::to_string(i)), out.mesh);
  }
}

// jayp97's meshes: "triangles": [{"v0": [..], "v1": [..], "v2": [..]}, ...],
// each triangle with corners of its own.
void readTriangleList(const JsonNode& list, InlineMesh& out) {
  std::vector<WorldPoint> points;
  for (const JsonNode& item : list.array()) {
    JsonObject triangle = item.object();
    for (const char* key : {"v0", "v1", "v2"}) points.push_back(triangle.required(key).point());
    triangle.reportUnknownKeys();
  }
  if (points.empty()) list.fail("must list at least one triangle");
  setWorldPositions(points, out);
  for (uint32_t i = 0; i < points.size(); i += 3) out.mesh.faces.emplace_back(i, i + 1, i + 2);
}

// Kierandon's boxes: the corners of `min` and `max` (in either order),
// turned by `rotation` degrees about the world axes x, then y, then z
// through the world origin, as the author's renderer turns them.
InlineMesh readBox(JsonObject& shape) {
  const WorldPoint lo = shape.required("min").point();
  const WorldPoint hi = shape.required("max").point();
  glm::dvec3 degrees(0.0);
  if (const std::optional<JsonNode> rotation = shape.optional("rotation")) {
    degrees = rotation->point();  // three numbers, kept in double like the corners
  }
  const glm::dmat4 turn = glm::rotate(glm::dmat4(1.0), glm::radians(degrees.z), {0, 0, 1}) *
                          glm::rotate(glm::dmat4(1.0), glm::radians(degrees.y), {0, 1, 0}) *
                          glm::rotate(glm::dmat4(1.0), glm::radians(degrees.x), {1, 0, 0});
  std::vector<WorldPoint> corners;
  for (int corner = 0; corner < 8; ++corner) {
    const WorldPoint p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                       corner & 4 ? hi.z : lo.z);
    corners.emplace_back(turn * glm::dvec4(p, 1.0));
  }
  InlineMesh out;
  setWorldPositions(corners, out);
  // Two triangles per face, corners numbered by their x, y, z bits.
  constexpr uint32_t kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    out.mesh.faces.emplace_back(f[0], f[1], f[2]);
    out.mesh.faces.emplace_back(f[0], f[2], f[3]);
  }
  return out;
}

// (u, v), or (u, v, w) as OBJ's `vt` and Seanst98's `texturecoordinates`
// write them: w is not used.
glm::vec2 readUv(const JsonNode& node) {
  const std::vector<JsonNode> pair = node.array();
  if (pair.size() != 2 && pair.size() != 3)
    node.fail("expected 2 texture coordinates, got " + std::to_string(pair.size()));
  if (pair.size() == 3) pair[2].floatValue();  // checked, unused
  return {pair[0].floatValue(), pair[1].floatValue()};
}

// Corner attributes of a triangle: texture coordinates (Ninteedo: `uv0`..`uv2`
// beside `v0`..`v2`) and shading normals (J-MR-T: `v0Normal`..`v2Normal`).
bool hasCornerAttributes(const JsonObject& shape) {
  return shape.has("uv0") || shape.has("uv1") || shape.has("v0Normal");
}

// Such a triangle is a one-triangle mesh, which carries them.
InlineMesh readAttributedTriangle(JsonObject& shape) {
  const Triangle corners = readTriangle(shape);
  InlineMesh out;
  setWorldPositions({corners.v0, corners.v1, corners.v2}, out);
  out.mesh.faces.emplace_back(0, 1, 2);
  // uv1..uv3 beside corners v1..v3 (sukriti27).
  const bool fromOne = !shape.has("uv0") && shape.has("uv1");
  if (shape.has("uv0") || fromOne) {
    for (const char* key :
         fromOne ? std::array{"uv1", "uv2", "uv3"} : std::array{"uv0", "uv1", "uv2"}) {
      out.mesh.uvs.push_back(readUv(shape.required(key)));
    }
  }
  if (shape.has("v0Normal")) {
    for (const char* key : {"v0Normal", "v1Normal", "v2Normal"}) {
      out.mesh.normals.push_back(unitVector(shape.required(key)));
    }
  }
  return out;
}

MeshInstance addInlineMesh(InlineMesh placed, Scene& scene) {
  scene.meshes.push_back(std::move(placed.mesh));
  return MeshInstance{static_cast<uint32_t>(scene.meshes.size() - 1),
                      glm::translate(WorldTransform(1.0), placed.origin)};
}

InlineMesh readInlineMesh(JsonObject& shape) {
  for (const char* key : {"center", "pos", "scale", "sizeScale"}) {
    shape.ignoreWithWarning(key,
                            std::string("mesh placement '") + key +
                                "' is only applied to PLY meshes; ignored for inline vertices");
  }
  InlineMesh placed;
  TriangleMesh& mesh = placed.mesh;
  if (shape.has("vertex") && shape.has("v0")) {  // Vergilc: vertex N, v0..; face M, f0..
    readNumberedMesh(shape, placed);
  } else if (shape.has("triangles") && !shape.has("vertices")) {
    readTriangleList(shape.required("triangles"), placed);
  } else {
    const std::optional<JsonNode> vertices = shape.optionalOneOf({"vertices", "points"});
    if (!vertices) shape.diagnostics().fail(shape.childPath("vertices"), "missing required key");
    std::vector<WorldPoint> points;
    for (const JsonNode& vertex : vertices->array()) points.push_back(vertex.point());
    if (points.empty()) vertices->fail("must list at least one vertex");
    setWorldPositions(points, placed);
    readFaces(shape, mesh);
  }
  if (const std::optional<JsonNode> uvs =
          shape.optionalOneOf({"uv", "uvs", "texturecoordinates", "textureCoordinates"})) {
    for (const JsonNode& uv : uvs->array()) mesh.uvs.push_back(readUv(uv));
    if (mesh.uvs.size() != mesh.positions.size()) {
      uvs->fail("has " + std::to_string(mesh.uvs.size()) + " entries for " +
                std::to_string(mesh.positions.size()) + " vertices");
    }
  }
  return placed;
}

// Students' placement of a PLY mesh: `center` | `pos` | `offset`
// (Trenza1ore) moves the model's own origin there; `scale` | `sizeScale`
// scales it about that origin, uniformly or per axis ([x, y, z]); `euler`
// (Trenza1ore) turns it first, in degrees about the world x, then y, then z
// axes (its author's PlyParser: rotate, scale, then offset).
WorldTransform readPlacement(JsonObject& shape) {
  WorldPoint translation(0.0);
  glm::dvec3 scale(1.0);
  if (const std::optional<JsonNode> node =
          shape.optionalOneOf({"center", "pos", "offset", "position"})) {
    translation = node->point();
  }
  if (const std::optional<JsonNode> node = shape.optionalOneOf({"scale", "sizeScale"})) {
    if (node->raw().is_array()) {
      scale = glm::dvec3(node->vec3());
      if (!(scale.x > 0.0 && scale.y > 0.0 && scale.z > 0.0)) node->fail("must be positive");
    } else {
      scale = glm::dvec3(node->positiveFloat());
    }
  }
  WorldTransform rotation(1.0);
  if (const std::optional<JsonNode> node = shape.optional("euler")) {
    const glm::dvec3 degrees(node->vec3());
    for (int axis = 2; axis >= 0; --axis) {
      glm::dvec3 around(0.0);
      around[axis] = 1.0;
      rotation = rotation * glm::rotate(WorldTransform(1.0), glm::radians(degrees[axis]), around);
    }
  }
  return glm::translate(WorldTransform(1.0), translation) * glm::scale(WorldTransform(1.0), scale) *
         rotation;
}

// Reads each PLY file once, however many shapes place it. PLY errors keep
// their "<file>: byte <offset>: ..." and gain the JSON path in front.
uint32_t addPlyMesh(const JsonNode& fileNode, const fs::path& file, ShapeContext& context,
                    Scene& scene) {
  if (const auto found = context.plyMeshes.find(file); found != context.plyMeshes.end()) {
    return found->second;
  }
  try {
    scene.meshes.push_back(loadPly(file));
  } catch (const Error& error) {
    fileNode.fail(error.what());
  }
  const auto index = static_cast<uint32_t>(scene.meshes.size() - 1);
  context.plyMeshes.emplace(file, index);
  return index;
}

// An OBJ or glTF model placed in the scene: its own shapes, with its own
// materials unless the JSON shape gives one for all of them.
void addModelShapes(const JsonNode& fileNode, const fs::path& file, JsonObject& shape,
                    ShapeContext& context, Scene& scene) {
  const WorldTransform placement = readPlacement(shape);
  const size_t firstShape = scene.shapes.size();
  const size_t firstAreaLight = scene.areaLights.size();
  try {
    if (isObjFile(file)) {
      appendScenePart(scene, loadObjPart(file, placement));
    } else {
      appendGltf(scene, file, placement);
    }
  } catch (const Error& error) {
    fileNode.fail(error.what());
  }
  if (shape.has("material")) {
    // The JSON material replaces the file's, its glow (OBJ Ke) included.
    scene.areaLights.resize(firstAreaLight);
    const uint32_t material = addShapeMaterial(shape, context, scene);
    for (size_t i = firstShape; i < scene.shapes.size(); ++i) scene.shapes[i].material = material;
  }
  std::string label;
  if (const std::optional<JsonNode> id = shape.optional("id")) label = id->string();
  for (size_t i = firstShape; i < scene.shapes.size(); ++i) {
    if (!label.empty()) scene.shapes[i].label = label;
  }
}

// Mesh file keys as the students spelled them.
std::optional<JsonNode> meshFileKey(JsonObject& shape) {
  return shape.optionalOneOf(
      {"mPath", "plyPath", "file", "path", "filename", "objPath", "model", "modelpath"});
}

// Makes the last shape an area light whose surface has `radiance` (below).
void addEmitter(const glm::vec3& radiance, const JsonNode& where, Scene& scene);

// A mesh shape that names a file: a PLY mesh as one shape, an OBJ or glTF
// model as its own shapes. A file that is not there is a warning and the
// shape is left out (`false`).
bool readMeshFileShape(const JsonNode& fileNode, JsonObject& shape, ShapeContext& context,
                       Scene& scene) {
  for (const char* key : {"vertices", "faces"}) {
    if (shape.has(key)) {
      shape.diagnostics().fail(shape.childPath(key), "conflicts with '" + fileNode.path() +
                                                         "': give inline vertices or a mesh file");
    }
  }
  shape.ignore({"vs", "fs"});  // MBaczun: the file's vertex and face counts
  const std::optional<fs::path> file = findReferencedFile(fileNode, context.sceneDir);
  if (!file) {
    fileNode.warn(notFoundMessage(fileNode, context.sceneDir, "mesh") + "; the shape is left out");
    readPlacement(shape);
    shape.ignore({"id", "material"});
    return false;
  }
  if (isObjFile(*file) || isGltfFile(*file)) {
    addModelShapes(fileNode, *file, shape, context, scene);
    return false;
  }
  Shape out;
  out.geometry = MeshInstance{addPlyMesh(fileNode, *file, context, scene), readPlacement(shape)};
  if (const std::optional<JsonNode> id = shape.optional("id")) out.label = id->string();
  std::optional<glm::vec3> emission;
  out.material = addShapeMaterial(shape, context, scene, emission);
  scene.shapes.push_back(std::move(out));
  if (emission) addEmitter(*emission, shape.required("material"), scene);
  return true;
}

// An axis-aligned rectangle (sukriti27's "rectangleXY": x0 x1 y0 y1 and the
// constant z; likewise XZ and YZ).
Quad readAxisRectangle(const std::string& axes, JsonObject& shape) {
  const int a = axes[0] - 'x';
  const int b = axes[1] - 'x';
  const int c = 3 - a - b;
  const std::string na(1, axes[0]), nb(1, axes[1]), nc(1, char('x' + c));
  const float a0 = shape.required(na + "0").floatValue(),
              a1 = shape.required(na + "1").floatValue();
  const float b0 = shape.required(nb + "0").floatValue(),
              b1 = shape.required(nb + "1").floatValue();
  const float k = shape.required(nc).floatValue();
  const auto corner = [&](float u, float v) {
    WorldPoint p(0.0);
    p[a] = u;
    p[b] = v;
    p[c] = k;
    return p;
  };
  return {corner(a0, b0), corner(a1, b0), corner(a1, b1), corner(a0, b1)};
}

// Shape type spellings, matched without regard to case: the canonical name
// first. "ply" and "obj" shapes always name a file.
// Trenza1ore's uvsphere, sphericalmap and cubemap are spheres and uvcylinder
// a cylinder, each with its own texture mapping (read as the plain shape's).
const std::vector<std::vector<std::string_view>> kShapeTypes = {
    {"sphere", "uvsphere", "sphericalmap", "cubemap"},
    {"plane", "planarquad", "planerquad", "planar_quad", "quad", "rectangle", "rect"},
    {"triangle", "traingle", "tri"},
    {"cylinder", "uvcylinder"},
    {"box", "cube", "aabb"},
    {"trimesh", "mesh", "ply", "obj", "model", "trianglemesh"},
    {"rectanglexy"},
    {"rectanglexz"},
    {"rectangleyz"},
};

// The canonical shape type of `typeNode`, e.g. "plane" for "PlanerQuad".
std::string shapeType(const JsonNode& typeNode) {
  const std::string written = lowercase(typeNode.string());
  for (const std::vector<std::string_view>& names : kShapeTypes) {
    if (std::find(names.begin(), names.end(), written) != names.end()) {
      return std::string(names.front());
    }
  }
  typeNode.fail("unknown shape type '" + typeNode.string() +
                "' (expected sphere, plane, triangle, cylinder, box, trimesh, mesh or ply; README "
                "'Student scenes' lists the other spellings)");
}

// isaacery's infinite plane {normal n, distance d}: the points p with
// n . p = d. Shapes here are finite, so it becomes a square this many units
// from its centre to each side, centred at the plane's point nearest the
// origin (a warning says so).
constexpr double kInfinitePlaneHalfSize = 1e4;

Quad readInfinitePlane(JsonObject& shape) {
  const glm::dvec3 normal(unitVector(shape.required("normal")));
  const double distance = shape.required("distance").number();
  shape.diagnostics().warn(shape.path(),
                           "an infinite plane: drawn as a square 20000 units across, centred at "
                           "its point nearest the origin");
  const WorldPoint center = normal * distance;
  const glm::dvec3 helper = std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(normal, helper)) * kInfinitePlaneHalfSize;
  const glm::dvec3 v = glm::cross(normal, u);
  return {center - u - v, center + u - v, center + u + v, center - u + v};
}

Geometry readGeometry(const JsonNode& typeNode, const std::string& type, JsonObject& shape,
                      Scene& scene) {
  if (type == "sphere") return readSphere(shape);
  if (type == "plane" && shape.has("normal") && shape.has("distance")) {
    return readInfinitePlane(shape);
  }
  if (type == "plane") return readQuad(shape);
  if (type == "triangle" && hasCornerAttributes(shape)) {
    return addInlineMesh(readAttributedTriangle(shape), scene);
  }
  if (type == "triangle") return readTriangle(shape);
  if (type == "cylinder") return readCylinder(shape);
  if (type == "box") return addInlineMesh(readBox(shape), scene);
  if (type == "rectanglexy" || type == "rectanglexz" || type == "rectangleyz") {
    return readAxisRectangle(type.substr(9), shape);
  }
  const std::string written = lowercase(typeNode.string());
  if (written == "ply" || written == "obj") {
    shape.diagnostics().fail(shape.childPath("file"), "missing: a " + written +
                                                          " shape needs its file (file, path, "
                                                          "mPath, plyPath or filename)");
  }
  return addInlineMesh(readInlineMesh(shape), scene);
}

// A shape that glows (nizqleo's path-traced scenes: "emittence": [r, g, b],
// its radiance) becomes an area light of that surface (addRadianceEmitter).
void addEmitter(const glm::vec3& radiance, const JsonNode& where, Scene& scene) {
  if (radiance == glm::vec3(0.0f)) return;
  const auto shape = static_cast<uint32_t>(scene.shapes.size() - 1);
  if (!addRadianceEmitter(scene, shape, radiance)) {
    where.fail("the shape has no area to emit from");
  }
}

void readShapeEmission(JsonObject& object, Scene& scene) {
  const std::optional<JsonNode> emitted =
      object.optionalOneOf({"emittence", "emittance", "emissive"});
  if (emitted) addEmitter(intensityOf(*emitted), *emitted, scene);
}

void readShape(const JsonNode& node, ShapeContext& context, Scene& scene) {
  JsonObject object = node.object();
  const JsonNode typeNode = object.required("type");
  const std::string type = shapeType(typeNode);
  const std::optional<JsonNode> file = type == "trimesh" ? meshFileKey(object) : std::nullopt;
  const size_t firstShape = scene.shapes.size();
  if (file) {
    readMeshFileShape(*file, object, context, scene);
  } else {
    Shape shape;
    shape.geometry = readGeometry(typeNode, type, object, scene);
    if (const std::optional<JsonNode> id = object.optional("id")) shape.label = id->string();
    std::optional<glm::vec3> materialEmission;
    shape.material = addShapeMaterial(object, context, scene, materialEmission);
    scene.shapes.push_back(std::move(shape));
    readShapeEmission(object, scene);
    if (materialEmission) addEmitter(*materialEmission, object.required("material"), scene);
  }
  for (size_t i = firstShape; i < scene.shapes.size(); ++i) {
    std::string& origin = scene.shapes[i].origin;
    origin = origin.empty() ? node.path() : node.path() + " (" + origin + ")";
  }
  ignoreRendererKeys(object);
  object.reportUnknownKeys();
}

// -------------------------------------------------------------------- scene

// The shape an area light names by its `id`: exactly one, not yet a light.
uint32_t findLightShape(const JsonNode& id, const Scene& scene) {
  const std::string label = id.nonEmptyString();
  std::optional<uint32_t> found;
  for (uint32_t i = 0; i < scene.shapes.size(); ++i) {
    if (scene.shapes[i].label != label) continue;
    if (found) id.fail("shape id '" + label + "' is not unique: give the light's shape one id");
    found = i;
  }
  if (!found) id.fail("no shape has the id '" + label + "'");
  for (const AreaLight& light : scene.areaLights) {
    if (light.shape == *found) id.fail("shape '" + label + "' already is a light");
  }
  return *found;
}

// A light's own surface becomes a shape that only emits (black otherwise),
// so that the camera and mirrors see it. Binary mode draws the file's shapes
// only.
void addAreaLights(const LightList& lights, RenderMode mode, Scene& scene) {
  for (const PendingAreaLight& pending : lights.areaLights) {
    AreaLight light = pending.light;
    if (pending.shapeId) {
      light.shape = findLightShape(*pending.shapeId, scene);
    } else {
      if (mode == RenderMode::Binary) continue;
      light.shape = addEmitterShape(scene, *pending.geometry,
                                    "area light " + std::to_string(scene.areaLights.size()));
    }
    scene.areaLights.push_back(light);
  }
}

// `ambientlight` (HlnnnWnng): light every hit receives, times its diffuse
// colour. The path tracer has no ambient term.
void readAmbientLight(JsonObject& object, Scene& scene) {
  const std::optional<JsonNode> node =
      object.optionalOneOf({"ambientlight", "ambient_light", "ambientLight"});
  if (node) setAmbientLight(node->nonNegativeVec3(), *node, scene);
  // isaacery: a number that each material's `ka` scales.
  object.ignoreWithWarning("ambient",
                           "ignored: an ambient light scaled per material (ka) is not drawn");
}

// Sampling settings inside `scene` (Seanst98's renderer reads them there):
// used where the top level and the camera give none, else ignored.
void readSceneSampling(JsonObject& object, RenderSettings& settings) {
  const auto ignored = [](const JsonNode& node) {
    node.warn("ignored: the top level or the camera already sets it");
  };
  if (const std::optional<JsonNode> node = samplerKey(object)) {
    if (settings.samplerGiven) {
      ignored(*node);
    } else {
      settings.sampler = parseSampler(*node);
      settings.samplerGiven = true;
    }
  }
  if (const std::optional<JsonNode> node = object.optionalOneOf({"nsamples", "samples", "spp"})) {
    if (settings.samplesPerPixel != 0) {
      ignored(*node);
    } else {
      settings.samplesPerPixel = parseSampleCount(*node);
    }
  }
}

// `object` is the file's `scene`, or the top level itself for files that
// put lights and shapes there (`flat`: its unknown keys are reported later).
LightList readSceneObject(JsonObject& object, ShapeContext& context, Scene& scene, bool flat) {
  if (const std::optional<JsonNode> background =
          object.optionalOneOf({"backgroundcolor", "backgroundcolour"})) {
    scene.backgroundColor = background->nonNegativeVec3();
  }
  readAmbientLight(object, scene);
  context.namedMaterials = readNamedMaterials(object, context.sceneDir, scene);
  LightList lights;
  if (const std::optional<JsonNode> list = object.optionalOneOf({"lightsources", "lights"})) {
    for (const JsonNode& light : list->array()) readLight(light, scene, lights);
  }
  const std::optional<JsonNode> shapes = object.optionalOneOf({"shapes", "objects"});
  if (!shapes) object.diagnostics().fail(object.childPath("shapes"), "missing required key");
  for (const JsonNode& shape : shapes->array()) readShape(shape, context, scene);
  addAreaLights(lights, context.mode, scene);
  ignoreRendererKeys(object);
  if (!flat) {
    readSceneSampling(object, scene.settings);
    object.reportUnknownKeys();
  }
  return lights;
}

// A camera without a view direction looks along the z axis (the 2019 file's
// spheres lie at +z, TsFreddie's at -z): towards the side the shapes are
// on, planes left out (floors and walls reach past the camera).
void chooseDefaultView(Scene& scene) {
  double side = 0.0;
  double planeSide = 0.0;
  for (const Shape& shape : scene.shapes) {
    const double z = geometryCenter(shape.geometry, scene.meshes).z - scene.camera.position.z;
    (std::holds_alternative<Quad>(shape.geometry) ? planeSide : side) += z;
  }
  if (side == 0.0) side = planeSide;
  if (side < 0.0) scene.camera.forward = -kDefaultForward;
}

// The loader's warnings, ahead of those models read from other files (OBJ,
// glTF) brought, and the values it read.
void takeDiagnostics(Diagnostics& diagnostics, Scene& scene) {
  std::vector<std::string> own = diagnostics.takeWarnings();
  makePrintable(own);
  scene.warnings.insert(scene.warnings.begin(), own.begin(), own.end());
  scene.valuesRead = diagnostics.takeReads();
}

Scene readScene(std::string_view jsonText, const fs::path& file) {
  Diagnostics diagnostics(file.string());
  const Json document = parseJson(jsonText, file.string(), diagnostics);
  if (looksLikeBlenderExport(document)) {
    Scene scene = readBlenderExport(document, file, diagnostics);
    takeDiagnostics(diagnostics, scene);
    return scene;
  }
  Scene scene;
  scene.sourcePath = file;
  const JsonNode root(document, "", diagnostics);
  JsonObject top = root.object();
  ChosenConventions chosen = chooseConventions(top, document);
  scene.settings.maxBounces = readBounces(top);
  scene.settings.mode = readRenderMode(top);
  scene.settings.distributedBounces = readDistributedBounces(top, scene.settings.mode);
  scene.settings.indirectClamp = readIndirectClamp(top);
  JsonObject camera = top.required("camera").object();
  const bool defaultView = std::none_of(kViewKeys.begin(), kViewKeys.end(),
                                        [&](const char* key) { return camera.has(key); });
  scene.camera = readCamera(camera);
  scene.camera.toneCurve = readToneCurve(top, camera);
  readOutputScale(top, scene.camera);
  const bool samplerGiven = readSampling(top, camera, scene.settings);
  camera.reportUnknownKeys();
  ShapeContext context{absoluteFolderOf(file), scene.settings.mode, {}};
  // Some students put lights and shapes at the top level, beside the camera.
  const bool flat = !top.has("scene") && (top.has("shapes") || top.has("objects"));
  if (flat) diagnostics.warn("", "no 'scene' object: lights and shapes read from the top level");
  std::optional<JsonObject> nested;
  if (!flat) nested = top.required("scene").object();
  const LightList lights = readSceneObject(flat ? top : *nested, context, scene, flat);
  if (lights.sampler && !samplerGiven) {
    scene.settings.sampler = *lights.sampler;
    scene.settings.samplerGiven = true;
  }
  readStratifiedSwitch(top, scene.settings);
  if (defaultView) chooseDefaultView(scene);
  setConventions(scene, chosen.conventions, std::move(chosen.reason));
  ignoreRendererKeys(top);
  readRendererSwitches(top);
  top.reportUnknownKeys();
  takeDiagnostics(diagnostics, scene);
  return scene;
}

}  // namespace

Scene parseJsonScene(std::string_view jsonText, const fs::path& file) {
  return withPrintableErrors([&] { return readScene(jsonText, file); });
}

Scene loadJsonScene(const fs::path& file) {
  return withPrintableErrors([&] { return readScene(readFileOrThrow(file), file); });
}

std::optional<SamplerKind> samplerKindNamed(const std::string& name) {
  if (name == "random") return SamplerKind::Random;
  if (name == "jittered" || name == "jittering" || name == "grid") return SamplerKind::Jittered;
  if (name == "sobol" || name == "owen-sobol" || name == "ld" || name == "lowdiscrepancy" ||
      name == "low-discrepancy") {
    return SamplerKind::Sobol;
  }
  return std::nullopt;
}

const char* samplerKindName(SamplerKind kind) {
  switch (kind) {
    case SamplerKind::Random: return "random";
    case SamplerKind::Jittered: return "jittered";
    case SamplerKind::Sobol: return "sobol";
  }
  return "unknown";
}

}  // namespace rt
