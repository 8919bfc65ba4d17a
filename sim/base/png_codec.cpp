#include "sim/base/png_codec.h"

#include <png.h>

#include <csetjmp>
#include <cstring>
#include <stdexcept>

namespace ambisim {
namespace {

// libpng reports errors through a callback that must not return; the documented way out of
// C code is longjmp back to the setjmp in the caller (png_jmpbuf). Everything these callbacks
// and the code between setjmp and longjmp touch is trivially destructible or owned by a frame
// outside it, so the jump skips no destructor.
struct ReadSource {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  std::size_t pos = 0;
  char message[200] = {};
};

struct WriteSink {
  std::string* out = nullptr;
  char message[200] = {};
};

void copy_message(char (&dst)[200], const char* msg) {
  std::strncpy(dst, msg != nullptr ? msg : "unknown libpng error", sizeof dst - 1);
  dst[sizeof dst - 1] = '\0';
}

void read_error(png_structp png, png_const_charp msg) {
  copy_message(static_cast<ReadSource*>(png_get_error_ptr(png))->message, msg);
  png_longjmp(png, 1);
}

void write_error(png_structp png, png_const_charp msg) {
  copy_message(static_cast<WriteSink*>(png_get_error_ptr(png))->message, msg);
  png_longjmp(png, 1);
}

void quiet_warning(png_structp, png_const_charp) {}

void read_bytes(png_structp png, png_bytep out, png_size_t n) {
  auto* src = static_cast<ReadSource*>(png_get_io_ptr(png));
  if (n > src->size - src->pos) png_error(png, "truncated file (ends inside the image data)");
  std::memcpy(out, src->data + src->pos, n);
  src->pos += n;
}

void write_bytes(png_structp png, png_bytep data, png_size_t n) {
  static_cast<WriteSink*>(png_get_io_ptr(png))->out->append(reinterpret_cast<const char*>(data), n);
}

void flush_nothing(png_structp) {}

// Reads the header and sets the transformations; fills the geometry of `out`. Returns false
// (message in src) on a libpng error.
bool read_image(png_structp png, png_infop info, ReadSource& src, PngSamples& out,
                std::vector<unsigned char>& bytes, std::vector<png_bytep>& rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, &src, read_bytes);
  png_set_user_limits(png, kPngMaxSide, kPngMaxSide);
  // Bounds the memory a hostile ancillary chunk (zTXt, iCCP) may ask for.
  png_set_chunk_malloc_max(png, 8u << 20);
  png_read_info(png, info);
  const int colour = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  out.palette = colour == PNG_COLOR_TYPE_PALETTE;
  if (out.palette) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out.width = static_cast<int>(png_get_image_width(png, info));
  out.height = static_cast<int>(png_get_image_height(png, info));
  out.channels = png_get_channels(png, info);
  out.bit_depth = png_get_bit_depth(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  bytes.resize(row_bytes * static_cast<std::size_t>(out.height));
  rows.resize(static_cast<std::size_t>(out.height));
  for (int y = 0; y < out.height; ++y) rows[y] = bytes.data() + row_bytes * y;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  return true;
}

bool write_image(png_structp png, png_infop info, WriteSink& sink, const PngSamples& img,
                 std::vector<unsigned char>& bytes, std::vector<png_bytep>& rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, &sink, write_bytes, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height),
               img.bit_depth, img.channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 9);
  png_write_info(png, info);
  for (int y = 0; y < img.height; ++y) rows[y] = bytes.data() + bytes.size() / img.height * y;
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

PngDecodeResult decode_png(std::string_view bytes) {
  PngDecodeResult result;
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0) {
    result.error = "not a PNG file (no PNG signature)";
    return result;
  }
  ReadSource src;
  src.data = reinterpret_cast<const unsigned char*>(bytes.data());
  src.size = bytes.size();
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, read_error, quiet_warning);
  if (png == nullptr) throw std::bad_alloc();
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw std::bad_alloc();
  }
  PngSamples out;
  std::vector<unsigned char> raw;
  std::vector<png_bytep> rows;
  const bool ok = read_image(png, info, src, out, raw, rows);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok) {
    result.error = std::string("corrupt or truncated PNG: ") + src.message;
    return result;
  }
  const std::size_t n = static_cast<std::size_t>(out.width) * out.height * out.channels;
  out.samples.resize(n);
  if (out.bit_depth == 16) {
    // PNG stores 16-bit samples big-endian.
    for (std::size_t k = 0; k < n; ++k) {
      out.samples[k] = static_cast<std::uint16_t>((raw[2 * k] << 8) | raw[2 * k + 1]);
    }
  } else {
    for (std::size_t k = 0; k < n; ++k) out.samples[k] = raw[k];
  }
  result.image = std::move(out);
  return result;
}

std::string encode_png(const PngSamples& img) {
  if (img.width <= 0 || img.height <= 0 || (img.channels != 1 && img.channels != 3) ||
      (img.bit_depth != 8 && img.bit_depth != 16) ||
      img.samples.size() != static_cast<std::size_t>(img.width) * img.height * img.channels) {
    throw std::invalid_argument("encode_png: malformed image");
  }
  const std::size_t bps = img.bit_depth / 8;
  std::vector<unsigned char> bytes(img.samples.size() * bps);
  for (std::size_t k = 0; k < img.samples.size(); ++k) {
    const std::uint16_t v = img.samples[k];
    if (v > img.max_value()) throw std::invalid_argument("encode_png: sample above the depth");
    if (bps == 2) {
      bytes[2 * k] = static_cast<unsigned char>(v >> 8);
      bytes[2 * k + 1] = static_cast<unsigned char>(v & 0xFF);
    } else {
      bytes[k] = static_cast<unsigned char>(v);
    }
  }
  std::string out;
  WriteSink sink;
  sink.out = &out;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, write_error, quiet_warning);
  if (png == nullptr) throw std::bad_alloc();
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw std::bad_alloc();
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(img.height));
  const bool ok = write_image(png, info, sink, img, bytes, rows);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error(std::string("encode_png: ") + sink.message);
  return out;
}

}  // namespace ambisim
