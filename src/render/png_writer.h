// One frame as a PNG file, through libavcodec's PNG encoder (the library the videos already
// use): the still of a video that a README or a page shows. Written atomically (util/atomic_file.h).
#pragma once

#include <cstdint>
#include <string>

namespace vaegail::render {

// rgb: [height, width, 3] bytes, the top row first. Throws RenderError naming `path` when the
// encoder is missing or fails, or the file cannot be written.
void write_png(const std::string& path, int width, int height, const std::uint8_t* rgb);

}  // namespace vaegail::render
