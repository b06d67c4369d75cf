#pragma once
// Guards in front of stb_image's decoders (core/stb_image_input.h), for the faults of the stb_image
// of Debian 12 (2022-09) that fuzz_image found; each check reads the file exactly where stb would
// and refuses what would make stb misbehave, before stb reads any of it. (Its JPEG decoder is not
// compiled in: it wrote past its Huffman tables and indexed them negatively on fuzzed input.)
#include <cstdint>
#include <string>

namespace kasha {

// PNG: stb grows its buffer for the image data to each IDAT chunk's declared length before
// reading it (2 GB for a 500-byte file). Walks the chunks and throws InputError naming `path` for
// one that declares more bytes than the file holds after it.
void checkPngChunks(const std::string& bytes, const std::string& path);

// Radiance HDR: in a run-length encoded scanline, a "dump" of length 0 (or data ending early, which
// stb reads as zeros) never advances stbi__hdr_load's loop. Walks the scanlines of a width × height
// image as stb does and throws InputError naming `path` at such a run.
void checkHdrRuns(const std::string& bytes, uint64_t width, uint64_t height, const std::string& path);

}  // namespace kasha
