#pragma once
// Small facts about affine maps given as glm matrices.
#include <glm/mat3x3.hpp>

#include <cmath>

#include "core/math.h"

namespace kasha {

// s if the linear part m is s times a rotation (orthogonal columns of equal length s > 0, no
// mirroring unless `mirrorAllowed`), else 0.
inline float uniformScale(const glm::mat3& m, bool mirrorAllowed = false) {
  const float s = glm::length(m[0]);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(glm::length(m[i]) - s) > 1e-4f * s) return 0.0f;
    if (std::abs(glm::dot(m[i], m[(i + 1) % 3])) > 1e-4f * s * s) return 0.0f;
  }
  return mirrorAllowed || glm::determinant(m) > 0.0f ? s : 0.0f;
}

}  // namespace kasha
