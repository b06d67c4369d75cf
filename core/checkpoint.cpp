#include "core/checkpoint.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"
#include "core/output_file.h"
#include "core/rng.h"

namespace kasha {
namespace {

constexpr char kMagic[8] = {'K', 'A', 'S', 'H', 'A', 'C', 'K', 'P'};
constexpr uint32_t kVersion = 1;
// Headers are small; a larger length means a corrupted or foreign file.
constexpr uint64_t kMaxHeader = uint64_t(1) << 20;

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
  // Its size is checked against the header below; the size of the file opened, not of whatever
  // the name points to by now (a running render replaces its checkpoint by renaming a new one over it).
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
  std::string text(headerLength, '\0');
  r.bytes(text.data(), text.size());
  CheckpointData d;
  try {
    const nlohmann::json header = nlohmann::json::parse(text);
    if (header.at("byte_order").get<std::string>() != byteOrder())
      throw InputError(path, "", "checkpoint was written on a machine of another byte order");
    d.settings = header.at("settings");
    d.run = header.at("run");
    const nlohmann::json& film = header.at("film");
    d.width = film.at("width").get<int>();
    d.height = film.at("height").get<int>();
    d.spp = film.at("spp").get<int>();
    d.nonFiniteSamples = film.at("non_finite_samples").get<uint64_t>();
    d.firstNonFinitePixel = {film.at("first_non_finite_pixel").at(0).get<int>(), film.at("first_non_finite_pixel").at(1).get<int>()};
    if (film.contains("spectral_bins")) {
      const nlohmann::json& b = film.at("spectral_bins");
      d.spectralBins = {b.at("min").get<float>(), b.at("step").get<float>(), b.at("count").get<int>()};
      if (d.spectralBins.count < 1 || d.spectralBins.count > SpectralBins::kMaxBins || !(d.spectralBins.step > 0.0f))
        throw InputError(path, "", "checkpoint header is corrupted (spectral bins)");
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "", std::string("checkpoint header is corrupted: ") + e.what());
  }
  if (d.width < 1 || d.height < 1 || d.width > 16384 || d.height > 16384 || d.spp < 0)
    throw InputError(path, "", "checkpoint header is corrupted (film size or sample count)");
  const uint64_t pixels = r.value<uint64_t>();
  if (pixels != uint64_t(d.width) * uint64_t(d.height))
    throw InputError(path, "", "checkpoint is corrupted (pixel count does not match the film size)");
  // The file must be as long as the header says before anything that size is allocated.
  const uint64_t spectralValues = pixels * uint64_t(d.spectralBins.count);
  const uint64_t expected = 8 + 4 + 4 + 8 + headerLength + 8 + 2 * pixels * sizeof(DVec3) + spectralValues * sizeof(double) + 8;
  if (fileSize != expected) throw InputError(path, "", "checkpoint is truncated or has trailing data");
  d.sums.resize(pixels);
  d.splats.resize(pixels);
  r.bytes(d.sums.data(), pixels * sizeof(DVec3));
  r.bytes(d.splats.data(), pixels * sizeof(DVec3));
  if (spectralValues > 0) {  // an empty vector's data() may be null, which memcpy must not get
    d.spectral.resize(spectralValues);
    r.bytes(d.spectral.data(), spectralValues * sizeof(double));
  }
  r.checksum();
  for (const double v : d.spectral)
    if (!std::isfinite(v)) throw InputError(path, "", "checkpoint is corrupted (a non-finite spectral sum)");
  for (const std::vector<DVec3>* buffer : {&d.sums, &d.splats})
    for (const DVec3& v : *buffer)
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw InputError(path, "", "checkpoint is corrupted (a non-finite pixel sum)");
  return d;
}

void requireSameSettings(const nlohmann::json& saved, const nlohmann::json& current, const std::string& path) {
  for (auto it = current.begin(); it != current.end(); ++it) {
    const auto s = saved.find(it.key());
    if (s == saved.end())
      throw InputError(path, "", "checkpoint does not record '" + it.key() + "' (written by another kasha version?)");
    if (*s != it.value())
      throw InputError(path, "", "checkpoint was made with " + it.key() + " " + s->dump() + ", this render has " +
                                     it.key() + " " + it.value().dump() + "; resume with the same scene and options");
  }
  for (auto it = saved.begin(); it != saved.end(); ++it)
    if (!current.contains(it.key()))
      throw InputError(path, "", "checkpoint records '" + it.key() + "', which this kasha version does not know");
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
