// Host-side scene: what a scene file describes, in one neutral form that
// both file families, PLY and glTF files are loaded into. Nothing here knows
// about the GPU; src/render flattens it into buffers.
#pragma once

#include <compare>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "io/Image.hpp"

namespace rt {

// World positions are double precision: a scene 1e-4 across placed 1e9 from
// the origin keeps its shape in the model, and the GPU encoding
// (encode/FlatScene) subtracts the camera's position before it rounds to
// float. Directions, radii and object-space mesh vertices stay float: their
// precision is relative to their own size.
using WorldPoint = glm::dvec3;
using WorldTransform = glm::dmat4;  // affine object-to-world placement

// Blinn-Phong material with Whitted-style mirror and refraction weights.
struct Material {
  glm::vec3 diffuseColor{0.8f};
  glm::vec3 specularColor{1.0f};
  float kd = 1.0f;
  float ks = 0.0f;
  float specularExponent = 1.0f;
  float reflectivity = 0.0f;  // mirror weight (family A `kr`, B `reflectivity` when `isreflective`)
  float transmission = 0.0f;  // refraction weight (family A `kt`, B 1.0 when `isrefractive`)
  float ior = 1.0f;           // index of refraction inside the surface (`eta`, `refractiveindex`)
  std::filesystem::path texture;  // where the diffuse texture came from (messages, UI)
  int32_t diffuseTexture = -1;    // index into Scene::textures, -1 when none
  // false: the texture replaces diffuseColor (coursework files);
  // true: texture * diffuseColor (glTF base colour factor).
  bool textureTintedByColor = false;
  // A tangent-space normal map (glTF normalTexture: x right along u, y up
  // against v, z out), index into Scene::textures, -1 when none; `normalScale`
  // scales its x and y.
  int32_t normalTexture = -1;
  float normalScale = 1.0f;
  // A glow: light the surface shows, `glow` times the texture `glowTexture`
  // (index into Scene::textures; -1: `glow` alone), and that lights nothing
  // else (glTF emissive textures, whose detail cannot be one light; glTF
  // unlit materials). A black glow without a texture is none.
  glm::vec3 glow{0.0f};
  int32_t glowTexture = -1;
  // Whether the glow is also multiplied by the mesh's vertex colours: a glTF
  // unlit material's base colour is, an emissive texture is not.
  bool glowTimesVertexColors = false;
  bool glows() const { return glowTexture >= 0 || glow != glm::vec3(0.0f); }
  // glTF metallic and roughness: with a metallic-roughness texture (index
  // into Scene::textures, data: blue metallic, green roughness; -1: none) the
  // factors its texels are multiplied by, and the kernels convert each
  // point's values (shaders/metal_rough.h; kd, ks, the exponent and
  // reflectivity above are those of the texture's mean); without, the values
  // themselves.
  int32_t metalRoughTexture = -1;
  float metallic = 0.0f;
  float roughness = 1.0f;
  // Mirror reflections tinted by specularColor (glTF materials, whose metals
  // reflect their base colour); the coursework files' mirrors are untinted.
  bool tintedMirror = false;
  // Light through the surface (transmission) tinted by the diffuse colour at
  // the point, texture and vertex colours included (glTF, whose transmitted
  // light takes the base colour); the coursework files' glass is untinted.
  bool tintedTransmission = false;
  // Light passes through the surface without bending: a thin shell, not the
  // face of a solid (glTF transmission without KHR_materials_volume's
  // thickness); the Fresnel reflection stays that of `ior`.
  bool thinWalled = false;
  // glTF's transmission texture (index into Scene::textures, linear data;
  // -1: none): the transmission at a point is `transmission` times its red
  // channel there, and kd follows as for metallic-roughness textures.
  int32_t transmissionTexture = -1;
  // Where the surface is there at all (glTF alphaMode): alpha is
  // `alphaFactor` times the alpha channel of `alphaTexture` (index into
  // Scene::textures, -1: none) at the point. Mask: there where alpha >=
  // `alphaCutoff`, a hole elsewhere. Blend: there for a share alpha of the
  // rays (stochastic transparency: samples average to alpha blending).
  // Mesh shapes only: a material with holes on other shapes draws them whole.
  enum class Alpha { Opaque, Mask, Blend };
  Alpha alphaMode = Alpha::Opaque;
  float alphaFactor = 1.0f;
  float alphaCutoff = 0.5f;
  int32_t alphaTexture = -1;
};

// A decoded texture image: sRGB-encoded colours as in the file, or data
// (`linear`: a normal map's directions).
// How a texture is read between and beyond its texels (glTF samplers; every
// other format repeats and filters bilinearly): per axis, repeat, clamp to
// the edge or mirror; bilinear or nearest (pixel art, voxel models).
struct TextureSampling {
  enum class Wrap { Repeat, Clamp, Mirror };
  Wrap wrapU = Wrap::Repeat;
  Wrap wrapV = Wrap::Repeat;
  bool nearest = false;
  bool isDefault() const { return *this == TextureSampling{}; }
  auto operator<=>(const TextureSampling&) const = default;
};

struct Texture {
  std::string source;  // file path or glTF image name
  ImageRgba8 image;
  bool linear = false;
  TextureSampling sampling;
};

struct Sphere {
  WorldPoint center{0.0};
  float radius = 1.0f;
};

struct Triangle {
  WorldPoint v0{0.0}, v1{0.0}, v2{0.0};
};

// Planar quad, vertices in cyclic order (family A `plane`).
struct Quad {
  WorldPoint v0{0.0}, v1{0.0}, v2{0.0}, v3{0.0};
};

// Finite capped cylinder (family B): caps at center +- axis * halfHeight.
struct Cylinder {
  WorldPoint center{0.0};
  glm::vec3 axis{0.0f, 1.0f, 0.0f};  // unit length after loading
  float radius = 1.0f;
  float halfHeight = 1.0f;
};

// An indexed triangle mesh in its own (object) space. `normals`, `uvs` and
// `colors` are per vertex and either empty or as long as `positions`.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> faces;   // indices into positions, validated on load
  std::vector<glm::vec3> normals;  // smooth shading normals (unit), optional
  std::vector<glm::vec2> uvs;      // texture coordinates, optional
  // Vertex colours, linear RGB in [0, 1], optional: the material's diffuse
  // colour (and its texture) is multiplied by them, as glTF's COLOR_0 is.
  std::vector<glm::vec3> colors;
};

// A shape that places one of Scene::meshes: meshes live apart from shapes so
// that several shapes can share one mesh (and, on the GPU, its BVH).
struct MeshInstance {
  uint32_t mesh = 0;  // index into Scene::meshes
  WorldTransform objectToWorld{1.0};
};

using Geometry = std::variant<Sphere, Triangle, Quad, Cylinder, MeshInstance>;

struct Shape {
  Geometry geometry;
  uint32_t material = 0;  // index into Scene::materials
  std::string label;      // optional `id` from the file, for messages
  // Where the file describes it ("scene.shapes[3]", "crate.obj: material
  // 'wood'"), for `raytracer check`; empty when the label says enough.
  std::string origin;
};

struct PointLight {
  WorldPoint position{0.0};
  glm::vec3 diffuseIntensity{1.0f};   // family A `id`, family B / 2019 `intensity`
  glm::vec3 specularIntensity{1.0f};  // family A `is`, family B / 2019 `intensity`
};

// A shape that emits light: an area light. Its intensities mean what a
// point light's mean (for family A the power that falls off as
// I / (4 pi d^2)), spread evenly over the shape's surface, so a small light
// far away lights like the point light of the same intensity.
// Isotropic: every point of the surface shines like a small point light,
// equally in all directions (what the coursework reports describe).
// Lambertian: the same power, radiance equal in all directions (physical
// lamps; a flat light then hardly lights surfaces in its own plane).
enum class EmissionProfile { Isotropic, Lambertian };

struct AreaLight {
  uint32_t shape = 0;                // index into Scene::shapes: the emitting surface
  glm::vec3 diffuseIntensity{1.0f};  // like PointLight
  glm::vec3 specularIntensity{1.0f};
  uint32_t samples = 1;  // shadow rays per shading point and pixel sample
  EmissionProfile profile = EmissionProfile::Isotropic;  // spheres are always Lambertian
};

enum class CameraType { Pinhole, ThinLens };

// Which way image right points: forward x up (right-handed; family A, glTF)
// or up x forward (family B's renderers: a camera at the origin looking down
// +z with up +y sees world -x on the left). Image up is `up` made orthogonal
// to forward either way.
enum class ImageRight { ForwardCrossUp, UpCrossForward };

struct Camera {
  CameraType type = CameraType::Pinhole;
  uint32_t width = 800;
  uint32_t height = 800;
  float fovYDegrees = 45.0f;  // vertical field of view
  WorldPoint position{0.0};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};    // unit view direction
  glm::vec3 up{0.0f, 1.0f, 0.0f};          // as given; orthogonalised when rays are built
  float exposure = 1.0f;                   // linear scale applied before tone mapping
  ToneCurve toneCurve = ToneCurve::Clamp;  // `tone_mapping`, `use_tone_mapping`
  float apertureRadius = 0.0f;             // thin lens: radius of the lens disc, 0 = pinhole
  float focusDistance = 1.0f;              // thin lens: distance to the plane in focus
  ImageRight imageRight = ImageRight::ForwardCrossUp;
};

// The camera's unit basis: image right, image up and the view direction.
struct CameraBasis {
  glm::vec3 right, up, forward;
};
CameraBasis cameraBasis(const Camera& camera);

// Phong: Whitted ray tracing (mirror and refraction branches), direct light
// from point and area lights, and optionally `distributedBounces` sampled
// diffuse bounces. PathTracer: Monte Carlo path tracing of the same
// materials (one sampled continuation per hit), physically consistent with
// the direct lighting of Phong mode.
enum class RenderMode { Binary, Phong, PathTracer };

enum class SamplerKind { Random, Jittered, Sobol };  // Sobol: Owen-scrambled (rng.glsl)

// How a scene's numbers become an image: light falloff and scale, the
// shading model, ambient light, how mirrors mix with a surface's own
// shading, which way image right points, and 8-bit quantization. Neither
// coursework wrote them down; README "Conventions" gives each set and its
// evidence, render/Conventions.hpp what each means for the renderer.
enum class Conventions {
  CourseworkA,  // "Path of Light": fitted to the official renders
  CourseworkB,  // "Rendering" 2023-24: fitted to a student's renders of the official files
  Textbook,     // Whitted with unit lights: no falloff, per-channel Blinn-Phong, no ambient
  // Physical units as the peers (Mitsuba, POV-Ray) read the common scene:
  // falloff I / (4 pi d^2), per-channel Blinn-Phong, sRGB-encoded output.
  Physical,
};

// The canonical names ("coursework-a", "coursework-b", "textbook", "physical") of the
// `conventions` scene key and --conventions; nullopt for anything else.
std::optional<Conventions> conventionsNamed(const std::string& name);
const char* conventionsName(Conventions conventions);

struct RenderSettings {
  RenderMode mode = RenderMode::Phong;
  uint32_t maxBounces = 4;          // `nbounces`: Whitted depth, path length in PathTracer mode
  uint32_t distributedBounces = 0;  // sampled diffuse bounces in Phong mode
  // Firefly clamp (`clampindirect`): the largest channel one light or
  // emitter contribution may add after a diffuse bounce; 0 = off. Biased
  // (it darkens caustics), so off unless asked for.
  float indirectClamp = 0.0f;
  // Russian roulette on the mirror and refraction rays of the Whitted tree:
  // a branch whose weight is below this survives with probability
  // weight / rouletteWeight, reweighted to rouletteWeight (unbiased). On
  // default.json 0.03 made samples 1.27x faster for 4-6% more error at equal
  // samples, but its lanes disagree: no faster on lavapipe (bench/README.md).
  // Off (0: every branch is traced) unless asked for
  // (`--roulette`).
  float rouletteWeight = 0.0f;
  // Bailout of the Whitted tree (`--bailout`, POV-Ray's adc_bailout): mirror,
  // glass and diffuse-bounce branches whose weight (the product of the
  // reflectivities, transmissions and albedos on the way) is below this are
  // not traced, nor shadow rays whose light could add less to the pixel
  // (shading.glsl directLighting). In steps of the written image (the
  // encoder divides by the display's slope). At 1/255 a dropped branch
  // changes an 8-bit pixel by at most its radiance in 1/255 steps; the
  // common scene renders 1.25x faster than with every ray traced,
  // `default.json` 1.27x (README "Speed vs accuracy"). The path tracer
  // ignores it: its weights are whole path throughputs, which fall below
  // 1/255 on long diffuse paths that matter.
  float branchBailout = 1.0f / 255.0f;
  // Light splitting (`--light-split`): each hit's area-light estimate is
  // made this many times over, with its own shadow rays, each through the
  // hit's whole shading (clamps included), and averaged: less noise from
  // the lights a sample for more shadow rays, converging to the image of
  // one (shading.glsl hitLocalLight). More samples per light
  // (`--light-samples`) change the image where the shading clamps a hit's
  // summed light; this does not. 0: automatic (encode/Features.cpp
  // lightReplicasFor: in adaptive renders of direct light), 1: off.
  uint32_t lightSplit = 0;
  uint32_t samplesPerPixel = 0;  // 0: not given in the file
  SamplerKind sampler = SamplerKind::Jittered;
  bool samplerGiven = false;  // the file names a sampler (see samplerUnlessAsked)
  bool adaptive = false;      // `adaptive`: adaptive sampling (render/AdaptiveSampling.hpp)
};

// The sampler of a render whose command line or viewer names none: the
// file's, but Sobol for progressive renders whatever the file names:
// adaptive ones, and those that a time budget or a target ends without a
// sample count. Their counts are not known when sampling starts, and
// jittered strata are laid out for one count: study-thinlens.json (which
// names jittered) adaptive at a mean of 6 had an RMSE of 0.0128 with
// jittered, 0.0083 with Sobol, 0.0118 uniform jittered; laid out for 2^20
// samples, the first few jittered ones are as good as random.
SamplerKind samplerUnlessAsked(const RenderSettings& settings, bool progressive);

struct Scene {
  std::filesystem::path sourcePath;
  // How the file was read ("coursework JSON", "Blender scene export",
  // "glTF", "OBJ"), for `raytracer check`.
  std::string fileKind;
  Conventions conventions = Conventions::CourseworkA;
  std::string conventionsReason;  // why the loader chose them, e.g. "key 'rendermode'"
  RenderSettings settings;
  Camera camera;
  glm::vec3 backgroundColor{0.0f};
  // `ambientlight`: light every hit receives, times its diffuse colour (Phong
  // mode); replaces the conventions' ambient term. nullopt: the conventions'.
  std::optional<glm::vec3> ambientLight;
  std::vector<PointLight> pointLights;
  std::vector<AreaLight> areaLights;
  std::vector<Material> materials;
  std::vector<Shape> shapes;
  std::vector<TriangleMesh> meshes;
  std::vector<Texture> textures;
  std::vector<std::string> warnings;  // unknown keys and ignored features, one line each
  // Every value the JSON loader read, "path = value" in reading order
  // ("camera.fov = 45"): where each setting came from, for `raytracer check`.
  std::vector<std::string> valuesRead;
};

// Gives the scene its conventions, and the camera the image right they
// imply; `reason` says why (for messages).
void setConventions(Scene& scene, Conventions conventions, std::string reason);

// Adds the visible shape of an area light that no scene shape stands for (an
// emitter given by its geometry alone): a shape of its own, with a black
// material of its own, so that it shows only the light's emission. Returns
// the shape's index, for AreaLight::shape.
uint32_t addEmitterShape(Scene& scene, Geometry geometry, std::string label);

// The area of any shape; meshes are looked up in `meshes`.
float surfaceArea(const Geometry& geometry, const std::vector<TriangleMesh>& meshes);

// Whether `geometry` places a mesh with vertex colours (any other shape has
// none: its colours count as white); meshes are looked up in `meshes`.
bool hasVertexColors(const Geometry& geometry, const std::vector<TriangleMesh>& meshes);

// Makes shape `shape` an area light whose surface glows with `radiance` (a
// Lambertian light, four shadow rays a hit): file formats that give an
// emitting material's radiance (JSON emitters, OBJ `Ke`). False, and no
// light, when the shape has no area to emit from.
bool addRadianceEmitter(Scene& scene, uint32_t shape, const glm::vec3& radiance);

// Gives every area light `samples` shadow rays a hit (`--light-samples`, the
// viewer's control): fewer noisy shadows a sample for more time a sample.
void setAreaLightSamples(Scene& scene, uint32_t samples);

}  // namespace rt
