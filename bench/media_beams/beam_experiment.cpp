// Photon beams against photon points in a fluorescent medium (issue 34, "measure whether beams
// earn their cost before keeping them"; docs/media-beams.md): renders, at equal time, the light that
// light subpaths bring into the medium and that re-emerges towards the camera after one event on
// the camera ray's first segment through a medium, with three estimators of the same light
// subpaths (Jarosz et al. 2008, "The beam radiance estimate"; Jarosz et al. 2011, "Progressive
// photon beams"; Křivánek et al. 2014, UPBP):
//   points:    each light subpath's collisions in the medium (photon points) merged at one point
//              drawn uniformly on the camera ray's segment, within a ball of radius r_p (P2P, 3D
//              kernel; vcm's volume merges, unweighted);
//   pointbeam: the same photon points against the whole camera segment (P2B, the beam radiance
//              estimate): a point within r_b of the camera ray adds power·f·T_c/(π r_b²);
//   beams:     each light subpath's flights through the medium (short photon beams: the flight
//              from a vertex to the next, whose power is the throughput leaving the vertex, since a
//              flight sampled by σ_t reaches s with probability T(s)) against the whole camera
//              segment (B2B): a beam within r_b of the camera ray adds power·f·T_c·(chord through the
//              beam's cylinder)/(π r_b²), the chord 2√(r_b² − d²)/sin θ (Jarosz et al. 2011 eq. 8
//              with a cylindrical kernel integrated along the query ray).
// Each shrinks its radius by Knaus and Zwicker's schedule for its kernel's dimension (3, 2 and 2).
// The camera ray reaches the medium directly or through specular surfaces; where it meets anything
// else first the images are black. The scene must have one medium. It writes points.exr,
// pointbeam.exr and beams.exr.
//   beam_experiment SCENE.json SECONDS SEED R_POINTS R_BEAMS OUTDIR
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/film.h"
#include "core/image_output.h"
#include "integrators/bidirectional/subpaths.h"
#include "integrators/point_map_impl.h"
#include "integrators/points_near_segments.h"
#include "integrators/beams_near_segments.h"
#include "integrators/progressive_schedule.h"
#include "scene/scene_loader.h"
#include "scene/wavelength_strategy.h"

namespace kasha {
namespace {

constexpr float kAlpha = 2.0f / 3.0f;

struct Beam {
  Vec3 a, d;          // start and unit direction
  float length;       // to the flight's end (a collision or a surface)
  float lambda, power;
  int medium;
};

struct Point {
  float p[3];  // first: a PointMap record
  float lambda, power;
  int medium;
  Vec3 position() const { return Vec3(p[0], p[1], p[2]); }
};

// The beams and points of `count` light subpaths of the own family (their own wavelengths).
void traceLight(const Scene& scene, const bidir::Lanes& lanes, const bidir::WalkSettings& walk, uint64_t seed,
                int pass, size_t count, std::vector<Beam>& beams, std::vector<Point>& points) {
  std::vector<std::vector<Beam>> beamsOf(count);
  std::vector<std::vector<Point>> pointsOf(count);
  tbb::parallel_for(size_t(0), count, [&](size_t i) {
    thread_local std::vector<bidir::PathVertex> L;
    Sampler rng(SamplerKind::Independent, seed, i, uint32_t(pass));
    RayCounter rays;
    L.clear();
    bidir::traceLightSubpath(scene, bidir::LightFamily::Own, lanes, walk, rng, rays, L);
    for (size_t j = 1; j < L.size(); ++j) {
      const bidir::PathVertex& v = L[j];
      if (!v.arrival.inMedia || !(v.beta[0] > 0.0f)) continue;
      // The flight's medium: a collision's own; a flight that left the medium for a surface (the
      // cell's wall, across the gap between it and the solution) ran through the scene's one medium.
      const int medium = v.inMedium() ? v.medium : 0;
      const float sigmaT = scene.media[size_t(medium)]->sigmaT(v.lambda);
      // β arriving at a collision is the throughput leaving the previous vertex over σ_t (T/p).
      const float leaving = v.inMedium() ? v.beta[0] * sigmaT : v.beta[0];
      const Vec3 span = v.p - L[j - 1].p;
      const float length = glm::length(span);
      if (length > 0.0f) beamsOf[i].push_back({L[j - 1].p, span / length, length, v.lambda, leaving, medium});
      if (v.inMedium()) pointsOf[i].push_back({{v.p.x, v.p.y, v.p.z}, v.lambda, v.beta[0], v.medium});
    }
  });
  beams.clear(), points.clear();
  for (size_t i = 0; i < count; ++i) {
    beams.insert(beams.end(), beamsOf[i].begin(), beamsOf[i].end());
    points.insert(points.end(), pointsOf[i].begin(), pointsOf[i].end());
  }
}

// The camera ray's first segment through a medium, [0, length] along `ray`: reached across
// index-matched boundaries and specular surfaces (each event drawn by the surface's own sampling at
// the camera's wavelength, its weight f·|cos|/pdf in `weight`); medium −1 where the camera ray meets
// anything else first (a diffuse surface, nothing, a wavelength-changing event).
struct Segment {
  Ray ray;
  float length = 0.0f, weight = 1.0f;
  int medium = -1;
};

Segment firstMediumSegment(const Scene& scene, Ray ray, float lambda, Sampler& rng) {
  constexpr int kMaxEvents = 16;
  int medium = scene.cameraMedium;
  float weight = 1.0f;
  for (int event = 0; event < kMaxEvents; ++event) {
    const std::optional<Hit> hit = scene.accel->intersect(ray);
    if (!hit) return {};
    if (medium >= 0) return {ray, hit->t, weight, medium};
    Vec3 d = ray.d;
    if (!scene.shapes[hit->shape].isMediumBoundary()) {
      const Bsdf b = scene.bsdf(*hit, {&lambda, 1});
      if (!b.has(BsdfFlags::DeltaDirection)) return {};
      const std::optional<ScatterSample> s = b.sample(TransportMode::Radiance, b.toLocal(-ray.d), lambda, rng.uniform3());
      if (!s || !s->specular || s->lambda != lambda || !(s->pdf > 0.0f)) return {};
      weight *= s->f * std::abs(s->w.z) / s->pdf;
      d = b.toWorld(s->w);
    }
    medium = scene.mediumBeyond(*hit, d, medium);
    ray = Ray{offsetPoint(hit->p, hit->ng, d), d, kInf};
  }
  return {};
}

// f_fl(λ_i → λ_o) of a medium's collision kernel (docs/media.md eq. 4, isotropic: any directions).
float fluorescence(const Bsdf& kernel, float lambdaIn, float lambdaOut) {
  const Vec3 w(0.0f, 0.0f, 1.0f);
  return kernel.eval({TransportMode::Radiance, SpectralLobe::Fluorescent, lambdaIn, lambdaOut}, w, w);
}

// P2P: photon points, a query point; P2B: photon points, the query beam; B2B: photon beams, the
// query beam.
enum class Estimator { Points, PointsAlongQuery, Beams };

// Renders into `film` with `estimator` for `seconds`: per pass N = w·h light subpaths, one camera
// sample per pixel; returns the passes.
int render(const Scene& scene, Estimator estimator, double seconds, uint64_t seed, float r1, Film& film) {
  const int w = scene.camera.width(), h = scene.camera.height();
  const WavelengthStrategy light(scene.render.wavelengths.light, WavelengthSources(scene), WavelengthSite::LightStart);
  bidir::WalkSettings walk;
  walk.maxDepth = scene.render.maxDepth;
  walk.lightWavelengths = &light.density();
  bidir::LaneTables tables;
  const WavelengthStrategy sensor(scene.render.wavelengths.sensor, WavelengthSources(scene), WavelengthSite::Sensor);
  const bidir::Lanes lanes = bidir::sensorLanes(scene, sensor.density(), 0.5f, 1, tables);
  const size_t count = size_t(w) * size_t(h);
  const float lo = scene.range.min, width = scene.range.max - scene.range.min;
  int passes = 0;
  std::vector<Beam> beams;
  std::vector<Point> points;
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
    traceLight(scene, lanes, walk, seed, passes, count, beams, points);
    const float r = progressiveRadius(r1, kAlpha, passes + 1, estimator == Estimator::Points ? 3 : 2);
    std::unique_ptr<PointMap<Point>> map;
    std::unique_ptr<PointsNearSegments> nearQuery;
    std::unique_ptr<BeamsNearSegments> accel;
    if (estimator == Estimator::Points) {
      map = std::make_unique<PointMap<Point>>(points);
    } else if (estimator == Estimator::PointsAlongQuery) {
      std::vector<Vec3> positions;
      for (const Point& p : points) positions.push_back(p.position());
      nearQuery = std::make_unique<PointsNearSegments>(positions, r);
    } else {
      std::vector<BeamsNearSegments::Beam> segments;
      for (const Beam& b : beams) segments.push_back({b.a, b.d, b.length});
      accel = std::make_unique<BeamsNearSegments>(segments, r);
    }
    const float kernelNorm = estimator == Estimator::Points ? 1.0f / (4.0f / 3.0f * kPi * r * r * r) : 1.0f / (kPi * r * r);
    tbb::parallel_for(0, h, [&](int y) {
      std::vector<uint32_t> found;
      std::vector<PointsNearSegments::Found> nearPoints;
      for (int x = 0; x < w; ++x) {
        Sampler rng(SamplerKind::Independent, seed ^ 0x9e3779b97f4a7c15ULL, uint64_t(y) * w + x, uint32_t(passes));
        const Vec2 filmPos = scene.pixelFilter.filmPosition(Vec2(float(x), float(y)), rng.uniform2());
        const float lambdaOut = lo + width * rng.uniform();
        const Segment seg = firstMediumSegment(scene, scene.camera.generateRay(filmPos, rng.uniform2()), lambdaOut, rng);
        if (seg.medium < 0) continue;
        const Ray& ray = seg.ray;
        const float sigmaOut = scene.media[size_t(seg.medium)]->sigmaT(lambdaOut);
        const Bsdf collision = scene.mediumBsdf(seg.medium, ray.o);  // homogeneous: the same everywhere
        double radiance = 0.0;
        if (estimator == Estimator::Points) {
          const float t = seg.length * rng.uniform();
          const Vec3 at = ray.o + ray.d * t;
          const float camera = std::exp(-sigmaOut * t) * seg.length;  // T_c / p(t)
          for (size_t i : map->within(at, r)) {
            const Point& p = (*map)[i];
            if (p.medium == seg.medium) radiance += double(p.power) * fluorescence(collision, p.lambda, lambdaOut) * camera;
          }
        } else if (estimator == Estimator::PointsAlongQuery) {
          // Σ_p β_p·f·T_c(t_p)·K_2(d_p): the camera ray's integral of the points' ball kernel, blurred
          // across the ray only (the beam radiance estimate, Jarosz et al. 2008).
          nearQuery->near(ray.o, ray.d, seg.length, nearPoints);
          for (const PointsNearSegments::Found& f : nearPoints) {
            const Point& p = points[f.index];
            if (p.medium == seg.medium)
              radiance += double(p.power) * fluorescence(collision, p.lambda, lambdaOut) * std::exp(-sigmaOut * f.t);
          }
        } else {
          found.clear();
          accel->near(ray.o, ray.d, seg.length, found);
          for (uint32_t i : found) {
            const Beam& b = beams[i];
            if (b.medium != seg.medium) continue;
            // Closest points of the camera line o + t·c and the beam line a + s·d.
            const Vec3 c = ray.d, w0 = ray.o - b.a;
            const float cd = glm::dot(c, b.d), sin2 = 1.0f - cd * cd;
            if (!(sin2 > 1e-8f)) continue;
            const float t = (cd * glm::dot(w0, b.d) - glm::dot(w0, c)) / sin2;
            const float s = (glm::dot(w0, b.d) - cd * glm::dot(w0, c)) / sin2;
            if (t < 0.0f || t > seg.length || s < 0.0f || s > b.length) continue;
            const Vec3 gap = (ray.o + c * t) - (b.a + b.d * s);
            const float d2 = glm::dot(gap, gap);
            if (d2 >= r * r) continue;
            const float chord = 2.0f * std::sqrt(r * r - d2) / std::sqrt(sin2);
            radiance += double(b.power) * fluorescence(collision, b.lambda, lambdaOut) *
                        std::exp(-sigmaOut * t) * chord;
          }
        }
        radiance *= seg.weight;
        // Per light subpath of the pass, with the kernel; λ_o uniform: W(λ_o)·width.
        const float value = float(radiance) * kernelNorm / float(count) * width;
        film.add(x, y, Observer::cie1931().weight(lambdaOut) * value);
      }
    });
    ++passes;
  }
  film.setSamplesPerPixel(passes);
  return passes;
}

}  // namespace
}  // namespace kasha

int main(int argc, char** argv) {
  using namespace kasha;
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s SCENE.json SECONDS SEED R_POINTS R_BEAMS OUTDIR\n", argv[0]);
    std::fprintf(stderr, "  (R_BEAMS is also the first radius of the points along the query beam)\n");
    return 2;
  }
  try {
    const auto scene = loadScene(argv[1]);
    if (scene->media.size() != 1 || scene->media[0]->heterogeneous() || scene->media[0]->spatiallyVaryingAlbedo())
      throw std::invalid_argument("the experiment takes a scene with one homogeneous medium");
    const double seconds = std::atof(argv[2]);
    const uint64_t seed = std::strtoull(argv[3], nullptr, 10);
    const std::string out = argv[6];
    const struct {
      Estimator estimator;
      const char* name;
      const char* radius;
    } runs[] = {{Estimator::Points, "points", argv[4]},
                {Estimator::PointsAlongQuery, "pointbeam", argv[5]},
                {Estimator::Beams, "beams", argv[5]}};
    for (const auto& run : runs) {
      Film film(scene->camera.width(), scene->camera.height());
      const int passes = render(*scene, run.estimator, seconds, seed, std::strtof(run.radius, nullptr), film);
      const std::string path = out + "/" + run.name + ".exr";
      writeExr(film, path);
      std::printf("%s: %d passes in %.3g s -> %s\n", run.name, passes, seconds, path.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beam_experiment: %s\n", e.what());
    return 1;
  }
  return 0;
}
