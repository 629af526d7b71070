#pragma once
// A PNG decoded to RGB pixels (libpng's simplified API), so tests of the tools' pictures assert
// what a picture shows (its size, which series are drawn and where) instead of its magic bytes.

#include <png.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace mcws::test {

/// \brief A colour as written in gnuplot scripts, 0xRRGGBB.
using Rgb = std::uint32_t;

/// \brief The pixel rectangle [x0, x1] x [y0, y1] (y down, as in the file) of the pixels of one
/// colour; empty when no pixel has it.
struct PixelBox {
  int x0 = 0, x1 = -1, y0 = 0, y1 = -1;
  bool empty() const { return x1 < x0; }
  int width() const { return empty() ? 0 : x1 - x0 + 1; }
  int height() const { return empty() ? 0 : y1 - y0 + 1; }
};

/// \brief Whether a colour is grey (white, black and the greys of text and grid): its channels
/// within `tolerance` of each other.
inline bool isGrey(Rgb colour, int tolerance = 8) {
  const int r = colour >> 16 & 0xff, g = colour >> 8 & 0xff, b = colour & 0xff;
  return std::max({r, g, b}) - std::min({r, g, b}) <= tolerance;
}

class PngImage {
 public:
  /// \throws std::runtime_error naming the file when it is not a readable PNG.
  explicit PngImage(const std::string& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
      throw std::runtime_error(path + ": not a PNG: " + image.message);
    }
    image.format = PNG_FORMAT_RGB;
    pixels_.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels_.data(), 0, nullptr)) {
      throw std::runtime_error(path + ": cannot decode: " + image.message);
    }
    width_ = static_cast<int>(image.width);
    height_ = static_cast<int>(image.height);
  }

  int width() const { return width_; }
  int height() const { return height_; }

  /// \brief Whether pixel (x, y) is `colour`, each channel within `tolerance`.
  bool is(int x, int y, Rgb colour, int tolerance = 0) const {
    return near(rgb(x, y), colour, tolerance);
  }

  /// \brief How many pixels are `colour` (each channel within `tolerance`).
  std::size_t count(Rgb colour, int tolerance = 0) const {
    std::size_t n = 0;
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) n += is(x, y, colour, tolerance);
    }
    return n;
  }

  /// \brief The rectangle the pixels for which `keep(rgb)` holds span inside `within`.
  template <typename Keep>
  PixelBox box(Keep&& keep, const PixelBox& within) const {
    PixelBox b{width_, -1, height_, -1};
    for (int y = std::max(within.y0, 0); y <= std::min(within.y1, height_ - 1); ++y) {
      for (int x = std::max(within.x0, 0); x <= std::min(within.x1, width_ - 1); ++x) {
        if (!keep(rgb(x, y))) continue;
        b.x0 = std::min(b.x0, x), b.x1 = std::max(b.x1, x);
        b.y0 = std::min(b.y0, y), b.y1 = std::max(b.y1, y);
      }
    }
    return b;
  }

  /// \brief The rectangle the pixels of `colour` (within `tolerance`) span inside `within`.
  PixelBox box(Rgb colour, int tolerance, const PixelBox& within) const {
    return box([&](Rgb c) { return near(c, colour, tolerance); }, within);
  }

  /// \brief Whether two colours agree within `tolerance` in each channel.
  static bool near(Rgb a, Rgb b, int tolerance) {
    for (int shift : {16, 8, 0}) {
      if (std::abs(static_cast<int>(a >> shift & 0xff) - static_cast<int>(b >> shift & 0xff)) >
          tolerance)
        return false;
    }
    return true;
  }

  /// \brief The rectangle the pixels of `colour` (within `tolerance`) span.
  PixelBox box(Rgb colour, int tolerance = 0) const {
    return box(colour, tolerance, PixelBox{0, width_ - 1, 0, height_ - 1});
  }

  /// \brief The colour of pixel (x, y).
  Rgb rgb(int x, int y) const {
    const std::uint8_t* p = &pixels_[3 * (static_cast<std::size_t>(y) * width_ + x)];
    return static_cast<Rgb>(p[0]) << 16 | static_cast<Rgb>(p[1]) << 8 | p[2];
  }

  /// \brief The frame of a one-panel gnuplot plot (its black border): the first and last rows
  /// crossed by a black line longer than `share` of the width, and that line's ends. Empty when
  /// there is none.
  PixelBox frame(double share = 0.4) const {
    PixelBox f;
    for (int y = 0; y < height_; ++y) {
      int run = 0;
      for (int x = 0; x < width_; ++x) {
        run = is(x, y, 0x000000, 40) ? run + 1 : 0;
        if (run < share * width_) continue;
        if (f.empty()) {
          f = {x - run + 1, x, y, y};
          while (f.x1 + 1 < width_ && is(f.x1 + 1, y, 0x000000, 40)) ++f.x1;
        }
        f.y1 = y;
        break;
      }
    }
    return f;
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace mcws::test
