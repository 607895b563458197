// The OBJ loader (formats/obj): geometry, indices, polygons and groups,
// .mtl materials, OBJ models inside JSON scenes, a standalone OBJ framed
// like a glTF file, and broken files as one-line errors.
#include <doctest/doctest.h>

#include <filesystem>
#include <glm/geometric.hpp>
#include <string>

#include "formats/SceneFile.hpp"
#include "formats/json/JsonSceneLoader.hpp"
#include "formats/obj/ObjLoader.hpp"
#include "io/Image.hpp"
#include "support/TestSupport.hpp"
#include "util/Error.hpp"

namespace {

namespace fs = std::filesystem;
using rt::test::TempDir;

const fs::path kCrate = fs::path(RT_SOURCE_SHADER_DIR) / ".." / "assets" / "models" / "crate.obj";

rt::Scene parseObj(const std::string& obj, const std::string& mtl = "") {
  return rt::parseObjPart(obj, mtl, "mem.obj", rt::WorldTransform(1.0));
}

std::string errorOf(const std::string& obj) {
  try {
    parseObj(obj);
  } catch (const rt::Error& error) {
    return error.what();
  }
  return "";
}

size_t triangleCount(const rt::Scene& scene) {
  size_t count = 0;
  for (const rt::TriangleMesh& mesh : scene.meshes) count += mesh.faces.size();
  return count;
}

const rt::Material& materialOf(const rt::Scene& scene, const std::string& label) {
  for (const rt::Shape& shape : scene.shapes) {
    if (shape.label.find(label) != std::string::npos) return scene.materials.at(shape.material);
  }
  FAIL("no shape labelled " << label);
  return scene.materials.front();
}

}  // namespace

TEST_SUITE("obj loader") {
  TEST_CASE("quads, a pentagon and negative indices become triangles, one mesh per material") {
    const rt::Scene scene = rt::loadObjPart(kCrate, rt::WorldTransform(1.0));
    CHECK(scene.warnings.empty());
    // 5 body quads + the lid quad (negative indices) + the pentagon badge.
    CHECK(triangleCount(scene) == 5 * 2 + 2 + 3);
    REQUIRE(scene.shapes.size() == 3);  // wood, red, gold
    for (const rt::TriangleMesh& mesh : scene.meshes) {
      for (const glm::uvec3& face : mesh.faces) {
        for (int c = 0; c < 3; ++c) CHECK(face[c] < mesh.positions.size());
      }
    }
    // The lid (f -5 -1 -2 -6 after 8 vertices: vertices 4 8 7 3) lies at y = 0.5.
    const rt::Shape& lid = scene.shapes[1];
    const rt::TriangleMesh& lidMesh =
        scene.meshes.at(std::get<rt::MeshInstance>(lid.geometry).mesh);
    for (const glm::vec3& p : lidMesh.positions) CHECK(p.y == doctest::Approx(0.5f));
    REQUIRE(lidMesh.normals.size() == lidMesh.positions.size());
    CHECK(lidMesh.normals[0].y == doctest::Approx(1.0f));
  }

  TEST_CASE("MTL materials: Kd, Ks, Ns and map_Kd on the Blinn-Phong material") {
    const rt::Scene scene = rt::loadObjPart(kCrate, rt::WorldTransform(1.0));
    const rt::Material& red = materialOf(scene, "material 'red'");
    CHECK(red.diffuseColor.x == doctest::Approx(0.8f));
    CHECK(red.diffuseColor.y == doctest::Approx(0.1f));
    CHECK(red.kd == doctest::Approx(1.0f));
    CHECK(red.ks == doctest::Approx(1.0f));
    CHECK(red.specularColor.x == doctest::Approx(0.5f));
    CHECK(red.specularExponent == doctest::Approx(50.0f));
    const rt::Material& wood = materialOf(scene, "material 'wood'");
    REQUIRE(wood.diffuseTexture >= 0);
    CHECK(wood.textureTintedByColor);
    CHECK(scene.textures.at(size_t(wood.diffuseTexture)).image.width == 32);
    CHECK(wood.ks == doctest::Approx(0.0f));
  }

  TEST_CASE("d, Tr and Ni: transparency and index of refraction") {
    const std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n";
    rt::Scene scene = parseObj(obj, "newmtl glass\nKd 1 1 1\nd 0.25\nNi 1.5\n");
    CHECK(scene.materials.at(scene.shapes.at(0).material).transmission == doctest::Approx(0.75f));
    CHECK(scene.materials.at(scene.shapes.at(0).material).ior == doctest::Approx(1.5f));
    scene = parseObj(obj, "newmtl glass\nKd 1 1 1\nTr 0.5\n");
    CHECK(scene.materials.at(scene.shapes.at(0).material).transmission == doctest::Approx(0.5f));
  }

  TEST_CASE("illum 3 and 5 reflect (max Ks), illum 6 and 7 refract (Tf); others as read") {
    const std::string obj =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n"
        "usemtl c\nf 1 2 3\nusemtl d\nf 1 2 3\n";
    const rt::Scene scene = parseObj(obj,
                                     "newmtl a\nKs 0.9 0.5 0.2\nillum 5\n"
                                     "newmtl b\nKs 0.9 0.5 0.2\nillum 2\nTf 1 1 1\n"
                                     "newmtl c\nTf 1 0.5 0\nNi 1.5\nillum 7\n"
                                     "newmtl d\nKs 0.4 0.4 0.4\nillum 3\n");
    CHECK(materialOf(scene, "'a'").reflectivity == doctest::Approx(0.9f));
    CHECK(materialOf(scene, "'a'").transmission == 0.0f);
    CHECK(materialOf(scene, "'b'").reflectivity == 0.0f);  // Tf alone, illum 2: opaque
    CHECK(materialOf(scene, "'b'").transmission == 0.0f);
    CHECK(materialOf(scene, "'c'").transmission == doctest::Approx(0.5f));
    CHECK(materialOf(scene, "'c'").ior == doctest::Approx(1.5f));
    CHECK(materialOf(scene, "'d'").reflectivity == doctest::Approx(0.4f));
  }

  TEST_CASE("Ke makes a material's faces an area light of that radiance") {
    // A unit square (area 1) glowing (2, 1, 0.5), a triangle that does not.
    const std::string obj =
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl plain\nf 1 2 3\n"
        "usemtl lamp\nf 1 2 3 4\nusemtl flat\nf 1 2 2\n";
    const rt::Scene scene =
        parseObj(obj,
                 "newmtl plain\nKd 1 1 1\nnewmtl lamp\nKd 1 1 1\nKe 2 1 0.5\nmap_Ke glow.png\n"
                 "newmtl flat\nKe 1 1 1\n");
    REQUIRE(scene.areaLights.size() == 1);
    const rt::AreaLight& light = scene.areaLights[0];
    CHECK(scene.shapes.at(light.shape).label.find("'lamp'") != std::string::npos);
    // Radiance L over area A: a Lambertian light of intensity 2 A L.
    CHECK(light.diffuseIntensity == glm::vec3(4.0f, 2.0f, 1.0f));
    CHECK(light.specularIntensity == light.diffuseIntensity);
    CHECK(light.profile == rt::EmissionProfile::Lambertian);
    REQUIRE(scene.warnings.size() == 2);
    CHECK(scene.warnings[0] ==
          "mem.obj: material 'lamp': emission texture map_Ke ignored (Ke "
          "alone decides the glow)");
    CHECK(scene.warnings[1].find("'flat': Ke: the faces have no area to emit from") !=
          std::string::npos);
  }

  TEST_CASE("a glowing OBJ on its own: its own lights only, physical conventions") {
    TempDir dir;
    const fs::path file =
        dir.write("lamp.obj",
                  "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                  "usemtl lamp\nf 1 2 3 4\nv 0 0 1\nv 0 1 1\nusemtl wall\nf 1 6 5\n");
    dir.write("lamp.mtl", "newmtl lamp\nKe 1 1 1\nnewmtl wall\nKd 0.5 0.5 0.5\n");
    const rt::Scene scene = rt::loadSceneFile(file);
    CHECK(scene.areaLights.size() == 1);
    CHECK(scene.pointLights.empty());  // no framing light beside the model's own
    CHECK(scene.conventions == rt::Conventions::Physical);
    CHECK(scene.conventionsReason == "an OBJ file whose materials glow (Ke)");
    // Framed straight on from +z, not from above: a lit room's ceiling would hide its lamp.
    CHECK(scene.camera.forward == glm::vec3(0, 0, -1));
    // In a JSON scene the lamp stays a light, its shape index shifted past
    // the shapes before it; a JSON material on the model replaces its glow.
    const std::string camera =
        R"("camera": {"type": "pinhole", "width": 8, "height": 8, "fov": 45,
                      "position": [0, 0, 5], "lookat": [0, 0, -1], "up": [0, 1, 0]})";
    const std::string sphere = R"({"type": "sphere", "center": [0, 0, -3], "radius": 1})";
    rt::Scene placed = rt::loadJsonScene(
        dir.write("placed.json", "{" + camera + R"(, "scene": {"shapes": [)" + sphere +
                                     R"(, {"type": "mesh", "file": "lamp.obj"}]}})"));
    REQUIRE(placed.areaLights.size() == 1);
    CHECK(placed.shapes.at(placed.areaLights[0].shape).label.find("'lamp'") != std::string::npos);
    rt::Scene painted = rt::loadJsonScene(dir.write(
        "painted.json", "{" + camera + R"(, "scene": {"shapes": [)" + sphere +
                            R"(, {"type": "mesh", "file": "lamp.obj", "material": {"kd": 1}}]}})"));
    CHECK(painted.areaLights.empty());
  }

  TEST_CASE("faces without a material, texture coordinates flipped to rows going down") {
    const rt::Scene scene = parseObj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
        "f 1/1 2/2 3/3\n");
    REQUIRE(scene.shapes.size() == 1);
    const rt::Material& material = scene.materials.at(scene.shapes[0].material);
    CHECK(material.diffuseColor == rt::Material{}.diffuseColor);
    const rt::TriangleMesh& mesh = scene.meshes.at(0);
    REQUIRE(mesh.uvs.size() == 3);
    CHECK(mesh.uvs[0].y == doctest::Approx(1.0f));  // OBJ v = 0 is the image's bottom row
    CHECK(mesh.normals.empty());                    // none in the file: flat shading
  }

  TEST_CASE("vertex colours after x y z are sRGB, read when every vertex has them") {
    const rt::Scene scene = parseObj(
        "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 1\nv 1 1 0 1 1 1\n"
        "f 1 2 3\nf 2 4 3\n");
    const rt::TriangleMesh& mesh = scene.meshes.at(0);
    REQUIRE(mesh.colors.size() == 4);
    CHECK(mesh.colors[0] == glm::vec3(1, 0, 0));
    CHECK(mesh.colors[1].y == doctest::Approx(0.21404f).epsilon(1e-4));  // sRGB 0.5
    CHECK(mesh.colors[2] == glm::vec3(0, 0, 1));
    // One vertex without a colour: none of them has one (as tinyobjloader reads them).
    CHECK(parseObj("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n").meshes.at(0).colors.empty());
    CHECK(parseObj("v 0 0 0 1 1 1\nv 1 0 0 1 1 1\nv 0 1 0 1 1 1\nf 1 2 3\n")
              .meshes.at(0)
              .colors.empty());  // all white
  }

  TEST_CASE("normal maps: norm, or map_Bump with -bm where it is not a grey height map") {
    TempDir dir;
    // A bluish normal map and a grey height map, 2 x 2.
    rt::writeImage(
        dir.path() / "normals.png",
        rt::ImageF{2, 2, {0.5f, 0.5f, 1, 1, 0.6f, 0.5f, 1, 1, 0.5f, 0.5f, 1, 1, 0.5f, 0.4f, 1, 1}},
        {});
    rt::writeImage(
        dir.path() / "height.png",
        rt::ImageF{2, 2, {0.2f, 0.2f, 0.2f, 1, 0.7f, 0.7f, 0.7f, 1, 0, 0, 0, 1, 1, 1, 1, 1}}, {});
    dir.write("model.obj",
              "mtllib model.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
              "usemtl named\nf 1/1 2/2 3/3\nusemtl blender\nf 1/1 3/3 2/2\n"
              "usemtl bumpy\nf 1/1 2/2 3/3\nusemtl lost\nf 1/1 3/3 2/2\n");
    dir.write("model.mtl",
              "newmtl named\nnorm normals.png\n"
              "newmtl blender\nmap_Bump -bm 0.5 normals.png\n"
              "newmtl bumpy\nmap_Bump height.png\n"
              "newmtl lost\nnorm gone.png\n");
    const rt::Scene scene = rt::loadObjPart(dir.path() / "model.obj", rt::WorldTransform(1.0));
    const rt::Material& named = materialOf(scene, "'named'");
    REQUIRE(named.normalTexture >= 0);
    CHECK(scene.textures.at(size_t(named.normalTexture)).linear);
    CHECK(named.normalScale == 1.0f);
    const rt::Material& blender = materialOf(scene, "'blender'");
    CHECK(blender.normalTexture == named.normalTexture);  // the file read once
    CHECK(blender.normalScale == 0.5f);
    CHECK(materialOf(scene, "'bumpy'").normalTexture == -1);
    CHECK(materialOf(scene, "'lost'").normalTexture == -1);
    CHECK(scene.textures.size() == 1);
    REQUIRE(scene.warnings.size() == 2);
    CHECK(scene.warnings[0].find("map_Bump height.png is a height map (grey)") !=
          std::string::npos);
    CHECK(scene.warnings[1].find("norm: texture file not found") != std::string::npos);
  }

  TEST_CASE("map_d: a mask that cuts holes, its grey level as coverage; a missing one no holes") {
    TempDir dir;
    // White left, black right: the left half there, the right a hole.
    rt::writeImage(dir.path() / "mask.png", rt::ImageF{2, 1, {1, 1, 1, 1, 0, 0, 0, 1}}, {});
    dir.write("model.obj",
              "mtllib model.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
              "usemtl leaves\nf 1/1 2/2 3/3\nusemtl twigs\nf 1/1 3/3 2/2\n"
              "usemtl lost\nf 1/1 2/2 3/3\n");
    dir.write("model.mtl",
              "newmtl leaves\nmap_d mask.png\nnewmtl twigs\nmap_d mask.png\n"
              "newmtl lost\nmap_d gone.png\n");
    const rt::Scene scene = rt::loadObjPart(dir.path() / "model.obj", rt::WorldTransform(1.0));
    const rt::Material& leaves = materialOf(scene, "'leaves'");
    CHECK(leaves.alphaMode == rt::Material::Alpha::Mask);
    CHECK(leaves.alphaCutoff == 0.5f);
    REQUIRE(leaves.alphaTexture >= 0);
    const rt::ImageRgba8& mask = scene.textures.at(size_t(leaves.alphaTexture)).image;
    REQUIRE(mask.rgba.size() == 8);
    CHECK(mask.rgba[3] == 255);
    CHECK(mask.rgba[7] == 0);
    CHECK(leaves.diffuseTexture == -1);  // the mask is not a colour
    CHECK(materialOf(scene, "'twigs'").alphaTexture == leaves.alphaTexture);  // read once
    CHECK(materialOf(scene, "'lost'").alphaMode == rt::Material::Alpha::Opaque);
    REQUIRE(scene.warnings.size() == 1);
    CHECK(scene.warnings[0].find("map_d: texture file not found") != std::string::npos);
  }

  TEST_CASE("a missing material library or texture is a warning with a visible stand-in") {
    TempDir dir;
    dir.write("model.obj",
              "mtllib gone.mtl\nmtllib here.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
              "usemtl painted\nf 1 2 3\n");
    dir.write("here.mtl", "newmtl painted\nKd 1 1 1\nmap_Kd textures\\paint.png\n");
    const rt::Scene scene = rt::loadObjPart(dir.path() / "model.obj", rt::WorldTransform(1.0));
    REQUIRE(scene.warnings.size() == 2);
    CAPTURE(scene.warnings[1]);
    CHECK(scene.warnings[0].find("material library gone.mtl") != std::string::npos);
    CHECK(scene.warnings[1].find("texture file not found: textures/paint.png") !=
          std::string::npos);
    const rt::Material& painted = scene.materials.at(scene.shapes.at(0).material);
    REQUIRE(painted.diffuseTexture >= 0);
    CHECK(scene.textures.at(size_t(painted.diffuseTexture)).source == "missing texture");
  }

  TEST_CASE("broken files are one-line errors naming the file") {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    CHECK(errorOf(triangle + "f 1 2 9\n") == "mem.obj: face 1: refers to vertex 9, the file has 3");
    CHECK(errorOf(triangle + "vn 0 0 1\nf 1//1 2//4 3//1\n") ==
          "mem.obj: face 1: refers to normal 4, the file has 1");
    CHECK(errorOf(triangle + "f -4 1 2\n").find("mem.obj: ") == 0);
    for (const std::string& bad : {std::string("f 1 2 3\n"), std::string("v 1e999 0 0\n")}) {
      CAPTURE(bad);
      const std::string error = errorOf(bad);
      if (!error.empty()) {
        CHECK(error.find('\n') == std::string::npos);
        CHECK(error.find("mem.obj: ") == 0);
      }
    }
    const rt::Scene empty = parseObj("# nothing\n");
    CHECK(empty.shapes.empty());
    CHECK(empty.warnings.at(0) == "mem.obj: no faces: nothing to draw");
  }

  TEST_CASE("an OBJ file on its own is framed like a glTF file") {
    const rt::Scene scene = rt::loadSceneFile(kCrate);
    CHECK(scene.conventions == rt::Conventions::Textbook);
    CHECK(scene.pointLights.size() == 1);
    CHECK(scene.camera.width == 800);
    CHECK(scene.camera.height == 600);
    // The camera looks at the crate's centre from above +z.
    CHECK(glm::dot(glm::normalize(-glm::vec3(scene.camera.position)), scene.camera.forward) ==
          doctest::Approx(1.0f).epsilon(0.01).scale(0));
    CHECK(scene.camera.position.z > 1.0f);
    CHECK(scene.camera.forward.y < -0.4f);
  }

  TEST_CASE("OBJ models in JSON scenes: type mesh, placement, and the JSON material wins") {
    TempDir dir;
    fs::copy_file(kCrate, dir.path() / "crate.obj");
    fs::copy_file(kCrate.parent_path() / "crate.mtl", dir.path() / "crate.mtl");
    fs::copy_file(kCrate.parent_path() / "crate.png", dir.path() / "crate.png");
    const std::string camera =
        R"("camera": {"type": "pinhole", "width": 64, "height": 48, "fov": 45,
                      "position": [0, 0, 5], "lookat": [0, 0, -1], "up": [0, 1, 0]})";
    const fs::path own = dir.write("own.json", "{" + camera + R"(, "scene": {"shapes": [
        {"type": "mesh", "filename": "crate.obj", "center": [1, 2, 3], "scale": 2}]}})");
    rt::Scene scene = rt::loadJsonScene(own);
    CHECK(scene.warnings.empty());
    REQUIRE(scene.shapes.size() == 3);
    const auto& placed = std::get<rt::MeshInstance>(scene.shapes[0].geometry);
    CHECK(placed.objectToWorld[3][1] == doctest::Approx(2.0f));
    CHECK(placed.objectToWorld[0][0] == doctest::Approx(2.0f));
    CHECK(scene.shapes[0].origin.find("scene.shapes[0]") == 0);

    const fs::path painted = dir.write("painted.json", "{" + camera + R"(, "scene": {"shapes": [
        {"type": "trimesh", "file": "crate.obj", "material": {"ks": 0.1, "kd": 0.9,
         "specularexponent": 5, "diffusecolor": [0, 0, 1]}}]}})");
    scene = rt::loadJsonScene(painted);
    for (const rt::Shape& shape : scene.shapes) {
      CHECK(scene.materials.at(shape.material).diffuseColor == glm::vec3(0, 0, 1));
    }
  }
}
