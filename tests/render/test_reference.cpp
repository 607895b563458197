// Reference renders pin down the conventions of both families.
// Family A: the official renders of the Path-of-Light example.json at
// successive coursework steps (light falloff I / (4 pi d^2), the coursework
// shading model). The step-6 figure shows Blinn-Phong with hard shadows but
// no mirror reflection and no textures, so the scene is rendered with those
// two switched off.
// Family B: a student's renders of the four official files (1200x800, one
// sample at each pixel centre; ../shared/scene-format/reference/
// family-b-student-renders): image right = up x forward, ambient 0.4 times
// the diffuse colour, no falloff, mirrors that replace the local light,
// exposure not applied, bytes truncated.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "formats/json/JsonSceneLoader.hpp"
#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

Scene stepSixScene(const std::filesystem::path& shared) {
  Scene scene = loadJsonScene(
      shared / "scene-format/official/cg-path-of-light-2021-2023/examples/example.json");
  for (Material& material : scene.materials) {
    material.reflectivity = 0.0f;
    material.diffuseTexture = -1;
  }
  return scene;
}

Image8 renderFigure(const Scene& scene, std::optional<ShadingModel> shading) {
  RenderOptions options;
  options.samplesPerPixel = 4;
  options.shading = shading;
  ImageF image = test::render(scene, options);
  // The figures are 800x800 renders shrunk to 383x383 for the handout.
  return test::downscale(toneMap(image, toneMappingFor(scene)), 383, 383);
}

struct FamilyBReference {
  const char* scene;      // under official/cgr-2023-2024
  const char* reference;  // under reference/family-b-student-renders
  bool phong;             // render scene.json in phong mode, as the student did
  double minimumPsnr;     // what the fitted conventions reach, less about 1.5 dB
};

// The student rendered one centred sample per pixel (aliased edges); ours
// are antialiased, which the edges' pixels cost.
Image8 renderFamilyB(const std::filesystem::path& shared, const FamilyBReference& figure,
                     std::optional<Conventions> conventions) {
  const std::filesystem::path file = shared / "scene-format/official/cgr-2023-2024" / figure.scene;
  std::ifstream stream(file);
  nlohmann::json document = nlohmann::json::parse(stream);
  if (figure.phong) document["rendermode"] = "phong";
  Scene scene = parseJsonScene(document.dump(), file);
  if (conventions) setConventions(scene, *conventions, "test");
  RenderOptions options;
  options.samplesPerPixel = 4;
  return toneMap(test::render(scene, options), toneMappingFor(scene));
}

}  // namespace

TEST_SUITE("reference") {
  TEST_CASE("family B: the student renders of the official files (five figures)" *
            test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    const FamilyBReference figures[] = {
        {"binary_primitves.json", "binary_primitives.png", false, 40.0},
        {"scene.json", "binary_scene.png", false, 42.5},
        {"simple_phong.json", "simple_phong.png", false, 42.5},
        {"mirror_image.json", "mirror_image.png", false, 41.5},
        {"scene.json", "phong_scene.png", true, 40.5},
    };
    for (const FamilyBReference& figure : figures) {
      CAPTURE(figure.reference);
      Image8 reference =
          readImage8(shared / "scene-format/reference/family-b-student-renders" / figure.reference);
      Image8 ours = renderFamilyB(shared, figure, std::nullopt);
      test::savePng(ours, std::string("reference-family-b-") + figure.reference);
      double fitted = test::psnr(ours, reference);
      MESSAGE(std::string(figure.reference), ": ", fitted, " dB with coursework-b");
      CHECK(fitted >= figure.minimumPsnr);
      // The reading before the fit (right-handed, no ambient, mirrors on top
      // of the local light) is far off: the fit is not lenient.
      double textbook = test::psnr(renderFamilyB(shared, figure, Conventions::Textbook), reference);
      MESSAGE(std::string(figure.reference), ": ", textbook, " dB with textbook");
      CHECK(textbook < 25.0);
    }
  }

  TEST_CASE("family B: binary_primitves.json draws the sphere at x = -0.3 on the left" *
            test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    const FamilyBReference figure{"binary_primitves.json", "", false, 0.0};
    Image8 image = renderFamilyB(shared, figure, std::nullopt);
    // At world y = 0.33 (z = 1) only the sphere (centre (-0.3, 0.19, 1),
    // radius 0.2) is in view: the triangle ends at y = 0.25.
    const double tanHalfFov = std::tan(22.5 * 3.14159265358979 / 180.0);
    const uint32_t row = uint32_t((1.0 - 0.33 / tanHalfFov) / 2.0 * image.height);
    uint32_t left = 0, right = 0;
    for (uint32_t x = 0; x < image.width; ++x) {
      const uint8_t* pixel = &image.rgb[(size_t(row) * image.width + x) * 3];
      bool hit = pixel[0] == 255 && pixel[1] == 0;
      (x < image.width / 2 ? left : right) += hit;
    }
    CHECK(left > 50);
    CHECK(right == 0);
  }

  TEST_CASE("example.json matches the official Blinn-Phong render (fig. 1e)" *
            test::needsShared()) {
    const std::filesystem::path shared = test::requireShared();
    Image8 reference = readImage8(shared / "scene-format/reference/fig1e_step6_blinn_phong.jpg");
    Scene scene = stepSixScene(shared);
    Image8 ours = renderFigure(scene, std::nullopt);
    double fitted = test::psnr(ours, reference);
    MESSAGE("PSNR against fig1e, coursework shading: ", fitted, " dB");
    test::savePng(ours, "reference-fig1e.png");
    CHECK(fitted >= 38.0);

    // The textbook model (per-channel colour, no normalisation) must be far
    // off: this is what makes the fit meaningful rather than lenient.
    double textbook = test::psnr(renderFigure(scene, ShadingModel::Standard), reference);
    MESSAGE("PSNR against fig1e, standard shading: ", textbook, " dB");
    CHECK(textbook < 25.0);
  }
}
