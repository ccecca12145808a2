// `vaegail bench render`: how fast episodes become video on this machine. One episode of
// uniform random actions (the body kept going after a fall, so every step has a state) is
// replayed and drawn frame by frame at the given size, and each frame encoded to H.264; the
// drawing (mjv_updateScene, mjr_render, mjr_readPixels on llvmpipe) and the encoding
// (RGB to yuv420p and libx264) are timed apart.
#pragma once

#include <string>

#include "env/registry.h"

namespace vaegail {

struct RenderBenchOptions {
  EnvRequest env;
  int width = 640, height = 480;
  int frames = 200;  // at most: the episode's length + 1 if shorter
};

struct RenderBenchResult {
  std::string gl_renderer;
  int frames = 0;
  double draw_seconds = 0, encode_seconds = 0;  // encode: every write() and finish()
  double draw_fps() const { return frames / draw_seconds; }
  double encode_fps() const { return frames / encode_seconds; }
  double total_fps() const { return frames / (draw_seconds + encode_seconds); }
};

RenderBenchResult run_render_bench(const RenderBenchOptions& options);
std::string format_render_bench(const RenderBenchOptions& options, const RenderBenchResult& result);

}  // namespace vaegail
