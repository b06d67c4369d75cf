// Mitsuba 3 XML import (mitsuba/): every supported plugin parses into the kasha scene it should,
// transforms move hand-computed points where they belong, and unsupported plugins, unknown
// properties and malformed XML are InputErrors naming the file, the line and the plugin.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <ImfRgbaFile.h>

#include "core/color.h"
#include "core/envmap_light.h"
#include "core/error.h"
#include "core/rgb_illuminant.h"
#include "core/rgb_spectrum.h"
#include "materials/material_json.h"
#include "scene/scene_loader.h"
#include "scene/mitsuba/mitsuba_scene.h"
#include "scene/mitsuba/xml_sensor.h"
#include "scene/mitsuba/xml_spectrum.h"
#include "scene/mitsuba/xml_transform.h"
#include "tests/texture_files.h"
#include "tests/volume_grid_files.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The message contains `part` (testing::HasSubstr without gmock).
::testing::AssertionResult contains(const std::string& message, const std::string& part) {
  if (message.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << part << "' is not in the message: " << message;
}

// A camera and one light: the smallest scene around the element under test.
const char* kSensor = R"(
  <sensor type="perspective">
    <float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>)";
const char* kLight = R"(<emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="1"/></emitter>)";
const char* kFloor = R"(<shape type="rectangle"><bsdf type="diffuse"/></shape>)";

class MitsubaImport : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::path(::testing::TempDir()) / ("kasha_mitsuba." + std::to_string(getpid())) / info->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir.parent_path());
  }
  std::string write(const std::string& rel, const std::string& text) const {
    const fs::path p = dir / rel;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  // A scene file holding kSensor and `body`.
  std::string scene(const std::string& body, const std::string& name = "scene.xml") const {
    return write(name, std::string("<scene version=\"3.0.0\">") + kSensor + body + "</scene>");
  }
  mitsuba::Translation translate(const std::string& body) const {
    const std::string path = scene(body);
    std::ifstream in(path);
    return mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), path);
  }
  std::unique_ptr<Scene> load(const std::string& body) const { return loadScene(scene(body)); }
  // A w×h OpenEXR image file of the pixels (row 0 at the top).
  void writeExr(const std::string& rel, int w, int h, const std::vector<Imf::Rgba>& px) const {
    Imf::RgbaOutputFile out((dir / rel).c_str(), w, h, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, size_t(w));
    out.writePixels(h);
  }
  // The message of the InputError loading the file `path` throws ("" and a test failure if none).
  static std::string fileError(const std::string& path) {
    try {
      loadScene(path);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded " << path << ", expected an InputError";
    return "";
  }
  // The same for a scene file holding kSensor and `body`.
  std::string error(const std::string& body) const { return fileError(scene(body)); }
  std::string file() const { return (dir / "scene.xml").string(); }

  fs::path dir;
};

void expectNear(const Vec3& a, const Vec3& b, float tol = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// ---- transforms against hand-computed points ------------------------------------------------

mitsuba::Mat4 transformOf(const std::string& ops) {
  mitsuba::XmlImport xml;
  const pugi::xml_document& doc = xml.parse("<scene><transform name=\"to_world\">" + ops + "</transform></scene>", "t.xml");
  return mitsuba::parseTransform(xml, doc.document_element().child("transform"));
}

TEST_F(MitsubaImport, TransformsComposeInOrderOfApplication) {
  // (1, 0, 0) → translate (1, 2, 3) → (2, 2, 3) → rotate 90° about +y: (x, y, z) → (z, y, −x) =
  // (3, 2, −2) → scale 2 → (6, 4, −4).
  const mitsuba::Mat4 m = transformOf(R"(<translate x="1" y="2" z="3"/><rotate y="1" angle="90"/><scale value="2"/>)");
  expectNear(mitsuba::transformPoint(m, Vec3(1, 0, 0)), Vec3(6, 4, -4));
  // Vectors ignore the translation: (0, 0, 1) → (1, 0, 0) → (2, 0, 0).
  expectNear(mitsuba::transformVector(m, Vec3(0, 0, 1)), Vec3(2, 0, 0));
}

TEST_F(MitsubaImport, MatrixIsRowMajorAndScaleTakesThreeValues) {
  const mitsuba::Mat4 m = transformOf(R"(<matrix value="1 0 0 5  0 2 0 6  0 0 1 7  0 0 0 1"/>)");
  expectNear(mitsuba::transformPoint(m, Vec3(1, 1, 1)), Vec3(6, 8, 8));
  const mitsuba::Mat4 s = transformOf(R"(<scale value="1, 2, 3"/><translate value="0 0 1"/>)");
  expectNear(mitsuba::transformPoint(s, Vec3(1, 1, 1)), Vec3(1, 2, 4));
}

TEST_F(MitsubaImport, LookAtFrame) {
  // Looking from (1, 2, 3) towards (1, 2, 4) with +y up: z → +z, y → +y, x = up × z = +x.
  const mitsuba::Mat4 m = transformOf(R"(<lookat origin="1, 2, 3" target="1, 2, 4" up="0, 1, 0"/>)");
  expectNear(mitsuba::transformPoint(m, Vec3(0, 0, 0)), Vec3(1, 2, 3));
  expectNear(mitsuba::transformVector(m, Vec3(1, 0, 0)), Vec3(1, 0, 0));
  expectNear(mitsuba::transformVector(m, Vec3(0, 0, 1)), Vec3(0, 0, 1));
  // Rotated: looking along −x, z maps to −x and "left" x = up × dir = (0, 1, 0) × (−1, 0, 0) = (0, 0, 1).
  const mitsuba::Mat4 r = transformOf(R"(<lookat origin="0, 0, 0" target="-3, 0, 0" up="0, 1, 0"/>)");
  expectNear(mitsuba::transformVector(r, Vec3(0, 0, 1)), Vec3(-1, 0, 0));
  expectNear(mitsuba::transformVector(r, Vec3(1, 0, 0)), Vec3(0, 0, 1));
}

TEST_F(MitsubaImport, RectangleCornersAndNormalFollowTheTransform) {
  // [−1, 1]² scaled by (2, 3), rotated −90° about x (z → +y) and moved up by 5: corners
  // (±2, 5, ∓3)... and the normal +y.
  const auto s = load(std::string(kLight) + R"(<shape type="rectangle"><transform name="to_world">
      <scale x="2" y="3"/><rotate x="1" angle="-90"/><translate y="5"/></transform></shape>)");
  const Shape& r = s->shapes.at(0);
  ASSERT_EQ(r.positions.size(), 4u);
  expectNear(r.positions[0], Vec3(-2, 5, 3));
  expectNear(r.positions[2], Vec3(2, 5, -3));
  expectNear(r.triangleNormal(0), Vec3(0, 1, 0));
  EXPECT_NEAR(r.area, 24.0f, 1e-3f);
  // flip_normals turns it over.
  const auto f = load(std::string(kLight) + R"(<shape type="rectangle"><boolean name="flip_normals" value="true"/></shape>)");
  expectNear(f->shapes.at(0).triangleNormal(0), Vec3(0, 0, -1));
}

TEST_F(MitsubaImport, SphereAndObjTransforms) {
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto s = load(std::string(kLight) + R"(
    <shape type="sphere"><float name="radius" value="0.5"/>
      <transform name="to_world"><scale value="2"/><translate x="1" y="2" z="3"/></transform></shape>
    <shape type="obj"><string name="filename" value="tri.obj"/>
      <transform name="to_world"><rotate z="1" angle="90"/><translate x="10"/></transform></shape>)");
  EXPECT_EQ(s->shapes.at(0).kind, Shape::Kind::Sphere);
  expectNear(s->shapes[0].center, Vec3(1, 2, 3));
  EXPECT_NEAR(s->shapes[0].radius, 1.0f, 1e-5f);
  // Rotating 90° about z: (1, 0, 0) → (0, 1, 0), (0, 1, 0) → (−1, 0, 0); then x + 10.
  const Shape& t = s->shapes.at(1);
  expectNear(t.positions[1], Vec3(10, 1, 0));
  expectNear(t.positions[2], Vec3(9, 0, 0));
  EXPECT_NE(error(std::string(kLight) + R"(<shape type="sphere"><transform name="to_world"><scale x="2"/></transform></shape>)")
                .find("uniformly"),
            std::string::npos);
}

// ---- one parse test per plugin ---------------------------------------------------------------

TEST_F(MitsubaImport, PerspectiveSensorFilmSamplerAndIntegrator) {
  const auto t = translate(R"(
    <integrator type="path"><integer name="max_depth" value="6"/><integer name="rr_depth" value="3"/></integrator>)" +
                           std::string(kLight) + kFloor);
  EXPECT_EQ(t.scene["render"]["max_depth"], 5);  // Mitsuba's path depth counts the emitter vertex
  EXPECT_EQ(t.scene["render"]["rr_depth"], 2);
  const json& cam = t.scene["camera"];
  EXPECT_EQ(cam["resolution"], json({8, 8}));
  EXPECT_NEAR(cam["fov"].get<float>(), 45.0f, 1e-4f);  // square film: x and y angles agree
  EXPECT_NEAR(cam["position"][2].get<float>(), -5.0f, 1e-6f);
  // fov along x of a 200 × 100 film: tan(fov_y/2) = tan(45°)·100/200 → fov_y = 2·atan(0.5) = 53.130°.
  EXPECT_NEAR(*mitsuba::verticalFov(90, "x", 200, 100), 53.1301f, 1e-3f);
  EXPECT_NEAR(*mitsuba::verticalFov(90, "y", 200, 100), 90.0f, 1e-4f);
  EXPECT_NEAR(*mitsuba::verticalFov(90, "smaller", 200, 100), 90.0f, 1e-4f);
  // diagonal: tan(fov_y/2) = tan(45°)·100/√(200² + 100²) → 2·atan(1/√5) = 48.190°.
  EXPECT_NEAR(*mitsuba::verticalFov(90, "diagonal", 200, 100), 48.1897f, 1e-3f);
  const std::string path = write("sampler.xml", std::string("<scene version=\"3.0.0\">") + R"(
  <sensor type="perspective"><float name="fov" value="30"/><string name="fov_axis" value="x"/>
    <sampler type="independent"><integer name="sample_count" value="7"/></sampler>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/></film>
  </sensor>)" + kLight + kFloor + "</scene>");
  const auto s = loadScene(path);
  EXPECT_EQ(s->render.spp, 7);
  EXPECT_EQ(s->camera.width(), 40);
  EXPECT_NEAR(s->camera.fovYDegrees(), 2.0f * std::atan(std::tan(glm::radians(15.0f)) * 0.5f) * 180.0f / kPi, 1e-3f);
}

// thinlens: a perspective camera with Mitsuba's aperture_radius and focus_distance (default: the
// far clip plane, 10⁴). orthographic: the film spans [−1, 1] × [−1/aspect, 1/aspect] of the camera's
// plane, scaled by to_world (Mitsuba 3's orthographic_projection), so a scale of 2 on a 960 × 720
// film gives 4 × 3 world units.
TEST_F(MitsubaImport, ThinLensAndOrthographicSensors) {
  const auto sensor = [&](const std::string& type, const std::string& properties) {
    return write("sensor.xml", std::string("<scene version=\"3.0.0\">") + "<sensor type=\"" + type + "\">" + properties + R"(
    <film type="hdrfilm"><integer name="width" value="960"/><integer name="height" value="720"/></film>
  </sensor>)" + kLight + kFloor + "</scene>");
  };
  auto s = loadScene(sensor("thinlens", R"(<float name="fov" value="40"/><string name="fov_axis" value="y"/>
    <float name="aperture_radius" value="0.2"/><float name="focus_distance" value="5.9"/>)"));
  EXPECT_NEAR(s->camera.fovYDegrees(), 40.0f, 1e-4f);
  EXPECT_FLOAT_EQ(s->camera.apertureRadius(), 0.2f);
  EXPECT_FLOAT_EQ(s->camera.focusDistance(), 5.9f);
  EXPECT_FLOAT_EQ(loadScene(sensor("thinlens", R"(<float name="aperture_radius" value="0.2"/>)"))->camera.focusDistance(), 1e4f);
  EXPECT_TRUE(contains(fileError(sensor("thinlens", "")), "aperture_radius"));
  s = loadScene(sensor("orthographic", R"(<transform name="to_world"><scale x="2" y="2"/>
    <lookat origin="0, 1, -5" target="0, 1, 0" up="0, 1, 0"/></transform>)"));
  ASSERT_TRUE(s->camera.parallelRays());
  EXPECT_NEAR(s->camera.filmExtent().x, 4.0f, 1e-5f);
  EXPECT_NEAR(s->camera.filmExtent().y, 3.0f, 1e-5f);
  EXPECT_NEAR(glm::length(s->camera.position() - Vec3(0, 1, -5)), 0.0f, 1e-5f);
  EXPECT_NEAR(s->camera.forward().z, 1.0f, 1e-6f);
  EXPECT_TRUE(contains(fileError(sensor("orthographic", R"(<float name="fov" value="40"/>)")), "unsupported property 'fov'"));
  EXPECT_TRUE(contains(fileError(sensor("fisheye", "")), "unsupported sensor plugin (perspective, thinlens, orthographic)"));
}

// <rfilter> inside <film>: box, tent and gaussian as kasha's filters with Mitsuba's parameters; none
// is Mitsuba's default Gaussian (stddev 0.5); the filters kasha lacks become the Gaussian of the
// same standard deviation or the box, with one note naming it; anything else is an error.
TEST_F(MitsubaImport, ReconstructionFilters) {
  const auto film = [&](const std::string& rfilter) {
    return write("film.xml", std::string("<scene version=\"3.0.0\">") + R"(
  <sensor type="perspective"><float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>)" + rfilter + R"(</film>
  </sensor>)" + kLight + kFloor + "</scene>");
  };
  const auto translated = [&](const std::string& rfilter) {
    const std::string path = film(rfilter);
    std::ifstream in(path);
    return mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), path);
  };
  const auto filterOf = [&](const std::string& rfilter) { return loadScene(film(rfilter))->pixelFilter; };
  // The notes about the filter (the floor's one-sided BSDF has its own).
  const auto filterNotes = [](const mitsuba::Translation& t) {
    std::vector<std::string> out;
    for (const std::string& n : t.notes)
      if (n.find("rfilter '") != std::string::npos) out.push_back(n);
    return out;
  };
  const PixelFilter none = filterOf("");
  EXPECT_EQ(none.type(), PixelFilterType::Gaussian);
  EXPECT_EQ(none.stddev(), 0.5f);
  EXPECT_EQ(filterOf(R"(<rfilter type="box"/>)").type(), PixelFilterType::Box);
  EXPECT_EQ(filterOf(R"(<rfilter type="tent"/>)").radius(), 1.0f);
  EXPECT_EQ(filterOf(R"(<rfilter type="tent"><float name="radius" value="1.25"/></rfilter>)").radius(), 1.25f);
  EXPECT_EQ(filterOf(R"(<rfilter type="gaussian"><float name="stddev" value="0.25"/></rfilter>)").radius(), 1.0f);
  for (const std::string& rfilter : {std::string(R"(<rfilter type="box"/>)"), std::string(R"(<rfilter type="gaussian"/>)")})
    EXPECT_TRUE(filterNotes(translated(rfilter)).empty()) << rfilter;
  // Mitchell–Netravali with B = C = 1/3: ∫x²k = 1/9 (its cubics integrated by hand).
  const mitsuba::Translation mitchell = translated(R"(<rfilter type="mitchell"/>)");
  EXPECT_NEAR(mitchell.scene["camera"]["filter"]["stddev"].get<float>(), 1.0f / 3.0f, 1e-6f);
  ASSERT_EQ(filterNotes(mitchell).size(), 1u);
  EXPECT_TRUE(contains(filterNotes(mitchell)[0], "rfilter 'mitchell': rendered with kasha's gaussian filter (stddev 0.333333), the closest it has"));
  for (const char* sharp : {"catmullrom", "lanczos"}) {
    const mitsuba::Translation t = translated(std::string("<rfilter type=\"") + sharp + "\"/>");
    EXPECT_EQ(t.scene["camera"]["filter"], "box") << sharp;
    ASSERT_EQ(filterNotes(t).size(), 1u) << sharp;
    EXPECT_TRUE(contains(filterNotes(t)[0], std::string("rfilter '") + sharp + "': rendered with kasha's box filter"));
  }
  EXPECT_EQ(translated(R"(<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>)").scene["camera"]["filter"], "box");
  EXPECT_TRUE(contains(fileError(film(R"(<rfilter type="sinc"/>)")), "rfilter 'sinc': unsupported rfilter plugin"));
  EXPECT_TRUE(contains(fileError(film(R"(<rfilter type="tent"><float name="radius" value="-1"/></rfilter>)")),
                       "/camera/filter/radius: must be in [1/64, 16] pixels"));
  EXPECT_TRUE(contains(fileError(film(R"(<rfilter type="box"/><rfilter type="tent"/>)")), "a second <rfilter>"));
  EXPECT_TRUE(contains(fileError(film(R"(<rfilter type="gaussian"><float name="radius" value="2"/></rfilter>)")),
                       "unsupported property 'radius'"));
}

// Without fov, Mitsuba's perspective camera has a focal length (default 50 mm) on a 36 × 24 mm film,
// whose angle is the diagonal's: 2·atan(√(36² + 24²)/(2·f)); on a 300 × 200 film (the 36 × 24
// aspect) the vertical angle is then 2·atan(24/(2·f)) exactly. focus_distance has no effect there.
TEST_F(MitsubaImport, PerspectiveFocalLengthAndFocusDistance) {
  const auto sensor = [&](const std::string& properties) {
    return write("focal.xml", std::string("<scene version=\"3.0.0\">") + R"(
  <sensor type="perspective">)" + properties + R"(
    <film type="hdrfilm"><integer name="width" value="300"/><integer name="height" value="200"/></film>
  </sensor>)" + kLight + kFloor + "</scene>");
  };
  const auto degrees = [](double radians) { return float(radians * 180.0 / 3.14159265358979323846); };
  EXPECT_NEAR(loadScene(sensor(""))->camera.fovYDegrees(), degrees(2.0 * std::atan(12.0 / 50.0)), 1e-3f);
  EXPECT_NEAR(loadScene(sensor(R"(<string name="focal_length" value="28mm"/><float name="focus_distance" value="3"/>)"))
                  ->camera.fovYDegrees(),
              degrees(2.0 * std::atan(12.0 / 28.0)), 1e-3f);
  EXPECT_TRUE(contains(fileError(sensor(R"(<string name="focal_length" value="wide"/>)")),
                       "focal_length must be a positive length in mm (\"50mm\"), got 'wide'"));
  EXPECT_TRUE(contains(fileError(sensor(R"(<float name="fov" value="40"/><string name="focal_length" value="28mm"/>)")),
                       "give fov or focal_length, not both"));
}

// <path value="dir"/> (Mitsuba's documentation scenes: <path value="../../common"/>): files are
// looked up in it, relative to the scene file, before the scene's own directory; includes too.
TEST_F(MitsubaImport, SearchPathsFindFilesBeforeTheScenesDirectory) {
  fs::create_directories(dir / "common" / "meshes");
  fs::create_directories(dir / "scenes");
  write("common/meshes/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write("common/light.xml", std::string("<scene version=\"3.0.0\">") + kLight + "</scene>");
  const std::string body = std::string(kSensor) + R"(<path value="../common"/><include filename="light.xml"/>
    <shape type="obj"><string name="filename" value="meshes/quad.obj"/><bsdf type="diffuse"/></shape>)";
  const std::string path = write("scenes/paths.xml", "<scene version=\"3.0.0\">" + body + "</scene>");
  const auto s = loadScene(path);
  ASSERT_EQ(s->shapes.size(), 1u);
  EXPECT_EQ(s->lights.size(), 1u);
  // A file in neither is reported where the scene's own directory would hold it.
  const std::string missing = write("scenes/missing.xml", std::string("<scene version=\"3.0.0\">") + kSensor +
                                                              R"(<path value="../common"/>
    <shape type="obj"><string name="filename" value="meshes/none.obj"/><bsdf type="diffuse"/></shape>)" + kLight + "</scene>");
  EXPECT_TRUE(contains(fileError(missing), (dir / "scenes" / "meshes" / "none.obj").string()));
  const std::string notDir = write("scenes/notdir.xml", std::string("<scene version=\"3.0.0\">") + kSensor +
                                                            R"(<path value="../nowhere"/>)" + kLight + kFloor + "</scene>");
  EXPECT_TRUE(contains(fileError(notDir), "path '../nowhere' is not a directory"));
}

TEST_F(MitsubaImport, AnIncludedFilesPathFallsBackToTheTopLevelScenesDirectory) {
  // As in Mitsuba's documentation scenes: a/b/include/x.xml says <path value="../../common"/>, which
  // is not a directory from there (a/common) but is from the including scene's a/b (common).
  fs::create_directories(dir / "common" / "meshes");
  fs::create_directories(dir / "a" / "b" / "include");
  write("common/meshes/quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write("a/b/include/x.xml", R"(<scene version="3.0.0"><path value="../../common"/>
    <shape type="obj"><string name="filename" value="meshes/quad.obj"/><bsdf type="diffuse"/></shape></scene>)");
  const std::string path = write("a/b/scene.xml", std::string("<scene version=\"3.0.0\">") + kSensor + kLight +
                                                      R"(<include filename="include/x.xml"/></scene>)");
  const auto s = loadScene(path);
  ASSERT_EQ(s->shapes.size(), 1u);
  EXPECT_NEAR(s->shapes[0].area, 1.0f, 1e-5f);
}

TEST_F(MitsubaImport, TheIntegratorElementChoosesKashasIntegrator) {
  const auto render = [&](const std::string& integrator) { return translate(integrator + kLight + kFloor).scene["render"]; };
  const auto notes = [&](const std::string& integrator) { return translate(integrator + kLight + kFloor).notes; };
  EXPECT_EQ(render(R"(<integrator type="path"><integer name="max_depth" value="4"/></integrator>)"),
            json({{"integrator", "pt"}, {"max_depth", 3}, {"rr_depth", 4}}));
  // direct: emitters seen directly and lit once, whatever its sample counts.
  const std::string direct = R"(<integrator type="direct"><integer name="emitter_samples" value="0"/></integrator>)";
  EXPECT_EQ(render(direct), json({{"integrator", "pt"}, {"max_depth", 1}}));
  bool noted = false;
  for (const std::string& n : notes(direct)) noted |= contains(n, "integrator 'direct': kasha's pt with max_depth 1");
  EXPECT_TRUE(noted);
  EXPECT_EQ(render(R"(<integrator type="ptracer"><integer name="samples_per_pass" value="64"/></integrator>)")["integrator"], "lt");
  EXPECT_EQ(render(R"(<integrator type="volpath"/>)")["integrator"], "pt");
  EXPECT_EQ(render(R"(<integrator type="bdpt"/>)")["integrator"], "bdpt");
  for (const char* output : {"aov", "moment", "depth"})
    EXPECT_TRUE(contains(error(std::string("<integrator type=\"") + output + "\"/>"), "writes other quantities than radiance"));
  // The loaded scene asks for it; the front ends' --integrator still wins (tests/cli).
  EXPECT_EQ(load(std::string(R"(<integrator type="ptracer"/>)") + kLight + kFloor)->render.integrator, "lt");
}

TEST_F(MitsubaImport, RefsNameAreaEmittersAndSamplersDeclaredAtTheTop) {
  // The shape names an area emitter declared after it; the sensor a sampler declared before it.
  const std::string body = R"(
    <sampler type="independent" id="s"><integer name="sample_count" value="9"/></sampler>
    <sensor type="perspective"><float name="fov" value="45"/><ref id="s"/></sensor>
    <bsdf type="diffuse" id="white"/>
    <shape type="rectangle"><ref id="white"/><ref id="glow"/></shape>
    <emitter type="area" id="glow"><spectrum name="radiance" value="2"/></emitter>)";
  const std::string path = write("declared.xml", "<scene version=\"3.0.0\">" + body + "</scene>");
  std::ifstream in(path);
  const mitsuba::Translation t = mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), path);
  EXPECT_EQ(t.scene["render"]["spp"], 9);
  ASSERT_EQ(t.scene["shapes"].size(), 1u);
  EXPECT_EQ(t.scene["shapes"][0]["material"], "white");
  // A number on an emitter is Mitsuba's D65 times it (its spectral variants), tabulated every nm.
  const json& glow = t.scene["shapes"][0]["emission"]["radiance"];
  ASSERT_EQ(glow["type"], "tabulated");
  EXPECT_EQ(glow["wavelengths"][190], 550.0);
  EXPECT_NEAR(glow["values"][190].get<double>(), 2.0 * unitD65(550.0f), 2e-4);
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><ref id="s"/></shape>)" +
                             R"(<sampler type="independent" id="s"/>)"),
                       "no <bsdf id=\"s\"> or area <emitter id=\"s\"> before this reference"));
  EXPECT_TRUE(contains(error(std::string(kLight) + kFloor + R"(<emitter type="area"/>)"),
                       "a top-level <emitter> of this kind needs an id to be referred to"));
}

TEST_F(MitsubaImport, ShapesObjPlyRectangleCubeSphereDisk) {
  write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write("tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n2 0 0\n0 2 0\n3 0 1 2\n");
  const auto s = load(std::string(kLight) + R"(
    <shape type="obj"><string name="filename" value="quad.obj"/></shape>
    <shape type="ply"><string name="filename" value="tri.ply"/></shape>
    <shape type="rectangle"/>
    <shape type="cube"/>
    <shape type="sphere"/>
    <shape type="disk"/>)");
  ASSERT_EQ(s->shapes.size(), 1u + 1u + 1u + 6u + 1u + 1u);
  EXPECT_NEAR(s->shapes[0].area, 1.0f, 1e-5f);  // the OBJ quad
  EXPECT_NEAR(s->shapes[1].area, 2.0f, 1e-5f);  // the PLY triangle
  EXPECT_NEAR(s->shapes[2].area, 4.0f, 1e-5f);  // [−1, 1]²
  float cube = 0.0f;
  for (int i = 3; i < 9; ++i) {
    cube += s->shapes[size_t(i)].area;
    // Outward normals: the face centre and its normal point the same way.
    const Shape& f = s->shapes[size_t(i)];
    const Vec3 c = (f.positions[0] + f.positions[2]) * 0.5f;
    EXPECT_NEAR(glm::dot(c, f.triangleNormal(0)), 1.0f, 1e-5f) << "cube face " << i - 3;
  }
  EXPECT_NEAR(cube, 24.0f, 1e-4f);
  EXPECT_EQ(s->shapes[9].kind, Shape::Kind::Sphere);
  EXPECT_NEAR(s->shapes[9].radius, 1.0f, 0.0f);
  // The 256-gon inscribed in the unit circle: 128·sin(2π/256).
  EXPECT_NEAR(s->shapes[10].area, 128.0 * std::sin(2.0 * M_PI / 256.0), 1e-4);
  expectNear(s->shapes[10].triangleNormal(0), Vec3(0, 0, 1));
}

TEST_F(MitsubaImport, AreaEmitterInsideAShape) {
  const auto s = load(R"(<shape type="rectangle"><emitter type="area"><spectrum name="radiance" value="2"/></emitter></shape>)");
  ASSERT_TRUE(s->shapes.at(0).emission.has_value());
  EXPECT_NEAR(s->shapes[0].emission->eval(550.0f, Vec3(0, 0, 1), Vec3(0, 0, 1)), 2.0f * unitD65(550.0f), 2e-4f);
  EXPECT_FLOAT_EQ(s->shapes[0].emission->eval(550.0f, Vec3(0, 0, 1), Vec3(0, 0, -1)), 0.0f);  // one-sided
  EXPECT_EQ(s->lights.size(), 1u);
}

TEST_F(MitsubaImport, Emitters) {
  const auto s = load(std::string(kFloor) + R"(
    <emitter type="point"><spectrum name="intensity" value="3"/>
      <transform name="to_world"><translate x="1" y="2" z="3"/></transform></emitter>
    <emitter type="spot"><float name="cutoff_angle" value="30"/><spectrum name="intensity" value="1"/>
      <transform name="to_world"><lookat origin="0, 4, 0" target="0, 0, 0" up="0, 0, 1"/></transform></emitter>
    <emitter type="directional"><vector name="direction" x="0" y="-1" z="0"/><spectrum name="irradiance" value="2"/></emitter>
    <emitter type="constant"><spectrum name="radiance" value="0.5"/></emitter>)");
  ASSERT_EQ(s->lights.size(), 4u);
  const auto* point = dynamic_cast<const PointLight*>(s->lights[0].get());
  ASSERT_NE(point, nullptr);
  expectNear(point->position(), Vec3(1, 2, 3));
  // Mitsuba's D65 times the number (the grey's sigmoid fit is flat within 1e-4)
  EXPECT_NEAR(point->intensity(500.0f), 3.0f * unitD65(500.0f), 3e-4f);
  const auto* spot = dynamic_cast<const SpotLight*>(s->lights[1].get());
  ASSERT_NE(spot, nullptr);
  EXPECT_GT(spot->emittedTowards(500.0f, Vec3(0), Vec3(0, -1, 0)), 0.9f);   // along the axis (down)
  EXPECT_EQ(spot->emittedTowards(500.0f, Vec3(0), glm::normalize(Vec3(1, -1, 0))), 0.0f);  // 45° > 30°
  const auto* distant = dynamic_cast<const DistantLight*>(s->lights[2].get());
  ASSERT_NE(distant, nullptr);
  expectNear(distant->direction(), Vec3(0, -1, 0));
  ASSERT_NE(s->environment(), nullptr);
  EXPECT_NEAR(s->environment()->Le(500.0f, Vec3(0, 1, 0)), 0.5f * unitD65(500.0f), 5e-5f);
}

// A spot's <texture>: the bitmap file, its encoding and the look-at's up go to kasha's spot, which
// casts it as Mitsuba's src/emitters/spot.cpp does: u = ½ + ½·x/(z·tan θc), v likewise in y, in
// the look-at frame (x = up × forward, y up, z forward), row 0 at v = 0.
TEST_F(MitsubaImport, TexturedSpot) {
  Imf::Rgba black(0.0f, 0.0f, 0.0f, 1.0f);
  writeExr("corner.exr", 2, 2, {Imf::Rgba(1.0f, 1.0f, 1.0f, 1.0f), black, black, black});
  const std::string spot = R"(<emitter type="spot"><float name="cutoff_angle" value="30"/><spectrum name="intensity" value="1"/>
      <texture name="texture" type="bitmap"><string name="filename" value="corner.exr"/></texture>
      <transform name="to_world"><lookat origin="0, 4, 0" target="0, 0, 0" up="0, 0, 1"/></transform></emitter>)";
  const auto t = translate(std::string(kFloor) + spot);
  const json& light = t.scene["lights"][0];
  EXPECT_EQ(light["texture"], (dir / "corner.exr").string());
  EXPECT_EQ(light["encoding"], "srgb");
  EXPECT_EQ(light["up"], json({0.0, 0.0, 1.0}));
  const auto s = load(std::string(kFloor) + spot);
  const auto* l = dynamic_cast<const SpotLight*>(s->lights.at(0).get());
  ASSERT_NE(l, nullptr);
  // Forward −y, up +z, so x = up × forward = +x: world (x, −1, z) has u = ½ + ½·x/tan 30°, v = ½ + ½·z/tan 30°.
  const float tan30 = std::tan(30.0f * kPi / 180.0f);
  const std::optional<Vec2> uv = l->directionToUv(glm::normalize(Vec3(0.2f, -1.0f, -0.1f)));
  ASSERT_TRUE(uv.has_value());
  EXPECT_NEAR(uv->x, 0.5f + 0.1f / tan30, 1e-5f);
  EXPECT_NEAR(uv->y, 0.5f - 0.05f / tan30, 1e-5f);
  // The top-left texel (u, v < ½) lights −x, −z alone.
  EXPECT_GT(l->emittedTowards(550.0f, Vec3(0.0f), glm::normalize(Vec3(-0.1f, -1.0f, -0.1f))), 0.0f);
  for (const Vec3 w : {Vec3(0.1f, -1.0f, -0.1f), Vec3(-0.1f, -1.0f, 0.1f), Vec3(0.1f, -1.0f, 0.1f)})
    EXPECT_EQ(l->emittedTowards(550.0f, Vec3(0.0f), glm::normalize(w)), 0.0f);
  // A texture other than a bitmap is refused.
  EXPECT_TRUE(contains(error(std::string(kFloor) + R"(<emitter type="spot"><rgb name="texture" value="1, 0, 0"/></emitter>)"),
                       "emitter 'spot': a spot's texture must be a bitmap <texture>"));
  EXPECT_TRUE(contains(error(std::string(kFloor) + R"(<emitter type="spot"><texture name="texture" type="checkerboard"/></emitter>)"),
                       "texture 'checkerboard': the spot emitter's 'texture' must be a bitmap texture"));
}

TEST_F(MitsubaImport, Bsdfs) {
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="diffuse" id="d"><spectrum name="reflectance" value="0.25"/></bsdf>
    <bsdf type="conductor" id="c"><spectrum name="eta" value="1.5"/><spectrum name="k" value="0"/></bsdf>
    <bsdf type="conductor" id="none"/>
    <bsdf type="roughconductor" id="rc"><float name="alpha" value="0.3"/><string name="distribution" value="ggx"/></bsdf>
    <bsdf type="dielectric" id="g"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1.0"/></bsdf>
    <bsdf type="dielectric" id="w"><string name="int_ior" value="water"/><string name="ext_ior" value="vacuum"/></bsdf>
    <bsdf type="roughdielectric" id="rg"><float name="alpha" value="0.2"/><float name="int_ior" value="1.5"/><float name="ext_ior" value="1.25"/></bsdf>
    <bsdf type="thindielectric" id="tg"><float name="int_ior" value="1.6"/><float name="ext_ior" value="1.0"/></bsdf>
    <bsdf type="plastic" id="p"><spectrum name="diffuse_reflectance" value="0.4"/></bsdf>
    <bsdf type="roughplastic" id="rp"><float name="alpha" value="0.05"/><string name="distribution" value="ggx"/>
      <boolean name="nonlinear" value="true"/></bsdf>
    <bsdf type="twosided" id="two"><bsdf type="diffuse"/></bsdf>
    <bsdf type="jung_fluorescent" id="j">
      <spectrum name="absorption" value="400:0.8, 500:0"/><spectrum name="emission" value="500:0, 550:1, 600:0"/>
      <spectrum name="reflectance" value="0.5"/><float name="c" value="0.5"/><float name="Q" value="0.9"/></bsdf>
    <shape type="rectangle"><ref id="j"/></shape>)");
  const json& m = t.scene["materials"];
  EXPECT_EQ(m["d"], json({{"type", "lambertian"}, {"reflectance", 0.25}, {"one_sided", true}}));
  EXPECT_EQ(m["c"], json({{"type", "mirror"}, {"reflectance", 1.0}, {"eta", 1.5}, {"k", 0.0}, {"one_sided", true}}));
  EXPECT_EQ(m["none"]["reflectance"], 1.0);
  EXPECT_EQ(m["rc"]["type"], "rough_conductor");
  EXPECT_EQ(m["rc"]["alpha"], 0.3f);
  EXPECT_EQ(m["g"], json({{"type", "dielectric"}, {"ior", 1.5f}}));
  EXPECT_NEAR(m["w"]["ior"].get<float>(), 1.333f, 1e-6f);
  EXPECT_EQ(m["rg"]["type"], "rough_dielectric");
  EXPECT_NEAR(m["rg"]["ior"].get<float>(), 1.2f, 1e-6f);  // relative index int/ext
  EXPECT_EQ(m["tg"], json({{"type", "thin_dielectric"}, {"ior", 1.6f}}));
  EXPECT_EQ(m["p"]["type"], "coated_fluorescent");
  EXPECT_EQ(m["p"]["c"], 0.0);
  EXPECT_EQ(m["p"]["reflectance"], 0.4f);
  EXPECT_NEAR(m["p"]["coat_ior"].get<float>(), 1.49f / 1.000277f, 1e-6f);
  EXPECT_EQ(m["rp"]["coat_alpha"], 0.05f);
  EXPECT_EQ(m["two"]["type"], "lambertian");
  EXPECT_EQ(m["two"]["reflectance"], 0.5);  // Mitsuba's default
  EXPECT_EQ(m["j"]["type"], "jung_fluorescent");
  EXPECT_EQ(m["j"]["c"], 0.5f);
  // Every approximation is reported: plastic, Beckmann, one-sided BSDFs.
  int plastic = 0;
  for (const std::string& n : t.notes) plastic += n.find("coated_fluorescent") != std::string::npos;
  EXPECT_EQ(plastic, 2);
  // nonlinear acts on light the approximation leaves out: accepted, and said.
  int nonlinear = 0;
  for (const std::string& n : t.notes) nonlinear += n.find("nonlinear = true acts on the light the coat reflects") != std::string::npos;
  EXPECT_EQ(nonlinear, 1);
  // The whole scene loads (the JSON loader accepts every translation).
  EXPECT_NO_THROW(load(std::string(kLight) + R"(
    <shape type="rectangle"><bsdf type="plastic"/></shape>
    <shape type="sphere"><bsdf type="roughdielectric"/></shape>
    <shape type="cube"><bsdf type="roughconductor"/></shape>)"));
}

TEST_F(MitsubaImport, Spectra) {
  write("s.spd", "# wavelength value\n400 0.1\n500 0.5\n\n600 0.2\n");
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="diffuse" id="a"><spectrum name="reflectance" value="400:0.1, 700:0.9"/></bsdf>
    <bsdf type="diffuse" id="b"><spectrum name="reflectance" filename="s.spd"/></bsdf>
    <bsdf type="diffuse" id="c"><float name="reflectance" value="0.3"/></bsdf>
    <bsdf type="diffuse" id="d"><spectrum name="reflectance" type="irregular">
      <string name="wavelengths" value="400, 500"/><string name="values" value="0.2, 0.4"/></spectrum></bsdf>
    <shape type="rectangle"><emitter type="area"><blackbody name="radiance" temperature="5000K"/></emitter></shape>)");
  const json& m = t.scene["materials"];
  EXPECT_EQ(m["a"]["reflectance"]["wavelengths"], json({400.0f, 700.0f}));
  EXPECT_EQ(m["b"]["reflectance"]["values"], json({0.1f, 0.5f, 0.2f}));
  EXPECT_EQ(m["c"]["reflectance"], 0.3f);
  EXPECT_EQ(m["d"]["reflectance"]["values"], json({0.2f, 0.4f}));
  // Blackbody: kasha's peak-normalised shape scaled to Planck's radiance at the peak (W·m⁻²·sr⁻¹·nm⁻¹):
  // 5000 K peaks at 2.8978e6/5000 = 579.6 nm. At 580 nm: hc/(λkT) = 0.0143878/(580e-9·5000) = 4.9613,
  // 2hc²/λ⁵ = 1.19104e-16/6.56357e-32 = 1.81463e15, / (e^4.9613 − 1 = 141.77) = 1.2800e13 per m = 1.2800e4 per nm.
  const json& bb = t.scene["shapes"][0]["emission"]["radiance"];
  EXPECT_EQ(bb["kelvin"], 5000.0f);
  EXPECT_NEAR(bb["scale"].get<double>(), 1.2800e4, 0.001e4);
  EXPECT_NEAR(mitsuba::planckRadiance(580.0, 5000.0), 1.2800e4, 0.001e4);
}

TEST_F(MitsubaImport, RgbColours) {
  const auto t = translate(R"(
    <bsdf type="diffuse" id="a"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>
    <shape type="rectangle"><ref id="a"/><emitter type="area"><rgb name="radiance" value="3, 2, 1"/></emitter></shape>)");
  // A reflectance stays kasha's rgb spectrum (Jakob–Hanika, upsampled by the JSON loader).
  EXPECT_EQ(t.scene["materials"]["a"]["reflectance"], json({{"type", "rgb"}, {"value", {0.2f, 0.5f, 0.8f}}}));
  // An emission is tabulated; on kasha's film (XYZ by the CIE observer) it has the colour given.
  const json& e = t.scene["shapes"][0]["emission"]["radiance"];
  Vec3 xyz(0.0f);
  for (size_t i = 0; i + 1 < e["wavelengths"].size(); ++i) {
    const float a = e["wavelengths"][i], b = e["wavelengths"][i + 1];
    const float mid = 0.5f * (a + b), v = 0.5f * (e["values"][i].get<float>() + e["values"][i + 1].get<float>());
    xyz += Observer::cie1931().weight(mid) * v * (b - a);
  }
  const Vec3 rgb = xyzToLinearSrgb(xyz);
  EXPECT_NEAR(rgb.x, 3.0f, 0.03f);
  EXPECT_NEAR(rgb.y, 2.0f, 0.02f);
  EXPECT_NEAR(rgb.z, 1.0f, 0.01f);
  EXPECT_NO_THROW(load(R"(<shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>
      <emitter type="area"><rgb name="radiance" value="3, 2, 1"/></emitter></shape>)"));
}

TEST_F(MitsubaImport, EnvmapEmitter) {
  std::vector<Imf::Rgba> px(8, Imf::Rgba(1.0f, 0.5f, 0.25f, 1.0f));
  {
    Imf::RgbaOutputFile out((dir / "sky.exr").c_str(), 4, 2, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, 4);
    out.writePixels(2);
  }
  const auto s = load(std::string(kFloor) + R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
      <float name="scale" value="2"/><transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>)");
  const auto* env = dynamic_cast<const EnvMapLight*>(s->environment());
  ASSERT_NE(env, nullptr);
  // Rotating 90° about +y takes local +x (u = 1/4) to world −z.
  EXPECT_NEAR(env->directionToUv(Vec3(0, 0, -1)).x, 0.25f, 1e-6f);
  EXPECT_FLOAT_EQ(env->Le(550.0f, Vec3(0, 1, 0)), 2.0f * rgbIlluminant(Vec3(1.0f, 0.5f, 0.25f))(550.0f));
}

// <texture type="bitmap"> on diffuse and plastic reflectances: kasha's RGB reflectance texture
// (reflectance 1 times the image's Jakob–Hanika colours) with Mitsuba's filter and wrap mode.
TEST_F(MitsubaImport, BitmapTextures) {
  std::vector<Imf::Rgba> px = {Imf::Rgba(0.25f, 0.5f, 0.75f, 1.0f), Imf::Rgba(0.75f, 0.5f, 0.25f, 1.0f)};
  {
    Imf::RgbaOutputFile out((dir / "wood.exr").c_str(), 2, 1, Imf::WRITE_RGBA);
    out.setFrameBuffer(px.data(), 1, 2);
    out.writePixels(1);
  }
  const std::string body = std::string(kLight) + R"(
    <shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
      <string name="filename" value="wood.exr"/><string name="filter_type" value="nearest"/>
      <string name="wrap_mode" value="clamp"/></texture></bsdf></shape>
    <shape type="sphere"><bsdf type="roughplastic"><texture type="bitmap" name="diffuse_reflectance">
      <string name="filename" value="wood.png"/></texture></bsdf></shape>)";
  const auto t = translate(body);
  const json& m = t.scene["materials"];
  std::vector<json> textured;
  for (const auto& [name, v] : m.items())
    if (v.contains("reflectance_texture")) textured.push_back(v);
  ASSERT_EQ(textured.size(), 2u);
  for (const json& v : textured) EXPECT_EQ(v["reflectance"], 1.0);
  const json& lambert = textured[0]["type"] == "lambertian" ? textured[0] : textured[1];
  const json& plastic = textured[0]["type"] == "lambertian" ? textured[1] : textured[0];
  EXPECT_EQ(lambert["reflectance_texture"], json({{"file", (dir / "wood.exr").string()}, {"channel", "rgb"},
                                                  {"filter", "nearest"}, {"wrap", "clamp"}, {"encoding", "srgb"}}));
  EXPECT_EQ(plastic["type"], "coated_fluorescent");
  EXPECT_EQ(plastic["reflectance_texture"]["filter"], "bilinear");
  EXPECT_EQ(plastic["reflectance_texture"]["wrap"], "repeat");
  // Without raw = true Mitsuba decodes integer-coded images from sRGB, and so does kasha (an
  // OpenEXR is linear either way); raw = true reads the codes as data.
  EXPECT_EQ(plastic["reflectance_texture"]["encoding"], "srgb");
  EXPECT_EQ(translate(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap"
      name="reflectance"><string name="filename" value="n.png"/><boolean name="raw" value="true"/></texture></bsdf>
      </shape>)").scene["materials"].begin().value()["reflectance_texture"]["encoding"], "linear");
  // Loaded (the EXR only), the hit's reflectance is the texel's colour as a Jakob–Hanika spectrum.
  const auto s = load(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="diffuse">
      <texture type="bitmap" name="reflectance"><string name="filename" value="wood.exr"/>
      <string name="filter_type" value="nearest"/></texture></bsdf></shape>)");
  ASSERT_EQ(s->materials.size(), 1u);
  ASSERT_TRUE(s->materials[0]->textured());
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const float lambda = 600.0f;
  const Bsdf b = s->materials[0]->bsdf(HitContext{Vec2(0.25f, 0.5f), world, world, {&lambda, 1}});
  const Vec3 n(0, 0, 1);
  EXPECT_NEAR(b.eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, n, n) * kPi,
              rgbToSigmoid(Vec3(0.25f, 0.5f, 0.75f))(lambda), 1e-6f);
  // Bad values are errors naming the plugin; other texture plugins are refused.
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="diffuse">
      <texture type="bitmap" name="reflectance"><string name="filename" value="wood.exr"/>
      <string name="wrap_mode" value="zero"/></texture></bsdf></shape>)"), "texture 'bitmap': wrap_mode 'zero' is not repeat, mirror or clamp"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="diffuse">
      <texture type="noise" name="reflectance"/></bsdf></shape>)"), "texture 'noise': unsupported texture plugin (bitmap, checkerboard, mesh_attribute)"));
}

// Every imported shape gives kasha (u, 1 − v) where Mitsuba has (u, v): kasha counts v from an
// image's bottom, Mitsuba from its top, so images and checkerboards land where Mitsuba puts them.
// Mitsuba's (u, v) at each point below is worked out by hand from its shape definitions (src/shapes).
TEST_F(MitsubaImport, TextureCoordinatesAreMitsubasWithVCountedFromTheBottom) {
  write("tri.obj", "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nvt 0.1 0.2\nvt 0.9 0.2\nvt 0.1 0.6\nf 1/1 2/2 3/3\n");
  write("tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "property float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                   "-1 -1 0 0.1 0.2\n1 -1 0 0.9 0.2\n-1 1 0 0.1 0.6\n3 0 1 2\n");
  // kasha's (u, v) and geometric normal where a ray from z = −5 along +z meets the shape at (x, y).
  struct Seen {
    Vec2 uv;
    Vec3 ng;
  };
  const auto seen = [&](const std::string& shape, float x, float y) {
    const auto s = load(std::string(kLight) + shape);
    const std::optional<Hit> h = s->accel->intersect(Ray{Vec3(x, y, -5), Vec3(0, 0, 1)});
    if (!h) {
      ADD_FAILURE() << "no hit on " << shape;
      return Seen{};
    }
    return Seen{s->shapes[h->shape].surfaceUv(h->prim, h->bary, h->ng), h->ng};
  };
  const auto expectUv = [](const Seen& k, Vec2 mitsuba, const std::string& what, float tolerance = 1e-5f) {
    EXPECT_NEAR(k.uv.x, mitsuba.x, tolerance) << what;
    EXPECT_NEAR(k.uv.y, 1.0f - mitsuba.y, tolerance) << what;
  };
  // rectangle: uv = ((x + 1)/2, (y + 1)/2); normal +z, turned by the inverse transpose.
  const Seen rect = seen(R"(<shape type="rectangle"><bsdf type="diffuse"/></shape>)", 0.5f, -0.5f);
  expectUv(rect, Vec2(0.75f, 0.25f), "rectangle");
  EXPECT_NEAR(rect.ng.z, 1.0f, 1e-6f);
  // Mirrored in x: the point at world (0.5, −0.5) is local (−0.5, −0.5), and the normal stays +z.
  const Seen mirrored = seen(R"(<shape type="rectangle"><transform name="to_world"><scale x="-1"/></transform>
      <bsdf type="diffuse"/></shape>)", 0.5f, -0.5f);
  expectUv(mirrored, Vec2(0.25f, 0.25f), "mirrored rectangle");
  EXPECT_NEAR(mirrored.ng.z, 1.0f, 1e-6f);
  // cube, face z = −1 (normal −z; corners 3, 1, 0, 2 with uv (0, 1), (1, 1), (1, 0), (0, 0)):
  // corner 3 = (1, 1), 1 = (1, −1), 0 = (−1, −1), 2 = (−1, 1), so u = (1 − y)/2, v = (x + 1)/2.
  const Seen cube = seen(R"(<shape type="cube"><bsdf type="diffuse"/></shape>)", 0.5f, -0.5f);
  expectUv(cube, Vec2(0.75f, 0.75f), "cube");
  EXPECT_NEAR(cube.ng.z, -1.0f, 1e-6f);
  // disk: uv = (r, φ/2π), at r = 0.5 on the middle of kasha's 65th triangle of 256, where its
  // linear uv differs from the disk's by r·(1/cos(π/256) − 1) in u only.
  const float phi = 2.0f * kPi * 64.5f / 256.0f;
  expectUv(seen(R"(<shape type="disk"><bsdf type="diffuse"/></shape>)", 0.5f * std::cos(phi), 0.5f * std::sin(phi)),
           Vec2(0.5f, 64.5f / 256.0f), "disk", 1e-4f);
  // OBJ: Mitsuba reads vt as (u, 1 − v) unless flip_tex_coords is false. At (−0.5, −0.5) the
  // barycentrics are (0.5, 0.25, 0.25): vt = (0.3, 0.3).
  expectUv(seen(R"(<shape type="obj"><string name="filename" value="tri.obj"/><bsdf type="diffuse"/></shape>)", -0.5f, -0.5f),
           Vec2(0.3f, 0.7f), "obj");
  expectUv(seen(R"(<shape type="obj"><string name="filename" value="tri.obj"/><boolean name="flip_tex_coords" value="false"/>
      <bsdf type="diffuse"/></shape>)", -0.5f, -0.5f), Vec2(0.3f, 0.3f), "obj without flip");
  // PLY: Mitsuba reads (u, v) as they are unless flip_tex_coords is true.
  expectUv(seen(R"(<shape type="ply"><string name="filename" value="tri.ply"/><bsdf type="diffuse"/></shape>)", -0.5f, -0.5f),
           Vec2(0.3f, 0.3f), "ply");
  expectUv(seen(R"(<shape type="ply"><string name="filename" value="tri.ply"/><boolean name="flip_tex_coords" value="true"/>
      <bsdf type="diffuse"/></shape>)", -0.5f, -0.5f), Vec2(0.3f, 0.7f), "ply with flip");
  // sphere: Mitsuba's uv = (atan2(y, x)/2π wrapped to [0, 1), acos(z)/π) of the point in its local
  // axes, the unit sphere under to_world · translate(center) · scale(radius).
  const auto sphereUv = [](Vec3 local) {
    const float u = std::atan2(local.y, local.x) / (2.0f * kPi);
    return Vec2(u < 0.0f ? u + 1.0f : u, std::acos(local.z) / kPi);
  };
  const float zNear = -std::sqrt(1.0f - 0.3f * 0.3f - 0.4f * 0.4f);  // where x = 0.3, y = 0.4 meets the unit sphere
  expectUv(seen(R"(<shape type="sphere"><bsdf type="diffuse"/></shape>)", 0.3f, 0.4f), sphereUv(Vec3(0.3f, 0.4f, zNear)),
           "sphere", 1e-5f);
  // Radius 2 about (1, 0, 0), then rotated 90° about x: world (x, y, z) = (lx, −lz, ly) + (1, 0, 0)
  // for the local point l/2 in the unit sphere; the ray at (1.6, 0.8) meets it at ly = −√(4 − 0.6² − 0.8²).
  const float ly = -std::sqrt(4.0f - 0.36f - 0.64f);
  expectUv(seen(R"(<shape type="sphere"><float name="radius" value="2"/><point name="center" x="1" y="0" z="0"/>
      <transform name="to_world"><rotate x="1" angle="90"/></transform><bsdf type="diffuse"/></shape>)", 1.6f, 0.8f),
           sphereUv(Vec3(0.6f, ly, -0.8f) / 2.0f), "rotated sphere", 1e-5f);
  // Mirrored in x: world (x, y, z) is local (−x, y, z).
  expectUv(seen(R"(<shape type="sphere"><transform name="to_world"><scale x="-1" y="1" z="1"/></transform>
      <bsdf type="diffuse"/></shape>)", 0.3f, 0.4f), sphereUv(Vec3(-0.3f, 0.4f, zNear)), "mirrored sphere", 1e-5f);
}

// Search paths given from outside (kasha render -a, Python's search_paths) come after the
// scene's <path>s and its own directory, in order.
TEST_F(MitsubaImport, FallbackSearchPathsComeAfterTheScenesOwn) {
  fs::create_directories(dir / "first");
  fs::create_directories(dir / "second");
  const std::string tri = "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nf 1 2 3\n";
  write("second/only_second.obj", tri);
  write("first/both.obj", tri);
  write("second/both.obj", tri);
  write("both_here.obj", tri);
  write("first/both_here.obj", tri);
  const std::string body = std::string(kLight) + R"(
    <shape type="obj"><string name="filename" value="only_second.obj"/></shape>
    <shape type="obj"><string name="filename" value="both.obj"/></shape>
    <shape type="obj"><string name="filename" value="both_here.obj"/></shape>)";
  const std::string path = scene(body);
  std::ifstream in(path);
  const mitsuba::Translation t = mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), path, {},
                                                                {(dir / "first").string(), (dir / "second").string()});
  const json& shapes = t.scene["shapes"];
  EXPECT_EQ(shapes[0]["file"], (dir / "second/only_second.obj").string());
  EXPECT_EQ(shapes[1]["file"], (dir / "first/both.obj").string());
  EXPECT_EQ(shapes[2]["file"], (dir / "both_here.obj").string());
}

// <shape type="shapegroup"> and <shape type="instance">: each instance places the group's shapes
// by its to_world after their own; a nested material is translated once; Mitsuba's rules (no
// emitters, no nesting, a reference to a group) are errors naming the element.
TEST_F(MitsubaImport, InstancesPlaceTheirShapeGroupsShapes) {
  const std::string group = R"(
    <shape type="shapegroup" id="pair">
      <shape type="rectangle"><bsdf type="diffuse" id="white"/></shape>
      <shape type="sphere"><float name="radius" value="0.5"/>
        <transform name="to_world"><translate z="3"/></transform><ref id="white"/></shape>
    </shape>)";
  const auto t = translate(std::string(kLight) + group + R"(
    <shape type="instance" id="left"><ref id="pair"/><transform name="to_world"><translate x="-4"/></transform></shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><scale value="2"/><translate x="4"/></transform></shape>)");
  const json& shapes = t.scene["shapes"];
  ASSERT_EQ(shapes.size(), 4u);
  EXPECT_EQ(t.scene["materials"].size(), 1u);
  EXPECT_EQ(shapes[0]["name"].get<std::string>().rfind("left/", 0), 0u);
  for (const json& sh : shapes) EXPECT_EQ(sh["material"], "white");
  const auto s = load(std::string(kLight) + group + R"(
    <shape type="instance" id="left"><ref id="pair"/><transform name="to_world"><translate x="-4"/></transform></shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><scale value="2"/><translate x="4"/></transform></shape>)");
  // The spheres: centre (0, 0, 3) placed by x − 4, and by 2x + 4 (radius 1).
  expectNear(s->shapes.at(1).center, Vec3(-4, 0, 3));
  expectNear(s->shapes.at(3).center, Vec3(4, 0, 6));
  EXPECT_NEAR(s->shapes[3].radius, 1.0f, 1e-5f);
  // The second rectangle spans x in [2, 6] at z = 0.
  const std::optional<Hit> h = s->accel->intersect(Ray{Vec3(5.9f, 1.9f, -5), Vec3(0, 0, 1)});
  ASSERT_TRUE(h);
  EXPECT_EQ(h->shape, 2u);
  EXPECT_NEAR(h->t, 5.0f, 1e-4f);
  // Errors.
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="instance"><ref id="nothing"/></shape>)"),
                       "no <shape type=\"shapegroup\" id=\"nothing\"> before this reference"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="shapegroup" id="g">
      <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape></shape>)"),
                       "an emitter in a shapegroup"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="shapegroup" id="g">
      <shape type="shapegroup" id="h"><shape type="rectangle"/></shape></shape>)"),
                       "a shapegroup inside a shapegroup"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="shapegroup"><shape type="rectangle"/></shape>)"),
                       "a shapegroup needs an id"));
  // A plugin outside kasha's scope in a group is named at its own line (the file's last).
  const std::string sdf = error(std::string(kLight) + R"(<shape type="shapegroup" id="g">
      <shape type="sdfgrid"/></shape>)");
  const std::string xml = scene(std::string(kLight) + R"(<shape type="shapegroup" id="g">
      <shape type="sdfgrid"/></shape>)");
  std::ifstream in(xml);
  const long lines = std::count(std::istreambuf_iterator<char>(in), {}, '\n') + 1;
  EXPECT_TRUE(contains(sdf, ":" + std::to_string(lines) + ": shape 'sdfgrid': outside kasha's scope (signed distance fields)"));
}

// <texture type="checkerboard"> declared at the top level and referred to by <ref>, nested on a
// roughness (Mitsuba's eval_1 reads the colours the other way round), on one axis, and
// mesh_attribute; errors in one line naming the element.
TEST_F(MitsubaImport, CheckerboardAndMeshAttributeTextures) {
  const std::string textures = std::string(kLight) + R"(
    <texture type="checkerboard" id="tex">
      <rgb name="color0" value="0.2"/><rgb name="color1" value="0.1, 0.2, 0.3"/>
      <transform name="to_uv"><scale x="8" y="4"/><translate x="0.5" y="0.25"/></transform>
    </texture>
    <bsdf type="diffuse" id="floor"><ref name="reflectance" id="tex"/></bsdf>
    <bsdf type="roughdielectric" id="glass"><texture name="alpha" type="checkerboard">
      <float name="color0" value="0.0"/><float name="color1" value="0.4"/></texture></bsdf>
    <bsdf type="roughconductor" id="metal"><texture name="alpha_u" type="checkerboard"/><float name="alpha_v" value="0.3"/></bsdf>
    <bsdf type="diffuse" id="painted"><texture type="mesh_attribute" name="reflectance">
      <string name="name" value="face_color"/></texture></bsdf>
    <shape type="rectangle"><ref id="floor"/></shape>)";
  const auto t = translate(textures);
  const json& m = t.scene["materials"];
  EXPECT_EQ(m["floor"]["reflectance"], 1.0);
  const json& floor = m["floor"]["reflectance_texture"];
  EXPECT_EQ(floor["type"], "checkerboard");
  EXPECT_FLOAT_EQ(floor["color0"].get<float>(), 0.2f);
  ASSERT_EQ(floor["color1"].size(), 3u);
  EXPECT_FLOAT_EQ(floor["color1"][2].get<float>(), 0.3f);
  // Mitsuba's to_uv = translate · scale: u' = 8u + 0.5, v' = 4v + 0.25, at Mitsuba's v, which is
  // 1 − kasha's v: v' = 4(1 − v) + 0.25 = −4v + 4.25.
  const std::vector<std::vector<float>> toUv = {{8, 0, 0.5f}, {0, -4, 4.25f}};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(floor["to_uv"][r][c].get<float>(), toUv[r][c]) << r << c;
  EXPECT_EQ(m["glass"]["alpha"], 1.0);
  EXPECT_FLOAT_EQ(m["glass"]["alpha_texture"]["color0"].get<float>(), 0.4f);  // swapped: eval_1
  EXPECT_FLOAT_EQ(m["glass"]["alpha_texture"]["color1"].get<float>(), 0.0f);
  EXPECT_FLOAT_EQ(m["metal"]["alpha"][1].get<float>(), 0.3f);
  EXPECT_FLOAT_EQ(m["metal"]["alpha_texture"][0]["color0"].get<float>(), 0.2f);  // the defaults, swapped
  EXPECT_FLOAT_EQ(m["metal"]["alpha_texture"][0]["color1"].get<float>(), 0.4f);
  EXPECT_TRUE(m["metal"]["alpha_texture"][1].is_null());
  EXPECT_EQ(m["painted"]["reflectance_texture"], json({{"type", "mesh_attribute"}, {"name", "face_color"}}));
  // It loads (the mesh attribute is not on a shape), and the floor reads the checkerboard.
  const auto s = load(textures);
  const float lambda = 550.0f;
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const Vec3 n(0, 0, 1);
  const auto at = [&](Vec2 uv) {
    return s->materials[0]
               ->bsdf(HitContext{uv, world, world, {&lambda, 1}})
               .eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, n, n) *
           kPi;
  };
  ASSERT_EQ(s->materialNames[0], "floor");
  EXPECT_NEAR(at(Vec2(0.01f, 0.1f)), rgbToSigmoid(Vec3(0.2f))(lambda), 1e-6f);  // (0.58, 3.85): color0
  EXPECT_NEAR(at(Vec2(0.01f, 0.01f)), rgbToSigmoid(Vec3(0.1f, 0.2f, 0.3f))(lambda), 1e-6f);  // (0.58, 4.21): color1
  // Errors.
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<bsdf type="diffuse" id="d"><ref name="reflectance" id="nope"/></bsdf>)" + kFloor),
                       "no <texture id=\"nope\"> before this reference"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<texture type="checkerboard"/>)" + kFloor),
                       "a top-level <texture> needs an id to be referred to"));
  // A bitmap on a scalar (a roughness) reads the luminance of R, G, B, as Mitsuba's eval_1 does.
  const auto bitmapAlpha = translate(std::string(kLight) + R"(<bsdf type="roughconductor" id="d"><texture name="alpha" type="bitmap">
      <string name="filename" value="x.exr"/></texture></bsdf>)" + kFloor);
  EXPECT_EQ(bitmapAlpha.scene["materials"]["d"]["alpha_texture"]["channel"], "luminance");
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<bsdf type="diffuse" id="d"><texture name="reflectance" type="checkerboard">
      <texture name="color0" type="checkerboard"/></texture></bsdf>)" + kFloor),
                       "a checkerboard colour must be a <float>, an <rgb> or a constant <spectrum>, not <texture>"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<bsdf type="diffuse" id="d"><texture name="reflectance" type="mesh_attribute">
      <string name="name" value="color"/></texture></bsdf>)" + kFloor), "name 'color' is not a mesh attribute's"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="diffuse"><texture name="reflectance" type="mesh_attribute">
      <string name="name" value="vertex_color"/></texture></bsdf></shape>)"), "which only PLY meshes carry"));
}

// normalmap and bumpmap (Mitsuba 3's documentation scenes bsdf_normalmap_with.xml,
// bsdf_bumpmap_with.xml, on a rectangle): kasha's normal_map and bump_map around the nested
// material; the bump map's texture may have any name and is read as one channel.
TEST_F(MitsubaImport, NormalAndBumpMaps) {
  writeExr("n.exr", 2, 2, std::vector<Imf::Rgba>(4, Imf::Rgba(0.5f, 0.5f, 1.0f, 1.0f)));
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="normalmap" id="nm"><texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/>
      <string name="filename" value="n.exr"/></texture><bsdf type="diffuse"/></bsdf>
    <bsdf type="bumpmap" id="bm"><float name="scale" value="0.02"/><texture name="tiles" type="bitmap">
      <boolean name="raw" value="true"/><string name="filename" value="n.exr"/></texture>
      <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf>
    <shape type="rectangle"><ref id="nm"/></shape><shape type="rectangle"><ref id="bm"/></shape>)");
  const json& m = t.scene["materials"];
  ASSERT_TRUE(m.contains("nm") && m.contains("bm")) << m.dump();
  EXPECT_EQ(m["nm"]["type"], "normal_map");
  EXPECT_EQ(m["nm"]["material"]["type"], "lambertian");
  EXPECT_EQ(m["nm"]["normals"], json({{"file", (dir / "n.exr").string()}, {"channel", "rgb"}, {"filter", "bilinear"},
                                      {"wrap", "repeat"}, {"encoding", "linear"}}));
  EXPECT_EQ(m["bm"]["type"], "bump_map");
  EXPECT_EQ(m["bm"]["material"]["type"], "lambertian");
  EXPECT_EQ(m["bm"]["height"]["channel"], "luminance");
  EXPECT_FLOAT_EQ(m["bm"]["scale"].get<float>(), 0.02f);
  const auto s = loadScene(file());
  ASSERT_EQ(s->materials.size(), 2u);
  for (const auto& mat : s->materials) EXPECT_TRUE(mat->textured());
  EXPECT_NE(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="bumpmap"><bsdf type="diffuse"/></bsdf>
      </shape>)").find("expected exactly one <texture> (the height)"), std::string::npos);
}

// mask (bsdf_mask_after.xml): kasha's mask, opacity a number (default 0.5) or a texture's mean.
TEST_F(MitsubaImport, OpacityMask) {
  writeExr("leaf.exr", 2, 2, std::vector<Imf::Rgba>(4, Imf::Rgba(1.0f, 1.0f, 1.0f, 1.0f)));
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="mask" id="leaf"><bsdf type="diffuse"/><texture name="opacity" type="bitmap">
      <string name="filename" value="leaf.exr"/></texture></bsdf>
    <bsdf type="mask" id="half"><bsdf type="diffuse"/></bsdf>
    <shape type="rectangle"><ref id="leaf"/></shape><shape type="rectangle"><ref id="half"/></shape>)");
  const json& m = t.scene["materials"];
  ASSERT_TRUE(m.contains("leaf") && m.contains("half")) << m.dump();
  EXPECT_EQ(m["leaf"]["type"], "mask");
  EXPECT_EQ(m["leaf"]["opacity"], 1.0);
  EXPECT_EQ(m["leaf"]["opacity_texture"]["channel"], "luminance");
  EXPECT_EQ(m["leaf"]["material"]["type"], "lambertian");
  EXPECT_FLOAT_EQ(m["half"]["opacity"].get<float>(), 0.5f);
  const auto s = loadScene(file());
  ASSERT_EQ(s->materials.size(), 2u);
  EXPECT_EQ(s->materials[0]->describe(), "mask(lambertian)");
}


// blendbsdf (bsdf_blendbsdf.xml): kasha's blend, weight a number (default 0.5) or a texture's
// mean, the two nested BSDFs in order. The XML blend scatters exactly as its JSON twin written by
// hand (a checkerboard read as a scalar swaps its colours, and reads v as 1 − v: xml_texture.cpp).
TEST_F(MitsubaImport, BlendScattersAsItsJsonTwin) {
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="blendbsdf" id="streaks"><texture name="weight" type="checkerboard">
        <float name="color0" value="0.8"/><float name="color1" value="0.3"/></texture>
      <bsdf type="diffuse"><spectrum name="reflectance" value="0.6"/></bsdf>
      <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf></bsdf>
    <bsdf type="blendbsdf" id="half"><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>
    <shape type="rectangle"><ref id="streaks"/></shape><shape type="rectangle"><ref id="half"/></shape>)");
  const json& m = t.scene["materials"];
  ASSERT_TRUE(m.contains("streaks") && m.contains("half")) << m.dump();
  EXPECT_EQ(m["streaks"]["type"], "blend");
  EXPECT_EQ(m["streaks"]["weight_texture"]["type"], "checkerboard");
  EXPECT_FLOAT_EQ(m["half"]["weight"].get<float>(), 0.5f);
  EXPECT_EQ(m["half"]["materials"][1]["type"], "mirror");
  const auto s = loadScene(file());
  ASSERT_EQ(s->materials.size(), 2u);
  const auto named = [&](const std::string& name) -> const Material& {
    const auto it = std::find(s->materialNames.begin(), s->materialNames.end(), name);
    return *s->materials[size_t(it - s->materialNames.begin())];
  };
  EXPECT_EQ(named("half").describe(), "blend(lambertian, mirror)");
  const json twin = json::parse(R"({"type": "blend", "weight": 1,
    "weight_texture": {"type": "checkerboard", "color0": 0.3, "color1": 0.8, "to_uv": [[1, 0, 0], [0, -1, 1]]},
    "materials": [{"type": "lambertian", "reflectance": 0.6}, {"type": "rough_conductor", "reflectance": 1, "alpha": 0.2}]})");
  const auto expected = parseMaterial(twin, SpectrumContext("twin.json", "."), "/materials/twin", s->range);
  const Material& imported = named("streaks");
  ASSERT_TRUE(imported.textured());
  const Frame world{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const float lambda = 550.0f;
  int compared = 0;
  for (const Vec2 uv : {Vec2(0.25f, 0.25f), Vec2(0.75f, 0.25f)}) {
    const HitContext hit{uv, world, world, {&lambda, 1}};
    const Bsdf a = imported.bsdf(hit), b = expected->bsdf(hit);
    for (float c = -0.95f; c < 1.0f; c += 0.1f) {
      const Vec3 wo = glm::normalize(Vec3(0.3f, -0.2f, 0.7f)), wi = glm::normalize(Vec3(std::sqrt(1 - c * c), 0.1f, c));
      for (const TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        EXPECT_EQ(a.eval({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo),
                  b.eval({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo));
        EXPECT_EQ(a.pdf({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo).pdf,
                  b.pdf({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo).pdf);
        compared += a.eval({mode, SpectralLobe::Elastic, lambda, lambda}, wi, wo) > 0.0f;
      }
    }
  }
  EXPECT_GT(compared, 20);
  // The twin's weight matters: the two colours give different values.
  const Vec3 wo(0.0f, 0.0f, 1.0f), wi = glm::normalize(Vec3(0.1f, 0.0f, 1.0f));
  const auto at = [&](Vec2 uv) {
    return imported.bsdf(HitContext{uv, world, world, {&lambda, 1}})
        .eval({TransportMode::Radiance, SpectralLobe::Elastic, lambda, lambda}, wi, wo);
  };
  EXPECT_NE(at(Vec2(0.25f, 0.25f)), at(Vec2(0.75f, 0.25f)));
  // Not two nested BSDFs, or a weight outside [0, 1]: errors.
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="blendbsdf"><bsdf type="diffuse"/></bsdf></shape>)"),
                       "bsdf 'blendbsdf': expected exactly two nested <bsdf>s, found 1"));
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="rectangle"><bsdf type="blendbsdf">
      <float name="weight" value="1.5"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf></shape>)"), "weight: must lie in [0, 1]"));
}

TEST_F(MitsubaImport, DefaultsRefsAndIncludes) {
  write("materials.xml", R"(<scene version="3.0.0"><bsdf type="diffuse" id="grey"><float name="reflectance" value="$refl"/></bsdf></scene>)");
  const auto t = translate(std::string(R"(<default name="refl" value="0.7"/><default name="w" value="2"/>)") + kLight + R"(
    <include filename="materials.xml"/>
    <shape type="rectangle" id="floor"><transform name="to_world"><scale x="$w" y="$w"/></transform><ref id="grey"/></shape>)");
  EXPECT_EQ(t.scene["materials"]["grey"]["reflectance"], 0.7f);
  EXPECT_EQ(t.scene["shapes"][0]["material"], "grey");
  EXPECT_EQ(t.scene["shapes"][0]["name"], "floor");
  EXPECT_EQ(t.scene["shapes"][0]["corners"][2], json({2.0f, 2.0f, 0.0f}));
  // The same file may be included twice (not a cycle); here it defines the same id again.
  const std::string plain = write("plain.xml", "<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"grey\"/></scene>");
  const std::string twice = write("twice.xml", "<scene version=\"3.0.0\"><include filename=\"plain.xml\"/>"
                                               "<include filename=\"plain.xml\"/></scene>");
  EXPECT_TRUE(contains(fileError(twice), "bsdf 'diffuse': duplicate id 'grey' (the <bsdf> at " + plain + ":1 has it)"));
}

TEST_F(MitsubaImport, DefaultsOfAnIncludedFileApplyUnlessSetBefore) {
  // As in Mitsuba 3: an included file's <default> sets its parameter if nothing set it yet, and
  // it stays set for the rest of the import.
  write("grey.xml", R"(<scene version="3.0.0"><default name="refl" value="0.3"/><default name="w" value="3"/>
    <bsdf type="diffuse" id="grey"><float name="reflectance" value="$refl"/></bsdf></scene>)");
  const std::string floor = R"(<shape type="rectangle"><transform name="to_world"><scale x="$w"/></transform><ref id="grey"/></shape>)";
  const auto own = translate(std::string(kLight) + R"(<include filename="grey.xml"/>)" + floor);
  EXPECT_EQ(own.scene["materials"]["grey"]["reflectance"], 0.3f);
  EXPECT_EQ(own.scene["shapes"][0]["corners"][2][0], 3.0f);  // the includer uses the included default
  const auto includer = translate(std::string(R"(<default name="refl" value="0.7"/>)") + kLight +
                                  R"(<include filename="grey.xml"/>)" + floor);
  EXPECT_EQ(includer.scene["materials"]["grey"]["reflectance"], 0.7f);
}

TEST_F(MitsubaImport, ExampleSceneLoads) {
  const auto s = loadScene(std::string(KASHA_SOURCE_DIR) + "/scenes/mitsuba/fluorescent_matpreview.xml");
  EXPECT_EQ(s->shapes.size(), 1u + 1u + 1u + 1u + 6u);  // ground, coaster, sphere, icosphere, cube faces
  EXPECT_EQ(s->lights.size(), 2u);                     // envmap and spot
  ASSERT_NE(dynamic_cast<const EnvMapLight*>(s->environment()), nullptr);
  EXPECT_EQ(s->shapes[3].indices.size(), 320u * 3u);   // the PLY icosphere
  EXPECT_EQ(s->render.spp, 128);
  EXPECT_EQ(s->camera.width(), 480);
  size_t fluorescent = 0;
  for (const auto& m : s->materials) fluorescent += has(m->flags(), BsdfFlags::Fluorescent);
  EXPECT_EQ(fluorescent, 1u);  // FITC only: roughplastic became coated_fluorescent with c = 0
}

// ---- errors name the file, the line and the plugin ------------------------------------------

TEST_F(MitsubaImport, UnsupportedPluginsAndPropertiesAreErrorsWithFileLineAndPlugin) {
  // kSensor spans lines 1–6 of the file; the element under test starts on line 7.
  const std::string prefix = "\n";
  EXPECT_TRUE(contains(error(prefix + "<bsdf type=\"measured\" id=\"h\"/>"), file() + ":7: bsdf 'measured': unsupported BSDF plugin"));
  // Outside kasha's scope, said as such.
  EXPECT_TRUE(contains(error(prefix + "<bsdf type=\"hair\" id=\"h\"/>"), file() + ":7: bsdf 'hair': outside kasha's scope (hair)"));
  EXPECT_TRUE(contains(error(prefix + "<bsdf type=\"pplastic\" id=\"p\"/>"), file() + ":7: bsdf 'pplastic': outside kasha's scope (polarisation)"));
  EXPECT_TRUE(contains(error(prefix + "<shape type=\"linearcurve\"/>"), file() + ":7: shape 'linearcurve': outside kasha's scope (curves)"));
  EXPECT_TRUE(contains(error(prefix + "<shape type=\"ellipsoids\"/>"), file() + ":7: shape 'ellipsoids': unsupported shape plugin"));
  EXPECT_TRUE(contains(error(prefix + "<emitter type=\"sky\"/>"), file() + ":7: emitter 'sky': unsupported emitter plugin"));
  EXPECT_TRUE(contains(error(prefix + "<integrator type=\"prb\"/>"), file() + ":7: integrator 'prb': unsupported integrator plugin"));
  EXPECT_TRUE(contains(error(prefix + "<integrator type=\"aov\"/>"), file() + ":7: integrator 'aov': integrator 'aov' writes other quantities than radiance"));
  EXPECT_TRUE(contains(error(prefix + "<medium type=\"homogeneous\"/>"), file() + ":7: medium 'homogeneous': a top-level <medium> needs an id"));
  // A property the plugin does not read: the line of the property, the plugin's name.
  EXPECT_TRUE(contains(error(prefix + std::string(kLight) + "<shape type=\"sphere\">\n<float name=\"radiuss\" value=\"1\"/></shape>"),
                  file() + ":8: shape 'sphere': unsupported property 'radiuss'"));
  EXPECT_TRUE(contains(error(prefix + std::string(kLight) + "<shape type=\"rectangle\"><bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"1.5, 0.2, 0.2\"/></bsdf></shape>"),
                  "reflectance colour component 1.500000 is outside [0, 1]"));
  EXPECT_TRUE(contains(error(prefix + "<shape type=\"rectangle\"><ref id=\"nowhere\"/></shape>"), "no <bsdf id=\"nowhere\">"));
  EXPECT_TRUE(contains(error(prefix + "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>"),
                  "parameter '$r' has no <default>"));
  // Values the JSON loader rejects are reported at the XML element they came from.
  EXPECT_TRUE(contains(error(prefix + std::string(kLight) + "\n<shape type=\"rectangle\"><bsdf type=\"diffuse\"><float name=\"reflectance\" value=\"1.5\"/></bsdf></shape>"),
                  file() + ":8: bsdf 'diffuse': in kasha's translation /materials/"));
  const std::string missingObj = error(prefix + "<shape type=\"obj\"><string name=\"filename\" value=\"missing.obj\"/></shape>");
  EXPECT_TRUE(contains(missingObj, file() + ":7: shape 'obj': in kasha's translation /shapes/0/file: "));
  EXPECT_TRUE(contains(missingObj, "missing.obj: cannot open mesh file"));
}

TEST_F(MitsubaImport, MalformedXmlNamesTheLine) {
  const std::string path = write("bad.xml", "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>\n");
  try {
    loadScene(path);
    FAIL() << "loaded malformed XML";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), path + ":3: malformed XML"));
  }
  const std::string notScene = write("root.xml", "<shape type=\"sphere\"/>");
  EXPECT_THROW(loadScene(notScene), InputError);
  const std::string cycle = write("cycle.xml", "<scene version=\"3.0.0\"><include filename=\"cycle.xml\"/></scene>");
  try {
    loadScene(cycle);
    FAIL() << "loaded a cycle of includes";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "includes itself"));
  }
}

// ---- hostile input (issue 36) ---------------------------------------------------------------

// A shape whose BSDF is `levels` twosided BSDFs, each inside the last, around a diffuse one; the
// BSDFs start on the second line of the text.
std::string nestedTwosided(int levels) {
  std::string s = "<shape type=\"rectangle\">\n";
  for (int i = 0; i < levels; ++i) s += "<bsdf type=\"twosided\">";
  s += "<bsdf type=\"diffuse\"/>";
  for (int i = 0; i < levels; ++i) s += "</bsdf>";
  return s + "</shape>";
}

// `tag` nested `levels` deep, written as <tag><tag>...</tag></tag>.
std::string nested(const std::string& open, const std::string& close, int levels) {
  std::string s;
  for (int i = 0; i < levels; ++i) s += open;
  for (int i = 0; i < levels; ++i) s += close;
  return s;
}

TEST_F(MitsubaImport, DeepNestingIsRefusedNotRecursedInto) {
  // <scene> is level 0, the shape 1, the BSDFs 2, 3, ...: 62 twosided BSDFs put the diffuse one at
  // level 64, the deepest allowed; the recursion through them works.
  EXPECT_EQ(load("\n" + std::string(kLight) + nestedTwosided(62))->materials.size(), 1u);
  // 100 000 levels used to overflow the stack (a crash, and through Python the interpreter's).
  const std::string deep = "\n" + std::string(kLight) + nestedTwosided(100000);
  EXPECT_TRUE(contains(error(deep), file() + ":8: bsdf 'twosided': nested deeper than 64 levels"));
  try {
    translate(deep);
    ADD_FAILURE() << "translated";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "nested deeper than 64 levels"));
  }
  // Any element: nested spectra, textures, unknown elements at the top.
  EXPECT_TRUE(contains(error(std::string(kLight) + "<shape type=\"rectangle\"><bsdf type=\"diffuse\">" +
                             nested("<spectrum type=\"uniform\" name=\"reflectance\">", "</spectrum>", 100000) + "</bsdf></shape>"),
                       "spectrum 'uniform': nested deeper than 64 levels"));
  EXPECT_TRUE(contains(error(std::string(kLight) + "<shape type=\"rectangle\"><bsdf type=\"diffuse\">" +
                             nested("<texture type=\"bitmap\" name=\"reflectance\">", "</texture>", 100000) + "</bsdf></shape>"),
                       "texture 'bitmap': nested deeper than 64 levels"));
  EXPECT_TRUE(contains(error(nested("<x>", "</x>", 100000)), "x: nested deeper than 64 levels"));
  // A chain of included files: each one is parsed and checked before the next is read.
  for (int i = 0; i < 20; ++i)
    write("chain" + std::to_string(i) + ".xml",
          "<scene version=\"3.0.0\"><include filename=\"chain" + std::to_string(i + 1) + ".xml\"/></scene>");
  EXPECT_TRUE(contains(error("<include filename=\"chain0.xml\"/>"), "<include>s nested deeper than 16 levels"));
}

TEST_F(MitsubaImport, NothingInTheFileIsIgnored) {
  // A second root element, or text, after </scene>: pugixml keeps them, XML allows one root.
  const std::string body = std::string(kSensor) + kLight + kFloor;
  const std::string second = write("second.xml", "<scene version=\"3.0.0\">" + body + "</scene>\n<scene version=\"3.0.0\"/>\n");
  EXPECT_TRUE(contains(fileError(second), second + ":7: a second root element <scene> after </scene>"));
  const std::string text = write("text.xml", "<scene version=\"3.0.0\">" + body + "</scene>\nand more\n");
  EXPECT_TRUE(contains(fileError(text), text + ":6: text after </scene>"));  // the text starts on the line of </scene>
  const std::string before = write("before.xml", "a scene:\n<scene version=\"3.0.0\">" + body + "</scene>\n");
  EXPECT_TRUE(contains(fileError(before), before + ":1: text before <scene>"));
  // Elements inside a transform operation or a property.
  EXPECT_TRUE(contains(error("\n<shape type=\"sphere\"><transform name=\"to_world\"><translate x=\"1\">\n"
                             "<rotate y=\"1\" angle=\"90\"/></translate></transform></shape>"),
                       file() + ":8: translate: <rotate> inside it (a property or transform operation holds no elements)"));
  EXPECT_TRUE(contains(error("\n<shape type=\"sphere\"><float name=\"radius\" value=\"1\">\n<float name=\"radius\" value=\"2\"/></float></shape>"),
                       file() + ":8: float 'radius': <float> inside it"));
  EXPECT_TRUE(contains(error("\n<shape type=\"rectangle\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" value=\"0.5\">\n"
                             "<rgb name=\"x\" value=\"1\"/></spectrum></bsdf></shape>"),
                       file() + ":8: spectrum 'reflectance': <rgb> inside it"));
}

TEST_F(MitsubaImport, NumbersAreReadToTheirEnd) {
  const auto kelvin = [&](const std::string& t) {
    const auto tr = translate(std::string(kFloor) + "<emitter type=\"point\"><blackbody name=\"intensity\" temperature=\"" + t + "\"/></emitter>");
    return tr.scene["lights"][0]["intensity"]["kelvin"].get<float>();
  };
  EXPECT_EQ(kelvin("6500"), 6500.0f);
  EXPECT_EQ(kelvin("6500K"), 6500.0f);
  EXPECT_EQ(kelvin(" 5000 k "), 5000.0f);
  // Used to be read as 6500 K.
  EXPECT_TRUE(contains(error(std::string(kFloor) + "\n<emitter type=\"point\"><blackbody name=\"intensity\" temperature=\"6500Kelvin, please\"/></emitter>"),
                       file() + ":7: blackbody 'intensity': temperature '6500Kelvin, please' is not a number of kelvin"));
  EXPECT_TRUE(contains(error(std::string(kFloor) + "<emitter type=\"point\"><blackbody name=\"intensity\" temperature=\"K\"/></emitter>"),
                       "temperature 'K' is not a number of kelvin"));
  // "+-1" used to be read as -1 (a '+' skipped before from_chars).
  EXPECT_TRUE(contains(error(std::string(kFloor) + "\n<shape type=\"sphere\"><float name=\"radius\" value=\"+-1\"/></shape>"),
                       file() + ":7: shape 'sphere': value '+-1' is not a finite number"));
  EXPECT_TRUE(contains(error(std::string(kFloor) + "<shape type=\"sphere\"><float name=\"radius\" value=\"2m\"/></shape>"),
                       "value '2m' is not a finite number"));
}

TEST_F(MitsubaImport, FovOutsideZeroTo180IsAnError) {
  // tan(fov/2) wraps round beyond 180 degrees: 405 used to render as 45.
  for (const std::string fov : {"180", "200", "405", "0", "-45"}) {
    std::string sensor = kSensor;
    sensor.replace(sensor.find("\"45\""), 4, "\"" + fov + "\"");
    const std::string path = write("fov.xml", "<scene version=\"3.0.0\">" + sensor + kLight + kFloor + "</scene>");
    EXPECT_TRUE(contains(fileError(path), path + ":3: sensor 'perspective': fov must be in (0, 180) degrees, got " + fov));
  }
}

TEST_F(MitsubaImport, DuplicateIdsNameBothElements) {
  // Two shapes with one id used to be reported as a second <bsdf> (their default materials').
  const std::string two = "\n" + std::string(kLight) + "<shape type=\"rectangle\" id=\"a\"/>\n<shape type=\"sphere\" id=\"a\"/>";
  EXPECT_TRUE(contains(error(two), file() + ":8: shape 'sphere': duplicate id 'a' (the <shape> at " + file() + ":7 has it)"));
  const std::string bsdfs = "\n" + std::string(kLight) + "<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"conductor\" id=\"a\"/>";
  EXPECT_TRUE(contains(error(bsdfs), file() + ":8: bsdf 'conductor': duplicate id 'a' (the <bsdf> at " + file() + ":7 has it)"));
  // A shape and a BSDF may share an id; a shape without a BSDF names its default material after
  // itself, and the BSDF's material takes another name.
  const auto t = translate(std::string(kLight) + "<shape type=\"rectangle\" id=\"a\"/><bsdf type=\"conductor\" id=\"a\"/>"
                           "<shape type=\"sphere\" id=\"b\"><ref id=\"a\"/></shape>");
  EXPECT_EQ(t.scene["shapes"][0]["material"], "a");
  EXPECT_EQ(t.scene["materials"]["a"]["type"], "lambertian");
  EXPECT_EQ(t.scene["materials"][t.scene["shapes"][1]["material"].get<std::string>()]["type"], "mirror");
}

TEST_F(MitsubaImport, ControlCharactersFromTheFileAreEscaped) {
  // An ESC sequence that would clear the terminal and a BEL, in an id quoted by the message.
  const std::string msg = error(std::string(kLight) + "<shape type=\"rectangle\"><ref id=\"\x1b[2Jx\x07\"/></shape>");
  EXPECT_TRUE(contains(msg, "no <bsdf id=\"\\x1b[2Jx\\x07\"> or area <emitter id=\"\\x1b[2Jx\\x07\"> before this reference"));
  EXPECT_EQ(msg.find('\x1b'), std::string::npos);
  EXPECT_EQ(msg.find('\x07'), std::string::npos);
}

// ---- media --------------------------------------------------------------------------------------

// A sphere of the medium `id` (declared in `medium`) with no BSDF, an index-matched boundary (shape
// 0), and a floor.
std::string mediumSphere(const std::string& medium, const std::string& id = "fog") {
  return std::string(kLight) + medium + "<shape type=\"sphere\"><ref name=\"interior\" id=\"" + id + "\"/></shape>" + kFloor;
}

TEST_F(MitsubaImport, HomogeneousMediumIsSigmaTTimesAlbedoTimesScale) {
  // σ_a = σ_t(1 − α)·scale = 2·0.25·0.5, σ_s = σ_t·α·scale = 2·0.75·0.5.
  const std::string medium = R"(<medium id="fog" type="homogeneous"><float name="sigma_t" value="2"/>
      <float name="albedo" value="0.75"/><float name="scale" value="0.5"/><phase type="hg"><float name="g" value="0.3"/></phase></medium>)";
  const auto t = translate(mediumSphere(medium));
  EXPECT_EQ(t.scene["media"]["fog"], json({{"type", "homogeneous"}, {"sigma_a", 0.25}, {"sigma_s", 0.75}, {"g", 0.3f}}));
  EXPECT_EQ(t.scene["shapes"][0]["interior"], "fog");
  EXPECT_FALSE(t.scene["shapes"][0].contains("material"));  // index-matched
  EXPECT_FALSE(t.scene["shapes"][0].contains("exterior"));  // vacuum
  const auto scene = load(mediumSphere(medium));
  ASSERT_EQ(scene->media.size(), 1u);
  EXPECT_FLOAT_EQ(scene->media[0]->sigmaT(500.0f), 1.0f);
  EXPECT_FLOAT_EQ(scene->media[0]->sigmaS(700.0f), 0.75f);
  ASSERT_TRUE(scene->shapes[0].media.has_value());
  EXPECT_EQ(scene->shapes[0].media->interior, 0);
  EXPECT_EQ(scene->shapes[0].media->exterior, -1);
  EXPECT_TRUE(scene->shapes[0].isMediumBoundary());
}

TEST_F(MitsubaImport, MediumDefaultsAreMitsubas) {
  // Mitsuba 3: σ_t = 1, albedo 0.75, scale 1, isotropic phase; hg's g defaults to 0.8.
  const auto t = translate(mediumSphere(R"(<medium id="fog" type="homogeneous"/>)"));
  EXPECT_EQ(t.scene["media"]["fog"], json({{"type", "homogeneous"}, {"sigma_a", 0.25}, {"sigma_s", 0.75}, {"g", 0.0}}));
  const auto hg = translate(mediumSphere(R"(<medium id="fog" type="homogeneous"><phase type="hg"/></medium>)"));
  EXPECT_FLOAT_EQ(hg.scene["media"]["fog"]["g"].get<float>(), 0.8f);
  const auto iso = translate(mediumSphere(R"(<medium id="fog" type="homogeneous"><phase type="isotropic"/></medium>)"));
  EXPECT_EQ(iso.scene["media"]["fog"]["g"], 0.0);
  // Mitsuba's default integrator, path, ignores media: said in a note; volpath does not.
  const auto ignores = [](const mitsuba::Translation& t) {
    return std::any_of(t.notes.begin(), t.notes.end(), [](const std::string& n) { return n.find("ignores participating media") != std::string::npos; });
  };
  EXPECT_TRUE(ignores(iso));
  EXPECT_TRUE(ignores(translate(mediumSphere("<integrator type=\"direct\"/><medium id=\"fog\" type=\"homogeneous\"/>"))));
  EXPECT_FALSE(ignores(translate(mediumSphere("<integrator type=\"volpath\"/><medium id=\"fog\" type=\"homogeneous\"/>"))));
  EXPECT_FALSE(ignores(translate(std::string(kLight) + kFloor)));
}

TEST_F(MitsubaImport, SpectralAlbedoAndExtinctionMultiply) {
  // An RGB albedo (Jakob–Hanika, the scene's reflectance upsampling) times a constant σ_t, as in
  // Mitsuba's medium_homogeneous_sss scene, and times a tabulated σ_t.
  const Vec3 rgb(0.85f, 0.97f, 0.3f);
  const Spectrum albedo = rgbToSpectrum(rgb, WavelengthRange{});
  const std::string colour = "<rgb name=\"albedo\" value=\"0.85, 0.97, 0.3\"/>";
  const auto constant = load(mediumSphere("<medium id=\"fog\" type=\"homogeneous\"><float name=\"scale\" value=\"5\"/>"
                                          "<float name=\"sigma_t\" value=\"10\"/>" + colour + "</medium>"));
  const auto tabulated = load(mediumSphere("<medium id=\"fog\" type=\"homogeneous\"><float name=\"scale\" value=\"2\"/>"
                                           "<spectrum name=\"sigma_t\" value=\"400:1, 700:4\"/>" + colour + "</medium>"));
  for (float nm : {380.0f, 451.5f, 532.25f, 610.0f, 699.7f, 800.0f}) {
    const float a = albedo(nm);
    const Medium& c = *constant->media[0];
    EXPECT_NEAR(c.sigmaS(nm), 50.0f * a, 1e-4f) << nm;
    EXPECT_NEAR(c.sigmaA(nm), 50.0f * (1.0f - a), 1e-4f) << nm;
    const float sigmaT = nm <= 400.0f ? 1.0f : nm >= 700.0f ? 4.0f : 1.0f + 3.0f * (nm - 400.0f) / 300.0f;
    const Medium& t = *tabulated->media[0];
    // Tabulated at ≤ 1 nm between the knots of both: the product's quadratic term is below
    // (1 nm)²/4 · |σ_t'·α'| ≈ 1e-4 of the value.
    EXPECT_NEAR(t.sigmaS(nm), 2.0f * sigmaT * a, 2e-3f * sigmaT) << nm;
    EXPECT_NEAR(t.sigmaA(nm), 2.0f * sigmaT * (1.0f - a), 2e-3f * sigmaT) << nm;
  }
}

TEST_F(MitsubaImport, InlineMediaExteriorAndSensorMedium) {
  const std::string body = R"(<medium id="air" type="homogeneous"><float name="sigma_t" value="0.01"/></medium>
    <sensor type="perspective"><ref id="air"/>
      <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="point"><point name="position" x="0" y="3" z="0"/><medium type="homogeneous" id="around_light"/></emitter>
    <shape type="sphere"><bsdf type="dielectric"/><ref name="exterior" id="air"/>
      <medium name="interior" type="homogeneous"><float name="sigma_t" value="3"/><float name="albedo" value="0"/></medium>
    </shape>)";
  const std::string path = write("scene.xml", "<scene version=\"3.0.0\">" + body + "</scene>");
  std::ifstream in(path);
  const auto t = mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), path);
  EXPECT_EQ(t.scene["camera"]["medium"], "air");
  EXPECT_EQ(t.scene["lights"][0]["medium"], "around_light");
  const json& sphere = t.scene["shapes"][0];
  EXPECT_EQ(sphere["exterior"], "air");
  EXPECT_EQ(t.scene["materials"][sphere["material"].get<std::string>()]["type"], "dielectric");
  EXPECT_EQ(t.scene["media"][sphere["interior"].get<std::string>()], json({{"type", "homogeneous"}, {"sigma_a", 3.0}, {"sigma_s", 0.0}, {"g", 0.0}}));
  const auto scene = loadScene(path);
  EXPECT_EQ(scene->media[size_t(scene->cameraMedium)]->name(), "air");
  EXPECT_EQ(scene->media[size_t(scene->shapes[0].media->exterior)]->name(), "air");
  EXPECT_FLOAT_EQ(scene->media[size_t(scene->shapes[0].media->interior)]->sigmaA(550.0f), 3.0f);
}

TEST_F(MitsubaImport, NullBsdfIsAMediumBoundary) {
  const std::string medium = R"(<medium id="fog" type="homogeneous"/><bsdf type="null" id="none"/>)";
  const auto t = translate(std::string(kLight) + medium +
                           R"(<shape type="sphere"><ref id="none"/><ref name="interior" id="fog"/></shape>
                              <shape type="sphere"><bsdf type="null"/><ref name="exterior" id="fog"/></shape>)" + kFloor);
  EXPECT_FALSE(t.scene["shapes"][0].contains("material"));
  EXPECT_FALSE(t.scene["shapes"][1].contains("material"));
  EXPECT_EQ(t.scene["shapes"][1]["exterior"], "fog");
  EXPECT_TRUE(contains(error(std::string(kLight) + R"(<shape type="sphere"><bsdf type="null"/></shape>)"),
                       file() + ":6: shape 'sphere': a null BSDF on a shape without media"));
}

TEST_F(MitsubaImport, FluorescentHomogeneousMedium) {
  // kasha's extension: the homogeneous medium's parameters plus fluorophores; σ_f is scaled by
  // `scale` like σ_t, a molar absorption is converted by length_unit instead.
  const std::string medium = R"(<medium id="fog" type="fluorescent_homogeneous">
      <float name="sigma_t" value="0.5"/><float name="albedo" value="0.5"/><float name="scale" value="2"/>
      <string name="length_unit" value="mm"/>
      <fluorophore><spectrum name="sigma_f" value="300:0.2, 500:0.2, 501:0, 900:0"/>
        <spectrum name="emission" value="500:0, 550:1, 600:0"/><float name="yield" value="0.9"/></fluorophore>
      <fluorophore><spectrum name="molar_absorption" value="400:1000, 900:1000"/><float name="concentration" value="0.01"/>
        <spectrum name="emission" value="600:0, 650:1, 700:0"/><float name="yield" value="0.5"/></fluorophore>
    </medium>)";
  const auto scene = load(mediumSphere(medium));
  const Medium& m = *scene->media[0];
  ASSERT_EQ(m.params().fluorophores.size(), 2u);
  EXPECT_FLOAT_EQ(m.sigmaF(0, 450.0f), 0.4f);
  // ln 10 · 1000 L/(mol·cm) · 0.01 mol/L · 0.1 cm per mm.
  EXPECT_NEAR(m.sigmaF(1, 450.0f), std::log(10.0f) * 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(m.params().fluorophores[1].yield, 0.5f);
  EXPECT_FLOAT_EQ(m.sigmaS(450.0f), 0.5f);
  EXPECT_FLOAT_EQ(m.sigmaT(450.0f), 1.0f + 0.4f + std::log(10.0f) * 1.0f);
  EXPECT_TRUE(m.fluoresces());
}

TEST_F(MitsubaImport, UnsupportedMediaAreOneLineErrors) {
  const std::string line = file() + ":7: ";  // kSensor, then kLight on line 6
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"homogeneous\"><phase type=\"rayleigh\"/></medium>")),
                       line + "phase 'rayleigh': unsupported phase plugin (isotropic, hg)"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"homogeneous\"><spectrum name=\"radiance\" value=\"1\"/></medium>")),
                       line + "medium 'homogeneous': unsupported property 'radiance'"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"heterogeneous\"><volume name=\"albedo\" type=\"gridvolume\">"
                                          "<string name=\"filename\" value=\"a.vol\"/></volume></medium>")),
                       line + "volume 'gridvolume': a spatially varying albedo is not supported here"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"homogeneous\"><volume name=\"albedo\" type=\"gridvolume\">"
                                          "<string name=\"filename\" value=\"a.vol\"/><string name=\"wrap_mode\" value=\"tile\"/>"
                                          "</volume></medium>")),
                       line + "volume 'gridvolume': wrap_mode 'tile' is not clamp, repeat or mirror"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"homogeneous\"><float name=\"albedo\" value=\"1.5\"/></medium>")),
                       line + "medium 'homogeneous': albedo must lie in [0, 1]"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"homogeneous\"><phase type=\"hg\"><float name=\"g\" value=\"1\"/></phase></medium>")),
                       line + "medium 'homogeneous': in kasha's translation /media/fog/g"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"fog\" type=\"fancy\"/>")),
                       line + "medium 'fancy': unsupported medium plugin"));
  EXPECT_TRUE(contains(error(mediumSphere("\n<medium id=\"other\" type=\"homogeneous\"/>")),
                       "'interior' must be a <medium> or a <ref> to a <medium id> declared before"));
  EXPECT_TRUE(contains(error(std::string(kLight) + "<medium id=\"fog\" type=\"homogeneous\"/>\n"
                                                   "<shape type=\"cube\"><ref name=\"interior\" id=\"fog\"/></shape>"),
                       line + "shape 'cube': a cube with different media inside and outside"));
  EXPECT_TRUE(contains(error("<medium id=\"fog\" type=\"homogeneous\"/>\n<emitter type=\"constant\"><ref id=\"fog\"/></emitter>" + std::string(kFloor)),
                       line + "emitter 'constant': a medium around a constant emitter"));
}

TEST_F(MitsubaImport, HeterogeneousGridMediumIsTranslatedAndLoaded) {
  std::ofstream(dir / "smoke.vol", std::ios::binary) << test::volBytes({2, 2, 2}, 1, {0, 1, 2, 3, 4, 5, 6, 7});
  const std::string medium = R"(
<medium id="fog" type="heterogeneous"><volume name="sigma_t" type="gridvolume"><string name="filename" value="smoke.vol"/>
  <transform name="to_world"><scale value="2"/></transform></volume><float name="albedo" value="0.9"/><float name="scale" value="10"/></medium>)";
  const auto t = translate(mediumSphere(medium));
  const json& fog = t.scene["media"]["fog"];
  EXPECT_EQ(fog["type"], "heterogeneous");
  EXPECT_EQ(fog["density"]["file"], (dir / "smoke.vol").string());
  EXPECT_EQ(fog["density"]["use_grid_bbox"], false);
  EXPECT_EQ(fog["density"]["transform"][0][0], 2.0);
  EXPECT_NEAR(fog["sigma_a"].get<double>(), 1.0, 1e-6);  // (1 − 0.9)·10, scaled by the density
  EXPECT_NEAR(fog["sigma_s"].get<double>(), 9.0, 1e-6);
  // Loaded: the grid, scaled by 2, covers [0, 2]³; at its centre the trilinear value is the mean of
  // its eight cells, 3.5; outside it the medium is empty; its maximum, 7, makes the majorant.
  const auto scene = load(mediumSphere(medium));
  const Medium& m = *scene->media.at(0);
  ASSERT_TRUE(m.heterogeneous());
  EXPECT_NEAR(m.density(Vec3(1.0f)), 3.5f, 1e-5f);
  EXPECT_EQ(m.density(Vec3(3.0f, 1.0f, 1.0f)), 0.0f);
  EXPECT_EQ(m.maxDensity(), 7.0f);
  EXPECT_NEAR(m.densityExtent(Vec3(-1.0f, 1.0f, 1.0f), Vec3(1, 0, 0)), 3.0f, 1e-5f);  // leaves the box at x = 2
  // The grid is read and checked.
  std::ofstream(dir / "smoke.vol", std::ios::binary) << test::volBytes({2, 2, 2}, 1, {0, 1, 2});
  EXPECT_TRUE(contains(error(mediumSphere(medium)), "smoke.vol: header: declares 2x2x2 cells of 1 channels (32 bytes), but 12 bytes follow the header"));
  // A heterogeneous medium without grids is homogeneous.
  const auto plain = translate(mediumSphere(R"(<medium id="fog" type="heterogeneous"><float name="sigma_t" value="4"/></medium>)"));
  EXPECT_EQ(plain.scene["media"]["fog"]["type"], "homogeneous");
}

// Mitsuba's medium_homogeneous_sss_textured: a homogeneous medium whose albedo is a colour grid that
// repeats (docs/media.md §7): σ_t·scale, and the grid as the medium's albedo_grid.
TEST_F(MitsubaImport, TexturedAlbedoMediumIsTranslatedAndLoaded) {
  std::ofstream(dir / "albedo.vol", std::ios::binary) << test::volBytes({2, 1, 1}, 3, {0.9f, 0.3f, 0.1f, 0.1f, 0.4f, 0.8f});
  const std::string medium = R"(
<medium id="fog" type="homogeneous"><float name="scale" value="2"/><phase type="hg"><float name="g" value="0.7"/></phase>
  <volume name="albedo" type="gridvolume"><string name="wrap_mode" value="repeat"/><string name="filename" value="albedo.vol"/>
  </volume></medium>)";
  const auto t = translate(mediumSphere(medium));
  const json& fog = t.scene["media"]["fog"];
  EXPECT_EQ(fog["type"], "homogeneous");
  EXPECT_EQ(fog["albedo_grid"]["file"], (dir / "albedo.vol").string());
  EXPECT_EQ(fog["albedo_grid"]["wrap_mode"], "repeat");
  EXPECT_EQ(fog["albedo_grid"]["use_grid_bbox"], false);
  EXPECT_NEAR(fog["sigma_t"].get<double>(), 2.0, 1e-6);  // Mitsuba's default σ_t = 1, times scale
  EXPECT_FALSE(fog.contains("sigma_a"));
  EXPECT_FALSE(fog.contains("sigma_s"));
  EXPECT_NEAR(fog["g"].get<double>(), 0.7, 1e-6);
  // Loaded: σ_t everywhere, the red cell's colour at its centre (x = 1/4) and a period on.
  const auto scene = load(mediumSphere(medium));
  const Medium& m = *scene->media.at(0);
  ASSERT_TRUE(m.spatiallyVaryingAlbedo());
  EXPECT_FLOAT_EQ(m.sigmaT(500.0f), 2.0f);
  const RgbSigmoid red = rgbToSigmoid(Vec3(0.9f, 0.3f, 0.1f));
  for (float x : {0.25f, 1.25f, -0.75f}) EXPECT_NEAR(m.albedo(Vec3(x, 0.5f, 0.5f))(600.0f), red(600.0f), 1e-5f) << x;
  // A raw colour grid is refused (Mitsuba upsamples colours unless raw).
  std::string raw = medium;
  raw.replace(raw.find("</volume>"), 0, R"(<boolean name="raw" value="true"/>)");
  EXPECT_TRUE(contains(error(mediumSphere(raw)), "raw = true: kasha upsamples an albedo grid's colours"));
}

TEST_F(MitsubaImport, MediumSphereRendersAsItsJsonTwin) {
  // The same scene written by hand in kasha's JSON (σ_a = 2·0.25·0.5, σ_s = 2·0.75·0.5) renders
  // the same image with pt at the same seed; the camera is the translation's (its field of view is
  // another test's business).
  const std::string xml = R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="40"/><string name="fov_axis" value="y"/>
      <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>
      <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/><rfilter type="box"/></film>
      <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
    </sensor>
    <emitter type="point"><point name="position" x="0" y="3" z="-2"/><spectrum name="intensity" value="20"/></emitter>
    <medium id="fog" type="homogeneous"><float name="sigma_t" value="2"/><float name="albedo" value="0.75"/>
      <float name="scale" value="0.5"/><phase type="hg"><float name="g" value="0.3"/></phase></medium>
    <shape type="sphere"><float name="radius" value="1.2"/><ref name="interior" id="fog"/></shape>
    <shape type="sphere"><point name="center" x="0" y="0" z="3"/><float name="radius" value="1.5"/>
      <bsdf type="diffuse"><spectrum name="reflectance" value="0.5"/></bsdf></shape>
  </scene>)";
  const std::string xmlPath = write("fog.xml", xml);
  std::ifstream in(xmlPath);
  const json camera = mitsuba::translateMitsubaScene(std::string(std::istreambuf_iterator<char>(in), {}), xmlPath).scene["camera"];
  // Mitsuba's intensity 20 is D65 times 20 (the translation tabulates core/rgb_illuminant.h's grey).
  const Spectrum d65 = rgbIlluminantSpectrum(Vec3(20.0f), WavelengthRange{360.0f, 830.0f});
  const json d65Times20 = {{"type", "tabulated"}, {"wavelengths", d65.lambdas()}, {"values", d65.values()}};
  const auto twin = [&](double sigmaS) {
    const json scene = {
        {"camera", camera},
        {"render", {{"spp", 4}}},
        {"media", {{"fog", {{"type", "homogeneous"}, {"sigma_a", 0.25}, {"sigma_s", sigmaS}, {"g", 0.3}}}}},
        {"materials", {{"grey", {{"type", "lambertian"}, {"reflectance", 0.5}}}}},
        {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1.2}, {"interior", "fog"}},
                    {{"type", "sphere"}, {"center", {0, 0, 3}}, {"radius", 1.5}, {"material", "grey"}}}},
        {"lights", {{{"type", "point"}, {"position", {0, 3, -2}}, {"intensity", d65Times20}}}}};
    return write("fog" + std::to_string(sigmaS) + ".json", scene.dump());
  };
  const std::vector<Vec3> fromXml = test::renderFilm(xmlPath, "pt"), fromJson = test::renderFilm(twin(0.75), "pt");
  ASSERT_EQ(fromXml.size(), 144u);
  size_t differing = 0, lit = 0;
  for (size_t i = 0; i < fromXml.size(); ++i) {
    differing += fromXml[i] != fromJson[i];
    lit += fromXml[i].y > 0.0f;
  }
  EXPECT_EQ(differing, 0u) << "bit-identical pixels expected";
  EXPECT_GT(lit, 30u);  // both spheres
  // The comparison sees the medium: another σ_s changes the image.
  const std::vector<Vec3> other = test::renderFilm(twin(0.7), "pt");
  size_t changed = 0;
  for (size_t i = 0; i < other.size(); ++i) changed += other[i] != fromXml[i];
  EXPECT_GT(changed, 10u);
}

}  // namespace
// Mitsuba's diffuse, conductors and plastics are black from behind: one-sided surfaces; inside a
// twosided they reflect on both sides; inside a wrapper (mask) both sides, with a note.
TEST_F(MitsubaImport, OneSidedBsdfsAreOneSidedSurfaces) {
  const auto t = translate(std::string(kLight) + R"(
    <bsdf type="diffuse" id="front"/>
    <bsdf type="twosided" id="both"><bsdf type="roughconductor"/></bsdf>
    <bsdf type="mask" id="cut"><bsdf type="plastic"/></bsdf>
    <bsdf type="dielectric" id="glass"/>
    <shape type="rectangle"><ref id="front"/></shape>)");
  const json& m = t.scene["materials"];
  EXPECT_EQ(m["front"].value("one_sided", false), true);
  EXPECT_EQ(m["both"].value("one_sided", false), false);
  EXPECT_EQ(m["cut"].value("one_sided", false), false);
  EXPECT_FALSE(m["cut"]["material"].contains("one_sided"));
  EXPECT_EQ(m["glass"].value("one_sided", false), false);
  bool noted = false;
  for (const std::string& n : t.notes) noted = noted || n.find("one-sided in Mitsuba") != std::string::npos;
  EXPECT_TRUE(noted);
}

}  // namespace kasha
