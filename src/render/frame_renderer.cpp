#include "render/frame_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vaegail::render {

namespace {

constexpr int kMaxSceneGeoms = 4000;
constexpr double kFloorLineSpacing = 1.0;  // m
constexpr double kFloorLineReach = 10.0;   // m either side of the look-at point
constexpr double kDistancePerRadius = 3.0;
constexpr int kShadowMapSize = 1024;  // pixels a side

// The first body with a joint: the root of what moves (an arm's first link, not its base and
// table); 0 (the world) when nothing does.
int moving_root(const mjModel* m) {
  for (int b = 1; b < m->nbody; ++b)
    if (m->body_jntnum[b] > 0) return b;
  return 0;
}

// Whether the body's joints let it translate: a body that moves about (free or slide root).
bool translates(const mjModel* m, int body) {
  for (int j = m->body_jntadr[body]; j >= 0 && j < m->body_jntadr[body] + m->body_jntnum[body]; ++j)
    if (m->jnt_type[j] == mjJNT_FREE || m->jnt_type[j] == mjJNT_SLIDE) return true;
  return false;
}

// MuJoCo's 150% font reads well from 480 pixels a tile; narrower tiles take the 100% one.
int font_scale(const FrameLayout& layout) { return layout.tile_width >= 480 ? mjFONTSCALE_150 : mjFONTSCALE_100; }

bool in_subtree(const mjModel* m, int body, int root) {
  for (; body > 0; body = m->body_parentid[body])
    if (body == root) return true;
  return root == 0;
}

// Distance from `center` to the farthest point of the non-plane geoms under `root`.
double subtree_radius(const mjModel* m, const mjData* d, int root, const mjtNum center[3]) {
  double radius = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_type[g] == mjGEOM_PLANE || !in_subtree(m, m->geom_bodyid[g], root)) continue;
    mjtNum offset[3];
    mju_sub3(offset, d->geom_xpos + 3 * g, center);
    radius = std::max(radius, mju_norm3(offset) + m->geom_rbound[g]);
  }
  return radius;
}

}  // namespace

FrameRenderer::FrameRenderer(const mjModel* model, FrameLayout layout, CameraOptions camera) : layout_(layout) {
  if (layout.rows < 1 || layout.cols < 1 || layout.tile_width < 16 || layout.tile_height < 16)
    throw RenderError("frame layout: " + std::to_string(layout.rows) + "x" + std::to_string(layout.cols) + " tiles of " +
                      std::to_string(layout.tile_width) + "x" + std::to_string(layout.tile_height) +
                      " pixels (at least 1x1 tiles of 16x16)");
  model_ = mj_copyModel(nullptr, model);
  model_->vis.global.offwidth = layout.width();
  model_->vis.global.offheight = layout.height();
  // On a software renderer MuJoCo's defaults cost 4x: a 4096x4096 shadow map drawn for every
  // light of every tile, and 4x multisampling. 1024 keeps soft contact shadows at video sizes.
  model_->vis.quality.shadowsize = kShadowMapSize;
  model_->vis.quality.offsamples = 0;

  // The reference pose fixes the still camera's aim and the automatic distance.
  mjData* reference = mj_makeData(model_);
  mj_forward(model_, reference);
  const int root = moving_root(model_);
  tracked_body_ = root > 0 && translates(model_, root) ? root : -1;
  mju_copy3(reference_center_, reference->subtree_com + 3 * root);
  const double radius = subtree_radius(model_, reference, root, reference_center_);
  mj_deleteData(reference);

  mjv_defaultCamera(&camera_);
  camera_.distance = camera.distance > 0 ? camera.distance : radius > 0 ? kDistancePerRadius * radius : 3.0;
  camera_.azimuth = camera.azimuth;
  camera_.elevation = camera.elevation;
  // A free camera whose look-at point draw() sets: MuJoCo's mjCAMERA_TRACKING eases towards
  // the body from where it last looked, so a tile's first frame (or a jump) would miss it.
  camera_.type = mjCAMERA_FREE;
  mju_copy3(camera_.lookat, reference_center_);

  mjv_defaultOption(&options_);
  mjv_defaultScene(&scene_);
  mjv_makeScene(model_, &scene_, kMaxSceneGeoms);
  mjr_defaultContext(&context_);
  mjr_makeContext(model_, &context_, font_scale(layout));
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  if (context_.currentBuffer != mjFB_OFFSCREEN || context_.offWidth != layout.width() ||
      context_.offHeight != layout.height()) {
    const std::string size = std::to_string(layout.width()) + "x" + std::to_string(layout.height());
    mjr_freeContext(&context_);
    mjv_freeScene(&scene_);
    mj_deleteModel(model_);
    throw RenderError("offscreen framebuffer of " + size + " pixels: not available from " + gl_.renderer());
  }
  bottom_up_.resize(static_cast<size_t>(layout.width()) * layout.height() * 3);
  pixels_.resize(bottom_up_.size());
}

FrameRenderer::~FrameRenderer() {
  mjr_freeContext(&context_);
  mjv_freeScene(&scene_);
  mj_deleteModel(model_);
}

mjrRect FrameRenderer::tile_rect(int row, int col) const {
  if (row < 0 || row >= layout_.rows || col < 0 || col >= layout_.cols)
    throw RenderError("tile (" + std::to_string(row) + ", " + std::to_string(col) + ") outside the " +
                      std::to_string(layout_.rows) + "x" + std::to_string(layout_.cols) + " frame");
  // OpenGL counts rows from the bottom.
  return {col * layout_.tile_width, (layout_.rows - 1 - row) * layout_.tile_height, layout_.tile_width,
          layout_.tile_height};
}

void FrameRenderer::draw(int row, int col, const mjData& data, const std::string& caption) {
  const mjrRect rect = tile_rect(row, col);
  mjvCamera camera = camera_;
  if (tracked_body_ >= 0) mju_copy3(camera.lookat, data.subtree_com + 3 * tracked_body_);
  // mjv_updateScene takes mjData* but only reads the state (positions, contacts, lights).
  mjv_updateScene(model_, const_cast<mjData*>(&data), &options_, nullptr, &camera, mjCAT_ALL, &scene_);
  add_floor_lines(camera);
  if (tracked_body_ >= 0) follow_lights(camera);
  mjr_render(rect, &scene_, &context_);
  if (!caption.empty()) mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, rect, caption.c_str(), nullptr, &context_);
}

void FrameRenderer::clear(int row, int col) { mjr_rectangle(tile_rect(row, col), 0, 0, 0, 1); }

// Lines along both axes of every plane, kFloorLineSpacing apart, within kFloorLineReach of the
// look-at point and inside the plane's extent (a size of 0 is an infinite plane).
void FrameRenderer::add_floor_lines(const mjvCamera& camera) {
  static const float kLineColour[4] = {0.25f, 0.28f, 0.32f, 1.f};
  for (int g = 0; g < model_->ngeom; ++g) {
    // Floors hang on the world body, where a geom's pose in the model is its pose in the world.
    if (model_->geom_type[g] != mjGEOM_PLANE || model_->geom_bodyid[g] != 0) continue;
    mjtNum axes[9], origin[3];  // axes: the plane's x, y and normal as the columns
    mju_quat2Mat(axes, model_->geom_quat + 4 * g);
    mju_copy3(origin, model_->geom_pos + 3 * g);
    mjtNum relative[3], local[3];
    mju_sub3(relative, camera.lookat, origin);
    mju_mulMatTVec(local, axes, relative, 3, 3);
    const double half[2] = {model_->geom_size[3 * g] > 0 ? model_->geom_size[3 * g] : mjMAXVAL,
                            model_->geom_size[3 * g + 1] > 0 ? model_->geom_size[3 * g + 1] : mjMAXVAL};
    for (int along = 0; along < 2; ++along) {  // 0: lines across the plane's x axis, 1: across y
      const int across = 1 - along;
      const double from = std::max(-half[across], local[across] - kFloorLineReach);
      const double to = std::min(half[across], local[across] + kFloorLineReach);
      const double line_from = std::max(-half[along], local[along] - kFloorLineReach);
      const double line_to = std::min(half[along], local[along] + kFloorLineReach);
      if (from > to || line_from > line_to) continue;
      for (double k = std::ceil(from / kFloorLineSpacing); k * kFloorLineSpacing <= to; ++k) {
        if (scene_.ngeom >= scene_.maxgeom) return;
        mjtNum centre_local[3] = {0, 0, 0.002}, size[3] = {0.01, 0.01, 0.001};
        centre_local[across] = k * kFloorLineSpacing;
        centre_local[along] = 0.5 * (line_from + line_to);
        size[along] = 0.5 * (line_to - line_from);
        mjtNum centre[3];
        mju_mulMatVec(centre, axes, centre_local, 3, 3);
        mju_addTo3(centre, origin);
        mjvGeom* line = scene_.geoms + scene_.ngeom++;
        mjv_initGeom(line, mjGEOM_BOX, size, centre, axes, kLineColour);
        line->category = mjCAT_DECOR;
      }
    }
  }
}

// The model's lights keep their place relative to the look-at point (horizontally), as
// MJCF's mode="trackcom" would: a walker 30 m down the floor is lit as at the start.
void FrameRenderer::follow_lights(const mjvCamera& camera) {
  for (int i = 0; i < scene_.nlight; ++i) {
    mjvLight& light = scene_.lights[i];
    if (light.headlight) continue;
    light.pos[0] += static_cast<float>(camera.lookat[0] - reference_center_[0]);
    light.pos[1] += static_cast<float>(camera.lookat[1] - reference_center_[1]);
  }
}

const std::vector<std::uint8_t>& FrameRenderer::read() {
  mjr_readPixels(bottom_up_.data(), nullptr, {0, 0, layout_.width(), layout_.height()}, &context_);
  const size_t row_bytes = static_cast<size_t>(layout_.width()) * 3;
  for (int r = 0; r < layout_.height(); ++r)
    std::memcpy(pixels_.data() + r * row_bytes, bottom_up_.data() + (layout_.height() - 1 - r) * row_bytes, row_bytes);
  return pixels_;
}

}  // namespace vaegail::render
