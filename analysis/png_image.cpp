#include "analysis/png_image.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "support/output_file.h"

namespace boxgen::analysis {

namespace {

// libpng reports through these instead of printing to stderr: an error ends the write (the
// caller's setjmp), a warning is dropped (the result is still checked by commit()).
[[noreturn]] void png_failed(png_structp png, png_const_charp /*message*/) { png_longjmp(png, 1); }
void png_warned(png_structp /*png*/, png_const_charp /*message*/) {}

}  // namespace

void write_png(const std::string& path, const RgbImage& image) {
  support::PendingOutput out(path);
  std::FILE* file = out.file();
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_failed, png_warned);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    // A failed fwrite (a full disk): commit() reports the system's reason from the stream.
    const int error = errno;
    png_destroy_write_struct(&png, &info);
    out.abandon(std::ferror(file) && error != 0 ? std::strerror(error)
                                                : "the image could not be encoded");
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, const_cast<png_bytep>(image.pixels.data() +
                                             static_cast<std::size_t>(y) * image.width * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  out.commit();
}

void colour_map(double t, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b) {
  // Piecewise-linear through samples of matplotlib's viridis.
  static const std::array<std::array<double, 3>, 6> stops = {{{0.267, 0.005, 0.329},
                                                              {0.254, 0.265, 0.530},
                                                              {0.164, 0.471, 0.558},
                                                              {0.135, 0.659, 0.518},
                                                              {0.478, 0.821, 0.318},
                                                              {0.993, 0.906, 0.144}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (stops.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double f = t - static_cast<double>(i);
  auto mix = [&](int c) {
    return static_cast<std::uint8_t>(
        std::lround(255 * ((1 - f) * stops[i][c] + f * stops[i + 1][c])));
  };
  r = mix(0);
  g = mix(1);
  b = mix(2);
}

}  // namespace boxgen::analysis
