// WritePng: libpng with its errors turned into exceptions through setjmp/longjmp, which is the
// error protocol libpng offers; nothing with a destructor lives between setjmp and the calls.
#include "dlmfd/viz/png_file.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <string>
#include <vector>

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace {

struct PngErrorState {
  char message[256] = {0};
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof(state->message), "%s", message);
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

// Returns an empty string on success, libpng's message otherwise.
std::string EncodePng(std::FILE* file, const RasterImage& image, png_bytepp rows) {
  PngErrorState state;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, OnPngError, OnPngWarning);
  if (png == nullptr) return "cannot create the PNG writer";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return "cannot create the PNG header";
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return state.message;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(image.Width()), png_uint_32(image.Height()), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return {};
}

}  // namespace

void WritePng(const RasterImage& image, const std::string& path) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr) throw Error("cannot write " + path + ": cannot open " + temporary);
  std::vector<png_bytep> rows(std::size_t(image.Height()));
  const std::size_t stride = std::size_t(image.Width()) * 3;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    // libpng's row type is non-const although png_write_image only reads the rows.
    rows[r] = const_cast<png_bytep>(image.Bytes().data() + r * stride);
  }
  const std::string failure = EncodePng(file, image, rows.data());
  const bool closed = std::fclose(file) == 0;
  if (!failure.empty() || !closed) {
    std::remove(temporary.c_str());
    throw Error("cannot write " + path + ": " + (failure.empty() ? "close failed" : failure));
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw Error("cannot write " + path + ": rename from " + temporary + " failed");
  }
}

}  // namespace dlmfd
