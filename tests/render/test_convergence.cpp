// Error measurement and convergence studies: the renderer's own RMSE
// estimate against the true error, --target-rmse stopping, split Sobol
// renders, the convergence summary and its plot.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "formats/json/JsonSceneLoader.hpp"
#include "imaging/Convergence.hpp"
#include "imaging/ImageError.hpp"
#include "imaging/Merge.hpp"
#include "io/Plot.hpp"
#include "render/ProgressiveRenderer.hpp"
#include "render/Renderer.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

using namespace rt;

namespace {

RenderOptions smallRender(SamplerKind sampler, uint32_t samples, uint32_t seed = 1,
                          uint32_t width = 48) {
  return test::studyRender(sampler, samples, seed, width);
}

const ImageF& studyTruth(const std::string& name, uint32_t width = 48) {
  return test::studyTruth(name, width, 1024);
}

const ImageF& thinLensTruth() { return studyTruth("study-thinlens.json"); }

ImageF uniformImage(uint32_t width, uint32_t height, float value) {
  ImageF image{width, height, std::vector<float>(size_t(width) * height * 4, value)};
  return image;
}

}  // namespace

TEST_SUITE("convergence") {
  TEST_CASE("display RMSE compares tone-mapped values over a region") {
    ToneMapping mapping;  // clamp to [0, 1], exposure 1
    ImageF a = uniformImage(4, 3, 0.5f);
    ImageF b = uniformImage(4, 3, 0.6f);
    CHECK(displayRmse(a, b, mapping) == doctest::Approx(0.1).epsilon(1e-5).scale(0));
    // Above 1 everything displays as 1.
    CHECK(displayRmse(uniformImage(4, 3, 2.0f), uniformImage(4, 3, 5.0f), mapping) == 0.0);
    b.pixel(3, 2)[0] = 1.5f;  // only pixel (3, 2) differs more
    CHECK(displayRmse(a, b, mapping, {0, 0, 2, 2}) == doctest::Approx(0.1).epsilon(1e-5).scale(0));
    CHECK(displayRmse(a, b, mapping) > 0.1);
    CHECK_THROWS_AS(displayRmse(a, b, mapping, {3, 2, 2, 2}), Error);
    CHECK_THROWS_AS(displayRmse(a, uniformImage(3, 3, 0.5f), mapping), Error);
  }

  TEST_CASE("the estimate weighs the two halves' difference by their sample counts") {
    // One pixel, 3 samples: even ones (2) average 0.4, the odd one 0.7.
    SampleSums sums{1, 1, {glm::vec4(0.8f + 0.7f, 0.8f + 0.7f, 0.8f + 0.7f, 3)}, {}};
    sums.odd = {glm::vec4(0.7f, 0.7f, 0.7f, 1)};
    std::optional<double> estimate = estimateDisplayRmse(sums, ToneMapping{});
    REQUIRE(estimate);
    CHECK(*estimate == doctest::Approx(std::sqrt(0.3 * 0.3 * 2.0 / 9.0)).epsilon(1e-5).scale(0));
    sums.odd[0] = glm::vec4(0);  // no odd sample yet: no estimate
    CHECK_FALSE(estimateDisplayRmse(sums, ToneMapping{}));
  }

  TEST_CASE("the error estimate is within 25% of the true error for every sampler") {
    for (const char* name : {"study-thinlens.json", "study-arealight.json"}) {
      CAPTURE(std::string(name));
      Scene scene = test::projectScene(name);
      ToneMapping mapping = toneMappingFor(scene);
      // 96x72: at 48x36 a few pixels of the penumbra carry the image's
      // error, and one unlucky sample moves it more than 25%.
      const ImageF& truth = studyTruth(name, 96);
      for (SamplerKind sampler : {SamplerKind::Random, SamplerKind::Jittered, SamplerKind::Sobol}) {
        for (uint32_t samples : {9u, 24u}) {
          RenderOptions options = smallRender(sampler, samples, 1, 96);
          options.estimateError = true;
          RenderStats stats;
          double trueRmse = displayRmse(test::render(scene, options, &stats), truth, mapping);
          CAPTURE(std::string(samplerKindName(sampler)));
          CAPTURE(samples);
          CAPTURE(trueRmse);
          REQUIRE(stats.rmseEstimate);
          CHECK(*stats.rmseEstimate == doctest::Approx(trueRmse).epsilon(0.25).scale(0));
        }
      }
    }
  }

  TEST_CASE("halves that share strata would make the estimate far too pessimistic") {
    // Without independent replicates the even and odd samples of a jittered
    // render split one stratified set: their difference is much larger than
    // the error of their mean, so the renderer offers no estimate then.
    Scene scene = test::projectScene("study-thinlens.json");
    ToneMapping mapping = toneMappingFor(scene);
    const ImageF& truth = thinLensTruth();
    ProgressiveOptions options;
    options.width = 48;
    options.height = 36;
    options.samplesTotal = 64;
    options.sampler = SamplerKind::Jittered;
    ProgressiveRenderer job(test::gpu(), test::shaderCompiler(), scene, options);
    job.addSamples(64);
    CHECK_FALSE(job.estimateRmse(mapping));
    double trueRmse = displayRmse(job.resolve(), truth, mapping);
    std::optional<double> naive = estimateDisplayRmse(job.sampleSums(), mapping);
    REQUIRE(naive);
    CHECK(*naive > 2 * trueRmse);
    test::checkNoValidationMessages();
  }

  TEST_CASE("--target-rmse stops at the first checkpoint whose estimate reaches the target") {
    Scene scene = test::projectScene("study-thinlens.json");
    RenderOptions options = smallRender(SamplerKind::Sobol, 4096);
    options.targetRmse = 0.012;
    RenderStats stats;
    test::render(scene, options, &stats);
    REQUIRE(stats.reachedTarget);
    CHECK(*stats.rmseEstimate <= 0.012);
    CHECK(stats.samplesDone < 4096);
    CHECK(stats.samplesDone >= kMinSamplesForTarget);
    CHECK(nextRmseCheckpoint(stats.samplesDone - 1) == stats.samplesDone);
    // The checkpoint before did not reach it (Sobol samples do not depend on
    // the render's total, so the shorter render has the same samples).
    uint32_t before = 0;
    while (nextRmseCheckpoint(before) < stats.samplesDone) before = nextRmseCheckpoint(before);
    if (before >= kMinSamplesForTarget) {
      RenderOptions shorter = smallRender(SamplerKind::Sobol, before);
      shorter.estimateError = true;
      RenderStats shorterStats;
      test::render(scene, shorter, &shorterStats);
      CHECK(*shorterStats.rmseEstimate > 0.012);
    }
  }

  TEST_CASE("split Sobol renders merge into the whole render") {
    Scene scene = test::projectScene("study-thinlens.json");
    RenderOptions options = smallRender(SamplerKind::Sobol, 10);
    ImageF whole = test::render(scene, options);
    std::vector<ImageF> parts;
    for (auto [first, end] : {std::pair{0u, 3u}, {3u, 8u}, {8u, 10u}}) {
      options.firstSample = first;
      options.endSample = end;
      parts.push_back(test::render(scene, options));
    }
    ImageF merged = mergeRenders(parts);
    double worst = 0;
    for (size_t i = 0; i < whole.rgba.size(); ++i) {
      double scale = std::max(1e-3, double(std::abs(whole.rgba[i])));
      worst = std::max(worst, std::abs(double(merged.rgba[i]) - whole.rgba[i]) / scale);
    }
    CHECK(worst < 1e-5);  // float rounding of the per-range sums only
  }

  TEST_CASE("a region render samples only the region") {
    Scene scene = test::projectScene("study-thinlens.json");
    RenderOptions options = smallRender(SamplerKind::Sobol, 4);
    ImageF whole = test::render(scene, options);
    options.region = {10, 5, 17, 9};
    ImageF part = test::render(scene, options);
    bool insideSame = true, outsideEmpty = true;
    for (uint32_t y = 0; y < part.height; ++y) {
      for (uint32_t x = 0; x < part.width; ++x) {
        bool inside = options.region.contains(x, y);
        for (int c = 0; c < 4; ++c) {
          if (inside && part.pixel(x, y)[c] != whole.pixel(x, y)[c]) insideSame = false;
          if (!inside && part.pixel(x, y)[c] != 0.0f) outsideEmpty = false;
        }
      }
    }
    CHECK(insideSame);
    CHECK(outsideEmpty);
    options.region = {40, 30, 9, 1};  // past the right edge
    CHECK_THROWS_AS(test::render(scene, options), Error);
  }

  TEST_CASE("error checkpoints grow by 2^(1/4) from 8") {
    std::vector<uint32_t> seen;
    for (uint32_t n = 0; n < 70; n = nextRmseCheckpoint(n)) seen.push_back(nextRmseCheckpoint(n));
    CHECK(seen ==
          std::vector<uint32_t>{2, 4, 8, 10, 11, 13, 16, 19, 23, 27, 32, 38, 45, 54, 64, 76});
  }

  TEST_CASE("sample series and summaries of synthetic power laws") {
    CHECK(geometricSampleCounts(9, 64, 2.0) == std::vector<uint32_t>{9, 18, 36, 64});
    CHECK(geometricSampleCounts(9, 72, 2.0) == std::vector<uint32_t>{9, 18, 36, 72});
    CHECK_THROWS_AS(geometricSampleCounts(9, 4, 2.0), Error);
    // rmse = 0.1 * n^-0.5 (reaches 0.01 at n = 100), 1 ms per sample.
    std::vector<ConvergencePoint> points;
    for (uint32_t n : {9u, 16u, 64u, 256u, 1024u}) {
      points.push_back(
          {SamplerKind::Random, n, n * 1e-3, n * 2e-3, 0.1 / std::sqrt(double(n)), {}});
    }
    ConvergenceSummary summary = summarizeConvergence(points, 0.01);
    CHECK(summary.slope == doctest::Approx(-0.5));
    CHECK(summary.samplesToTarget == doctest::Approx(100));
    CHECK(summary.secondsToTarget == doctest::Approx(0.1));
    CHECK_FALSE(summary.extrapolated);
    CHECK(summarizeConvergence(points, 0.01, ConvergenceClock::Cpu).secondsToTarget ==
          doctest::Approx(0.2));
    // A target beyond the data follows the fitted law.
    summary = summarizeConvergence(points, 0.001);
    CHECK(summary.extrapolated);
    CHECK(summary.samplesToTarget == doctest::Approx(10000));
    CHECK(summary.secondsToTarget == doctest::Approx(10));
    std::string csv = convergenceCsv(points);
    CHECK(
        csv.rfind(
            "sampler,samples,seconds,cpu_seconds,rmse,estimated_rmse\nrandom,9,0.009000,0.018000,",
            0) == 0);
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 6);
  }

  TEST_CASE("the log-log plot draws every series in its colour, with decade labels") {
    std::vector<ConvergencePoint> points;
    for (uint32_t n : {9u, 64u, 512u}) {
      points.push_back(
          {SamplerKind::Random, n, n * 1e-3, n * 2e-3, 0.1 / std::sqrt(double(n)), {}});
      points.push_back({SamplerKind::Sobol, n, n * 2e-3, n * 2e-3, 0.1 / double(n), {}});
    }
    Image8 plot = drawLogLogPlot(convergencePlotPanels(points, 0.01, "test"));
    CHECK(plot.width == 2 * PlotSize{}.panelWidth);
    auto count = [&](Rgb8 color) {
      size_t n = 0;
      for (size_t i = 0; i < plot.rgb.size(); i += 3) {
        if (plot.rgb[i] == color[0] && plot.rgb[i + 1] == color[1] && plot.rgb[i + 2] == color[2])
          ++n;
      }
      return n;
    };
    const Rgb8 red{214, 39, 40}, green{44, 160, 44}, blue{31, 119, 180};
    CHECK(count(red) > 200);
    CHECK(count(green) > 200);
    CHECK(count(blue) == 0);  // no jittered series
    test::savePng(plot, "convergence-plot.png");
    CHECK(decadeLabel(-2) == "0.01");
    CHECK(decadeLabel(3) == "1000");
    CHECK(decadeLabel(-5) == "1e-05");
    CHECK_THROWS_AS(drawLogLogPlot({PlotPanel{"empty", "x", "y", {}, {}}}), Error);
  }
}
