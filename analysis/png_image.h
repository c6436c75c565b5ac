// RGB images written as PNG through libpng (renders, slices), atomically.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace boxgen::analysis {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, 3 bytes per pixel, top row first
  RgbImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3, 0) {}
  void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    pixels[i] = r;
    pixels[i + 1] = g;
    pixels[i + 2] = b;
  }
};

// Throws std::invalid_argument for an unwritable path, std::runtime_error if libpng fails.
void write_png(const std::string& path, const RgbImage& image);

// A perceptual colour map (viridis-like, from dark blue through green to yellow) for t in [0, 1].
void colour_map(double t, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b);

}  // namespace boxgen::analysis
