// The official renders of the Path-of-Light example.json at successive
// coursework steps are the ground truth for family A's conventions (light
// falloff I / (4 pi d^2), the coursework shading model). The step-6 figure
// shows Blinn-Phong with hard shadows but no mirror reflection and no
// textures, so the scene is rendered with those two switched off.
#include <doctest/doctest.h>

#include "render/Renderer.hpp"
#include "scene/SceneLoader.hpp"
#include "support/TestSupport.hpp"

using namespace rt;

namespace {

Scene stepSixScene(const std::filesystem::path& shared) {
  Scene scene =
      loadScene(shared / "scene-format/official/cg-path-of-light-2021-2023/examples/example.json");
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
  Renderer renderer(test::gpu(), test::shaderCompiler());
  ImageF image = renderer.render(scene, options);
  test::checkNoValidationMessages();
  // The figures are 800x800 renders shrunk to 383x383 for the handout.
  return test::downscale(toneMap(image, toneMappingFor(scene)), 383, 383);
}

}  // namespace

TEST_SUITE("reference") {
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
