#pragma once
// Render checkpoints: the film's sums and sample count plus a JSON header, written atomically
// (temporary file, fsync, rename), so that a render killed at any moment (even by SIGKILL) can be
// resumed from its last checkpoint. Together with the render loop's fixed sample streams and
// pass grouping (integrators/render_loop.h), a resumed render gives the same bits as an
// uninterrupted one.
//
// File layout (native byte order, recorded in the header; little-endian on every supported machine):
//   8 bytes   magic "KASHACKP"
//   u32       format version (1)
//   u32       0 (reserved)
//   u64       header length n, then n bytes of JSON: {"settings": {...}, "film": {...}, "run": {...}}
//   u64       pixel count w·h, then w·h·3 doubles of camera-sample sums, w·h·3 doubles of splat sums
//   if the header's film has "spectral_bins" {min, step, count}: w·h·count doubles of spectral
//   sums (core/spectral_film.h), pixel-major
//   u64       checksum of every byte before it (hashBytes)
// The reader verifies the checksum over the whole file before it parses the header (the layout of
// the sums follows from the pixel count and the file's size), and bounds the parse: at most 1 MiB
// of header, nested at most kMaxJsonDepth levels, every field typed and in range.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/film.h"
#include "core/spectral_film.h"

namespace kasha {

struct CheckpointData {
  nlohmann::json settings;  // what must match to resume (scene hash, integrator, seed, ...)
  nlohmann::json run;       // free-form progress information (samples per pass, seconds, ...)
  int width = 0, height = 0, spp = 0;
  uint64_t nonFiniteSamples = 0;
  std::pair<int, int> firstNonFinitePixel{-1, -1};
  std::vector<DVec3> sums, splats;
  SpectralBins spectralBins;     // count 0: the render kept no spectral bins
  std::vector<double> spectral;  // SpectralFilm::sums()
};

// Writes the film's state (and the spectral film's, if any) with `settings` and `run` to `path`
// atomically. Throws std::runtime_error naming the file if it cannot be written (the previous
// checkpoint stays).
void writeCheckpoint(const std::string& path, const nlohmann::json& settings, const nlohmann::json& run, const Film& film,
                     const SpectralFilm* spectral = nullptr);

// Reads a checkpoint. A missing, truncated, corrupted, forged or foreign file is an InputError
// naming it (one line), never a crash or an allocation larger than the file.
CheckpointData readCheckpoint(const std::string& path);

// Throws an InputError naming `path` for the first entry (in reportedBefore's order) of `saved` that
// differs from `current` ("was made with seed 1, this render has seed 2"); entries missing from
// either count as different.
void requireSameSettings(const nlohmann::json& saved, const nlohmann::json& current, const std::string& path);

// The order in which settings that differ are reported, here and between MPI ranks
// (integrators/rank_agreement.h): the integrator first (another one records other settings),
// scene_hash last (it covers the --set options too, which a setting of its own names better),
// the rest by name.
bool reportedBefore(const std::string& a, const std::string& b);

// Puts a checkpoint's state into the film (which must have its resolution) and the spectral film,
// which must be given, with the same bins, exactly when the checkpoint has spectral sums.
void restoreFilm(CheckpointData&& data, Film& film, SpectralFilm* spectral = nullptr);

// A 64-bit hash of bytes (word-wise FNV-1a with a SplitMix64 finaliser): checksums and scene hashes.
uint64_t hashBytes(const void* data, size_t size, uint64_t seed = 0);

}  // namespace kasha
