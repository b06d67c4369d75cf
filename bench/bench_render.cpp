// Render benchmark on the default Cornell scene: kasha's path tracer as `kasha render` runs it (its
// default wavelength lanes; samples/s, rays/s) beside a plain Embree loop that casts the same
// numbers of closest-hit and occlusion rays, random and incoherent, into the same Embree scene on
// the same threads. The ratio says how much of the time is Embree's and how much is kasha's.
#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "core/sampling.h"
#include "scene/scene_loader.h"
#include "integrators/integrator_factory.h"
#include "integrators/render_loop.h"

using namespace kasha;

namespace {

// Casts `closest` closest-hit and `shadow` occlusion rays with origins uniform in the scene's
// bounding box and uniform directions; returns seconds.
double plainEmbreeLoop(const Scene& scene, uint64_t closest, uint64_t shadow, uint64_t& hits) {
  const RTCScene handle = scene.accel->handle();
  const SceneBounds b = scene.accel->bounds();
  const uint64_t total = closest + shadow, chunk = 4096;
  std::atomic<uint64_t> hitCount{0};
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(uint64_t(0), (total + chunk - 1) / chunk, [&](uint64_t c) {
    Rng rng(mixBits(c + 17), c);
    uint64_t localHits = 0;
    for (uint64_t i = c * chunk; i < std::min(total, (c + 1) * chunk); ++i) {
      const Vec3 o = b.center + 0.5f * b.radius * (2.0f * Vec3(rng.uniform(), rng.uniform(), rng.uniform()) - 1.0f);
      const Vec3 d = sampleUniformSphere(Vec2(rng.uniform(), rng.uniform()));
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      if (i < closest) {
        RTCRayHit rh{};
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
        rh.ray.tfar = kInf;
        rh.ray.mask = 0xFFFFFFFF;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(handle, &ctx, &rh);
        localHits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      } else {
        RTCRay r{};
        r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
        r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
        r.tfar = b.radius * rng.uniform();
        r.mask = 0xFFFFFFFF;
        rtcOccluded1(handle, &ctx, &r);
        localHits += r.tfar < 0.0f;
      }
    }
    hitCount.fetch_add(localHits);
  });
  hits = hitCount.load();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr const char* kUsage =
    "usage: bench_render [SCENE.json] [--spp N] [--json OUT.json]\n"
    "  Renders SCENE (default: scenes/cornell_fluorescent.json) with pt on all cores and casts the\n"
    "  same numbers of closest-hit and shadow rays in a plain Embree loop; prints both ray rates.\n";

int run(int argc, char** argv) {
  std::string scenePath = std::string(KASHA_SOURCE_DIR) + "/scenes/cornell_fluorescent.json", jsonOut;
  int spp = 16;
  for (int i = 1; i < argc; ++i) {
    const bool hasValue = i + 1 < argc;
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (!std::strcmp(argv[i], "--spp") && hasValue) {
      spp = std::atoi(argv[++i]);
      if (spp < 1) throw std::invalid_argument(std::string("--spp: must be a positive integer, not '") + argv[i] + "'");
    } else if (!std::strcmp(argv[i], "--json") && hasValue) {
      jsonOut = argv[++i];
    } else if (argv[i][0] == '-') {
      throw std::invalid_argument(std::string(argv[i]) + ": unknown option or missing value");
    } else {
      scenePath = argv[i];
    }
  }
  auto scene = loadScene(scenePath);
  const std::unique_ptr<Integrator> pt = makeIntegrator("pt", *scene, scene->render);  // as `kasha render` builds it
  Film film(scene->camera.width(), scene->camera.height());
  RenderOptions opt;
  opt.spp = spp;
  opt.seed = 1;
  const RenderStats st = render(*scene, *pt, film, opt);
  uint64_t hits = 0;
  const double plain = plainEmbreeLoop(*scene, st.closestRays, st.shadowRays, hits);
  const double plainRate = double(st.rays) / plain;
  std::printf("scene            %s (%dx%d, %d spp, %d threads, %d lanes)\n", scenePath.c_str(), film.width(), film.height(),
              st.spp, st.threads, pt->lanes());
  std::printf("kasha pt         %.2f s  %.4g samples/s  %.4g rays/s  (%llu closest-hit + %llu shadow rays)\n", st.seconds,
              st.samplesPerSecond, st.raysPerSecond, (unsigned long long)st.closestRays, (unsigned long long)st.shadowRays);
  std::printf("plain Embree     %.2f s  %.4g rays/s  (same ray counts, random incoherent rays)\n", plain, plainRate);
  std::printf("ratio            kasha ray rate = %.2f x plain Embree; Embree's share of kasha's time <= %.0f%%\n",
              st.raysPerSecond / plainRate, 100.0 * plain / st.seconds);
  if (!jsonOut.empty()) {
    nlohmann::json j = toJson(st);
    j["plain_embree_seconds"] = plain;
    j["plain_embree_rays_per_second"] = plainRate;
    j["ratio"] = st.raysPerSecond / plainRate;
    std::ofstream(jsonOut) << j.dump(2) << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: error: %s\n%s", e.what(), kUsage);
    return 2;
  }
}
