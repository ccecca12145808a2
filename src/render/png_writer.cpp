#include "render/png_writer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/frame.h>
}

#include <cstring>
#include <memory>

#include "render/gl_context.h"
#include "util/atomic_file.h"

namespace vaegail::render {

namespace {
struct CodecContextFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
}  // namespace

void write_png(const std::string& path, int width, int height, const std::uint8_t* rgb) {
  const auto fail = [&](const std::string& what) { throw RenderError(path + ": " + what); };
  if (width < 1 || height < 1) fail("an image of " + std::to_string(width) + "x" + std::to_string(height) + " pixels");
  const AVCodec* codec = avcodec_find_encoder(AV_CODEC_ID_PNG);
  if (!codec) fail("no PNG encoder in this libavcodec");
  std::unique_ptr<AVCodecContext, CodecContextFree> encoder(avcodec_alloc_context3(codec));
  std::unique_ptr<AVFrame, FrameFree> frame(av_frame_alloc());
  std::unique_ptr<AVPacket, PacketFree> packet(av_packet_alloc());
  if (!encoder || !frame || !packet) fail("out of memory for the PNG encoder");
  encoder->width = width;
  encoder->height = height;
  encoder->pix_fmt = AV_PIX_FMT_RGB24;
  encoder->time_base = {1, 1};
  if (avcodec_open2(encoder.get(), codec, nullptr) < 0) fail("opening the PNG encoder");
  frame->format = AV_PIX_FMT_RGB24;
  frame->width = width;
  frame->height = height;
  if (av_frame_get_buffer(frame.get(), 0) < 0) fail("a frame buffer");
  for (int y = 0; y < height; ++y)  // the frame's rows may be padded
    std::memcpy(frame->data[0] + static_cast<size_t>(y) * frame->linesize[0], rgb + static_cast<size_t>(y) * width * 3,
                static_cast<size_t>(width) * 3);
  if (avcodec_send_frame(encoder.get(), frame.get()) < 0 || avcodec_send_frame(encoder.get(), nullptr) < 0 ||
      avcodec_receive_packet(encoder.get(), packet.get()) < 0)
    fail("encoding the PNG");
  write_file_atomically(path, std::string(reinterpret_cast<const char*>(packet->data), packet->size));
}

}  // namespace vaegail::render
