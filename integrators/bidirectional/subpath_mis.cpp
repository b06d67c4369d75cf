#include "integrators/bidirectional/subpath_mis.h"

namespace kasha::bidir {

MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j, SpectralLobe lobe, float lambdaOut,
                          const Strategies& st, bool gather, bool ends, double cameraBeam, double beamSine) {
  if (j < 0) return {};
  if (j == 0) return hitMultiplicity();  // the camera subpath hits the light (0 where pC_0 is)
  const PathVertex& v = L[size_t(j)];
  // x_j next to the camera (gather, t = 1) is x_{k−1}.
  const MisSums merges =
      mergeMultiplicity(mergeable(v, ends), lobe, v.pdfFwd, gather, gather, st, v.inMedium(), cameraBeam,
                        photonBeamRatio(v.lightBeam, beamSine));
  if (j == 1) {  // x_1: next-event estimation, and the light vertex through a fluorescent x_1
    const double specCam1 = v.bsdf->spectralPdf(TransportMode::Radiance, lambdaOut, v.lambda, lobe);
    return merges + firstVertexMultiplicity(v.joinable(ends), lobe, specCam1, L[0].kind == PathVertex::Kind::Light, st);
  }
  const PathVertex& u = L[size_t(j - 1)];
  return merges + joinMultiplicity(u.joinable(false) && v.joinable(ends), u.lobe, lobe, st);
}

MisSums lightMultiplicity(const std::vector<PathVertex>& L, int j, const Strategies& st, bool gather, bool ends) {
  if (j < 1) return lightMultiplicity(L, j, SpectralLobe::Elastic, 0.0f, st, false, ends, 0.0, 0.0);
  const PathVertex& v = L[size_t(j)];
  return lightMultiplicity(L, j, v.lobe, v.lambdaNext, st, gather, ends, v.cameraBeam, v.beamSine);
}

MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j, SpectralLobe lobe, float lambdaIn,
                           const Strategies& st, bool ends, double lightBeam, double beamSine) {
  if (j < 1) return {};
  const PathVertex& v = C[size_t(j)];
  const MisSums merges =
      mergeMultiplicity(mergeable(v, ends), lobe, v.pdfFwd, v.gather, j == 1, st, v.inMedium(), v.cameraBeam,
                        photonBeamRatio(lightBeam, beamSine));
  if (j == 1) {  // t = 1: the light side samples x_{k−1}'s event
    const double specLight = v.bsdf->spectralPdf(TransportMode::Importance, lambdaIn, v.lambda, lobe);
    return merges + lightTracingMultiplicity(v.joinable(ends), specLight, st);
  }
  const PathVertex& u = C[size_t(j - 1)];
  return merges + joinMultiplicity(u.joinable(false) && v.joinable(ends), lobe, u.lobe, st);
}

MisSums cameraMultiplicity(const std::vector<PathVertex>& C, int j, const Strategies& st, bool ends) {
  if (j < 1) return {};
  const PathVertex& v = C[size_t(j)];
  return cameraMultiplicity(C, j, v.lobe, v.lambdaNext, st, ends, v.lightBeam, v.beamSine);
}

void updateSums(std::vector<PathVertex>& path, TransportMode mode, const Strategies& st) {
  const size_t j = path.size() - 1;
  PathVertex& v = path[j];
  if (j < 2) {
    v.sums = {};
    v.elasticBefore = true;
    return;
  }
  const PathVertex& back2 = path[j - 2];
  const PathVertex& back1 = path[j - 1];
  const double r = densityRatio(back2.pdfRev, back2.pdfFwd);
  const MisSums m = mode == TransportMode::Radiance ? cameraMultiplicity(path, int(j - 2), st, false)
                                                    : lightMultiplicity(path, int(j - 2), st, false, false);
  v.sums = extend(back1.sums, r, m);
  v.elasticBefore = back1.elasticBefore && back1.lobe == SpectralLobe::Elastic;
}

}  // namespace kasha::bidir
