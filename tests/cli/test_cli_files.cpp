// `kasha` on the files a user can give it (issue 15), as a separate process: one case per class of
// problem, each with its exit code (1 bad input, 2 a command-line mistake) and its one-line
// message, and nothing written (no output, no temporary file) when it refuses.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/process.h"
#include "tests/expect_contains.h"
#include "tests/ply_files.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

// 8×8 pixels, 1 sample: a lambertian floor under an emissive rectangle, its reflectance from a CSV.
const char* kScene = R"({
  "render": {"spp": 1, "max_depth": 2},
  "camera": {"position": [0, 1, -4], "look_at": [0, 1, 0], "fov": 50, "resolution": [8, 8]},
  "materials": {"white": {"type": "lambertian", "reflectance": {"type": "file", "file": "grey.csv", "outside": "clamp"}}},
  "shapes": [
    {"type": "rectangle", "center": [0, 0, 0], "u": [0, 0, 2], "v": [2, 0, 0], "material": "white"},
    {"type": "rectangle", "center": [0, 1.5, 2], "u": [1, 0, 0], "v": [0, 1, 0], "material": "white",
     "emission": {"radiance": "D65", "two_sided": true}}
  ]
})";

class CliFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = (fs::path(::testing::TempDir()) / ("kasha_cli_files." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
    scene = write("scene.json", kScene);
    csv = write("grey.csv", "wavelength,r\n380,0.5\n780,0.5\n");
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir + "/" + name, std::ios::binary) << text;
    return dir + "/" + name;
  }
  test::Finished run(const std::vector<std::string>& args) const {
    return test::runKasha(args, dir + "/../" + std::to_string(++runs_), 60.0);
  }
  // `kasha args` exits with `code` and one line "kasha: error: ..." containing `message`.
  void expectRefused(const std::vector<std::string>& args, int code, const std::string& message) const {
    const test::Finished r = run(args);
    EXPECT_EQ(r.code, code) << r.err;
    const std::vector<std::string> lines = test::textLines(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("kasha: error: ", 0), 0u) << lines[0];
    EXPECT_CONTAINS(lines[0], message);
  }
  // The scene as JSON and as Mitsuba XML, each with the PLY file `ply` as a mesh: {json, xml}.
  std::vector<std::string> plyScenes(const std::string& ply) const {
    std::string json = kScene;
    json.insert(json.find("\"shapes\": [") + 11,
                "{\"type\": \"mesh\", \"file\": \"" + ply + "\", \"translate\": [0, 0.5, 0], \"material\": \"white\"},");
    const std::string xml = R"(<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 1, -4" target="0, 0.5, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="1"/></emitter>
  <shape type="ply"><string name="filename" value=")" + ply + R"("/><boolean name="face_normals" value="true"/>
    <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
</scene>
)";
    return {write("ply_scene.json", json), write("ply_scene.xml", xml)};
  }
  std::vector<std::string> entries() const {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
  }
  std::string dir, scene, csv;
  mutable int runs_ = 0;
};

TEST_F(CliFiles, NonRegularInputsAreRefusedAtOnce) {
  const std::string fifo = dir + "/fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Each would block forever reading a FIFO nobody writes to (run() kills it after 60 s).
  expectRefused({"render", fifo, "-q"}, 1, fifo + ": cannot open scene file (a FIFO, not a regular file)");
  expectRefused({"metrics", fifo, fifo}, 1, fifo + ": cannot open image file (a FIFO, not a regular file)");
  expectRefused({"render", "/dev/zero", "-q"}, 1, "/dev/zero: cannot open scene file (a character device, not a regular file)");
  nlohmann::json j = nlohmann::json::parse(kScene);
  j["materials"]["white"] = {{"type", "file"}, {"file", "fifo.json"}};
  write("mat.json", j.dump());
  expectRefused({"render", dir + "/mat.json", "-q"}, 1, fifo + ": cannot open material file (a FIFO, not a regular file)");
}

TEST_F(CliFiles, OutputProblemsAreFoundBeforeTheFirstSample) {
  fs::create_directories(dir + "/folder");
  fs::create_directories(dir + "/dir.exr");
  const std::vector<std::string> before = entries();
  expectRefused({"render", scene, "-q", "-o", dir + "/folder"}, 2, dir + "/folder: -o: must end in .exr");
  expectRefused({"render", scene, "-q", "-o", dir + "/folder.exr/x.exr"}, 2, "does not exist");
  expectRefused({"render", scene, "-q", "-o", dir + "/dir.exr"}, 2, dir + "/dir.exr: -o: is a directory");
  // -o x.png used to write the EXR to x.png and then the PNG over it.
  expectRefused({"render", scene, "-q", "-o", dir + "/x.png"}, 2, dir + "/x.png: -o: must end in .exr");
  expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--png", dir + "/x.exr"}, 2,
                dir + "/x.exr: --png: must end in .png");
  expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--png", dir + "/x.stats.json"}, 2, "must end in .png");
  // Outputs that name an input of the render, or each other.
  expectRefused({"render", scene, "-q", "-o", dir + "/scene.exr", "--png", csv}, 2, csv + ": --png: must end in .png");
  const std::string png = write("grey.png", "");
  fs::remove(png);
  fs::create_symlink(csv, png);
  expectRefused({"render", scene, "-q", "-o", dir + "/y.exr", "--png", png}, 2,
                png + ": --png: is one of the inputs; it would be overwritten");
  fs::remove(png);
  expectRefused({"render", scene, "-q", "-o", dir + "/y.exr", "--checkpoint", scene}, 2,
                scene + ": --checkpoint: is one of the inputs; it would be overwritten");
  expectRefused({"render", scene, "-q", "-o", dir + "/y.exr", "--checkpoint", dir + "/y.png"}, 2,
                dir + "/y.png: --checkpoint: is also the output of -o (its PNG); each output needs its own file");
  expectRefused({"render", scene, "-q", "-o", dir + "/y.exr", "--checkpoint", dir + "/folder"}, 2,
                dir + "/folder: --checkpoint: is a directory");
  EXPECT_EQ(entries(), before);  // nothing written, no temporary file
}

TEST_F(CliFiles, AFullDiskFailsTheRenderAndLeavesNoFile) {
  // The file size limit stands in for a full disk: write() fails with EFBIG. One block (512 bytes
  // in /bin/sh, dash) holds the one-line message but not the EXR.
  const std::string err = dir + "/../full.stderr";
  const std::string sh = "trap '' XFSZ; ulimit -f 1; exec '" + test::kKashaBinary + "' render '" + scene + "' -q -o '" +
                         dir + "/full.exr' 2>'" + err + "'";
  const std::vector<std::string> before = entries();
  const int status = std::system(sh.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(test::readTextFile(err), "kasha: error: cannot write '" + dir + "/full.exr': write failed (File too large)\n");
  std::vector<std::string> after = entries();
  // The EXR (over 512 bytes) failed; nothing else was written after it, nothing is left half.
  EXPECT_EQ(after, before);
}

TEST_F(CliFiles, ConcurrentRendersToOneNameLeaveOneWholeFile) {
  const std::string out = dir + "/same.exr";
  const test::Child a = test::spawnKasha({"render", scene, "-q", "-o", out, "--spp", "4"}, dir + "/../a");
  const test::Child b = test::spawnKasha({"render", scene, "-q", "-o", out, "--spp", "4", "--seed", "9"}, dir + "/../b");
  EXPECT_EQ(test::waitChild(a, 60.0), 0);
  EXPECT_EQ(test::waitChild(b, 60.0), 0);
  // One of the two, whole: kasha metrics reads it against itself.
  const test::Finished m = run({"metrics", out, out});
  EXPECT_EQ(m.code, 0) << m.err;
  EXPECT_CONTAINS(m.out, "\"rmse\":0.0");
  EXPECT_EQ(entries(), (std::vector<std::string>{"grey.csv", "same.exr", "same.png", "same.stats.json", "scene.json"}));
}

// The files a scene names are part of what a checkpoint continues (and what MPI ranks must agree
// on, tests/mpi): the same scene text with another reflectance file is another scene.
TEST_F(CliFiles, ACheckpointIsOfTheSceneFilesContentNotOnlyItsText) {
  const std::string ckpt = dir + "/render.ckpt";
  const test::Finished first = run({"render", scene, "-q", "--no-png", "-o", dir + "/a.exr", "--checkpoint", ckpt});
  ASSERT_EQ(first.code, 0) << first.err;
  const test::Finished same = run({"render", scene, "-q", "--no-png", "--spp", "2", "-o", dir + "/b.exr", "--resume", ckpt});
  EXPECT_EQ(same.code, 0) << same.err;
  write("grey.csv", "wavelength,r\n380,0.6\n780,0.6\n");
  expectRefused({"render", scene, "-q", "--no-png", "--spp", "3", "-o", dir + "/c.exr", "--resume", ckpt}, 1,
                "checkpoint was made with scene_hash");
  EXPECT_FALSE(fs::exists(dir + "/c.exr"));
}

// -D NAME=VALUE gives a Mitsuba scene's $NAME (the documentation scenes' $spp, $integrator): it
// wins over a <default>, and a parameter with neither is the importer's error.
TEST_F(CliFiles, MitsubaParametersFromTheCommandLine) {
  const std::string xml = write("params.xml", R"(<scene version="3.0.0">
  <default name="res" value="8"/>
  <sensor type="perspective"><float name="fov" value="$fov"/>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
  </sensor>
  <emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="1"/></emitter>
  <shape type="rectangle"><bsdf type="diffuse"/></shape>
</scene>
)");
  const test::Finished r = run({"render", xml, "-q", "--no-png", "-o", dir + "/p.exr", "-D", "fov=40", "-D", "spp=2", "-D", "res=4"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto stats = nlohmann::json::parse(test::readTextFile(dir + "/p.stats.json"));
  EXPECT_EQ(stats["spp"], 2);
  EXPECT_EQ(stats["resolution"], nlohmann::json({4, 4}));
  expectRefused({"render", xml, "-q", "--no-png", "-o", dir + "/q.exr", "-D", "fov=40"}, 1,
                "parameter '$spp' has no <default> value");
  expectRefused({"render", xml, "-q", "-D", "fov"}, 2, "-D fov: expected NAME=VALUE");
  expectRefused({"render", xml, "-q", "-D", "f-v=1"}, 2, "-D f-v=1: expected NAME=VALUE");
  expectRefused({"render", scene, "-q", "-D", "fov=40"}, 2, "-D fov=40: sets a parameter of a Mitsuba XML scene, not of");
  EXPECT_FALSE(fs::exists(dir + "/q.exr"));
}

// -a DIR: a directory where a Mitsuba scene's files are also looked for (Mitsuba's -a), as
// Mitsuba's documentation scenes without a <path> need for the shared meshes.
TEST_F(CliFiles, MitsubaSearchPathsFromTheCommandLine) {
  fs::create_directories(dir + "/shared/meshes");
  write("shared/meshes/tri.obj", "v -1 -1 0\nv 1 -1 0\nv -1 1 0\nf 1 2 3\n");
  const std::string xml = write("uses_shared.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <emitter type="point"><point name="position" x="0" y="3" z="0"/><spectrum name="intensity" value="1"/></emitter>
  <shape type="obj"><string name="filename" value="meshes/tri.obj"/><boolean name="face_normals" value="true"/>
    <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
</scene>
)");
  expectRefused({"render", xml, "-q", "--no-png", "--spp", "1", "-o", dir + "/a.exr"}, 1, "meshes/tri.obj: cannot open mesh file");
  const test::Finished r = run({"render", xml, "-q", "--no-png", "--spp", "1", "-o", dir + "/b.exr", "-a", dir + "/shared"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/b.exr"));
  expectRefused({"render", xml, "-q", "-a", dir + "/none"}, 2, "/none: no such directory");
  expectRefused({"render", scene, "-q", "-a", dir + "/shared"}, 2, "adds a search path for a Mitsuba XML scene, not for");
  EXPECT_FALSE(fs::exists(dir + "/a.exr"));
}

TEST_F(CliFiles, TheSceneChoosesTheIntegratorAndTheCommandLineOverrides) {
  std::string text = kScene;
  text.replace(text.find("\"spp\": 1"), 8, "\"spp\": 1, \"integrator\": \"lt\"");
  const std::string lt = write("lt.json", text);
  const auto integratorOf = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", lt, "-q", "--no-png", "-o", dir + "/i.exr"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::Finished r = run(args);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(test::readTextFile(dir + "/i.stats.json"))["integrator"].get<std::string>();
  };
  EXPECT_EQ(integratorOf({}), "lt");
  EXPECT_EQ(integratorOf({"--integrator", "pt"}), "pt");
  EXPECT_EQ(integratorOf({"--set", "integrator=bdpt"}), "bdpt");
  text.replace(text.find("\"lt\""), 4, "\"nope\"");
  const std::string nope = write("nope.json", text);
  expectRefused({"render", nope, "-q"}, 1, nope + ": /render/integrator: unknown integrator 'nope' (pt, lt, bdpt");
  expectRefused({"render", scene, "-q", "--set", "integrator=nope"}, 2, "--set integrator=nope: unknown integrator 'nope'");
}

TEST_F(CliFiles, CommandLineMistakesExitWith2) {
  expectRefused({"render", scene, "-q", "--integrator", "foo"}, 2, "unknown integrator 'foo'");
  expectRefused({"render", scene, "-q", "--light-sampling", "uniform"}, 2, "--light-sampling: ");
  // --set KEY=VALUE: the loader checks the value; settings the integrator does not read are refused.
  expectRefused({"render", scene, "-q", "--set", "fluorescent_lanes=sideways"}, 2, "--set fluorescent_lanes=sideways: ");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "fluorescent_lanes=end"}, 2,
                "--set fluorescent_lanes=end: fluorescent_lanes 'end' is an experiment of pt and lt, not of ppm");
  expectRefused({"render", scene, "-q", "--set", "ppm.direct=photons"}, 2, "--set ppm.direct=photons: only for --integrator ppm");
  expectRefused({"render", scene, "-q", "--integrator", "vcm", "--set", "ppm.direct=photons"}, 2,
                "--set ppm.direct=photons: only for --integrator ppm");
  expectRefused({"render", scene, "-q", "--integrator", "vcm", "--set", "bdpt.families=both"}, 2,
                "--set bdpt.families=both: only for --integrator bdpt");
  expectRefused({"render", scene, "-q", "--integrator", "bpm", "--set", "vcm.paths=camera"}, 2,
                "--set vcm.paths=camera: only for --integrator vcm");
  expectRefused({"render", scene, "-q", "--integrator", "vc", "--set", "vcm.radius=0.1"}, 2,
                "--set vcm.radius=0.1: only for --integrator vcm, bpm");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "vcm.photons_per_pass=100"}, 2,
                "--set vcm.photons_per_pass=100: only for --integrator vcm, vc, bpm");
  expectRefused({"render", scene, "-q", "--integrator", "vcm", "--set", "vcm.paths=light"}, 2, "--set vcm.paths=light: ");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "ppm.nee_wavelengths=camera,cmf"}, 2,
                "--set ppm.nee_wavelengths=camera,cmf: ");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "ppm.direct=both"}, 2,
                "--set ppm.direct=both: expected \"nee-elastic\", \"nee\" or \"photons\"");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "ppm.alpha=7"}, 2, "--set ppm.alpha=7: must be in (1/3, 1)");
  expectRefused({"render", scene, "-q", "--integrator", "ppm", "--set", "ppm.nee_wavelengths=emission"}, 2,
                "--set ppm.nee_wavelengths=emission: 'emission': wavelength strategy 'emission': the scene has no fluorescent material");
  expectRefused({"render", scene, "-q", "--set", "no_such_setting=1"}, 2, "--set no_such_setting=1: ");
  expectRefused({"render", scene, "-q", "--set", "spp"}, 2, "--set spp: expected KEY=VALUE");
  expectRefused({"render", scene, "-q", "--set", "ppm..alpha=1"}, 2, "--set ppm..alpha=1: ");
  expectRefused({"render", scene, "-q", "--set", "seed=2", "--set", "seed.x=1"}, 2, "--set seed.x=1: ");
  std::string text = kScene;
  text.replace(text.find("\"max_depth\": 2"), 14, "\"max_depth\": 2, \"ppm\": {\"nee_wavelengths\": \"emission\"}");
  const std::string ppmScene = write("ppm.json", text);
  expectRefused({"render", ppmScene, "-q", "--integrator", "ppm"}, 1,
                ppmScene + ": /render/ppm/nee_wavelengths: 'emission': wavelength strategy 'emission'");
  expectRefused({"render", scene, "-q", "--seed", "3000000000"}, 2, "--seed: must be at most 2147483647, got '3000000000'");
  expectRefused({"compare", scene, "--reference", dir + "/ref.exr"}, 2, "give a time budget or a sample count");
  expectRefused({"compare", scene, "--reference", dir + "/ref.exr", "--spp", "1", "--integrators", "pt,foo"}, 2,
                "unknown integrator 'foo'");
  expectRefused({"matrix", scene, "--material", "none"}, 2, "--material: none: no material of that name");
}

// Hostile scenes (issue 36): nesting deep enough to overflow the stack, control characters meant
// for the terminal; one line and exit code 1 each.
TEST_F(CliFiles, HostileScenesGetOneLine) {
  const auto nested = [](const std::string& open, const std::string& inner, const std::string& close, int levels) {
    std::string s;
    for (int i = 0; i < levels; ++i) s += open;
    s += inner;
    for (int i = 0; i < levels; ++i) s += close;
    return s;
  };
  const std::string sensor = R"(<sensor type="perspective"><float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0"/></transform></sensor>)";
  const std::string xml = write("deep.xml", "<scene version=\"3.0.0\">" + sensor + "\n<shape type=\"rectangle\">" +
                                                nested("<bsdf type=\"twosided\">", "<bsdf type=\"diffuse\"/>", "</bsdf>", 100000) +
                                                "</shape></scene>");
  expectRefused({"render", xml, "-q"}, 1, xml + ":3: bsdf 'twosided': nested deeper than 64 levels");
  const std::string json = write("deep.json", "{\"camera\": " + nested("[", "0", "]", 100000) + "}");
  expectRefused({"render", json, "-q"}, 1, json + ": /camera/0/0/0/");
  expectRefused({"render", json, "-q"}, 1, ": nested deeper than 64 levels");
  // --set's value is JSON read as strictly as a scene file's (50 000 levels: one argument holds
  // at most 128 KiB).
  expectRefused({"render", scene, "-q", "--set", "ppm.alpha=" + nested("[", "", "]", 50000)}, 2,
                "nested deeper than 64 levels");
  expectRefused({"render", scene, "-q", "--set", "ppm={\"alpha\": 0.5, \"alpha\": 0.6}"}, 2, "duplicate key 'alpha'");
  // ESC [2J clears the screen, BEL rings; the message shows them as \x1b and \x07.
  const std::string esc = write("esc.xml", "<scene version=\"3.0.0\">" + sensor +
                                               "<shape type=\"rectangle\"><ref id=\"\x1b[2J\x07\"/></shape></scene>");
  const test::Finished r = run({"render", esc, "-q"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_CONTAINS(r.err, "kasha: error: " + esc + ":2: shape 'rectangle': no <bsdf id=\"\\x1b[2J\\x07\"> or area <emitter id=\"\\x1b[2J\\x07\"> before this reference\n");
  EXPECT_EQ(r.err.find_first_of("\x1b\x07"), std::string::npos);
}

// An output the system refuses although access(2) allows it (root may "write" to /proc), and a
// spectral step too small to be one: refused before the first sample.
TEST_F(CliFiles, OutputsAndStepsThatCannotWorkAreRefusedBeforeRendering) {
  expectRefused({"render", scene, "-q", "-o", "/proc/kasha_test.exr"}, 2,
                "/proc/kasha_test.exr: -o: directory '/proc' is not writable: cannot create a temporary file beside it");
  expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--checkpoint", "/proc/self/x.ckpt"}, 2,
                "/proc/self/x.ckpt: --checkpoint: directory '/proc/self' is not writable");
  // 1e-300 used to become 0 (a float), taken as no spectral bins at all.
  expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--spectral-step", "1e-300"}, 2,
                "--spectral-step: spectral step: 1e-300 nm makes more than 4096 bins of the scene's wavelength range");
  expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--spectral-step", "0.01"}, 2, "makes more than 4096 bins");
  for (const char* bad : {"nan", "inf", "-10", "0"})
    expectRefused({"render", scene, "-q", "-o", dir + "/x.exr", "--spectral-step", bad}, 2, "--spectral-step: ");
  EXPECT_FALSE(fs::exists(dir + "/x.exr"));
}

TEST_F(CliFiles, ExtractNeverOverwritesItsOwnInput) {
  const std::string sample = write("m_spectra.csv", "wavelength,ex_400,ex_450\n400,0.5,0\n450,0.1,0.5\n500,0.05,0.1\n");
  const std::string before = test::readTextFile(sample);
  expectRefused({"extract", "--sample", sample, "-o", dir + "/m.json"}, 2,
                sample + ": -o (its spectra): is one of the inputs; it would be overwritten");
  EXPECT_EQ(test::readTextFile(sample), before);
}

TEST_F(CliFiles, BadInputFilesExitWith1) {
  // Duplicate keys, a mesh with a non-number, an image with NaN pixels.
  write("dup.json", std::string(kScene).insert(1, "\n  \"render\": {\"spp\": 4},"));
  expectRefused({"render", dir + "/dup.json", "-q"}, 1, dir + "/dup.json: /render: duplicate key 'render'");
  write("m.obj", "v 0 0 0\nv a b c\nv 0 1 0\nf 1 2 3\n");
  std::string mesh = kScene;
  mesh.insert(mesh.find("\"shapes\": [") + 11, "{\"type\": \"mesh\", \"file\": \"m.obj\", \"material\": \"white\"},");
  write("mesh.json", mesh);
  expectRefused({"render", dir + "/mesh.json", "-q"}, 1,
                dir + "/mesh.json: /shapes/0/file: " + dir + "/m.obj:2: 'a' is not a finite number (v component 1)");
  expectRefused({"extract", "--sample", dir + "/none.csv", "-o", dir + "/m.json"}, 1,
                dir + "/none.csv: cannot open spectrum file (No such file or directory)");
}

// Issue 36: hostile PLY files through a JSON "mesh" shape and a Mitsuba <shape type="ply">: each
// is exit code 1, one line naming the file, the field and the reason, within seconds, and nothing
// written. Before the check, assimp crashed (truncated binary, a face of no vertices), looped
// forever (a header cut short), took 4 GB (a count far beyond the file) or rendered (ASCII with
// fewer vertex lines than declared).
TEST_F(CliFiles, HostilePlyMeshesAreRefusedWithOneLine) {
  const std::string binary = test::binaryPlyTetrahedron(false);
  const struct {
    std::string bytes, message;
  } cases[] = {
      {binary.substr(0, binary.size() - 7), "m.ply: face 3: the file ends inside it (it is truncated)"},
      {test::plyHeader("ascii", 4, 2) + test::kPlyAsciiVertices + "3 0 1 2\n0\n",
       "m.ply:15: face 1: has 0 vertex indices; a face needs at least 3"},
      {test::plyHeader("binary_little_endian", 4, 2) + test::PlyBinary().vertices().face({0, 1, 2}).face({0, 1}).bytes,
       "m.ply: face 1: has 2 vertex indices; a face needs at least 3"},
      {test::plyHeader("ascii", 4, 1) + test::kPlyAsciiVertices + "3 0 1 4\n",
       "m.ply:14: face 0: vertex index 4 is not below the number of vertices, 4"},
      {"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n",
       "m.ply: header: the file ends before an 'end_header' line"},
      {test::plyHeader("ascii", 5, 4) + test::kPlyAsciiVertices + test::kPlyAsciiFaces,
       "m.ply:14: vertex 4: has 4 numbers, more than its properties take (3)"},
      {test::plyHeader("binary_little_endian", 300000000, 1) + std::string(40, '\0'),
       "m.ply: element vertex: 300000000 declared need at least 3.35 GiB of data"},
  };
  for (const auto& c : cases) {
    write("m.ply", c.bytes);
    for (const std::string& scene : plyScenes(dir + "/m.ply")) {
      const std::vector<std::string> before = entries();
      const auto start = std::chrono::steady_clock::now();
      expectRefused({"render", scene, "-q", "--spp", "1", "--memory-limit", "1G", "-o", dir + "/out.exr"}, 1, dir + "/" + c.message);
      EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << c.message;
      EXPECT_EQ(entries(), before) << c.message;  // nothing written
    }
  }
}

TEST_F(CliFiles, ValidPlyMeshesRender) {
  for (const std::string& ply :
       {test::asciiPlyTetrahedron(), test::binaryPlyTetrahedron(false), test::binaryPlyTetrahedron(true)}) {
    write("m.ply", ply);
    for (const std::string& scene : plyScenes(dir + "/m.ply")) {
      const test::Finished r = run({"render", scene, "-q", "--spp", "1", "-o", dir + "/out.exr"});
      EXPECT_EQ(r.code, 0) << scene << ": " << r.err;
      EXPECT_TRUE(fs::exists(dir + "/out.exr")) << scene;
      fs::remove(dir + "/out.exr");
    }
  }
}


}  // namespace
}  // namespace kasha
