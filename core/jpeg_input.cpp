#include "core/jpeg_input.h"

#include <algorithm>
#include <climits>
#include <csetjmp>
#include <cstdio>
#include <vector>

#include <jpeglib.h>

#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"

namespace kasha {
namespace {

// libjpeg reports errors through error_exit, which must not return: it jumps back to the setjmp in
// runJpeg. Nothing between the two owns resources (runJpeg's frame holds only plain data), so the
// jump skips no destructor.
struct JpegErrors {
  jpeg_error_mgr mgr;
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};

void failJpeg(j_common_ptr cinfo) {
  JpegErrors* e = reinterpret_cast<JpegErrors*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->back, 1);
}

// Warnings (msg_level −1: corrupt data libjpeg would work around) are errors; trace messages are ignored.
void noteJpeg(j_common_ptr cinfo, int level) {
  if (level < 0) failJpeg(cinfo);
}

struct JpegHeader {
  uint64_t width = 0, height = 0, components = 0;
};

// Reads the header, and with `rgb` non-null decodes the pixels into it (width·height·3 bytes)
// with libjpeg's memory capped at maxMemory. Returns false with `message` set on any error.
bool runJpeg(const unsigned char* data, unsigned long size, long maxMemory, JpegHeader* header, unsigned char* rgb,
             char* message) {
  jpeg_decompress_struct cinfo;
  JpegErrors errors;
  cinfo.err = jpeg_std_error(&errors.mgr);
  errors.mgr.error_exit = failJpeg;
  errors.mgr.emit_message = noteJpeg;
  if (setjmp(errors.back)) {
    std::snprintf(message, JMSG_LENGTH_MAX, "%s", errors.message);
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  cinfo.mem->max_memory_to_use = maxMemory;
  jpeg_mem_src(&cinfo, data, size);
  jpeg_read_header(&cinfo, TRUE);
  header->width = cinfo.image_width;
  header->height = cinfo.image_height;
  header->components = uint64_t(cinfo.num_components);
  if (rgb) {
    cinfo.out_color_space = JCS_RGB;  // grayscale and YCbCr convert; CMYK/YCCK stop in an error
    jpeg_start_decompress(&cinfo);
    if (cinfo.output_width != header->width || cinfo.output_height != header->height || cinfo.output_components != 3) {
      std::snprintf(message, JMSG_LENGTH_MAX, "the decoded size differs from the header's");
      jpeg_destroy_decompress(&cinfo);
      return false;
    }
    while (cinfo.output_scanline < cinfo.output_height) {
      JSAMPROW row = rgb + size_t(cinfo.output_scanline) * size_t(header->width) * 3;
      jpeg_read_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_decompress(&cinfo);
  }
  jpeg_destroy_decompress(&cinfo);
  return true;
}

const unsigned char* jpegBytes(const std::string& s) { return reinterpret_cast<const unsigned char*>(s.data()); }

// Working memory libjpeg needs besides the caller's RGB buffer: its line buffers and tables (a few
// MiB at most), and a progressive file's whole coefficient array.
constexpr uint64_t kJpegWorkingBytes = uint64_t(16) << 20;

}  // namespace

JpegInput::JpegInput(const std::string& path, const std::string& what)
    : path_(path), bytes_(readInputFile(path, what, kMaxImageFileBytes)) {
  if (bytes_.compare(0, 2, "\xFF\xD8") != 0) throw InputError(path, "", "cannot read JPEG: not JPEG (its signature is missing)");
  JpegHeader h;
  char message[JMSG_LENGTH_MAX] = {};
  if (!runJpeg(jpegBytes(bytes_), (unsigned long)bytes_.size(), long(kJpegWorkingBytes), &h, nullptr, message))
    throw InputError(path, "", std::string("cannot read JPEG: ") + message);
  if (h.width == 0 || h.height == 0) throw InputError(path, "", "cannot read JPEG: the image has no pixels");
  width_ = h.width;
  height_ = h.height;
  components_ = h.components;
}

uint64_t JpegInput::decodeBytes() const {
  const uint64_t pixels = saturatingMul(width_, height_);
  return saturatingMul(pixels, 3 + 2 * components_);
}

void JpegInput::decode(const PixelVisitor& pixel) const {
  std::vector<unsigned char> rgb(size_t(width_) * size_t(height_) * 3);
  JpegHeader h;
  char message[JMSG_LENGTH_MAX] = {};
  const uint64_t cap = saturatingMul(saturatingMul(width_, height_), 2 * components_) + kJpegWorkingBytes;
  if (!runJpeg(jpegBytes(bytes_), (unsigned long)bytes_.size(), long(std::min<uint64_t>(cap, uint64_t(LONG_MAX))), &h,
               rgb.data(), message))
    throw InputError(path_, "", std::string("cannot read JPEG: ") + message);
  for (size_t i = 0; i < rgb.size(); i += 3) pixel(float(rgb[i]) / 255.0f, float(rgb[i + 1]) / 255.0f, float(rgb[i + 2]) / 255.0f, 1.0f);
}

}  // namespace kasha
