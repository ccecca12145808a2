#include "plot/canvas.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "plot/font.h"
#include "util/atomic_file.h"

namespace vaegail::plot {
namespace {

std::uint8_t mix(std::uint8_t under, std::uint8_t ink, double alpha) {
  return static_cast<std::uint8_t>(std::lround(under + alpha * (ink - under)));
}

double distance_to_segment(Point p, Point a, Point b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double length2 = dx * dx + dy * dy;
  const double t =
      length2 > 0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2, 0.0, 1.0)
                  : 0.0;
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

// Fraction of a pixel covered by ink whose edge is `distance_past_edge` from the pixel centre
// (negative inside): a one-pixel ramp, which is what makes edges look smooth.
double coverage(double distance_past_edge) {
  return std::clamp(0.5 - distance_past_edge, 0.0, 1.0);
}

// First pixel index whose centre is at or after coordinate v.
int first_centre_at_or_after(double v) { return static_cast<int>(std::ceil(v - 0.5)); }

int aligned_offset(int extent, Align align) {
  switch (align) {
    case Align::Start: return 0;
    case Align::Center: return -extent / 2;
    case Align::End: return -extent;
  }
  return 0;
}

Point lerp(Point a, Point b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb background) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("canvas: size must be positive, got " + std::to_string(width) +
                                "x" + std::to_string(height));
  rgb_.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = background.r;
    rgb_[i + 1] = background.g;
    rgb_[i + 2] = background.b;
  }
}

Rgb Canvas::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw std::out_of_range("canvas: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") is outside the canvas");
  const std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

void Canvas::blend_pixel(int x, int y, Rgb color, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || alpha <= 0) return;
  std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  const double a = std::min(alpha, 1.0);
  p[0] = mix(p[0], color.r, a);
  p[1] = mix(p[1], color.g, a);
  p[2] = mix(p[2], color.b, a);
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, Rgb color, double alpha) {
  const int left = std::max(0, first_centre_at_or_after(std::min(x0, x1)));
  const int right = std::min(width_, first_centre_at_or_after(std::max(x0, x1)));
  const int top = std::max(0, first_centre_at_or_after(std::min(y0, y1)));
  const int bottom = std::min(height_, first_centre_at_or_after(std::max(y0, y1)));
  for (int y = top; y < bottom; ++y)
    for (int x = left; x < right; ++x) blend_pixel(x, y, color, alpha);
}

void Canvas::draw_rect_outline(double x0, double y0, double x1, double y1, Rgb color) {
  const double left = std::min(x0, x1), right = std::max(x0, x1);
  const double top = std::min(y0, y1), bottom = std::max(y0, y1);
  fill_rect(left, top, right, top + 1, color);
  fill_rect(left, bottom - 1, right, bottom, color);
  fill_rect(left, top, left + 1, bottom, color);
  fill_rect(right - 1, top, right, bottom, color);
}

template <typename SignedDistance>
void Canvas::shade(double left, double top, double right, double bottom, Rgb color,
                   SignedDistance distance) {
  // One pixel of slack on every side holds the anti-aliasing ramp.
  const int x0 = std::max(0, static_cast<int>(std::floor(left)) - 1);
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(right)) + 1);
  const int y0 = std::max(0, static_cast<int>(std::floor(top)) - 1);
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(bottom)) + 1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) blend_pixel(x, y, color, coverage(distance(Point{x + 0.5, y + 0.5})));
}

void Canvas::draw_line(Point from, Point to, Rgb color, double width) {
  const double half = width / 2;
  shade(std::min(from[0], to[0]) - half, std::min(from[1], to[1]) - half,
        std::max(from[0], to[0]) + half, std::max(from[1], to[1]) + half, color,
        [&](Point p) { return distance_to_segment(p, from, to) - half; });
}

void Canvas::draw_polyline(const std::vector<Point>& points, Rgb color, double width,
                           double dash_length) {
  if (dash_length <= 0) {
    for (std::size_t i = 1; i < points.size(); ++i) draw_line(points[i - 1], points[i], color, width);
    return;
  }
  // Distance travelled within the current dash or gap, carried over vertices so that short
  // segments of a densely sampled path still show the pattern.
  double phase = 0;
  bool ink = true;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Point a = points[i - 1], b = points[i];
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    double done = 0;
    while (done < length) {
      const double step = std::min(dash_length - phase, length - done);
      if (ink) draw_line(lerp(a, b, done / length), lerp(a, b, (done + step) / length), color, width);
      done += step;
      phase += step;
      if (phase >= dash_length) {
        phase = 0;
        ink = !ink;
      }
    }
  }
}

void Canvas::fill_circle(Point centre, double radius, Rgb color) {
  shade(centre[0] - radius, centre[1] - radius, centre[0] + radius, centre[1] + radius, color,
        [&](Point p) { return std::hypot(p[0] - centre[0], p[1] - centre[1]) - radius; });
}

template <typename Place>
void Canvas::stamp_text(const std::string& text, Rgb color, int scale, Place place) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto& rows = glyph_rows(text[i]);
    for (std::size_t row = 0; row < rows.size(); ++row)
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (rows[row][static_cast<std::size_t>(col)] != '#') continue;
        const auto [x, y] = place(static_cast<int>(i) * kGlyphAdvance + col, static_cast<int>(row));
        fill_rect(x, y, x + scale, y + scale, color);
      }
  }
}

void Canvas::draw_text(double x, double y, const std::string& text, Rgb color, int scale,
                       Align horizontal, Align vertical) {
  const int left = static_cast<int>(std::lround(x)) + aligned_offset(text_width(text, scale), horizontal);
  const int top = static_cast<int>(std::lround(y)) + aligned_offset(text_height(scale), vertical);
  stamp_text(text, color, scale, [&](int col, int row) {
    return std::array<int, 2>{left + col * scale, top + row * scale};
  });
}

void Canvas::draw_text_upwards(double x, double y, const std::string& text, Rgb color, int scale,
                               Align horizontal, Align vertical) {
  // Turning anticlockwise sends the text's left edge to the bottom and its top to the left.
  const int left = static_cast<int>(std::lround(x)) + aligned_offset(text_height(scale), horizontal);
  const int top = static_cast<int>(std::lround(y)) + aligned_offset(text_width(text, scale), vertical);
  const int bottom = top + text_width(text, scale);
  stamp_text(text, color, scale, [&](int col, int row) {
    return std::array<int, 2>{left + row * scale, bottom - (col + 1) * scale};
  });
}

void Canvas::save_png(const std::string& path) const {
  write_atomically(path, [&](const std::string& tmp) {
    FILE* file = std::fopen(tmp.c_str(), "wb");
    if (file == nullptr)
      throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(width_);
    image.height = static_cast<png_uint_32>(height_);
    image.format = PNG_FORMAT_RGB;
    const bool written = png_image_write_to_stdio(&image, file, 0, rgb_.data(), 0, nullptr) != 0;
    const bool closed = std::fclose(file) == 0;
    if (!written) throw std::runtime_error(path + ": PNG encoding failed: " + image.message);
    if (!closed) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
  });
}

Canvas read_png(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, path.c_str()) == 0)
    throw std::runtime_error(path + ": cannot read PNG: " + image.message);
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr) == 0)
    throw std::runtime_error(path + ": cannot decode PNG: " + image.message);
  Canvas canvas(static_cast<int>(image.width), static_cast<int>(image.height));
  for (int y = 0; y < canvas.height(); ++y)
    for (int x = 0; x < canvas.width(); ++x) {
      const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * canvas.width() + x) * 3];
      canvas.blend_pixel(x, y, {p[0], p[1], p[2]});
    }
  return canvas;
}

int text_width(const std::string& text, int scale) { return text_width(text) * scale; }

int text_height(int scale) { return kCapHeight * scale; }

}  // namespace vaegail::plot
