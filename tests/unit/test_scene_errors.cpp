// The JSON scene loader (scene/scene_loader.h): a scene using every feature loads as written, and
// every class of bad input is an InputError "file: /json/pointer: reason".
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "core/medium.h"
#include "scene/scene_loader.h"
#include "materials/lambertian.h"
#include "tests/support.h"
#include "tests/expect_contains.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kJungMaterial = R"({"type": "jung_fluorescent",
  "absorption": {"type": "gaussian", "center": 450, "fwhm": 40},
  "emission": {"type": "gaussian", "center": 520, "fwhm": 30},
  "reflectance": 0.5, "c": 0.5, "Q": 0.9})";

class SceneLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps concurrent runs (two build directories, ctest -j) apart.
    dir = (fs::path(::testing::TempDir()) / ("kasha_scene_errors." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
    path = dir + "/scene.json";
    base = json::parse(test::kMinimalScene);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());  // kept for inspection on failure
  }

  std::string write(const std::string& rel, const std::string& text) const {
    const fs::path p = fs::path(dir) / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }

  // The message of the InputError that loading `text` throws.
  std::string errorOfText(const std::string& text) const {
    try {
      loadSceneFromString(text, path);
    } catch (const InputError& e) {
      return e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "threw a non-InputError: " << e.what();
      return "";
    }
    ADD_FAILURE() << "the scene loaded, expected an InputError";
    return "";
  }

  // Loading j fails with "file: pointer: ...reason...".
  void expectError(const json& j, const std::string& pointer, const std::string& reason) const {
    const std::string msg = errorOfText(j.dump());
    const std::string prefix = path + ": " + pointer + ": ";
    EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "expected prefix '" << prefix << "' in: " << msg;
    EXPECT_CONTAINS(msg, reason);
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }

  // Loads `base` with one mutation applied.
  void expectError(const std::function<void(json&)>& mutate, const std::string& pointer,
                   const std::string& reason) const {
    json j = base;
    mutate(j);
    expectError(j, pointer, reason);
  }

  std::string dir, path;
  json base;
};

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST_F(SceneLoader, BaseSceneLoadsWithDefaults) {
  const auto scene = loadSceneFromString(base.dump(), path);
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->path, path);
  EXPECT_EQ(scene->range.min, 360.0f);
  EXPECT_EQ(scene->range.max, 830.0f);
  EXPECT_EQ(scene->render.spp, 16);
  EXPECT_EQ(scene->render.timeBudgetSeconds, 0.0);
  EXPECT_EQ(scene->render.maxDepth, 64);
  EXPECT_EQ(scene->render.rrDepth, 3);
  EXPECT_EQ(scene->render.seed, 1u);
  EXPECT_EQ(scene->render.wavelengths.sensor.text, "cmf");
  EXPECT_FALSE(scene->render.bdpt.mollify);
  EXPECT_EQ(scene->render.bdpt.mollifyBandwidth, 0.0f);
  EXPECT_EQ(scene->render.bdpt.mollifyAlpha, 2.0f / 3.0f);
  EXPECT_EQ(scene->camera.width(), 8);
  EXPECT_EQ(scene->camera.height(), 8);
  ASSERT_EQ(scene->shapes.size(), 1u);
  EXPECT_EQ(scene->shapes[0].name, "shape0");
  ASSERT_TRUE(scene->shapes[0].emission);
  EXPECT_EQ(scene->shapes[0].emission->scale, 1.0f);
  EXPECT_FALSE(scene->shapes[0].emission->twoSided);
  EXPECT_NEAR(scene->shapes[0].area, 4.0f, 1e-5f);  // u, v are half edges
  // A one-sided rectangle emits on the side of u × v (here +z, away from the camera).
  EXPECT_NEAR(glm::dot(scene->shapes[0].triangleNormal(0), Vec3(0, 0, 1)), 1.0f, 1e-6f);
  EXPECT_EQ(scene->shapes[0].emission->eval(550.0f, scene->shapes[0].triangleNormal(0), Vec3(0, 0, 1)), 1.0f);
  EXPECT_EQ(scene->shapes[0].emission->eval(550.0f, scene->shapes[0].triangleNormal(0), Vec3(0, 0, -1)), 0.0f);
  EXPECT_EQ(scene->materials.size(), 1u);
  EXPECT_EQ(scene->lights.size(), 1u);  // the area light of the emissive rectangle
  EXPECT_EQ(scene->shapeLight, (std::vector<int>{0}));
  EXPECT_EQ(scene->environmentLight, -1);
}

TEST_F(SceneLoader, EveryFeatureLoads) {
  write("spectra/lamp.csv", "# a lamp\nwavelength_nm,lamp,other\n400,1,5\n700,3,5\n");
  // The mtllib names a file that does not exist: OBJ materials are ignored.
  write("mesh/tet.obj",
        "mtllib missing.mtl\no tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\n"
        "usemtl nothing\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write("mesh/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const json j = json::parse(R"({
    "description": "every feature of the format",
    "wavelength_range": [380, 780],
    "render": {"spp": 4, "time": 1.5, "max_depth": 8, "rr_depth": 2, "seed": 7, "sensor_sampling": "uniform"},
    "camera": {"position": [0, 1, -5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 45, "resolution": [32, 24]},
    "spectra": {
      "lamp": {"type": "file", "file": "spectra/lamp.csv", "column": "lamp", "outside": "zero"},
      "grey": {"type": "constant", "value": 0.4},
      "ramp": {"type": "tabulated", "wavelengths": [380, 780], "values": [0.2, 0.8]},
      "absorb": {"type": "gaussian", "center": 460, "fwhm": 40, "peak": 0.9},
      "warm": {"type": "blackbody", "kelvin": 3000, "scale": 2},
      "band": {"type": "box", "min": 500, "max": 560, "value": 0.7},
      "daylight": {"type": "preset", "name": "D65", "scale": 0.01}
    },
    "materials": {
      "wall": {"type": "lambertian", "reflectance": "ramp"},
      "grey": {"type": "lambertian", "reflectance": "grey"},
      "tinted": {"type": "lambertian", "reflectance": "band"},
      "dye": {"type": "jung_fluorescent", "absorption": "absorb",
              "emission": {"type": "gaussian", "center": 530, "fwhm": 35},
              "reflectance": 0.3, "c": 0.6, "Q": 0.8}
    },
    "shapes": [
      {"name": "floor", "type": "rectangle", "corners": [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]],
       "material": "wall"},
      {"name": "lamp", "type": "rectangle", "center": [0, 3, 0], "u": [0.5, 0, 0], "v": [0, 0, 0.5],
       "material": "grey", "emission": {"radiance": "daylight", "scale": 3, "two_sided": true}},
      {"name": "ball", "type": "sphere", "center": [0, 1, 0], "radius": 0.5, "material": "dye"},
      {"name": "tet", "type": "mesh", "file": "mesh/tet.obj", "scale": 2, "translate": [1, 0, 0], "material": "tinted"},
      {"type": "mesh", "file": "mesh/quad.obj", "material": "grey"}
    ],
    "lights": [
      {"type": "point", "position": [0, 2, 0], "intensity": "lamp", "scale": 5},
      {"type": "spot", "position": [0, 3, -1], "look_at": [0, 0, 0], "cone_angle": 30, "falloff_start": 20,
       "intensity": "warm"},
      {"type": "distant", "direction": [0, -1, 0], "irradiance": "E", "scale": 1.5},
      {"type": "environment", "radiance": 0.1, "scale": 2}
    ]
  })");
  const auto scene = loadSceneFromString(j.dump(), path);
  ASSERT_TRUE(scene);

  EXPECT_EQ(scene->range.min, 380.0f);
  EXPECT_EQ(scene->range.max, 780.0f);
  EXPECT_EQ(scene->render.spp, 4);
  EXPECT_EQ(scene->render.timeBudgetSeconds, 1.5);
  EXPECT_EQ(scene->render.maxDepth, 8);
  EXPECT_EQ(scene->render.rrDepth, 2);
  EXPECT_EQ(scene->render.seed, 7u);
  EXPECT_EQ(scene->render.wavelengths.sensor.text, "uniform");
  EXPECT_EQ(scene->camera.width(), 32);
  EXPECT_EQ(scene->camera.height(), 24);
  EXPECT_EQ(scene->camera.fovYDegrees(), 45.0f);

  // Materials, in the (alphabetical) order of the JSON object.
  ASSERT_EQ(scene->materials.size(), 4u);
  EXPECT_EQ(scene->materialNames, (std::vector<std::string>{"dye", "grey", "tinted", "wall"}));
  EXPECT_EQ(scene->materials[0]->describe(), "jung_fluorescent");
  EXPECT_TRUE(has(scene->materials[0]->flags(), BsdfFlags::Fluorescent));

  ASSERT_EQ(scene->shapes.size(), 5u);
  const auto& s = scene->shapes;
  EXPECT_EQ(s[0].name, "floor");
  EXPECT_EQ(scene->materialNames[s[0].material], "wall");
  EXPECT_NEAR(s[0].area, 16.0f, 1e-4f);
  EXPECT_NEAR(glm::dot(s[0].triangleNormal(0), Vec3(0, 1, 0)), 1.0f, 1e-6f);  // corners order: normal +y
  EXPECT_EQ(s[1].name, "lamp");
  EXPECT_NEAR(s[1].area, 1.0f, 1e-5f);
  ASSERT_TRUE(s[1].emission);
  EXPECT_EQ(s[1].emission->scale, 3.0f);
  EXPECT_TRUE(s[1].emission->twoSided);
  EXPECT_NEAR(s[1].emission->radiance(560.0f), 1.0f, 5e-3f);  // D65 is 100 at 560 nm, scaled by 0.01
  EXPECT_EQ(s[2].kind, Shape::Kind::Sphere);
  EXPECT_EQ(s[2].center, Vec3(0, 1, 0));
  EXPECT_EQ(s[2].radius, 0.5f);
  EXPECT_NEAR(s[2].area, 3.14159265f, 1e-5f);
  EXPECT_EQ(scene->materialNames[s[2].material], "dye");
  // The tetrahedron, scaled by 2 then moved by (1, 0, 0): three right triangles of area 2 and an
  // equilateral one of side 2√2.
  EXPECT_EQ(s[3].kind, Shape::Kind::Mesh);
  EXPECT_EQ(s[3].indices.size(), 12u);
  ASSERT_EQ(s[3].positions.size(), 4u);
  EXPECT_EQ(s[3].positions[0], Vec3(1, 0, 0));
  EXPECT_EQ(s[3].positions[1], Vec3(3, 0, 0));
  EXPECT_EQ(s[3].positions[3], Vec3(1, 0, 2));
  EXPECT_NEAR(s[3].area, 6.0f + 2.0f * std::sqrt(3.0f), 1e-4f);
  EXPECT_EQ(s[4].name, "shape4");
  EXPECT_EQ(s[4].indices.size(), 6u);  // the quad face, triangulated
  EXPECT_NEAR(s[4].area, 1.0f, 1e-6f);

  // 4 lights from /lights plus the area light of the emissive shape, appended after them.
  ASSERT_EQ(scene->lights.size(), 5u);
  EXPECT_EQ(scene->shapeLight, (std::vector<int>{-1, 4, -1, -1, -1}));
  EXPECT_EQ(scene->environmentLight, 3);
  ASSERT_NE(scene->environment(), nullptr);
  EXPECT_NEAR(scene->environment()->Le(500.0f, Vec3(0, 1, 0)), 0.2f, 1e-6f);
  const auto* point = dynamic_cast<const PointLight*>(scene->lights[0].get());
  ASSERT_NE(point, nullptr);
  const float fourPi = 4.0f * 3.14159265f;
  EXPECT_NEAR(point->power(550.0f), fourPi * 5.0f * 2.0f, 1e-3f);  // the file's column, scaled by 5
  EXPECT_EQ(point->power(390.0f), 0.0f);                            // "outside": "zero"
  EXPECT_EQ(point->power(750.0f), 0.0f);
  EXPECT_NE(dynamic_cast<const SpotLight*>(scene->lights[1].get()), nullptr);
  const auto* distant = dynamic_cast<const DistantLight*>(scene->lights[2].get());
  ASSERT_NE(distant, nullptr);
  EXPECT_NEAR(distant->irradiance(600.0f), 1.5f, 1e-6f);
  EXPECT_NEAR(distant->direction().y, -1.0f, 1e-6f);
  EXPECT_NE(dynamic_cast<const AreaLight*>(scene->lights[4].get()), nullptr);
  EXPECT_TRUE(scene->accel);
  EXPECT_TRUE(scene->lightSelector);
}

TEST_F(SceneLoader, PathsAreRelativeToTheSceneFile) {
  write("data/grey.csv", "wavelength,v\n300,0.5\n900,0.5\n");
  const std::string obj = write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  json j = base;
  j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "data/grey.csv"}};
  j["shapes"].push_back({{"type", "mesh"}, {"file", obj}, {"material", "white"}});  // absolute path
  write("scene.json", j.dump());
  const auto scene = loadScene(path);
  EXPECT_EQ(scene->shapes.size(), 2u);
  // The same text, named as a file in another directory, does not find the CSV.
  const std::string other = dir + "/elsewhere/scene.json";
  try {
    loadSceneFromString(j.dump(), other);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), other + ": /materials/white/reflectance: " + dir + "/elsewhere/data/grey.csv");
    EXPECT_CONTAINS(e.what(), "cannot open spectrum file (No such file or directory)");
  }
}

TEST_F(SceneLoader, ShippedScenesLoad) {
  for (const char* name : {"scenes/cornell_fluorescent.json", "scenes/cornell_uv.json"}) {
    SCOPED_TRACE(name);
    const auto scene = loadScene(test::sourcePath(name));
    EXPECT_GT(scene->shapes.size(), 5u);
    EXPECT_GE(scene->lights.size(), 1u);
    EXPECT_EQ(scene->materials.size(), 5u);
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input, one class at a time

TEST_F(SceneLoader, MissingSceneFile) {
  const std::string missing = dir + "/nope.json";
  try {
    loadScene(missing);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": cannot open scene file (No such file or directory)");
  }
}

TEST_F(SceneLoader, MalformedJson) {
  for (const char* text : {"", "{", "{\"camera\": }", "{\"camera\": {\"fov\": 40,}}", "[1, 2", "{\"a\": 1} x"}) {
    SCOPED_TRACE(text);
    const std::string msg = errorOfText(text);
    EXPECT_EQ(msg.rfind(path + ": malformed JSON: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // The parser's position is in the message.
  EXPECT_CONTAINS(errorOfText("{\n  \"camera\": ?\n}"), "line 2");
  // A number that overflows a double is also a parse failure naming the file.
  const std::string msg = errorOfText(R"({"camera": {"fov": 1e400}})");
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_CONTAINS(msg, "1e400");
  // Not an object at the top level.
  EXPECT_EQ(errorOfText("[1, 2]"), path + ": /: expected an object, got array");
}

// The camera's "type": a thin lens (aperture_radius, focus_distance) and an orthographic camera
// (extent instead of fov); their fields are checked like the pinhole's.
TEST_F(SceneLoader, CameraTypes) {
  json j = base;
  j["camera"]["type"] = "thinlens";
  j["camera"]["aperture_radius"] = 0.1;
  j["camera"]["focus_distance"] = 3;
  auto scene = loadSceneFromString(j.dump(), path);
  EXPECT_FALSE(scene->camera.pinhole());
  EXPECT_FALSE(scene->camera.parallelRays());
  EXPECT_FLOAT_EQ(scene->camera.apertureRadius(), 0.1f);
  EXPECT_FLOAT_EQ(scene->camera.focusDistance(), 3.0f);
  j = base;
  j["camera"]["type"] = "orthographic";
  j["camera"].erase("fov");
  j["camera"]["extent"] = {4, 2};
  scene = loadSceneFromString(j.dump(), path);
  EXPECT_TRUE(scene->camera.parallelRays());
  EXPECT_EQ(scene->camera.filmExtent(), Vec2(4, 2));
  expectError([](json& j) { j["camera"]["type"] = "fisheye"; }, "/camera/type", "'fisheye' is not a camera (pinhole, thinlens, orthographic)");
  expectError([](json& j) { j["camera"]["type"] = "thinlens"; j["camera"]["focus_distance"] = 1; },
              "/camera/aperture_radius", "missing required field");
  expectError([](json& j) { j["camera"]["type"] = "thinlens"; j["camera"]["aperture_radius"] = -1; j["camera"]["focus_distance"] = 1; },
              "/camera/aperture_radius", "must be finite and at least 0");
  expectError([](json& j) { j["camera"]["type"] = "thinlens"; j["camera"]["aperture_radius"] = 0.1; j["camera"]["focus_distance"] = 0; },
              "/camera/focus_distance", "must be positive and finite");
  expectError([](json& j) { j["camera"]["aperture_radius"] = 0.1; }, "/camera/aperture_radius", "unknown field");
  expectError([](json& j) { j["camera"]["type"] = "orthographic"; }, "/camera/extent", "missing required field");
  expectError([](json& j) { j["camera"]["type"] = "orthographic"; j["camera"]["extent"] = {4, 2}; }, "/camera/fov", "unknown field");
  expectError([](json& j) { j["camera"]["type"] = "orthographic"; j["camera"].erase("fov"); j["camera"]["extent"] = {4, 0}; },
              "/camera/extent", "the film's width and height must be positive and finite");
}

TEST_F(SceneLoader, MissingRequiredField) {
  expectError([](json& j) { j.erase("camera"); }, "/camera", "missing required field");
  expectError([](json& j) { j.erase("materials"); }, "/materials", "missing required field");
  expectError([](json& j) { j.erase("shapes"); }, "/shapes", "missing required field");
  expectError([](json& j) { j["camera"].erase("fov"); }, "/camera/fov", "missing required field");
  expectError([](json& j) { j["camera"].erase("position"); }, "/camera/position", "missing required field");
  expectError([](json& j) { j["camera"].erase("resolution"); }, "/camera/resolution", "missing required field");
  expectError([](json& j) { j["materials"]["white"].erase("reflectance"); }, "/materials/white/reflectance",
              "missing required field");
  expectError([](json& j) { j["materials"]["white"].erase("type"); }, "/materials/white/type", "missing required field");
  expectError([](json& j) { j["shapes"][0].erase("material"); }, "/shapes/0/material", "missing required field");
  expectError([](json& j) { j["shapes"][0].erase("type"); }, "/shapes/0/type", "missing required field");
  expectError([](json& j) { j["shapes"][0].erase("v"); }, "/shapes/0/v", "missing required field");
  expectError([](json& j) { j["shapes"][0]["emission"].erase("radiance"); }, "/shapes/0/emission/radiance",
              "missing required field");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "point", "intensity": 1}])"); }, "/lights/0/position",
              "missing required field");
  expectError([](json& j) { j["materials"]["fluo"] = json::parse(kJungMaterial); j["materials"]["fluo"].erase("Q"); },
              "/materials/fluo/Q", "missing required field");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "gaussian"}, {"center", 500}}; },
              "/materials/white/reflectance/fwhm", "missing required field");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"value", 0.5}}; },
              "/materials/white/reflectance/type", "missing required field");
}

TEST_F(SceneLoader, UnknownField) {
  expectError([](json& j) { j["colour"] = "red"; }, "/colour", "unknown field");
  expectError([](json& j) { j["camera"]["fov_deg"] = 40; }, "/camera/fov_deg", "unknown field");
  expectError([](json& j) { j["render"] = {{"samples", 4}}; }, "/render/samples", "unknown field");
  expectError([](json& j) { j["materials"]["white"]["albedo"] = 0.5; }, "/materials/white/albedo", "unknown field");
  expectError([](json& j) { j["shapes"][0]["radius"] = 1; }, "/shapes/0/radius", "unknown field");
  expectError([](json& j) { j["shapes"][0]["emission"]["power"] = 1; }, "/shapes/0/emission/power", "unknown field");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": 1, "color": 1}])"); },
              "/lights/0/color", "unknown field");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "constant"}, {"value", 0.5}, {"unit", "W"}}; },
              "/materials/white/reflectance/unit", "unknown field");
  // A rectangle given both ways: the unused form is reported.
  expectError([](json& j) { j["shapes"][0]["corners"] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}; },
              "/shapes/0/center", "unknown field");
}

TEST_F(SceneLoader, WrongType) {
  expectError([](json& j) { j["camera"]["fov"] = "wide"; }, "/camera/fov", "expected a number, got string");
  expectError([](json& j) { j["camera"]["position"] = "origin"; }, "/camera/position", "expected an array of 3 numbers");
  expectError([](json& j) { j["camera"]["position"] = {0, 0}; }, "/camera/position", "expected an array of 3 numbers");
  expectError([](json& j) { j["camera"]["look_at"] = {0, "0", 0}; }, "/camera/look_at", "expected an array of 3 finite numbers");
  expectError([](json& j) { j["camera"] = 5; }, "/camera", "expected an object, got number");
  expectError([](json& j) { j["materials"] = json::array(); }, "/materials", "expected an object of named materials");
  expectError([](json& j) { j["materials"] = json::object(); }, "/materials", "expected an object of named materials");
  expectError([](json& j) { j["materials"]["white"] = "lambertian"; }, "/materials/white", "expected an object, got string");
  expectError([](json& j) { j["shapes"] = json::object(); }, "/shapes", "expected a non-empty array of shapes");
  expectError([](json& j) { j["shapes"] = json::array(); }, "/shapes", "expected a non-empty array of shapes");
  expectError([](json& j) { j["shapes"][0] = 3; }, "/shapes/0", "expected an object, got number");
  expectError([](json& j) { j["shapes"][0]["type"] = 1; }, "/shapes/0/type", "expected a string, got number");
  expectError([](json& j) { j["shapes"][0]["emission"]["two_sided"] = "yes"; }, "/shapes/0/emission/two_sided",
              "expected true or false, got string");
  expectError([](json& j) { j["render"] = {{"spp", 2.5}}; }, "/render/spp", "expected an integer, got number");
  expectError([](json& j) { j["render"] = 16; }, "/render", "expected an object, got number");
  expectError([](json& j) { j["lights"] = json::object(); }, "/lights", "expected an array of lights");
  expectError([](json& j) { j["spectra"] = json::array(); }, "/spectra", "expected an object of named spectra");
  expectError([](json& j) { j["description"] = 1; }, "/description", "expected a string, got number");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = true; }, "/materials/white/reflectance",
              "expected a spectrum (number, name or object), got boolean");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {0.5, 0.5}; }, "/materials/white/reflectance",
              "expected a spectrum (number, name or object), got array");
}

TEST_F(SceneLoader, UnknownTypes) {
  expectError([](json& j) { j["materials"]["white"]["type"] = "glass"; }, "/materials/white/type",
              "unknown material type 'glass'");
  expectError([](json& j) { j["shapes"][0]["type"] = "cube"; }, "/shapes/0/type",
              "unknown shape type 'cube' (sphere, cylinder, rectangle, mesh, disk)");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "area"}])"); }, "/lights/0/type",
              "unknown light type 'area' (point, spot, projector, distant, environment, envmap)");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "hsv"}}; },
              "/materials/white/reflectance/type", "unknown spectrum type 'hsv'");
  expectError([](json& j) { j["render"] = {{"sensor_sampling", "random"}}; }, "/render/sensor_sampling",
              "unknown kind 'random'");
  expectError([](json& j) { j["render"] = {{"bdpt", {{"mollify_alpha", 1.0}}}}; }, "/render/bdpt/mollify_alpha",
              "must be in (0, 1)");
  expectError([](json& j) { j["render"] = {{"bdpt", {{"mollify_bandwidth", -2}}}}; }, "/render/bdpt/mollify_bandwidth",
              "must not be negative");
  expectError([](json& j) { j["render"] = {{"bdpt", {{"mollify", true}}}}; }, "/render/bdpt/mollify",
              "needs render/bdpt/families \"own\"");
  expectError([](json& j) { j["render"] = {{"bdpt", {{"h", 2}}}}; }, "/render/bdpt/h", "unknown field");
  expectError([](json& j) { j["render"] = {{"vcm", {{"alpha", 0.3}}}}; }, "/render/vcm/alpha", "must be in (1/3, 1)");
  expectError([](json& j) { j["render"] = {{"vcm", {{"photons_per_pass", -1}}}}; }, "/render/vcm/photons_per_pass",
              "must not be negative");
  // Where the integrators' settings were before they had objects of their own.
  expectError([](json& j) { j["render"] = {{"mollify", {{"alpha", 0.5}}}}; }, "/render/mollify",
              "is now render/bdpt/mollify");
  expectError([](json& j) { j["render"] = {{"bdpt_families", "own"}}; }, "/render/bdpt_families",
              "is now render/bdpt/families");
  expectError([](json& j) { j["render"] = {{"vcm_paths", "camera"}}; }, "/render/vcm_paths", "is now render/vcm/paths");
  expectError([](json& j) { j["render"] = {{"ppm", {{"nee_wavelengths", "cmf*sun"}}}}; }, "/render/ppm/nee_wavelengths",
              "expected \"cmf*light\", \"camera\" or a wavelength strategy");
  expectError([](json& j) { j["render"] = {{"ppm", {{"nee_wavelengths", "ms-power:cmf,light"}}}}; },
              "/render/ppm/nee_wavelengths", "'ms-power:cmf,light' is not one density");
  expectError([](json& j) { j["render"] = {{"ppm", {{"volume_radius", -0.1}}}}; }, "/render/ppm/volume_radius",
              "must not be negative");
  expectError([](json& j) { j["render"] = {{"fluorescence_sampling", "mix:light"}}; }, "/render/fluorescence_sampling",
              "a combination needs at least two components");
  expectError([](json& j) { j["render"] = {{"light_sampling", "yamamoto=2"}}; }, "/render/light_sampling",
              "w_F must lie in [0, 1]");
  expectError([](json& j) { j["render"] = {{"hero_wavelengths", 17}}; }, "/render/hero_wavelengths",
              "must be in [1, 16]");
  expectError([](json& j) { j["render"] = {{"fluorescent_lanes", "sideways"}}; }, "/render/fluorescent_lanes",
              "'sideways' is not what lanes do at fluorescent events (through, end)");
  expectError([](json& j) { j["render"] = {{"bdpt", {{"families", "neither"}}}}; }, "/render/bdpt/families",
              "'neither' is not a choice of bdpt's light subpaths (auto, both, shared, own)");
  expectError([](json& j) { j["render"] = {{"vcm", {{"paths", "light"}}}}; }, "/render/vcm/paths",
              "'light' is not a choice of vcm's subpaths (auto, bidirectional, gather, connections, camera)");
  expectError([](json& j) { j["render"] = {{"vcm", {{"beams", "yes"}}}}; }, "/render/vcm/beams",
              "expected true or false, got string");
  expectError([](json& j) { j["render"] = {{"vcm", {{"photon_beams", 1}}}}; }, "/render/vcm/photon_beams",
              "expected true or false, got number");
}

TEST_F(SceneLoader, MissingMaterial) {
  expectError([](json& j) { j["shapes"][0]["material"] = "black"; }, "/shapes/0/material",
              "no material named 'black' in /materials");
}

TEST_F(SceneLoader, UnknownNamedSpectrum) {
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = "chartreuse"; }, "/materials/white/reflectance",
              "unknown spectrum 'chartreuse' (not in /spectra; presets: E, D65, A, F1");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "preset"}, {"name", "D50"}}; },
              "/materials/white/reflectance/name", "unknown preset 'D50'");
  // Named spectra are looked up case-sensitively.
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = "d65"; }, "/shapes/0/emission/radiance",
              "unknown spectrum 'd65'");
}

TEST_F(SceneLoader, NegativeSpectrum) {
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = -0.5; }, "/materials/white/reflectance",
              "must not be negative");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "constant"}, {"value", -1}}; },
              "/materials/white/reflectance/value", "must not be negative");
  expectError([](json& j) {
    j["materials"]["white"]["reflectance"] = {{"type", "tabulated"}, {"wavelengths", {400, 500}}, {"values", {0.5, -0.1}}};
  }, "/materials/white/reflectance/values/1", "negative value");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = {{"type", "box"}, {"min", 400}, {"max", 500}, {"value", -2}}; },
              "/shapes/0/emission/radiance/value", "must not be negative");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = {{"type", "gaussian"}, {"center", 500}, {"fwhm", 20}, {"peak", -1}}; },
              "/shapes/0/emission/radiance/peak", "must not be negative");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = {{"type", "preset"}, {"name", "D65"}, {"scale", -1}}; },
              "/shapes/0/emission/radiance/scale", "must not be negative");
  // In a CSV file, the message names the CSV line.
  const std::string csv = write("neg.csv", "wavelength,v\n400,0.5\n500,-0.5\n");
  expectError([&](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "neg.csv"}}; },
              "/materials/white/reflectance", csv + ":3: v: negative value");
}

TEST_F(SceneLoader, InvalidNumbers) {
  // JSON has no NaN or infinity; the ways one is attempted all fail.
  expectError([](json& j) { j["camera"]["fov"] = "NaN"; }, "/camera/fov", "expected a number, got string");
  expectError([](json& j) { j["camera"]["fov"] = nullptr; }, "/camera/fov", "expected a number, got null");
  expectError([](json& j) { j["camera"]["position"] = {0, "inf", 0}; }, "/camera/position", "finite numbers");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = "NaN"; }, "/materials/white/reflectance",
              "unknown spectrum 'NaN'");
  expectError([](json& j) {
    j["materials"]["white"]["reflectance"] = {{"type", "tabulated"}, {"wavelengths", {400, 500}}, {"values", {0.5, "nan"}}};
  }, "/materials/white/reflectance/values/1", "expected a finite number");
  expectError([](json& j) { j["shapes"][0]["corners"] = {{0, 0, 0}, {1, 0, 0}, {1, nullptr, 0}, {0, 1, 0}};
                            j["shapes"][0].erase("center"); j["shapes"][0].erase("u"); j["shapes"][0].erase("v"); },
              "/shapes/0/corners/2", "expected 3 finite numbers");
  // Finite as a double but not as the 32-bit float the renderer uses.
  expectError([](json& j) { j["shapes"][0]["emission"]["scale"] = 1e39; }, "/shapes/0/emission/scale", "32-bit");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = 1e39; }, "/shapes/0/emission/radiance", "32-bit");
  // Integers that do not fit an int are not wrapped around.
  expectError([](json& j) { j["render"] = {{"spp", 4294967297LL}}; }, "/render/spp", "out of range");
  expectError([](json& j) { j["render"] = {{"seed", 4294967296LL}}; }, "/render/seed", "out of range");
}

TEST_F(SceneLoader, SpectrumFileProblems) {
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "missing.csv"}}; },
              "/materials/white/reflectance", dir + "/missing.csv: cannot open spectrum file (No such file or directory)");
  write("two.csv", "wavelength,a,b\n400,0.1,0.2\n500,0.1,0.2\n");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "two.csv"}}; },
              "/materials/white/reflectance", "2 value columns; name one");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "two.csv"}, {"column", "c"}}; },
              "/materials/white/reflectance", "no column named 'c'");
  expectError([](json& j) {
    j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "two.csv"}, {"column", "a"}, {"outside", "extend"}};
  }, "/materials/white/reflectance/outside", "expected \"clamp\" or \"zero\"");
  const std::string bad = write("bad.csv", "wavelength,a\n400,0.1\n500,x\n");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", "bad.csv"}}; },
              "/materials/white/reflectance", bad + ":3: a: 'x' is not a number");
}

TEST_F(SceneLoader, BadSpectrumParameters) {
  auto refl = [](json spec) { return [spec](json& j) { j["materials"]["white"]["reflectance"] = spec; }; };
  expectError(refl({{"type", "gaussian"}, {"center", 500}, {"fwhm", 0}}), "/materials/white/reflectance/fwhm", "must be positive");
  expectError(refl({{"type", "gaussian"}, {"center", -5}, {"fwhm", 10}}), "/materials/white/reflectance/center",
              "must be a positive wavelength");
  expectError(refl({{"type", "blackbody"}, {"kelvin", 0}}), "/materials/white/reflectance/kelvin", "must be positive");
  expectError(refl({{"type", "box"}, {"min", 500}, {"max", 500}}), "/materials/white/reflectance/max", "must exceed /min");
  expectError(refl({{"type", "tabulated"}, {"wavelengths", {500, 400}}, {"values", {0.1, 0.2}}}),
              "/materials/white/reflectance/wavelengths/1", "strictly increasing");
  expectError(refl({{"type", "tabulated"}, {"wavelengths", {400, 500}}, {"values", {0.1}}}),
              "/materials/white/reflectance/values", "as long as /wavelengths (2)");
  expectError(refl({{"type", "tabulated"}, {"wavelengths", json::array()}, {"values", json::array()}}),
              "/materials/white/reflectance/wavelengths", "non-empty array");
}

TEST_F(SceneLoader, JungParametersOutsideUnitInterval) {
  auto jung = [](const char* key, json value) {
    return [=](json& j) {
      j["materials"]["fluo"] = json::parse(kJungMaterial);
      j["materials"]["fluo"][key] = value;
    };
  };
  // The valid material loads.
  {
    json j = base;
    jung("c", 0.5)(j);
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
  }
  expectError(jung("c", 1.5), "/materials/fluo/c", "outside [0, 1]");
  expectError(jung("c", -0.1), "/materials/fluo/c", "outside [0, 1]");
  expectError(jung("Q", 1.01), "/materials/fluo/Q", "outside [0, 1]");
  expectError(jung("Q", -1), "/materials/fluo/Q", "outside [0, 1]");
  expectError(jung("absorption", 1.5), "/materials/fluo/absorption", "exceeds 1");
  expectError(jung("reflectance", 2), "/materials/fluo/reflectance", "exceeds 1");
  expectError(jung("emission", json{{"type", "box"}, {"min", 900}, {"max", 950}}), "/materials/fluo/emission",
              "integrates to zero");
}

TEST_F(SceneLoader, ReflectanceAboveOne) {
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = 1.5; }, "/materials/white/reflectance", "exceeds 1");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = "D65"; }, "/materials/white/reflectance", "exceeds 1");
  // Only the scene's wavelength range counts.
  json j = base;
  j["materials"]["white"]["reflectance"] = {{"type", "tabulated"}, {"wavelengths", {300, 340, 360, 830}}, {"values", {3, 3, 0.5, 0.5}}};
  EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
  j["wavelength_range"] = {300, 830};
  expectError(j, "/materials/white/reflectance", "exceeds 1");
}

TEST_F(SceneLoader, EmissionThatIntegratesToZero) {
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = {{"type", "box"}, {"min", 900}, {"max", 1000}}; },
              "/shapes/0/emission/radiance", "emission integrates to zero over the wavelength range [360, 830] nm");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = 0; }, "/shapes/0/emission/radiance",
              "integrates to zero");
  expectError([](json& j) { j["shapes"][0]["emission"]["scale"] = 0; }, "/shapes/0/emission/scale", "must be positive");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": {"type": "gaussian", "center": 300, "fwhm": 10}}])"); },
              "/lights/0/intensity", "integrates to zero");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "environment", "radiance": 1, "scale": -1}])"); },
              "/lights/0/scale", "must be positive");
}

TEST_F(SceneLoader, DegenerateShapes) {
  expectError([](json& j) {
    auto& s = j["shapes"][0];
    s.erase("center"), s.erase("u"), s.erase("v");
    s["corners"] = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  }, "/shapes/0", "degenerate rectangle: total area is zero");
  expectError([](json& j) { j["shapes"][0]["v"] = {2, 0, 0}; }, "/shapes/0", "degenerate rectangle");  // u ∥ v
  expectError([](json& j) { j["shapes"][0]["corners"] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
                            j["shapes"][0].erase("center"); },
              "/shapes/0/corners", "expected 4 corner points");
  expectError([](json& j) { j["shapes"][0] = {{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 0}, {"material", "white"}}; },
              "/shapes/0/radius", "must be positive");
}

TEST_F(SceneLoader, MeshProblems) {
  auto mesh = [](const std::string& file) {
    return [file](json& j) { j["shapes"].push_back({{"type", "mesh"}, {"file", file}, {"material", "white"}}); };
  };
  expectError(mesh("nope.obj"), "/shapes/1/file", dir + "/nope.obj: cannot open mesh file (No such file or directory)");
  write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\nf 1 1 2\n");
  expectError(mesh("flat.obj"), "/shapes/1", "degenerate mesh: total area is zero");
  write("empty.obj", "# no faces\nv 0 0 0\n");
  expectError(mesh("empty.obj"), "/shapes/1", "degenerate mesh: total area is zero");
  write("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError(mesh("inf.obj"), "/shapes/1/file", dir + "/inf.obj:2: '1e999' is not a finite number (v component 1)");
  write("missing_vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  {
    json j = base;
    mesh("missing_vertex.obj")(j);
    const std::string msg = errorOfText(j.dump());
    EXPECT_EQ(msg.rfind(path + ": /shapes/1/file: ", 0), 0u) << msg;
    EXPECT_CONTAINS(msg, "missing_vertex.obj");
  }
  // tinyobjloader alone would read "nan" as 0; the strict pass refuses it (more in test_obj_validation.cpp).
  write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError(mesh("nan.obj"), "/shapes/1/file", dir + "/nan.obj:1: 'nan' is not a finite number (v component 1)");
  expectError([&](json& j) { mesh("flat.obj")(j); j["shapes"][1]["scale"] = 0; }, "/shapes/1/scale", "must be positive");
}

TEST_F(SceneLoader, BadWavelengthRange) {
  expectError([](json& j) { j["wavelength_range"] = {700, 400}; }, "/wavelength_range", "expected 200 <= min < max <= 2500 nm");
  expectError([](json& j) { j["wavelength_range"] = {500, 500}; }, "/wavelength_range", "expected 200 <= min < max <= 2500 nm");
  expectError([](json& j) { j["wavelength_range"] = {100, 900}; }, "/wavelength_range", "expected 200 <= min < max <= 2500 nm");
  expectError([](json& j) { j["wavelength_range"] = {400, 3000}; }, "/wavelength_range", "expected 200 <= min < max <= 2500 nm");
  expectError([](json& j) { j["wavelength_range"] = {850, 1000}; }, "/wavelength_range", "does not overlap the visible range");
  expectError([](json& j) { j["wavelength_range"] = {250, 360}; }, "/wavelength_range", "does not overlap the visible range");
  expectError([](json& j) { j["wavelength_range"] = {400}; }, "/wavelength_range", "expected [min, max] in nm");
  expectError([](json& j) { j["wavelength_range"] = "visible"; }, "/wavelength_range", "expected [min, max] in nm");
  expectError([](json& j) { j["wavelength_range"] = {"400", 700}; }, "/wavelength_range", "expected [min, max] in nm");
}

TEST_F(SceneLoader, BadResolution) {
  for (const json& res : {json{0, 8}, json{8, -1}, json{20000, 8}}) {
    SCOPED_TRACE(res.dump());
    expectError([&](json& j) { j["camera"]["resolution"] = res; }, "/camera/resolution", "width and height must be in 1..16384");
  }
  for (const json& res : {json{8}, json{8, 8, 8}, json{8.5, 8}, json{"8", 8}, json("8x8")}) {
    SCOPED_TRACE(res.dump());
    expectError([&](json& j) { j["camera"]["resolution"] = res; }, "/camera/resolution", "expected [width, height] in pixels");
  }
  // 2³² + 8 must not wrap around to 8.
  expectError([](json& j) { j["camera"]["resolution"] = {4294967304LL, 8}; }, "/camera/resolution",
              "width and height must be in 1..16384");
}

TEST_F(SceneLoader, BadCamera) {
  expectError([](json& j) { j["camera"]["look_at"] = {0, 0, -3}; }, "/camera/look_at", "equals /camera/position");
  expectError([](json& j) { j["camera"]["up"] = {0, 0, 2}; }, "/camera/up", "parallel to the viewing direction");
  expectError([](json& j) { j["camera"]["up"] = {0, 0, 0}; }, "/camera/up", "must not be zero");
  // A camera far away: the distance overflows, which is the look_at's fault, not the up vector's.
  expectError([](json& j) { j["camera"]["position"] = {-3e38, 0, 0}; j["camera"]["look_at"] = {3e38, 0, 0}; },
              "/camera/look_at", "is too far from /camera/position");
  expectError([](json& j) { j["camera"]["fov"] = 0; }, "/camera/fov", "(0, 180) degrees");
  expectError([](json& j) { j["camera"]["fov"] = 180; }, "/camera/fov", "(0, 180) degrees");
  expectError([](json& j) { j["camera"]["fov"] = 405; }, "/camera/fov", "(0, 180) degrees");  // tan would wrap round to 45
  expectError([](json& j) { j["camera"]["fov"] = -45; }, "/camera/fov", "(0, 180) degrees");
}

TEST_F(SceneLoader, CameraFilters) {
  const auto filterOf = [&](const json& filter) {
    json j = base;
    j["camera"]["filter"] = filter;
    return loadSceneFromString(j.dump(), path)->pixelFilter;
  };
  EXPECT_EQ(loadSceneFromString(base.dump(), path)->pixelFilter.type(), PixelFilterType::Box);  // the default
  EXPECT_EQ(filterOf("box").type(), PixelFilterType::Box);
  EXPECT_EQ(filterOf("tent").radius(), 1.0f);
  EXPECT_EQ(filterOf({{"type", "tent"}, {"radius", 1.5}}).radius(), 1.5f);
  const PixelFilter g = filterOf("gaussian");
  EXPECT_EQ(g.type(), PixelFilterType::Gaussian);
  EXPECT_EQ(g.stddev(), 0.5f);
  EXPECT_EQ(g.radius(), 2.0f);
  EXPECT_EQ(filterOf({{"type", "gaussian"}, {"stddev", 0.25}}).radius(), 1.0f);
  expectError([](json& j) { j["camera"]["filter"] = "mitchell"; }, "/camera/filter", "unknown reconstruction filter 'mitchell' (box, tent, gaussian)");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "lanczos"}}; }, "/camera/filter/type", "unknown reconstruction filter");
  expectError([](json& j) { j["camera"]["filter"] = 1; }, "/camera/filter", "expected an object");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "tent"}, {"radius", 0}}; }, "/camera/filter/radius", "[1/64, 16] pixels");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "tent"}, {"radius", 17}}; }, "/camera/filter/radius", "[1/64, 16] pixels");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "gaussian"}, {"stddev", -1}}; }, "/camera/filter/stddev", "[1/256, 4] pixels");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "gaussian"}, {"radius", 1}}; }, "/camera/filter/radius", "unknown field");
  expectError([](json& j) { j["camera"]["filter"] = {{"type", "box"}, {"stddev", 1}}; }, "/camera/filter/stddev", "unknown field");
}

TEST_F(SceneLoader, BadRenderSettings) {
  expectError([](json& j) { j["render"] = {{"spp", 0}}; }, "/render/spp", "must be at least 1");
  expectError([](json& j) { j["render"] = {{"time", -1}}; }, "/render/time", "must not be negative");
  expectError([](json& j) { j["render"] = {{"max_depth", -1}}; }, "/render/max_depth", "must not be negative");
  expectError([](json& j) { j["render"] = {{"rr_depth", -2}}; }, "/render/rr_depth", "must not be negative");
  expectError([](json& j) { j["render"] = {{"seed", -3}}; }, "/render/seed", "must not be negative");
}

TEST_F(SceneLoader, BadLights) {
  auto light = [](json l) { return [l](json& j) { j["lights"] = json::array({l}); }; };
  expectError(light({{"type", "spot"}, {"position", {0, 1, 0}}, {"look_at", {0, 1, 0}}, {"cone_angle", 30}, {"intensity", 1}}),
              "/lights/0/look_at", "equals the position");
  expectError(light({{"type", "spot"}, {"position", {0, 1, 0}}, {"look_at", {0, 0, 0}}, {"cone_angle", 120}, {"intensity", 1}}),
              "/lights/0/cone_angle", "(0, 90] degrees");
  expectError(light({{"type", "spot"}, {"position", {0, 1, 0}}, {"look_at", {0, 0, 0}}, {"cone_angle", 30},
                     {"falloff_start", 40}, {"intensity", 1}}),
              "/lights/0/falloff_start", "(0, cone_angle] degrees");
  expectError(light({{"type", "distant"}, {"direction", {0, 0, 0}}, {"irradiance", 1}}), "/lights/0/direction",
              "must not be zero");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "environment", "radiance": 1}, {"type": "environment", "radiance": 2}])"); },
              "/lights/1/type", "only one environment light is allowed");
  expectError([](json& j) { j["lights"] = json::array({5}); }, "/lights/0", "expected an object, got number");
}

TEST_F(SceneLoader, BadSpotTexture) {
  auto spot = [](json extra) {
    json l = {{"type", "spot"}, {"position", {0, 1, 0}}, {"look_at", {1, 0, 0}}, {"cone_angle", 30}, {"intensity", 1}};
    l.update(extra);
    return [l](json& j) { j["lights"] = json::array({l}); };
  };
  const unsigned char black[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const std::string blackPng = dir + "/black.png";
  ASSERT_TRUE(stbi_write_png(blackPng.c_str(), 2, 2, 3, black, 6));
  expectError(spot({{"texture", dir + "/missing.png"}}), "/lights/0/texture", "missing.png");
  expectError(spot({{"texture", blackPng}}), "/lights/0/texture", "black where it is cast");
  expectError(spot({{"texture", blackPng}, {"encoding", "gamma"}}), "/lights/0/encoding", "is not srgb or linear");
  expectError(spot({{"texture", blackPng}, {"cone_angle", 90}}), "/lights/0/cone_angle", "narrower than 90 degrees");
  expectError(spot({{"texture", blackPng}, {"up", {-2, 2, 0}}}), "/lights/0/up", "parallel to the spot's axis");
  expectError(spot({{"up", {0, 0, 1}}}), "/lights/0/up", "give it with a \"texture\"");
  // The light's texels, spectra and density (64 bytes a pixel) are checked against the memory
  // limit before they are built: a 16×16 texture decodes within 10 000 bytes, its light does not.
  const std::vector<unsigned char> white(16 * 16 * 3, 255);
  const std::string whitePng = dir + "/white.png";
  ASSERT_TRUE(stbi_write_png(whitePng.c_str(), 16, 16, 3, white.data(), 48));
  json j = base;
  spot({{"texture", whitePng}})(j);
  SceneLoadOptions small;
  small.memoryLimit = 10000;
  try {
    loadSceneFromString(j.dump(), path, small);
    ADD_FAILURE() << "loaded within the memory limit";
  } catch (const InputError& e) {
    EXPECT_CONTAINS(e.what(), "/lights/0/texture: '" + whitePng + "' (16 x 16): the light's image needs 16.0 KiB");
  }
}

TEST_F(SceneLoader, SceneWithoutLight) {
  expectError([](json& j) { j["shapes"][0].erase("emission"); }, "/lights", "the scene has no light");
  expectError([](json& j) { j["shapes"][0].erase("emission"); j["lights"] = json::array(); }, "/lights",
              "the scene has no light");
  // A light alone is enough.
  json j = base;
  j["shapes"][0].erase("emission");
  j["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, -1], "intensity": "D65"}])");
  const auto scene = loadSceneFromString(j.dump(), path);
  EXPECT_EQ(scene->lights.size(), 1u);
  EXPECT_EQ(scene->shapeLight, (std::vector<int>{-1}));
}

// ---------------------------------------------------------------------------------------------
// Reliability (issue 6): coverage of the scene's range, file sizes and kinds, named-spectrum
// references, nesting depth, and the explicit opt-in for physically invalid parameters.

TEST_F(SceneLoader, SpectrumFileMustCoverTheScenesRange) {
  const std::string part = write("part.csv", "wavelength,v\n400,0.5\n700,0.6\n");
  auto refl = [](json spec) { return [spec](json& j) { j["materials"]["white"]["reflectance"] = spec; }; };
  // Covering 400-700 nm of 360-830: an error unless "outside" says how to extend it.
  expectError(refl({{"type", "file"}, {"file", "part.csv"}}), "/materials/white/reflectance",
              part + " covers 400-700 nm, less than the scene's wavelength range 360-830 nm: add \"outside\": "
                     "\"clamp\" (continue its end values) or \"zero\"");
  for (const char* outside : {"clamp", "zero"}) {
    json j = base;
    refl({{"type", "file"}, {"file", "part.csv"}, {"outside", outside}})(j);
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path)) << outside;
  }
  // The same file in a scene whose range it covers needs nothing.
  {
    json j = base;
    j["wavelength_range"] = {400, 700};
    refl({{"type", "file"}, {"file", "part.csv"}})(j);
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
  }
  // No overlap at all is an error even with "outside".
  const std::string ir = write("ir.csv", "wavelength,v\n900,0.5\n1000,0.5\n");
  expectError(refl({{"type", "file"}, {"file", "ir.csv"}, {"outside", "clamp"}}), "/materials/white/reflectance",
              ir + " covers 900-1000 nm, outside the scene's wavelength range 360-830 nm");
  // The message names the named spectrum, and emitters are checked too.
  expectError([&](json& j) {
    j["spectra"] = {{"lamp", {{"type", "file"}, {"file", "part.csv"}}}};
    j["shapes"][0]["emission"]["radiance"] = "lamp";
  }, "/spectra/lamp", "covers 400-700 nm");
  // Inline tabulated spectra are written on purpose: their documented constant extrapolation stays.
  json j = base;
  refl({{"type", "tabulated"}, {"wavelengths", {400, 700}}, {"values", {0.5, 0.6}}})(j);
  EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
}

TEST_F(SceneLoader, SpectrumFileThatIsNotARegularFileOrTooLarge) {
  auto refl = [](const std::string& file) {
    return [file](json& j) { j["materials"]["white"]["reflectance"] = {{"type", "file"}, {"file", file}, {"outside", "clamp"}}; };
  };
  fs::create_directories(dir + "/folder.csv");
  expectError(refl("folder.csv"), "/materials/white/reflectance",
              dir + "/folder.csv: cannot open spectrum file (a directory, not a regular file)");
  expectError(refl("/dev/zero"), "/materials/white/reflectance",
              "/dev/zero: cannot open spectrum file (a character device, not a regular file)");
  // A sparse file: large on paper, no disk used.
  const std::string big = write("big.csv", "wavelength,v\n");
  fs::resize_file(big, (uint64_t(256) << 20) + 1);
  expectError(refl("big.csv"), "/materials/white/reflectance",
              big + ": spectrum file is 256 MiB, more than the 256 MiB allowed");
}

TEST_F(SceneLoader, NamedSpectraMayReferToEachOtherButNotInACycle) {
  // "a" refers to "b", which sorts later: references do not depend on the order of the names.
  json j = base;
  j["spectra"] = {{"a", "b"}, {"b", {{"type", "constant"}, {"value", 0.25}}}, {"c", "a"}};
  j["materials"]["white"]["reflectance"] = "c";
  const auto scene = loadSceneFromString(j.dump(), path);
  EXPECT_EQ(static_cast<const Lambertian*>(scene->materials[0].get())->reflectance()(500.0f), 0.25f);
  // Cycles.
  expectError([](json& j) { j["spectra"] = {{"loop", "loop"}}; }, "/spectra/loop",
              "named spectra refer to each other in a cycle: loop -> loop");
  expectError([](json& j) { j["spectra"] = {{"a", "b"}, {"b", {{"type", "constant"}, {"value", 1}, {"scale", 1}}}, {"c", "d"}, {"d", "e"}, {"e", "c"}}; },
              "/spectra/e", "named spectra refer to each other in a cycle: c -> d -> e -> c");
  // A name that shadows a preset cannot refer to the preset by that name.
  expectError([](json& j) { j["spectra"] = {{"D65", "D65"}}; }, "/spectra/D65",
              "cycle: D65 -> D65 (for the preset write {\"type\": \"preset\", \"name\": \"D65\"})");
  json k = base;
  k["spectra"] = {{"D65", {{"type", "preset"}, {"name", "D65"}, {"scale", 0.01}}}};
  k["shapes"][0]["emission"]["radiance"] = "D65";
  EXPECT_NO_THROW(loadSceneFromString(k.dump(), path));
}

TEST_F(SceneLoader, DeeplyNestedJson) {
  // 100 000 levels: refused while parsing, before anything recursive (a copy, a dump, the
  // destructor) meets the tree; arrays and objects alike.
  for (const auto& [open, close] : {std::pair{"[", "]"}, std::pair{"{\"a\": ", "}"}}) {
    std::string text = "{\"camera\": ";
    for (int i = 0; i < 100000; ++i) text += open;
    text += "1";
    for (int i = 0; i < 100000; ++i) text += close;
    text += "}";
    const std::string msg = errorOfText(text);
    EXPECT_EQ(msg.rfind(path + ": /camera/", 0), 0u) << msg.substr(0, 200);
    EXPECT_CONTAINS(msg, ": nested deeper than 64 levels");
  }
}

TEST_F(SceneLoader, UnphysicalParametersNeedAnExplicitOptIn) {
  auto jung = [](json changes) {
    return [changes](json& j) {
      j["materials"]["fluo"] = json::parse(kJungMaterial);
      j["materials"]["fluo"].update(changes);
    };
  };
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = 1.2; }, "/materials/white/reflectance",
              "exceeds 1 in the wavelength range");
  expectError(jung({{"Q", 1.5}}), "/materials/fluo/Q", "outside [0, 1]");
  expectError(jung({{"reflectance", 1.5}}), "/materials/fluo/reflectance", "exceeds 1 in the wavelength range");
  // With the opt-in they load ...
  for (const json& changes : {json{{"Q", 1.5}}, json{{"reflectance", 1.5}}, json{{"c", 1.0}, {"absorption", 1.0}}}) {
    SCOPED_TRACE(changes.dump());
    json j = base;
    json c = changes;
    c["allow_unphysical"] = true;
    jung(c)(j);
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
  }
  {
    json j = base;
    j["materials"]["white"]["reflectance"] = 1.2;
    j["materials"]["white"]["allow_unphysical"] = true;
    const auto scene = loadSceneFromString(j.dump(), path);
    EXPECT_NEAR(static_cast<const Lambertian*>(scene->materials[0].get())->reflectance()(500.0f), 1.2f, 1e-6f);
  }
  // ... but negative values, and c·a > 1 (a negative elastic weight), stay errors.
  expectError(jung({{"Q", -0.5}, {"allow_unphysical", true}}), "/materials/fluo/Q", "is negative");
  expectError(jung({{"c", 2.0}, {"allow_unphysical", true}}), "/materials/fluo/c", "c·a reaches 2");
  expectError([](json& j) { j["materials"]["white"]["reflectance"] = -0.1; j["materials"]["white"]["allow_unphysical"] = true; },
              "/materials/white/reflectance", "must not be negative");
  expectError([](json& j) { j["materials"]["white"]["allow_unphysical"] = "yes"; }, "/materials/white/allow_unphysical",
              "expected true or false, got string");
}

TEST_F(SceneLoader, NumbersThatOverflowOnceCombined) {
  // Each number fits a float; their product or sum does not.
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = {{"type", "constant"}, {"value", 3e38}, {"scale", 10}}; },
              "/shapes/0/emission/radiance/scale", "the scaled spectrum overflows a 32-bit float");
  expectError([](json& j) { j["shapes"][0]["emission"]["radiance"] = 3e38; }, "/shapes/0/emission/radiance",
              "emission over the wavelength range overflows a 32-bit float");
  expectError([](json& j) { j["shapes"][0]["emission"]["scale"] = 1e37; }, "/shapes/0/emission/scale",
              "the scaled emission overflows a 32-bit float");
  expectError([](json& j) { j["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": 1e30, "scale": 1e36}])"); },
              "/lights/0/scale", "overflows");
  expectError([](json& j) { j["shapes"][0]["center"] = {3e38, 0, 0}; j["shapes"][0]["u"] = {3e38, 0, 0}; }, "/shapes/0",
              "rectangle has a vertex beyond the range of a 32-bit float");
  expectError([](json& j) { j["shapes"].push_back({{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1e20}, {"material", "white"}}); },
              "/shapes/1", "sphere is too large: its area overflows a 32-bit float");
  expectError([](json& j) { j["shapes"][0]["u"] = {1e9, 0, 0}; j["shapes"][0]["v"] = {0, 1e9, 0}; j["shapes"][0]["emission"]["radiance"] = 1e17; },
              "/shapes/0/emission", "the emitted power overflows a 32-bit float");
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectError([](json& j) { j["shapes"].push_back({{"type", "mesh"}, {"file", "tri.obj"}, {"scale", 1e38}, {"translate", {3e38, 0, 0}}, {"material", "white"}}); },
              "/shapes/1", "mesh has a vertex beyond the range of a 32-bit float");
}

// ---------------------------------------------------------------------------------------------
// Participating media (docs/scene-format.md#media)

// The minimal scene with a fog sphere in front of the lamp, and a fluorescent medium "ink".
json withMedia(json j) {
  j["media"] = json::parse(R"({
    "fog": {"type": "homogeneous", "sigma_a": 0.1, "sigma_s": 0.5, "g": 0.3},
    "ink": {"type": "homogeneous", "sigma_s": 0.2, "length_unit": "cm",
            "fluorophores": [{"sigma_f": {"type": "gaussian", "center": 450, "fwhm": 40}, "emission": {"type": "gaussian", "center": 520, "fwhm": 30}, "yield": 0.9},
                             {"molar_absorption": {"type": "box", "min": 400, "max": 500, "value": 7e4}, "concentration": 1e-5,
                              "emission": {"type": "gaussian", "center": 600, "fwhm": 30}, "yield": 0.5}]}})");
  j["shapes"].push_back(json::parse(R"({"type": "sphere", "center": [0, 0, -1], "radius": 0.5, "interior": "fog"})"));
  return j;
}

TEST_F(SceneLoader, MediaLoad) {
  json j = withMedia(base);
  j["camera"]["medium"] = "ink";
  j["shapes"][0]["medium"] = "ink";  // the lamp immersed in ink: the same medium on both sides
  j["shapes"][1]["exterior"] = "ink";  // the fog sphere in it (the camera's rays check it)
  j["lights"] = json::parse(R"([{"type": "point", "position": [0, 0, -1], "intensity": 1, "medium": "fog"}])");
  const auto scene = loadSceneFromString(j.dump(), path);
  ASSERT_EQ(scene->media.size(), 2u);
  const Medium& ink = *scene->media[size_t(scene->cameraMedium)];
  EXPECT_EQ(ink.name(), "ink");
  // σ_f = ln 10·ε·c·(cm per scene unit): 7e4 L/(mol·cm) at 1e-5 mol/L is 0.7 per cm, 1.612 per cm as
  // a natural-log coefficient; σ_t at 450 nm adds σ_s and the first fluorophore's peak.
  EXPECT_NEAR(ink.sigmaF(1, 450.0f), std::log(10.0) * 0.7, 1e-4);
  EXPECT_NEAR(ink.sigmaT(450.0f), 0.2 + 1.0 + std::log(10.0) * 0.7, 1e-4);
  EXPECT_EQ(scene->media[size_t(scene->lightMedium[0])]->name(), "fog");
  // In metres, the same dye absorbs 100 times more per scene unit.
  j["media"]["ink"]["length_unit"] = "m";
  EXPECT_NEAR(loadSceneFromString(j.dump(), path)->media[size_t(scene->cameraMedium)]->sigmaF(1, 450.0f),
              100.0 * std::log(10.0) * 0.7, 1e-2);
}

TEST_F(SceneLoader, BadMediumCoefficients) {
  auto media = [](const std::function<void(json&)>& change) {
    return [change](json& j) {
      j = withMedia(j);
      change(j["media"]);
    };
  };
  // Negative, NaN and infinite coefficients.
  expectError(media([](json& m) { m["fog"]["sigma_a"] = -0.1; }), "/media/fog/sigma_a", "must not be negative");
  expectError(media([](json& m) { m["fog"]["sigma_s"] = json::parse(R"({"type": "tabulated", "wavelengths": [400, 500], "values": [0.5, -1]})"); }),
              "/media/fog/sigma_s/values/1", "negative value");
  expectError(media([](json& m) { m["fog"]["sigma_s"] = json::parse(R"({"type": "tabulated", "wavelengths": [400, 500], "values": [0.5, "nan"]})"); }),
              "/media/fog/sigma_s/values/1", "expected a finite number");
  expectError(media([](json& m) { m["fog"]["sigma_a"] = "NaN"; }), "/media/fog/sigma_a", "unknown spectrum 'NaN'");
  expectError(media([](json& m) { m["fog"]["sigma_a"] = 1e39; }), "/media/fog/sigma_a", "32-bit");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0]["sigma_f"] = -1; }), "/media/ink/fluorophores/0/sigma_f",
              "must not be negative");
  expectError(media([](json& m) { m["ink"]["fluorophores"][1]["molar_absorption"] = -1; }),
              "/media/ink/fluorophores/1/molar_absorption", "must not be negative");
  expectError(media([](json& m) { m["ink"]["fluorophores"][1]["molar_absorption"] = 3e38; m["ink"]["fluorophores"][1]["concentration"] = 10; }),
              "/media/ink/fluorophores/1/molar_absorption", "infinite value in the wavelength range");
  // Each coefficient fits a float; their sum σ_t does not.
  expectError(media([](json& m) { m["fog"]["sigma_a"] = 3e38; m["fog"]["sigma_s"] = 3e38; }), "/media/fog/sigma_s",
              "overflows a 32-bit float");
  // g in (−1, 1), yields in [0, 1], emission with energy in the range.
  for (const double g : {1.0, -1.0, 1.5})
    expectError(media([g](json& m) { m["fog"]["g"] = g; }), "/media/fog/g", "is outside (-1, 1)");
  expectError(media([](json& m) { m["fog"]["g"] = "forward"; }), "/media/fog/g", "expected a number, got string");
  for (const double y : {1.2, -0.1})
    expectError(media([y](json& m) { m["ink"]["fluorophores"][1]["yield"] = y; }), "/media/ink/fluorophores/1/yield",
                "is outside [0, 1]");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0]["emission"] = json::parse(R"({"type": "box", "min": 900, "max": 1000})"); }),
              "/media/ink/fluorophores/0/emission", "integrates to zero over the wavelength range");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0]["emission"] = 0; }), "/media/ink/fluorophores/0/emission",
              "integrates to zero");
}

TEST_F(SceneLoader, BadMediumFields) {
  auto media = [](const std::function<void(json&)>& change) {
    return [change](json& j) {
      j = withMedia(j);
      change(j["media"]);
    };
  };
  // Molar absorption needs the scene's length unit, and is the alternative to sigma_f.
  expectError(media([](json& m) { m["ink"].erase("length_unit"); }), "/media/ink/length_unit",
              "is needed with molar_absorption");
  expectError(media([](json& m) { m["ink"]["length_unit"] = "inch"; }), "/media/ink/length_unit",
              "'inch' is not a length unit (m, cm, mm, um)");
  expectError(media([](json& m) { m["fog"]["length_unit"] = "km"; }), "/media/fog/length_unit",
              "'km' is not a length unit (m, cm, mm, um)");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0]["molar_absorption"] = 1e4; }),
              "/media/ink/fluorophores/0/sigma_f", "give either sigma_f or molar_absorption");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0].erase("sigma_f"); }),
              "/media/ink/fluorophores/0/sigma_f", "give either sigma_f or molar_absorption");
  expectError(media([](json& m) { m["ink"]["fluorophores"][1].erase("concentration"); }),
              "/media/ink/fluorophores/1/concentration", "missing");
  expectError(media([](json& m) { m["ink"]["fluorophores"][1]["concentration"] = -1e-5; }),
              "/media/ink/fluorophores/1/concentration", "non-negative molarity");
  expectError(media([](json& m) { m["ink"]["fluorophores"][1].erase("yield"); }), "/media/ink/fluorophores/1/yield",
              "missing");
  expectError(media([](json& m) { m["ink"]["fluorophores"][0]["Q"] = 0.5; }), "/media/ink/fluorophores/0/Q",
              "unknown field");
  expectError(media([](json& m) { m["ink"]["fluorophores"] = {{"yield", 1}}; }), "/media/ink/fluorophores",
              "expected an array");
  expectError(media([](json& m) { m["fog"]["type"] = "smoke"; }), "/media/fog/type",
              "'smoke' is not a medium type (homogeneous, heterogeneous)");
  expectError(media([](json& m) { m["fog"]["type"] = "heterogeneous"; }), "/media/fog/density", "missing required field");
  expectError(media([](json& m) {
    m["ink"]["type"] = "heterogeneous";
    m["ink"]["density"] = {{"file", "missing.vol"}};
  }), "/media/ink/density/file", "missing.vol");
  // A grid that reads, but a heterogeneous medium cannot fluoresce yet (docs/media.md §4).
  write("smoke.vol", test::volBytes({2, 2, 2}, 1, {0, 1, 2, 3, 4, 5, 6, 7}));
  expectError(media([](json& m) {
    m["ink"]["type"] = "heterogeneous";
    m["ink"]["density"] = {{"file", "smoke.vol"}};
  }), "/media/ink/fluorophores", "a heterogeneous medium cannot fluoresce yet");
  // Without fluorophores it loads.
  {
    json j = withMedia(base);
    j["media"]["fog"]["type"] = "heterogeneous";
    j["media"]["fog"]["density"] = {{"file", "smoke.vol"}};
    EXPECT_TRUE(loadSceneFromString(j.dump(), path)->media[0]->heterogeneous());
  }
  expectError(media([](json& m) { m["fog"]["sigma_t"] = 1; }), "/media/fog/sigma_t", "is read with albedo_grid only");
  expectError(media([](json& m) { m = json::array(); }), "/media", "expected an object of named media");
}

// A homogeneous medium's albedo grid (docs/media.md §7): sigma_t alone, 1 or 3 channels in [0, 1],
// a known wrap mode; not with a density, fluorophores or sigma_a/sigma_s.
TEST_F(SceneLoader, AlbedoGridFields) {
  write("albedo.vol", test::volBytes({2, 1, 1}, 3, {0.9f, 0.5f, 0.1f, 0.2f, 0.4f, 1.0f}));
  auto fog = [](const std::function<void(json&)>& change) {
    return [change](json& j) {
      j = withMedia(j);
      j["media"]["fog"] = {{"type", "homogeneous"}, {"sigma_t", 2.0}, {"g", 0.3},
                           {"albedo_grid", {{"file", "albedo.vol"}, {"wrap_mode", "repeat"}}}};
      change(j["media"]["fog"]);
    };
  };
  {
    json j = base;
    fog([](json&) {})(j);
    const auto scene = loadSceneFromString(j.dump(), path);
    const Medium& m = *scene->media[0];
    ASSERT_TRUE(m.spatiallyVaryingAlbedo());
    EXPECT_FALSE(m.heterogeneous());
    EXPECT_FLOAT_EQ(m.sigmaT(500.0f), 2.0f);
  }
  expectError(fog([](json& m) { m["sigma_s"] = 1; }), "/media/fog/sigma_s", "with albedo_grid, give sigma_t");
  expectError(fog([](json& m) { m["sigma_a"] = 1; }), "/media/fog/sigma_a", "with albedo_grid, give sigma_t");
  expectError(fog([](json& m) { m.erase("sigma_t"); }), "/media/fog/albedo_grid", "needs sigma_t");
  expectError(fog([](json& m) { m["sigma_t"] = -1; }), "/media/fog/sigma_t", "negative");
  expectError(fog([](json& m) { m["albedo_grid"]["wrap_mode"] = "wrap"; }), "/media/fog/albedo_grid/wrap_mode",
              "'wrap' is not a wrap mode (clamp, repeat, mirror)");
  expectError(fog([](json& m) { m["albedo_grid"]["filter"] = "nearest"; }), "/media/fog/albedo_grid/filter",
              "unknown field");
  expectError(fog([](json& m) { m["albedo_grid"]["file"] = "missing.vol"; }), "/media/fog/albedo_grid/file",
              "missing.vol");
  expectError(fog([](json& m) { m["type"] = "heterogeneous"; }), "/media/fog/albedo_grid",
              "only a homogeneous medium takes an albedo grid");
  expectError(fog([](json& m) { m["fluorophores"] = json::parse(R"([{"sigma_f": 1, "emission": 1, "yield": 0.5}])"); }),
              "/media/fog/albedo_grid", "a medium with fluorophores takes no albedo grid");
  write("six.vol", test::volBytes({1, 1, 1}, 6, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}));
  expectError(fog([](json& m) { m["albedo_grid"]["file"] = "six.vol"; }), "/media/fog/albedo_grid/file",
              "an albedo grid has 3 channels (linear RGB) or 1 (grey), 'six.vol' has 6");
  write("bright.vol", test::volBytes({2, 1, 1}, 3, {0.9f, 0.5f, 0.1f, 0.2f, 1.5f, 1.0f}));
  expectError(fog([](json& m) { m["albedo_grid"]["file"] = "bright.vol"; }), "/media/fog/albedo_grid/file",
              "albedo values must lie in [0, 1]; channel 1 reaches 1.5");
}

TEST_F(SceneLoader, BadMediumReferences) {
  const auto shape = [](const char* key, const char* value) {
    return [key, value](json& j) {
      j = withMedia(j);
      j["shapes"][1].erase("interior");
      j["shapes"][1][key] = value;
    };
  };
  // Unknown names, wherever a medium is named.
  expectError(shape("interior", "smoke"), "/shapes/1/interior", "no medium named 'smoke' in /media");
  expectError(shape("exterior", "smoke"), "/shapes/1/exterior", "no medium named 'smoke' in /media");
  expectError(shape("medium", "smoke"), "/shapes/1/medium", "no medium named 'smoke' in /media");
  expectError([](json& j) { j = withMedia(j); j["camera"]["medium"] = "smoke"; }, "/camera/medium",
              "no medium named 'smoke' in /media");
  expectError([](json& j) { j["camera"]["medium"] = "fog"; }, "/camera/medium", "no medium named 'fog' in /media");
  expectError([](json& j) {
    j = withMedia(j);
    j["lights"] = json::parse(R"([{"type": "point", "position": [0, 1, 0], "intensity": 1, "medium": "smoke"}])");
  }, "/lights/0/medium", "no medium named 'smoke' in /media");
  expectError([](json& j) {
    j = withMedia(j);
    j["lights"] = json::parse(R"([{"type": "spot", "position": [0, 1, 0], "look_at": [0, 0, 0], "cone_angle": 30, "intensity": 1, "medium": "smoke"}])");
  }, "/lights/0/medium", "no medium named 'smoke' in /media");
  // Lights at infinity are outside every medium.
  expectError([](json& j) {
    j = withMedia(j);
    j["lights"] = json::parse(R"([{"type": "distant", "direction": [0, 0, 1], "irradiance": 1, "medium": "fog"}])");
  }, "/lights/0/medium", "unknown field");
  expectError([](json& j) { j = withMedia(j); j["shapes"][1]["interior"] = 3; }, "/shapes/1/interior",
              "expected a string, got number");
  // Both ways of naming media.
  expectError([](json& j) { j = withMedia(j); j["shapes"][1]["medium"] = "fog"; }, "/shapes/1/medium",
              "give either medium or interior/exterior");
}

TEST_F(SceneLoader, MediumBoundaries) {
  // A surface that does not enclose a volume cannot separate two media ...
  expectError([](json& j) { j = withMedia(j); j["shapes"][0]["interior"] = "fog"; }, "/shapes/0/interior",
              "shape 'shape0' is not closed");
  expectError([](json& j) { j = withMedia(j); j["shapes"][0]["exterior"] = "fog"; }, "/shapes/0/exterior",
              "is not closed");
  // A mesh file with openings loads with a note that counts them (a scanned model often has some):
  // a cube without one triangle of the face that looks away from the camera, filled with ink.
  write("open_cube.obj",
        "v -0.25 -0.25 1\nv 0.25 -0.25 1\nv 0.25 0.25 1\nv -0.25 0.25 1\n"
        "v -0.25 -0.25 1.5\nv 0.25 -0.25 1.5\nv 0.25 0.25 1.5\nv -0.25 0.25 1.5\n"
        "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n");
  {
    json j = withMedia(base);
    j["shapes"].push_back({{"type", "mesh"}, {"file", "open_cube.obj"}, {"interior", "ink"}, {"name", "cube"}});
    std::ostringstream notes;
    SceneLoadOptions options;
    options.notes = &notes;
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path, options));
    // The missing triangle's three edges.
    EXPECT_EQ(notes.str(), "kasha: note: " + path + ": /shapes/2/interior: shape 'cube' is not closed (3 edges are not "
                           "shared by exactly two triangles): a path changes medium where it crosses a triangle, and "
                           "keeps its medium through an opening\n");
  }
  // ... but may sit in one (the same medium on both sides).
  {
    json j = withMedia(base);
    j["shapes"][0]["medium"] = "fog";
    j["shapes"][1]["exterior"] = "fog";
    j["camera"]["medium"] = "fog";  // the camera's rays check that it is in fog too
    EXPECT_NO_THROW(loadSceneFromString(j.dump(), path));
  }
  // A boundary without a material is index-matched: it cannot emit.
  expectError([](json& j) {
    j = withMedia(j);
    j["shapes"][1]["emission"] = {{"radiance", 1}};
  }, "/shapes/1/emission", "a medium boundary without a material cannot emit");
  // Without media, a shape still needs a material.
  expectError([](json& j) { j = withMedia(j); j["shapes"][1].erase("interior"); }, "/shapes/1/material", "missing");
}

}  // namespace
}  // namespace kasha
