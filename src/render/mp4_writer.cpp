#include "render/mp4_writer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <cstdio>
#include <filesystem>

#include "render/gl_context.h"
#include "util/atomic_file.h"

namespace vaegail::render {

namespace {

std::string av_message(int error) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(error, text, sizeof text);
  return text;
}

}  // namespace

void Mp4Writer::fail(const std::string& what, int error) const {
  throw RenderError(path_ + ": " + what + (error < 0 ? ": " + av_message(error) : std::string()));
}

Mp4Writer::Mp4Writer(std::string path, VideoFormat format)
    : path_(std::move(path)), tmp_path_(fresh_temporary_path(path_)), format_(format) {
  if (format.width < 2 || format.height < 2 || format.width % 2 || format.height % 2)
    fail("video of " + std::to_string(format.width) + "x" + std::to_string(format.height) +
         " pixels: width and height must be even (H.264 in yuv420p)", 0);
  if (format.fps < 1 || format.fps > 1000) fail("fps " + std::to_string(format.fps) + ": must be 1..1000", 0);
  av_log_set_level(AV_LOG_ERROR);  // x264's settings and the muxer's passes are no news
  try {
    // Debian's libavcodec encodes H.264 with libx264; another H.264 encoder will do.
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) fail("no H.264 encoder in this libavcodec (Debian's libavcodec59 has libx264)", 0);
    int error = avformat_alloc_output_context2(&muxer_, nullptr, "mp4", tmp_path_.c_str());
    if (error < 0) fail("MP4 muxer", error);
    AVStream* stream = avformat_new_stream(muxer_, nullptr);
    encoder_ = avcodec_alloc_context3(codec);
    if (!stream || !encoder_) fail("out of memory for the video stream", 0);
    stream_ = stream->index;
    encoder_->width = format.width;
    encoder_->height = format.height;
    encoder_->time_base = {1, format.fps};
    encoder_->framerate = {format.fps, 1};
    encoder_->pix_fmt = AV_PIX_FMT_YUV420P;
    encoder_->gop_size = 2 * format.fps;  // a key frame every 2 s: seeking stays quick
    if (muxer_->oformat->flags & AVFMT_GLOBALHEADER) encoder_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    av_opt_set(encoder_->priv_data, "preset", "veryfast", 0);
    av_opt_set_int(encoder_->priv_data, "crf", format.crf, 0);
    if ((error = avcodec_open2(encoder_, codec, nullptr)) < 0) fail(std::string("opening encoder ") + codec->name, error);
    if ((error = avcodec_parameters_from_context(stream->codecpar, encoder_)) < 0) fail("stream parameters", error);
    stream->time_base = encoder_->time_base;
    stream->avg_frame_rate = encoder_->framerate;
    if ((error = avio_open(&muxer_->pb, tmp_path_.c_str(), AVIO_FLAG_WRITE)) < 0) fail("cannot open for writing", error);
    AVDictionary* options = nullptr;
    av_dict_set(&options, "movflags", "+faststart", 0);  // index first: browsers play while loading
    error = avformat_write_header(muxer_, &options);
    av_dict_free(&options);
    if (error < 0) fail("MP4 header", error);

    frame_ = av_frame_alloc();
    packet_ = av_packet_alloc();
    if (!frame_ || !packet_) fail("out of memory for frames", 0);
    frame_->format = AV_PIX_FMT_YUV420P;
    frame_->width = format.width;
    frame_->height = format.height;
    if ((error = av_frame_get_buffer(frame_, 0)) < 0) fail("frame buffer", error);
    to_yuv_ = sws_getContext(format.width, format.height, AV_PIX_FMT_RGB24, format.width, format.height,
                             AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
    if (!to_yuv_) fail("RGB to yuv420p converter", 0);
  } catch (...) {
    close();
    throw;
  }
}

Mp4Writer::~Mp4Writer() { close(); }

void Mp4Writer::close() {
  sws_freeContext(to_yuv_);
  to_yuv_ = nullptr;
  av_packet_free(&packet_);
  av_frame_free(&frame_);
  avcodec_free_context(&encoder_);
  if (muxer_) {
    if (muxer_->pb) avio_closep(&muxer_->pb);
    avformat_free_context(muxer_);
    muxer_ = nullptr;
  }
  if (!finished_) {
    std::error_code ignored;
    std::filesystem::remove(tmp_path_, ignored);
  }
}

void Mp4Writer::write(const std::uint8_t* rgb) {
  if (finished_ || !encoder_) fail("frame written after finish()", 0);
  int error = av_frame_make_writable(frame_);
  if (error < 0) fail("frame buffer", error);
  const std::uint8_t* planes[1] = {rgb};
  const int strides[1] = {3 * format_.width};
  sws_scale(to_yuv_, planes, strides, 0, format_.height, frame_->data, frame_->linesize);
  frame_->pts = frames_++;
  if ((error = avcodec_send_frame(encoder_, frame_)) < 0) fail("encoding frame " + std::to_string(frames_), error);
  drain(false);
}

// Moves every packet the encoder has ready into the file.
void Mp4Writer::drain(bool flushing) {
  for (;;) {
    int error = avcodec_receive_packet(encoder_, packet_);
    if (error == AVERROR(EAGAIN) || (flushing && error == AVERROR_EOF)) return;
    if (error < 0) fail("encoding", error);
    av_packet_rescale_ts(packet_, encoder_->time_base, muxer_->streams[stream_]->time_base);
    packet_->stream_index = stream_;
    if ((error = av_interleaved_write_frame(muxer_, packet_)) < 0) fail("write failed", error);
  }
}

void Mp4Writer::finish() {
  if (finished_ || !encoder_) fail("finish() called twice", 0);
  if (frames_ == 0) fail("no frames to write", 0);
  int error = avcodec_send_frame(encoder_, nullptr);
  if (error < 0) fail("flushing the encoder", error);
  drain(true);
  if ((error = av_write_trailer(muxer_)) < 0) fail("cannot write the MP4 index", error);
  if ((error = avio_closep(&muxer_->pb)) < 0) fail("write failed", error);
  move_into_place(tmp_path_, path_);  // removes tmp_path_ itself on failure
  finished_ = true;
  close();
}

}  // namespace vaegail::render
