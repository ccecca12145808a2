#include "plot/canvas.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "plot/font.h"

namespace vaegail::plot {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

TEST(Canvas, PngRoundTripKeepsEveryPixel) {
  Canvas canvas(37, 23, Rgb{10, 20, 30});
  canvas.fill_rect(2, 3, 10, 12, Rgb{200, 50, 25});
  canvas.draw_line({0, 0}, {36, 22}, Rgb{0, 255, 0}, 2.0);
  canvas.draw_text(12, 4, "Ab1", kWhite);
  const std::string path = temp_path("vaegail_canvas_roundtrip.png");
  canvas.save_png(path);
  const Canvas back = read_png(path);
  ASSERT_EQ(back.width(), 37);
  ASSERT_EQ(back.height(), 23);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) ASSERT_EQ(back.pixel(x, y), canvas.pixel(x, y)) << x << "," << y;
  std::filesystem::remove(path);
}

TEST(Canvas, SaveToUnwritablePathNamesIt) {
  const std::string path = "/nonexistent-dir/figure.png";
  try {
    Canvas(4, 4).save_png(path);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_png("/nonexistent-dir/missing.png"), std::runtime_error);
}

TEST(Canvas, FillRectCoversPixelCentresInsideOnlyAndBlends) {
  Canvas canvas(10, 10);
  canvas.fill_rect(2, 2, 5, 4, kBlack, 0.5);
  EXPECT_EQ(canvas.pixel(2, 2), (Rgb{128, 128, 128}));
  EXPECT_EQ(canvas.pixel(4, 3), (Rgb{128, 128, 128}));
  EXPECT_EQ(canvas.pixel(5, 3), kWhite);
  EXPECT_EQ(canvas.pixel(4, 4), kWhite);
}

TEST(Canvas, LinesAreAntiAliasedAndClipped) {
  Canvas canvas(20, 20);
  canvas.draw_line({-10, 10}, {30, 10}, kBlack, 1.0);  // centred on the boundary of rows 9, 10
  EXPECT_EQ(canvas.pixel(5, 9), (Rgb{128, 128, 128}));
  EXPECT_EQ(canvas.pixel(5, 10), (Rgb{128, 128, 128}));
  EXPECT_EQ(canvas.pixel(5, 8), kWhite);
}

TEST(Canvas, TextLandsWhereAligned) {
  Canvas canvas(60, 20);
  canvas.draw_text(30, 10, "I", kBlack, 1, Align::Center, Align::Center);
  // "I" is a vertical bar in the middle column of its 5x7 cell, rows 0..6.
  const int left = 30 - text_width("I", 1) / 2, top = 10 - text_height(1) / 2;
  EXPECT_EQ(canvas.pixel(left + 2, top + 3), kBlack);
  EXPECT_EQ(canvas.pixel(left + 2, top - 1), kWhite);
}

TEST(Font, EveryPrintableGlyphHasFullRows) {
  for (int c = 32; c < 127; ++c) {
    const auto& rows = glyph_rows(static_cast<char>(c));
    EXPECT_TRUE(rows.size() >= kCapHeight && rows.size() <= kCellHeight) << char(c);
  }
  EXPECT_EQ(glyph_rows('\x01'), glyph_rows('?'));
  EXPECT_EQ(text_width("ab"), 2 * kGlyphAdvance - 1);
  EXPECT_EQ(text_width(""), 0);
}

}  // namespace
}  // namespace vaegail::plot
