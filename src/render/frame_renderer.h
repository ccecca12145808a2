// MuJoCo's own renderer (mjv_updateScene, mjr_render) drawing one video frame as a grid of
// tiles: each tile a body's state (its own mjData) seen by a camera that follows the body's
// root, with a caption in the tile's top-left corner.
//
// The camera: the root is the first body with a joint. A root that can translate (a free or
// a slide joint: the walker, the humanoid, a hopper) is tracked: the look-at point is its
// subtree's centre of mass, set every frame, and the model's lights move along with it so that
// a body far from the origin stays lit. A root that only turns (the arm's first link, on a
// fixed base) is watched by a still camera aimed at its subtree's centre in the model's
// reference pose. The distance, unless given, is 3x the subtree's radius in that pose. Every
// plane on the world body (a floor) gets lines 1 m apart near the look-at point: on a plain
// floor a tracked body would otherwise seem to walk on the spot. Captions use MuJoCo's 100%
// font below 480 pixels a tile, its 150% one from there.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <string>
#include <vector>

#include "render/gl_context.h"

namespace vaegail::render {

struct CameraOptions {
  double distance = 0;     // m from the look-at point; 0: 3x the body's radius in its reference pose
  double azimuth = 90;     // degrees about the vertical; 90 looks along +y, at a walker's side
  double elevation = -10;  // degrees; negative looks down
};

struct FrameLayout {
  int rows = 1, cols = 1;
  int tile_width = 320, tile_height = 240;  // pixels
  int width() const { return cols * tile_width; }
  int height() const { return rows * tile_height; }
};

class FrameRenderer {
 public:
  // Creates the OpenGL context (gl_context.h) and MuJoCo's offscreen framebuffer of the whole
  // frame. Throws RenderError when the frame is larger than the renderer allows.
  FrameRenderer(const mjModel* model, FrameLayout layout, CameraOptions camera = {});
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // Draws the state `data` (of the model given at construction; positions computed, as after
  // mj_step or mj_forward) into tile (row, col), row 0 at the top; `caption` may hold '\n'.
  void draw(int row, int col, const mjData& data, const std::string& caption);
  // Clears the tile (row, col) to black: a grid cell with nothing in it.
  void clear(int row, int col);
  // The frame drawn so far: RGB bytes [height, width, 3], the top row first.
  const std::vector<std::uint8_t>& read();

  const FrameLayout& layout() const { return layout_; }
  const std::string& gl_renderer() const { return gl_.renderer(); }
  // The body the camera tracks; -1 when the root is fixed and the camera is still.
  int tracked_body() const { return tracked_body_; }
  double camera_distance() const { return camera_.distance; }

 private:
  mjrRect tile_rect(int row, int col) const;
  void add_floor_lines(const mjvCamera& camera);
  void follow_lights(const mjvCamera& camera);

  GlContext gl_;
  FrameLayout layout_;
  mjModel* model_ = nullptr;  // a copy, sized for the offscreen framebuffer
  mjvScene scene_;
  mjrContext context_;
  mjvOption options_;
  mjvCamera camera_;
  int tracked_body_ = -1;
  mjtNum reference_center_[3] = {0, 0, 0};  // the look-at point of the reference pose
  std::vector<std::uint8_t> bottom_up_, pixels_;
};

}  // namespace vaegail::render
