// H.264 video in an MP4 file through FFmpeg's libraries (libavcodec's libx264 encoder,
// libavformat's muxer, libswscale for RGB to yuv420p), the format every browser and player
// reads. The file appears whole or not at all (util/atomic_file.h): frames go to a temporary
// file beside the target, which finish() moves into place; a writer destroyed before finish()
// (an exception, an interrupted render) removes it.
#pragma once

#include <cstdint>
#include <string>

struct AVFormatContext;
struct AVCodecContext;
struct AVFrame;
struct AVPacket;
struct SwsContext;

namespace vaegail::render {

struct VideoFormat {
  int width = 640, height = 480;  // pixels, both even (yuv420p halves the colour planes)
  int fps = 30;                   // frames per second of playback
  int crf = 23;                   // x264's constant quality: 0 lossless .. 51 worst; 23 its default
};

class Mp4Writer {
 public:
  // Throws RenderError (gl_context.h) naming `path` when the format is invalid, no H.264
  // encoder is available or the temporary file cannot be opened.
  Mp4Writer(std::string path, VideoFormat format);
  ~Mp4Writer();
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  // rgb: [height, width, 3] bytes, the top row first.
  void write(const std::uint8_t* rgb);
  // Flushes the encoder, writes the MP4 index and moves the file into place.
  void finish();
  std::int64_t frames_written() const { return frames_; }

 private:
  void drain(bool flushing);
  void close();
  [[noreturn]] void fail(const std::string& what, int error) const;

  std::string path_, tmp_path_;
  VideoFormat format_;
  AVFormatContext* muxer_ = nullptr;
  AVCodecContext* encoder_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* to_yuv_ = nullptr;
  int stream_ = 0;
  std::int64_t frames_ = 0;
  bool finished_ = false;
};

}  // namespace vaegail::render
