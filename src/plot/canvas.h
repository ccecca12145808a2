// An RGB raster with the few drawing primitives charts need, saved as PNG through libpng.
//
// Coordinates are in pixels with the origin at the top-left corner; pixel (i, j) covers the
// square [i, i+1) x [j, j+1), so its centre is (i + 0.5, j + 0.5). Lines and circles are
// anti-aliased by blending towards the ink by the covered fraction of a pixel; rectangles and
// text are crisp. Anything outside the canvas is clipped.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vaegail::plot {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

inline constexpr Rgb kWhite{255, 255, 255};
inline constexpr Rgb kBlack{0, 0, 0};

using Point = std::array<double, 2>;

// Which point of a text's box the anchor coordinate names, per direction.
enum class Align { Start, Center, End };

class Canvas {
 public:
  Canvas(int width, int height, Rgb background = kWhite);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb pixel(int x, int y) const;

  // alpha is the ink's opacity in [0, 1]; 1 replaces the pixel.
  void blend_pixel(int x, int y, Rgb color, double alpha = 1.0);

  // Fills the pixels whose centres lie in [x0, x1) x [y0, y1) (corners in any order).
  void fill_rect(double x0, double y0, double x1, double y1, Rgb color, double alpha = 1.0);
  void draw_rect_outline(double x0, double y0, double x1, double y1, Rgb color);
  void draw_line(Point from, Point to, Rgb color, double width = 1.0);
  // dash_length > 0 draws dashes and gaps of that length, continuing across vertices.
  void draw_polyline(const std::vector<Point>& points, Rgb color, double width = 1.0,
                     double dash_length = 0.0);
  void fill_circle(Point centre, double radius, Rgb color);

  // Text in the built-in font magnified `scale` times; (x, y) is the point of the text's box
  // (its width by the capital height) chosen by the two alignments.
  void draw_text(double x, double y, const std::string& text, Rgb color, int scale = 1,
                 Align horizontal = Align::Start, Align vertical = Align::Start);
  // The same, turned 90 degrees anticlockwise (reads upwards, as a y-axis label); the
  // alignments refer to the turned box.
  void draw_text_upwards(double x, double y, const std::string& text, Rgb color, int scale = 1,
                         Align horizontal = Align::Start, Align vertical = Align::Start);

  // Writes an 8-bit RGB PNG that appears whole or not at all; throws std::runtime_error naming
  // the path when it cannot.
  void save_png(const std::string& path) const;

 private:
  // Blends `color` into the pixels of the box by how far inside the shape each centre is;
  // `distance` is the signed distance from a point to the shape's edge (negative inside).
  template <typename SignedDistance>
  void shade(double left, double top, double right, double bottom, Rgb color,
             SignedDistance distance);
  // Draws the ink of `text` through `place`, which maps a font pixel (column, row) to the
  // top-left canvas pixel of its scale x scale block.
  template <typename Place>
  void stamp_text(const std::string& text, Rgb color, int scale, Place place);

  int width_;
  int height_;
  std::vector<std::uint8_t> rgb_;  // [height, width, 3] row-major
};

// Reads an 8-bit RGB(A) PNG back, alpha dropped; throws std::runtime_error naming the path.
Canvas read_png(const std::string& path);

// The width in canvas pixels of `text` drawn at `scale`, and the height of its capitals.
int text_width(const std::string& text, int scale);
int text_height(int scale);

}  // namespace vaegail::plot
