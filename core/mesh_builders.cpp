#include "core/mesh_builders.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <stdexcept>

#include "core/ply_validation.h"

namespace kasha {

void readPlyMesh(const std::string& bytes, const std::string& path, uint64_t memoryLimit, Shape& s,
                 const std::vector<std::string>& attributes) {
  if (!attributes.empty() && !s.positions.empty())
    throw std::logic_error("readPlyMesh: mesh attributes are read into an empty shape only");
  std::vector<MeshAttribute> read;
  const std::string checked = validatePly(bytes, path, memoryLimit, attributes, &read);
  Assimp::Importer importer;
  // Only triangulation: no vertex joining, no normal generation (kasha uses face normals). The
  // hint "ply" picks the PLY reader, whatever the bytes look like to the others.
  const aiScene* scene = importer.ReadFileFromMemory(checked.data(), checked.size(),
                                                     aiProcess_Triangulate | aiProcess_SortByPType, "ply");
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || scene->mNumMeshes == 0)
    throw std::runtime_error("'" + path + "': " + (scene ? "holds no mesh" : importer.GetErrorString()));
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh& m = *scene->mMeshes[mi];
    if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines have no area
    const uint32_t base = uint32_t(s.positions.size());
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& p = m.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw std::runtime_error("'" + path + "': vertex " + std::to_string(v + 1) + " is not finite");
      s.positions.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m.mNumVertices) throw std::runtime_error("'" + path + "': face refers to a missing vertex");
        s.indices.push_back(base + face.mIndices[k]);
        if (m.HasTextureCoords(0)) {
          const aiVector3D& t = m.mTextureCoords[0][face.mIndices[k]];
          s.cornerUvs.emplace_back(t.x, t.y);
        }
      }
    }
  }
  if (s.indices.empty()) throw std::runtime_error("'" + path + "': has no triangles");
  // Attribute values are in the file's order; assimp keeps it (no vertex joining; triangles are
  // copied in order), which the counts confirm.
  for (MeshAttribute& a : read) {
    const size_t expected = a.perFace() ? s.indices.size() / 3 : s.positions.size();
    if (scene->mNumMeshes != 1 || a.values.size() != expected)
      throw std::runtime_error("'" + path + "': mesh attribute " + a.name + ": assimp read " + std::to_string(expected) +
                               (a.perFace() ? " triangles" : " vertices") + " from " + std::to_string(a.values.size()));
    s.attributes.push_back(std::move(a));
  }
  if (!s.cornerUvs.empty() && s.cornerUvs.size() != s.indices.size())
    throw std::runtime_error("'" + path + "': some parts have texture coordinates and some do not");
}

void tessellateUnitDisk(Shape& s, int segments) {
  s.positions = {Vec3(0.0f)};
  s.indices.clear();
  s.cornerUvs.clear();
  for (int i = 0; i < segments; ++i) {
    const float phi = 2.0f * kPi * float(i) / float(segments);
    s.positions.emplace_back(std::cos(phi), std::sin(phi), 0.0f);
  }
  for (int i = 0; i < segments; ++i) {
    const uint32_t a = uint32_t(1 + i), b = uint32_t(1 + (i + 1) % segments);
    s.indices.insert(s.indices.end(), {0u, a, b});  // counter-clockwise seen from +z: normal +z
    const float v0 = float(i) / float(segments), v1 = float(i + 1) / float(segments);
    s.cornerUvs.insert(s.cornerUvs.end(), {Vec2(0.0f, 0.5f * (v0 + v1)), Vec2(1.0f, v0), Vec2(1.0f, v1)});
  }
}

void transformMesh(Shape& s, const glm::mat4& m) {
  for (Vec3& p : s.positions) p = Vec3(m * glm::vec4(p, 1.0f));
  // Normals by the inverse transpose (PBR4 §3.10.3), so they stay perpendicular to the surface.
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
  for (Vec3& n : s.cornerNormals) n = normalMatrix * n;
}

void flipMeshNormals(Shape& s) {
  for (size_t t = 0; t + 2 < s.indices.size(); t += 3) {
    std::swap(s.indices[t + 1], s.indices[t + 2]);
    if (!s.cornerUvs.empty()) std::swap(s.cornerUvs[t + 1], s.cornerUvs[t + 2]);
  }
}

void flipMeshTexCoords(Shape& s) {
  for (Vec2& uv : s.cornerUvs) uv.y = 1.0f - uv.y;
}

}  // namespace kasha
