// raytracer check SCENE: how the renderer reads a scene file, without
// rendering: what the student runs when the image does not look like their
// own renderer's. Exit 0 when the scene loads (1 with --strict and a
// warning), 1 on an error.
#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <variant>

#include "app/CommandLine.hpp"
#include "app/Commands.hpp"
#include "encode/Conventions.hpp"
#include "encode/Features.hpp"
#include "encode/FlatScene.hpp"
#include "formats/SceneFile.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "util/Error.hpp"

namespace {

struct CommandLine {
  std::string scenePath;
  std::string conventions;
  bool strict = false;
  rt::cli::ModeOptions modeOptions;
};

// + 0.0f: no "-0" in what people read.
std::string vec(glm::vec3 v) {
  return fmt::format("({:g}, {:g}, {:g})", v.x + 0.0f, v.y + 0.0f, v.z + 0.0f);
}

// Positions in their double precision: the shortest text that reads back the same.
std::string vec(const glm::dvec3& v) {
  return fmt::format("({}, {}, {})", v.x + 0.0, v.y + 0.0, v.z + 0.0);
}

const char* modeName(rt::RenderMode mode) {
  switch (mode) {
    case rt::RenderMode::Binary: return "binary";
    case rt::RenderMode::Phong: return "phong (Whitted)";
    case rt::RenderMode::PathTracer: return "path tracer";
  }
  return "?";
}

std::string geometryText(const rt::Geometry& geometry, const rt::Scene& scene) {
  return std::visit(
      [&](const auto& g) -> std::string {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, rt::Sphere>) {
          return fmt::format("sphere centre {} radius {:g}", vec(g.center), g.radius);
        } else if constexpr (std::is_same_v<T, rt::Triangle>) {
          return fmt::format("triangle {} {} {}", vec(g.v0), vec(g.v1), vec(g.v2));
        } else if constexpr (std::is_same_v<T, rt::Quad>) {
          return fmt::format("quad {} {} {} {}", vec(g.v0), vec(g.v1), vec(g.v2), vec(g.v3));
        } else if constexpr (std::is_same_v<T, rt::Cylinder>) {
          return fmt::format("cylinder centre {} axis {} radius {:g} half height {:g}",
                             vec(g.center), vec(g.axis), g.radius, g.halfHeight);
        } else {
          const rt::TriangleMesh& mesh = scene.meshes.at(g.mesh);
          return fmt::format("mesh of {} triangles{}{}{}", mesh.faces.size(),
                             mesh.normals.empty() ? "" : ", smooth normals",
                             mesh.uvs.empty() ? "" : ", texture coordinates",
                             mesh.colors.empty() ? "" : ", vertex colours");
        }
      },
      geometry);
}

// ", alpha MASK at 0.5: 1 times the texture's alpha", ", alpha BLEND: 0.25";
// nothing when opaque.
std::string alphaText(const rt::Scene& scene, const rt::Material& m) {
  if (m.alphaMode == rt::Material::Alpha::Opaque) return "";
  std::string text = m.alphaMode == rt::Material::Alpha::Mask
                         ? fmt::format(", alpha MASK at {:g}: {:g}", m.alphaCutoff, m.alphaFactor)
                         : fmt::format(", alpha BLEND: {:g}", m.alphaFactor);
  if (m.alphaTexture >= 0 && m.alphaTexture == m.diffuseTexture) {
    text += " times the texture's alpha";
  } else if (m.alphaTexture >= 0) {
    text += " times the alpha of " + scene.textures.at(size_t(m.alphaTexture)).source;
  }
  return text;
}

// `vertexColors`: whether the shape using `m` has vertex colours.
std::string materialText(const rt::Scene& scene, const rt::Material& m, bool vertexColors) {
  std::string text =
      fmt::format("kd {:g} diffuse {}, ks {:g} specular {} exponent {:g}", m.kd,
                  vec(m.diffuseColor), m.ks, vec(m.specularColor), m.specularExponent);
  if (m.reflectivity > 0.0f) text += fmt::format(", mirror {:g}", m.reflectivity);
  if (m.transmission > 0.0f) {
    text += fmt::format(", glass {:g}", m.transmission);
    if (m.transmissionTexture >= 0) {
      text += " times the red of " + scene.textures.at(size_t(m.transmissionTexture)).source;
    }
    text += fmt::format(" ior {:g}", m.ior);
    if (m.tintedTransmission) text += ", tinted by the diffuse colour";
    if (m.thinWalled) text += ", a thin wall";
  }
  if (!m.texture.empty()) text += ", texture " + m.texture.string();
  if (m.normalTexture >= 0) {
    text += fmt::format(", normal map {}", scene.textures.at(size_t(m.normalTexture)).source);
    if (m.normalScale != 1.0f) text += fmt::format(" scale {:g}", m.normalScale);
  }
  if (m.glows()) {
    text += fmt::format(", glow {}", vec(m.glow));
    if (m.glowTexture >= 0) text += " times " + scene.textures.at(size_t(m.glowTexture)).source;
    if (m.glowTimesVertexColors && vertexColors) text += " times vertex colours";
  }
  if (m.metalRoughTexture >= 0) {
    text += fmt::format(", metallic {:g} roughness {:g} times {}", m.metallic, m.roughness,
                        scene.textures.at(size_t(m.metalRoughTexture)).source);
  }
  return text + alphaText(scene, m);
}

void printCamera(const rt::Scene& scene) {
  const rt::Camera& c = scene.camera;
  const rt::CameraBasis basis = rt::cameraBasis(c);
  std::printf("camera: %s %ux%u, vertical fov %g degrees\n",
              c.type == rt::CameraType::ThinLens ? "thin lens" : "pinhole", c.width, c.height,
              double(c.fovYDegrees));
  std::printf("  position %s, looking along %s, image right %s, image up %s\n",
              vec(c.position).c_str(), vec(basis.forward).c_str(), vec(basis.right).c_str(),
              vec(basis.up).c_str());
  if (c.type == rt::CameraType::ThinLens) {
    std::printf("  lens radius %g, in focus at distance %g\n", double(c.apertureRadius),
                double(c.focusDistance));
  }
  if (c.exposure != 1.0f) std::printf("  exposure %g\n", double(c.exposure));
  if (c.toneCurve != rt::ToneCurve::Clamp) {
    std::printf("  tone curve %s (after the exposure)\n", rt::toneCurveName(c.toneCurve));
  }
}

void printLights(const rt::Scene& scene) {
  std::printf("lights: %zu point, %zu area\n", scene.pointLights.size(), scene.areaLights.size());
  for (size_t i = 0; i < scene.pointLights.size(); ++i) {
    const rt::PointLight& light = scene.pointLights[i];
    std::printf("  point light %zu at %s, diffuse %s, specular %s\n", i,
                vec(light.position).c_str(), vec(light.diffuseIntensity).c_str(),
                vec(light.specularIntensity).c_str());
  }
  for (size_t i = 0; i < scene.areaLights.size(); ++i) {
    const rt::AreaLight& light = scene.areaLights[i];
    std::printf("  area light %zu: shape %u, diffuse %s, specular %s, %u shadow ray(s), %s\n", i,
                light.shape, vec(light.diffuseIntensity).c_str(),
                vec(light.specularIntensity).c_str(), light.samples,
                light.profile == rt::EmissionProfile::Isotropic ? "isotropic" : "lambertian");
  }
}

void printShapes(const rt::Scene& scene) {
  std::printf("shapes: %zu\n", scene.shapes.size());
  for (size_t i = 0; i < scene.shapes.size(); ++i) {
    const rt::Shape& shape = scene.shapes[i];
    std::string from = shape.origin.empty() ? shape.label : shape.origin;
    if (!shape.label.empty() && shape.label != from) from += " '" + shape.label + "'";
    std::printf("  %zu%s: %s\n", i, from.empty() ? "" : (" [" + from + "]").c_str(),
                geometryText(shape.geometry, scene).c_str());
    std::printf("     material: %s\n",
                materialText(scene, scene.materials.at(shape.material),
                             rt::hasVertexColors(shape.geometry, scene.meshes))
                    .c_str());
  }
}

void printList(const char* title, const std::vector<std::string>& lines) {
  std::printf("%s: %zu\n", title, lines.size());
  for (const std::string& line : lines) std::printf("  %s\n", line.c_str());
}

int run(const CommandLine& cli) {
  rt::Scene scene = rt::loadSceneFile(cli.scenePath, {cli.strict});
  rt::cli::applyConventionsOption(cli.conventions, scene);
  rt::cli::applyModeOptions(cli.modeOptions, scene);
  std::printf("scene: %s, read as %s\n", cli.scenePath.c_str(), scene.fileKind.c_str());
  std::printf("conventions: %s (%s)\n", rt::conventionsName(scene.conventions),
              scene.conventionsReason.c_str());
  const rt::RenderSettings& s = scene.settings;
  std::printf("mode: %s, %u bounces, %s, sampler %s%s\n", modeName(s.mode), s.maxBounces,
              s.samplesPerPixel ? fmt::format("{} samples per pixel", s.samplesPerPixel).c_str()
                                : "samples per pixel not given (16 unless --spp)",
              rt::samplerKindName(rt::samplerUnlessAsked(s, s.adaptive)),
              s.adaptive ? ", adaptive sampling" : "");
  std::printf("background: %s\n", vec(scene.backgroundColor).c_str());
  if (scene.ambientLight) {
    std::printf("ambient light: %s times each hit's diffuse colour\n",
                vec(*scene.ambientLight).c_str());
  }
  printCamera(scene);
  printLights(scene);
  printShapes(scene);
  printList("values read (key = value)", scene.valuesRead);
  printList("warnings (defaults taken, files missing, keys ignored)", scene.warnings);
  const rt::FlatScene flat = rt::flattenScene(scene);
  printList("found on encoding it for the GPU (left out, or unlit)", flat.warnings);
  std::printf("kernel features: %s\n",
              rt::detectFeatures(scene, flat, scene.settings.adaptive).summary().c_str());
  return 0;
}

}  // namespace

int runCheckCommand(int argc, char** argv) {
  CommandLine cli;
  CLI::App app{
      "Prints how a scene file is read (conventions and why, camera, lights, shapes with "
      "where each value came from, defaults taken, warnings, the kernel features it needs) "
      "without rendering.",
      "raytracer check"};
  app.add_option("scene", cli.scenePath, rt::cli::kSceneFileHelp)->required();
  rt::cli::addConventionsOption(app, cli.conventions);
  rt::cli::addModeOptions(app, cli.modeOptions);
  rt::cli::addStrictOption(app, cli.strict);
  if (std::optional<int> status = rt::cli::parse(app, argc, argv)) return *status;
  try {
    return run(cli);
  } catch (const std::exception& error) {
    std::fflush(stdout);
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
