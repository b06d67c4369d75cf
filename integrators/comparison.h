#pragma once
// Equal-time (or equal-sample) comparisons of integrators on one scene against a reference image:
// the error measures researchers report.
#include <string>
#include <vector>

#include "core/film.h"
#include "core/image_input.h"
#include "integrators/render_loop.h"
#include "scene/render_settings.h"

namespace kasha {

struct ImageError {
  double rmse = 0.0;    // root mean square error over pixels and X, Y, Z
  double relMse = 0.0;  // mean of (x − ref)² / (ref² + 1e-2), over pixels and channels
};

// Both measures of `image` against `reference` (XYZ); throws std::invalid_argument if their sizes differ.
ImageError compareImages(const XyzImage& image, const XyzImage& reference);
ImageError compareToReference(const Film& film, const XyzImage& reference);
// Per pixel, row-major: the relative squared error (x − ref)² / (ref² + 1e-2) averaged over
// X, Y, Z, so that the mean of the map is ImageError::relMse.
std::vector<float> relativeErrorMap(const XyzImage& image, const XyzImage& reference);
XyzImage filmToXyz(const Film& film);

struct ComparisonRow {
  std::string integrator;
  RenderStats stats;
  ImageError error;
};

// Renders `scene` with each integrator (a RenderJob, render_job.h) for the same budget
// (settings.timeBudgetSeconds and/or settings.spp) and measures each image against the reference.
std::vector<ComparisonRow> compareIntegrators(const Scene& scene, const std::vector<std::string>& integrators,
                                              const RenderSettings& settings, int threads, const XyzImage& reference);

}  // namespace kasha
