#include "core/checkpoint.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"
#include "core/json_fields.h"
#include "core/json_parse.h"
#include "core/output_file.h"
#include "core/rng.h"

namespace kasha {
namespace {

constexpr char kMagic[8] = {'K', 'A', 'S', 'H', 'A', 'C', 'K', 'P'};
constexpr uint32_t kVersion = 1;
// Headers are small; a larger length means a corrupted or foreign file.
constexpr uint64_t kMaxHeader = uint64_t(1) << 20;
// The largest film side a checkpoint may hold (the scene loader's limit).
constexpr int kMaxCheckpointSide = 16384;

const char* byteOrder() { return std::endian::native == std::endian::little ? "little" : "big"; }

// Streaming form of hashBytes.
class Hasher {
 public:
  explicit Hasher(uint64_t seed) : h_(0xcbf29ce484222325ULL ^ mixBits(seed)) {}
  void update(const void* data, size_t len) {
    const auto* b = static_cast<const unsigned char*>(data);
    total_ += len;
    if (n_ > 0) {  // complete the buffered word
      const size_t take = std::min(len, sizeof buf_ - n_);
      std::memcpy(buf_ + n_, b, take);
      n_ += take, b += take, len -= take;
      if (n_ < sizeof buf_) return;
      word(load(buf_));
      n_ = 0;
    }
    for (; len >= 8; b += 8, len -= 8) word(load(b));
    std::memcpy(buf_, b, len);
    n_ = len;
  }
  uint64_t finish() {
    uint64_t w = 0;
    std::memcpy(&w, buf_, n_);
    word(w ^ (uint64_t(n_) << 56));
    word(total_);
    return mixBits(h_);
  }

 private:
  static uint64_t load(const unsigned char* p) {
    uint64_t w;
    std::memcpy(&w, p, 8);
    return w;
  }
  // FNV-1a on 64-bit words; the shift carries high-bit differences down.
  void word(uint64_t w) {
    h_ = (h_ ^ w) * 0x100000001b3ULL;
    h_ ^= h_ >> 29;
  }
  uint64_t h_, total_ = 0;
  unsigned char buf_[8] = {};
  size_t n_ = 0;
};

// Writes to an output file, hashing what it writes.
class Writer {
 public:
  explicit Writer(OutputFile& out) : out_(out), hash_(0) {}
  void bytes(const void* data, size_t len) {
    hash_.update(data, len);
    out_.write(data, len);
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  void checksum() {
    const uint64_t h = hash_.finish();
    out_.write(&h, sizeof h);
  }

 private:
  OutputFile& out_;
  Hasher hash_;
};

// Reads from an input file, hashing what it reads; a short read is an InputError naming the file.
class Reader {
 public:
  explicit Reader(InputFile& in) : in_(in), hash_(0) {}
  void bytes(void* data, size_t len) {
    in_.read(data, len);
    hash_.update(data, len);
  }
  template <class T>
  T value() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  void checksum() {
    const uint64_t expected = hash_.finish();
    uint64_t stored = 0;
    in_.read(&stored, sizeof stored);
    if (stored != expected) throw InputError(in_.path(), "", "checkpoint is corrupted (checksum mismatch)");
    if (!in_.atEnd()) throw InputError(in_.path(), "", "checkpoint has trailing data");
  }

 private:
  InputFile& in_;
  Hasher hash_;
};

// The header's fields, each checked for its type and range (JsonFields names its pointer).
void readHeader(const nlohmann::json& header, const std::string& path, CheckpointData& d) {
  JsonFields h(header, path, "");
  if (h.string("byte_order") != byteOrder())
    throw InputError(path, "", "checkpoint was written on a machine of another byte order");
  d.settings = h.get("settings");
  d.run = h.get("run");
  if (!d.settings.is_object()) h.fail("settings", "expected an object");
  if (!d.run.is_object()) h.fail("run", "expected an object");
  JsonFields film(h.get("film"), path, "/film");
  d.width = film.integer("width");
  d.height = film.integer("height");
  d.spp = film.integer("spp");
  for (const auto& [key, side] : {std::pair<const char*, int>{"width", d.width}, {"height", d.height}})
    if (side < 1 || side > kMaxCheckpointSide)
      film.fail(key, std::to_string(side) + " is out of range (1 to " + std::to_string(kMaxCheckpointSide) + ")");
  if (d.spp < 0) film.fail("spp", "must not be negative");
  const nlohmann::json& nonFinite = film.get("non_finite_samples");
  if (!nonFinite.is_number_unsigned()) film.fail("non_finite_samples", "expected a count");
  d.nonFiniteSamples = nonFinite.get<uint64_t>();
  const nlohmann::json& first = film.get("first_non_finite_pixel");
  if (!first.is_array() || first.size() != 2 || !first[0].is_number_integer() || !first[1].is_number_integer() ||
      first[0].get<int64_t>() < -1 || first[0].get<int64_t>() >= d.width || first[1].get<int64_t>() < -1 ||
      first[1].get<int64_t>() >= d.height)
    film.fail("first_non_finite_pixel", "expected [x, y] in the film or [-1, -1]");
  d.firstNonFinitePixel = {first[0].get<int>(), first[1].get<int>()};
  if (film.has("spectral_bins")) {
    JsonFields b(film.get("spectral_bins"), path, "/film/spectral_bins");
    d.spectralBins = {b.number("min"), b.number("step"), b.integer("count")};
    if (d.spectralBins.count < 1 || d.spectralBins.count > SpectralBins::kMaxBins || !(d.spectralBins.step > 0.0f))
      b.fail("count", "spectral bins out of range");
    b.finish();
  }
  film.finish();
  h.finish();
}

}  // namespace

uint64_t hashBytes(const void* data, size_t size, uint64_t seed) {
  Hasher h(seed);
  h.update(data, size);
  return h.finish();
}

void writeCheckpoint(const std::string& path, const nlohmann::json& settings, const nlohmann::json& run, const Film& film,
                     const SpectralFilm* spectral) {
  nlohmann::json header = {
      {"settings", settings},
      {"run", run},
      {"film",
       {{"width", film.width()},
        {"height", film.height()},
        {"spp", film.samplesPerPixel()},
        {"non_finite_samples", film.nonFiniteCount()},
        {"first_non_finite_pixel", {film.firstNonFinitePixel().first, film.firstNonFinitePixel().second}}}},
      {"byte_order", byteOrder()}};
  if (spectral) {
    const SpectralBins& b = spectral->bins();
    header["film"]["spectral_bins"] = {{"min", b.min}, {"step", b.step}, {"count", b.count}};
  }
  const std::string text = header.dump();
  OutputFile out(path);
  Writer w(out);
  w.bytes(kMagic, sizeof kMagic);
  w.value(kVersion);
  w.value(uint32_t(0));
  w.value(uint64_t(text.size()));
  w.bytes(text.data(), text.size());
  const std::vector<DVec3>& sums = film.sampleSums();
  const std::vector<DVec3>& splats = film.splatSums();
  static_assert(sizeof(DVec3) == 3 * sizeof(double));
  w.value(uint64_t(sums.size()));
  w.bytes(sums.data(), sums.size() * sizeof(DVec3));
  w.bytes(splats.data(), splats.size() * sizeof(DVec3));
  if (spectral) w.bytes(spectral->sums().data(), spectral->sums().size() * sizeof(double));
  w.checksum();
  // fsync before the rename, so that after a crash the name holds the old or the new checkpoint.
  out.commit();
}

CheckpointData readCheckpoint(const std::string& path) {
  // Every byte is read and the checksum verified before the header is parsed: a forged or damaged
  // header never reaches the JSON parser unless it was written with the checksum of the format, and
  // then the parse is bounded (parseJsonStrict: nesting, duplicate keys; each field read by
  // JsonFields, typed and in range). The file's size bounds what is allocated: the size of the
  // file opened, not of whatever the name points to by now (a running render replaces its
  // checkpoint by renaming a new one over it).
  InputFile in(path, "checkpoint file", UINT64_MAX);
  const uint64_t fileSize = in.size();
  Reader r(in);
  char magic[8];
  r.bytes(magic, sizeof magic);
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) throw InputError(path, "", "not a kasha checkpoint");
  const uint32_t version = r.value<uint32_t>();
  if (version != kVersion)
    throw InputError(path, "", "checkpoint format version " + std::to_string(version) + " is not supported (expected " +
                                   std::to_string(kVersion) + ")");
  r.value<uint32_t>();
  const uint64_t headerLength = r.value<uint64_t>();
  if (headerLength > kMaxHeader) throw InputError(path, "", "checkpoint is corrupted (header length)");
  constexpr uint64_t kFixed = 8 + 4 + 4 + 8 + 8 + 8;  // magic, version, reserved, two lengths, checksum
  if (fileSize < kFixed + headerLength) throw InputError(path, "", "checkpoint is truncated");
  std::string text(headerLength, '\0');
  r.bytes(text.data(), text.size());
  // The film's layout follows from the pixel count and the file's size: sums and splats, then
  // whole spectral bins of every pixel.
  const uint64_t pixels = r.value<uint64_t>();
  const uint64_t payload = fileSize - kFixed - headerLength;
  constexpr uint64_t kMaxPixels = uint64_t(kMaxCheckpointSide) * kMaxCheckpointSide;
  if (pixels < 1 || pixels > kMaxPixels || 2 * pixels * sizeof(DVec3) > payload ||
      (payload - 2 * pixels * sizeof(DVec3)) % (pixels * sizeof(double)) != 0)
    throw InputError(path, "", "checkpoint is truncated or has trailing data");
  const uint64_t spectralValues = (payload - 2 * pixels * sizeof(DVec3)) / sizeof(double);
  CheckpointData d;
  d.sums.resize(pixels);
  d.splats.resize(pixels);
  r.bytes(d.sums.data(), pixels * sizeof(DVec3));
  r.bytes(d.splats.data(), pixels * sizeof(DVec3));
  if (spectralValues > 0) {  // an empty vector's data() may be null, which memcpy must not get
    d.spectral.resize(spectralValues);
    r.bytes(d.spectral.data(), spectralValues * sizeof(double));
  }
  r.checksum();
  readHeader(parseJsonStrict(text, path), path, d);
  if (uint64_t(d.width) * uint64_t(d.height) != pixels)
    throw InputError(path, "", "checkpoint is corrupted (pixel count does not match the film size)");
  if (spectralValues != pixels * uint64_t(d.spectralBins.count))
    throw InputError(path, "", "checkpoint is corrupted (spectral sums do not match the header's bins)");
  for (const double v : d.spectral)
    if (!std::isfinite(v)) throw InputError(path, "", "checkpoint is corrupted (a non-finite spectral sum)");
  for (const std::vector<DVec3>* buffer : {&d.sums, &d.splats})
    for (const DVec3& v : *buffer)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw InputError(path, "", "checkpoint is corrupted (a non-finite pixel sum)");
  return d;
}

bool reportedBefore(const std::string& a, const std::string& b) {
  const auto group = [](const std::string& key) { return key == "integrator" ? 0 : key == "scene_hash" ? 2 : 1; };
  return group(a) != group(b) ? group(a) < group(b) : a < b;
}

void requireSameSettings(const nlohmann::json& saved, const nlohmann::json& current, const std::string& path) {
  std::vector<std::string> keys;
  for (const nlohmann::json* settings : {&saved, &current})
    for (auto it = settings->begin(); it != settings->end(); ++it) keys.push_back(it.key());
  std::sort(keys.begin(), keys.end(), reportedBefore);
  for (const std::string& key : keys) {
    const auto s = saved.find(key), c = current.find(key);
    if (s == saved.end()) throw InputError(path, "", "checkpoint does not record '" + key + "' (written by another kasha version?)");
    if (c == current.end())
      throw InputError(path, "", "checkpoint records '" + key + "', which this kasha version does not know");
    if (*s != *c)
      throw InputError(path, "", "checkpoint was made with " + key + " " + s->dump() + ", this render has " + key + " " +
                                     c->dump() + "; resume with the same scene and options");
  }
}

void restoreFilm(CheckpointData&& d, Film& film, SpectralFilm* spectral) {
  if (d.width != film.width() || d.height != film.height())
    throw InputError("", "", "checkpoint film is " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                                 ", the render's is " + std::to_string(film.width()) + "x" + std::to_string(film.height()));
  const int bins = spectral ? spectral->bins().count : 0;
  if (d.spectralBins.count != bins || (spectral && (d.spectralBins.min != spectral->bins().min ||
                                                    d.spectralBins.step != spectral->bins().step)))
    throw InputError("", "", "checkpoint has " + std::to_string(d.spectralBins.count) + " spectral bins, the render " +
                                 std::to_string(bins) + " (or other wavelengths)");
  if (spectral) spectral->restore(std::move(d.spectral), d.spp);
  film.restore(std::move(d.sums), std::move(d.splats), d.spp, d.nonFiniteSamples, d.firstNonFinitePixel);
}

}  // namespace kasha
