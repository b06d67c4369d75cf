#include "core/serialized_mesh.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"

namespace kasha {
namespace {

constexpr uint16_t kMagic = 0x041C;
// Versions 3 and 4's flag word.
constexpr uint32_t kHasNormals = 0x0001, kHasTexcoords = 0x0002, kHasColors = 0x0008, kDoublePrecision = 0x2000;
// Version 5's: the record layout's bits, face normals, single precision (always set).
constexpr uint32_t kLayoutNormals = 0x0001, kLayoutTangents = 0x0002, kLayoutTexcoords = 0x0004, kFaceNormals = 0x0010,
                   kSinglePrecision = 0x1000;
// Version 5's records: 8 floats a vertex (position, normal or encoded frame, uv), 4 words a face
// (three vertex indices and the BSDF index).
constexpr uint64_t kVertexRecordFloats = 8, kFaceRecordWords = 4;
// A version 5 custom attribute has 1 to 4 channels.
constexpr uint32_t kMaxAttributeChannels = 4;
// DEFLATE's largest expansion: a 258-byte match in about 2 bits, i.e. at most 1032 output bytes a
// compressed byte (zlib's technical details, "Maximum compression factor").
constexpr uint64_t kMaxInflateRatio = 1032;
// A mesh name (version 4, 5) or attribute name (5) longer than this is not a name.
constexpr size_t kMaxNameBytes = 65536;
// What kasha holds beyond the inflated data: per vertex the decoded floats (up to 8), its position
// and Embree's copy; per triangle its indices, corner normals and uvs, twice while Shape::finalize
// drops degenerate ones, face normal, area sum, Embree's copy and BVH.
constexpr uint64_t kBytesPerVertex = 56, kBytesPerTriangle = 256;

uint64_t loadU64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
uint32_t loadU32(const unsigned char* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }
uint16_t loadU16(const unsigned char* p) { return uint16_t(p[0] | p[1] << 8); }

// One zlib stream of the file, inflated on demand into the caller's buffers.
class Inflater {
 public:
  Inflater(const unsigned char* begin, const unsigned char* end, const std::string& path, const std::string& mesh)
      : next_(begin), end_(end), path_(path), mesh_(mesh) {
    if (inflateInit(&z_) != Z_OK) throw InputError(path_, mesh_, "zlib cannot start inflating");
  }
  ~Inflater() { inflateEnd(&z_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  // Up to n bytes into out; fewer only where the stream ends. Corrupt data is an InputError.
  size_t read(void* out, size_t n) {
    unsigned char* dst = static_cast<unsigned char*>(out);
    size_t got = 0;
    while (got < n && !ended_) {
      if (z_.avail_in == 0) {  // feed the compressed bytes in pieces zlib's 32-bit counts hold
        const size_t chunk = std::min<size_t>(size_t(end_ - next_), size_t(1) << 30);
        z_.next_in = const_cast<unsigned char*>(next_);
        z_.avail_in = uInt(chunk);
        next_ += chunk;
      }
      const size_t want = std::min<size_t>(n - got, size_t(1) << 30);
      z_.next_out = dst + got;
      z_.avail_out = uInt(want);
      const int status = inflate(&z_, Z_NO_FLUSH);
      got += want - z_.avail_out;
      if (status == Z_STREAM_END) {
        ended_ = true;
      } else if (status == Z_BUF_ERROR && z_.avail_in == 0 && next_ == end_) {
        throw InputError(path_, mesh_, "the compressed data is truncated");
      } else if (status != Z_OK && status != Z_BUF_ERROR) {
        throw InputError(path_, mesh_, std::string("the compressed data is corrupt (zlib: ") +
                                           (z_.msg ? z_.msg : "error " + std::to_string(status)) + ")");
      }
    }
    return got;
  }
  // Exactly n bytes, or InputError naming `field`.
  void readExactly(void* out, size_t n, const std::string& field) {
    if (read(out, n) != n) throw InputError(path_, mesh_ + ": " + field, "the mesh's data ends before it");
  }

 private:
  z_stream z_{};
  const unsigned char* next_;
  const unsigned char* end_;
  bool ended_ = false;
  const std::string& path_;
  std::string mesh_;
};

// The file offset of mesh `index`'s header, from the dictionary at the end of the file.
uint64_t meshOffset(const std::string& bytes, const std::string& path, uint16_t version, uint64_t index) {
  if (index == 0) return 0;
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const uint64_t size = bytes.size();
  if (size < 8) throw InputError(path, "dictionary", "missing: the file ends after its header");
  const uint64_t entry = version == 3 ? 4 : 8;
  const uint64_t count = loadU32(b + size - 4);
  if (saturatingMul(count, entry) > size - 8)
    throw InputError(path, "dictionary", "declares " + std::to_string(count) + " meshes, more than the file's " +
                                             std::to_string(size) + " bytes can index");
  if (index >= count)
    throw InputError(path, "shape_index", std::to_string(index) + " is out of range: the file holds " +
                                              std::to_string(count) + " meshes (0 to " + std::to_string(count - 1) + ")");
  const uint64_t dictionary = size - 4 - count * entry;
  const unsigned char* at = b + dictionary + index * entry;
  const uint64_t offset = entry == 4 ? loadU32(at) : loadU64(at);
  if (offset > dictionary || dictionary - offset < 4)
    throw InputError(path, "dictionary", "mesh " + std::to_string(index) + " starts at byte " + std::to_string(offset) +
                                             ", beyond the meshes (" + std::to_string(dictionary) + " bytes)");
  if (loadU16(b + offset) != kMagic || loadU16(b + offset + 2) != version)
    throw InputError(path, "mesh " + std::to_string(index), "no header (0x041C, version " + std::to_string(version) +
                                                                ") at byte " + std::to_string(offset));
  return offset;
}

// One mesh's stream after its header: the counts checked before anything is allocated for them, the
// decoded vertices, and the triangles appended to a Shape.
class MeshReader {
 public:
  MeshReader(Inflater& in, const std::string& path, std::string mesh, uint64_t compressedBytes, uint64_t memoryLimit)
      : in_(in), path_(path), mesh_(std::move(mesh)), compressedBytes_(compressedBytes), memoryLimit_(memoryLimit) {}

  uint32_t u32(const char* field) {
    unsigned char b[4];
    in_.readExactly(b, 4, field);
    return loadU32(b);
  }
  uint64_t u64(const char* field) {
    unsigned char b[8];
    in_.readExactly(b, 8, field);
    return loadU64(b);
  }
  // A name of `length` bytes (versions 5).
  std::string name(uint64_t length, const std::string& field) {
    if (length > kMaxNameBytes) fail(field, "a name longer than " + std::to_string(kMaxNameBytes) + " bytes");
    std::string text(size_t(length), '\0');
    in_.readExactly(text.data(), text.size(), field);
    return text;
  }
  // A name up to its NUL byte (version 4), dropped.
  void skipNulTerminated(const std::string& field) {
    for (size_t length = 0;; ++length) {
      if (length > kMaxNameBytes) fail(field, "a name longer than " + std::to_string(kMaxNameBytes) + " bytes");
      char c;
      in_.readExactly(&c, 1, field);
      if (c == 0) return;
    }
  }
  // n bytes read and dropped, in pieces (no allocation that depends on n).
  void skip(uint64_t n, const std::string& field) {
    unsigned char buffer[65536];
    for (; n > 0; n -= std::min<uint64_t>(n, sizeof buffer)) in_.readExactly(buffer, size_t(std::min<uint64_t>(n, sizeof buffer)), field);
  }

  // V and F, and the bytes of the data they declare (dataBytes more than kasha keeps besides).
  void setCounts(uint64_t vertices, uint64_t triangles) {
    if (vertices == 0 || triangles == 0) fail("", "holds no triangles");
    if (vertices > uint64_t(UINT32_MAX)) fail("vertex count", std::to_string(vertices) + " is more than 32-bit indices reach");
    if (triangles > uint64_t(UINT32_MAX) / 3) fail("face count", std::to_string(triangles) + " is more than 2^32 vertex indices");
    vertices_ = vertices, triangles_ = triangles;
  }
  // Inflates the next `dataBytes` (at most 13·8 a vertex and 16 a face plus 8 a vertex of maps,
  // with counts below 2^32: no overflow) after checking them against the compressed data's size and
  // the memory limit.
  void readData(uint64_t dataBytes) {
    if (dataBytes > saturatingMul(compressedBytes_, kMaxInflateRatio))
      fail("counts", std::to_string(vertices_) + " vertices and " + std::to_string(triangles_) + " triangles need " +
                         formatBytes(dataBytes) + ", more than the " + formatBytes(compressedBytes_) +
                         " of compressed data can hold");
    requireMemory(dataBytes + vertices_ * kBytesPerVertex + triangles_ * kBytesPerTriangle,
                  "'" + path_ + "' " + mesh_ + " (" + std::to_string(vertices_) + " vertices, " +
                      std::to_string(triangles_) + " triangles)",
                  memoryLimit_);
    data_.resize(dataBytes);
    in_.readExactly(data_.data(), data_.size(), "data");
  }
  // The stream ends here: more data than declared is an error (and zlib checks its checksum).
  void finish() {
    unsigned char extra;
    if (in_.read(&extra, 1) != 0) fail("", "the compressed data holds more than its counts declare");
  }
  const unsigned char* data() const { return data_.data(); }
  uint64_t vertices() const { return vertices_; }
  uint64_t triangles() const { return triangles_; }

  // Numbers of `bytesEach` (4: float, 8: double) at data() + offset, `stride` apart, `count` of
  // them per vertex: finite floats or an error naming what they are.
  std::vector<float> floats(uint64_t offset, size_t bytesEach, uint64_t stride, int count, const char* what) const {
    std::vector<float> out(vertices_ * uint64_t(count));
    for (uint64_t v = 0; v < vertices_; ++v)
      for (int k = 0; k < count; ++k) {
        const unsigned char* p = data_.data() + offset + v * stride + uint64_t(k) * bytesEach;
        double value;
        if (bytesEach == 8) {
          const uint64_t bits = loadU64(p);
          std::memcpy(&value, &bits, 8);
        } else {
          const uint32_t bits = loadU32(p);
          float f;
          std::memcpy(&f, &bits, 4);
          value = f;
        }
        const float f = float(value);
        if (!std::isfinite(f)) fail("vertex " + std::to_string(v), std::string(what) + " is not finite as a 32-bit float");
        out[v * uint64_t(count) + uint64_t(k)] = f;
      }
    return out;
  }

  // Appends the mesh: positions, and per corner of the triangles (vertex indices at data() +
  // faceOffset, faceStride bytes apart) the normals and Mitsuba's uvs as kasha's (u, 1 − v).
  void append(const std::vector<float>& positions, const std::vector<float>& normals, const std::vector<float>& uvs,
              uint64_t faceOffset, uint64_t faceStride, Shape& s) const {
    const uint32_t base = uint32_t(s.positions.size());
    if (uint64_t(base) + vertices_ > uint64_t(UINT32_MAX)) fail("", "more than 2^32 vertices in one shape");
    for (uint64_t v = 0; v < vertices_; ++v) s.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    for (uint64_t t = 0; t < triangles_; ++t)
      for (uint64_t k = 0; k < 3; ++k) {
        const uint32_t index = loadU32(data_.data() + faceOffset + t * faceStride + 4 * k);
        if (index >= vertices_)
          fail("face " + std::to_string(t),
               "vertex index " + std::to_string(index) + " is not below the vertex count " + std::to_string(vertices_));
        s.indices.push_back(base + index);
        if (!normals.empty()) s.cornerNormals.emplace_back(normals[3 * index], normals[3 * index + 1], normals[3 * index + 2]);
        if (!uvs.empty()) s.cornerUvs.emplace_back(uvs[2 * index], 1.0f - uvs[2 * index + 1]);
      }
  }

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw InputError(path_, field.empty() ? mesh_ : mesh_ + ": " + field, reason);
  }

 private:
  Inflater& in_;
  const std::string& path_;
  std::string mesh_;
  uint64_t compressedBytes_, memoryLimit_;
  uint64_t vertices_ = 0, triangles_ = 0;
  std::vector<unsigned char> data_;
};

// Versions 3 and 4: flags, [name up to NUL], V, F, then one array per quantity.
bool readLegacy(MeshReader& r, uint16_t version, Shape& s) {
  const uint32_t flags = r.u32("flags");
  if (version == 4) r.skipNulTerminated("name");
  const uint64_t vertices = r.u64("vertex count");
  r.setCounts(vertices, r.u64("face count"));
  const size_t scalar = (flags & kDoublePrecision) ? 8 : 4;
  const bool normals = flags & kHasNormals, uvs = flags & kHasTexcoords;
  const uint64_t perVertex = 3 + (normals ? 3 : 0) + (uvs ? 2 : 0) + ((flags & kHasColors) ? 3 : 0);
  const uint64_t vertexBytes = vertices * perVertex * scalar;
  r.readData(vertexBytes + r.triangles() * 12);
  r.finish();
  // The arrays follow each other: positions, [normals], [uvs], [colours, dropped], indices.
  const std::vector<float> p = r.floats(0, scalar, 3 * scalar, 3, "position");
  const std::vector<float> n = normals ? r.floats(vertices * 3 * scalar, scalar, 3 * scalar, 3, "normal") : std::vector<float>();
  const std::vector<float> uv =
      uvs ? r.floats(vertices * (normals ? 6 : 3) * scalar, scalar, 2 * scalar, 2, "texture coordinate") : std::vector<float>();
  r.append(p, n, uv, vertexBytes, 12, s);
  return false;
}

// The unit normal of a frame encoded as modified Rodrigues parameters p (Terzakis et al. 2018;
// Mitsuba 3's mesh_utils.h): the quaternion (w, x, y, z) = (2a − 1, 2a·p) with a = 1/(1 + |p|²),
// and R·e_z = (2(xz + wy), 2(yz − wx), 1 − 2(x² + y²)) its rotation's third column.
Vec3 frameNormal(float px, float py, float pz) {
  const double a = 1.0 / (1.0 + double(px) * px + double(py) * py + double(pz) * pz);
  const double w = 2.0 * a - 1.0, x = 2.0 * a * px, y = 2.0 * a * py, z = 2.0 * a * pz;
  return Vec3(float(2.0 * (x * z + w * y)), float(2.0 * (y * z - w * x)), float(1.0 - 2.0 * (x * x + y * y)));
}

// Version 5: flags, name (uint32 length, bytes), V, F, P, N, the vertex and face records, the
// optional maps (checked, dropped) and the custom attributes (skipped).
bool readV5(MeshReader& r, Shape& s) {
  const uint32_t flags = r.u32("flags");
  if (!(flags & kSinglePrecision)) r.fail("flags", "version 5 data must be single precision (flag 0x1000)");
  const bool normals = flags & kLayoutNormals, tangents = flags & kLayoutTangents, uvs = flags & kLayoutTexcoords;
  if (tangents && !normals) r.fail("flags", "tangents without normals");
  r.name(r.u32("name"), "name");
  const uint64_t vertices = r.u64("vertex count");
  r.setCounts(vertices, r.u64("face count"));
  const uint64_t surfacePoints = r.u64("surface point count"), normalGroups = r.u64("normal group count");
  if (surfacePoints > vertices || normalGroups > vertices)
    r.fail("counts", "more surface points or normal groups than vertices");
  const uint64_t recordBytes = vertices * kVertexRecordFloats * 4, faceBytes = r.triangles() * kFaceRecordWords * 4;
  const uint64_t mapBytes = (surfacePoints ? 4 * vertices : 0) + (normalGroups ? 4 * vertices : 0);
  r.readData(recordBytes + faceBytes + mapBytes);
  // The maps' indices are below their counts.
  uint64_t at = recordBytes + faceBytes;
  for (const uint64_t count : {surfacePoints, normalGroups}) {
    if (count == 0) continue;
    for (uint64_t v = 0; v < vertices; ++v)
      if (loadU32(r.data() + at + 4 * v) >= count)
        r.fail("vertex " + std::to_string(v), "map index beyond its " + std::to_string(count) + " entries");
    at += 4 * vertices;
  }
  // Custom attributes: name, a flag byte, channels, then channels floats per face ("face_" names)
  // or per vertex; kasha has no use for them.
  const uint32_t attributes = r.u32("attribute count");
  for (uint32_t i = 0; i < attributes; ++i) {
    const std::string field = "attribute " + std::to_string(i);
    const std::string name = r.name(r.u32(field.c_str()), field);
    r.skip(1, field);
    const uint32_t channels = r.u32(field.c_str());
    if (channels == 0 || channels > kMaxAttributeChannels)
      r.fail(field, std::to_string(channels) + " channels (1 to " + std::to_string(kMaxAttributeChannels) + ")");
    r.skip((name.rfind("face_", 0) == 0 ? r.triangles() : vertices) * channels * 4, field);
  }
  r.finish();
  const std::vector<float> p = r.floats(0, 4, kVertexRecordFloats * 4, 3, "position");
  std::vector<float> n = normals ? r.floats(12, 4, kVertexRecordFloats * 4, 3, "normal") : std::vector<float>();
  if (tangents)
    for (size_t v = 0; v < n.size(); v += 3) {
      const Vec3 decoded = frameNormal(n[v], n[v + 1], n[v + 2]);
      n[v] = decoded.x, n[v + 1] = decoded.y, n[v + 2] = decoded.z;
    }
  const std::vector<float> uv = uvs ? r.floats(24, 4, kVertexRecordFloats * 4, 2, "texture coordinate") : std::vector<float>();
  r.append(p, n, uv, recordBytes, kFaceRecordWords * 4, s);
  return flags & kFaceNormals;
}

}  // namespace

bool readSerializedMesh(const std::string& bytes, const std::string& path, uint64_t shapeIndex, uint64_t memoryLimit,
                        Shape& s) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 4 || loadU16(b) != kMagic)
    throw InputError(path, "header", "not a Mitsuba serialized mesh (it does not start with 0x041C)");
  const uint16_t version = loadU16(b + 2);
  if (version < 3 || version > 5)
    throw InputError(path, "header", "unknown version " + std::to_string(version) + " (3, 4 and 5 are read)");
  const uint64_t offset = meshOffset(bytes, path, version, shapeIndex);
  const std::string mesh = "mesh " + std::to_string(shapeIndex);
  Inflater in(b + offset + 4, b + bytes.size(), path, mesh);
  MeshReader reader(in, path, mesh, bytes.size() - offset - 4, memoryLimit);
  return version == 5 ? readV5(reader, s) : readLegacy(reader, version, s);
}

}  // namespace kasha
