#include "render/episode_video.h"

#include <gtest/gtest.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <filesystem>

#include "data/record.h"
#include "env/registry.h"
#include "render/mp4_writer.h"
#include "render/png_writer.h"
#include "util/atomic_file.h"
#include "util/test_small_fs.h"

namespace vaegail::render {
namespace {

namespace fs = std::filesystem;

// What a player finds in the file: the stream's size and frame rate, and the frames decoded.
struct Decoded {
  int width = 0, height = 0, frames = 0;
  double fps = 0;
  std::string codec;
};

Decoded decode(const std::string& path) {
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) throw std::runtime_error(path + ": unreadable");
  avformat_find_stream_info(format, nullptr);
  const AVCodec* codec = nullptr;
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (stream < 0) throw std::runtime_error(path + ": no video stream");
  AVCodecContext* decoder = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(decoder, format->streams[stream]->codecpar);
  avcodec_open2(decoder, codec, nullptr);
  Decoded out{decoder->width, decoder->height, 0, av_q2d(format->streams[stream]->avg_frame_rate), codec->name};
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const auto receive = [&] {
    while (avcodec_receive_frame(decoder, frame) == 0) ++out.frames;
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == stream && avcodec_send_packet(decoder, packet) == 0) receive();
    av_packet_unref(packet);
  }
  avcodec_send_packet(decoder, nullptr);
  receive();
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  avformat_close_input(&format);
  return out;
}

class EpisodeVideo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("vaegail_render_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    EnvRequest request;
    request.episode_length = 12;
    env = make_env(request);
    RecordRequest record;
    record.seeds = {3, 4};
    record.num_envs = 1;
    episodes = record_episodes(*env, record, random_policy(*env, 7));
  }
  void TearDown() override { fs::remove_all(dir); }

  fs::path dir;
  std::unique_ptr<Env> env;
  std::vector<Episode> episodes;
};

TEST_F(EpisodeVideo, DecodesWithTheRequestedFramesSizeAndRate) {
  Episode shorter = episodes[1];
  shorter.actions.resize(5 * env->act_dim());
  shorter.rewards.resize(5);
  shorter.terminations.resize(5);
  shorter.truncations.resize(5);
  shorter.observations.resize(6 * env->obs_dim());
  const std::vector<std::vector<Clip>> grid{{{"a", episodes[0]}, {"b", shorter}}, {{"c", episodes[1]}}};
  VideoOptions options;
  options.tile_width = 96;
  options.tile_height = 64;
  options.fps = 10;
  const std::string path = (dir / "grid.mp4").string();
  const auto reports = write_episode_video(*env, grid, options, path);
  const Decoded video = decode(path);
  EXPECT_EQ(video.codec, "h264");
  EXPECT_EQ(video.width, 2 * 96);
  EXPECT_EQ(video.height, 2 * 64);
  EXPECT_DOUBLE_EQ(video.fps, 10.0);
  EXPECT_EQ(video.frames, 13);  // the longest episode's 12 steps + its initial state
  ASSERT_EQ(reports.size(), 3u);
  EXPECT_EQ(reports[1].steps, 5);
  // Nothing but the video is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// The PNG's size, and its pixels as RGB bytes.
struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

Image decode_png(const std::string& path) {
  const std::string bytes = read_file(path);
  const AVCodec* codec = avcodec_find_decoder(AV_CODEC_ID_PNG);
  AVCodecContext* decoder = avcodec_alloc_context3(codec);
  avcodec_open2(decoder, codec, nullptr);
  AVPacket* packet = av_packet_alloc();
  av_new_packet(packet, static_cast<int>(bytes.size()));
  std::copy(bytes.begin(), bytes.end(), packet->data);
  AVFrame* frame = av_frame_alloc();
  Image image;
  if (avcodec_send_packet(decoder, packet) == 0 && avcodec_receive_frame(decoder, frame) == 0 &&
      frame->format == AV_PIX_FMT_RGB24) {
    image.width = frame->width;
    image.height = frame->height;
    for (int y = 0; y < frame->height; ++y)
      image.rgb.insert(image.rgb.end(), frame->data[0] + y * frame->linesize[0],
                       frame->data[0] + y * frame->linesize[0] + 3 * frame->width);
  }
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  return image;
}

TEST_F(EpisodeVideo, AStillIsTheFrameAskedForAsAPng) {
  const std::vector<std::vector<Clip>> grid{{{"a", episodes[0]}, {"b", episodes[1]}}};
  VideoOptions options;
  options.tile_width = 96;
  options.tile_height = 64;
  const auto still_at = [&](int frame, const std::string& name) {
    options.still_path = (dir / name).string();
    options.still_frames = {frame};
    write_episode_video(*env, grid, options, (dir / "v.mp4").string());
    return decode_png(options.still_path);
  };
  const Image middle = still_at(-1, "middle.png"), sixth = still_at(6, "sixth.png"), first = still_at(0, "first.png");
  EXPECT_EQ(middle.width, 2 * 96);
  EXPECT_EQ(middle.height, 64);
  EXPECT_EQ(middle.rgb.size(), 2u * 96 * 64 * 3);
  EXPECT_EQ(middle.rgb, sixth.rgb);  // 13 frames: the middle one is frame 6
  EXPECT_NE(first.rgb, sixth.rgb);   // the bodies moved
  options.still_frames = {13};
  EXPECT_THROW(write_episode_video(*env, grid, options, (dir / "v.mp4").string()), RenderError);

  // A strip: the frames side by side in the order asked, each the whole grid.
  options.still_path = (dir / "strip.png").string();
  options.still_frames = {6, 0, 6};
  write_episode_video(*env, grid, options, (dir / "v.mp4").string());
  const Image strip = decode_png(options.still_path);
  ASSERT_EQ(strip.width, 3 * middle.width);
  ASSERT_EQ(strip.height, middle.height);
  const auto part = [&](int k) {
    std::vector<std::uint8_t> rgb;
    const size_t row = static_cast<size_t>(middle.width) * 3;
    for (int y = 0; y < strip.height; ++y) {
      const auto start = strip.rgb.begin() + static_cast<std::ptrdiff_t>(y * 3 * row + k * row);
      rgb.insert(rgb.end(), start, start + static_cast<std::ptrdiff_t>(row));
    }
    return rgb;
  };
  EXPECT_EQ(part(0), sixth.rgb);
  EXPECT_EQ(part(1), first.rgb);
  EXPECT_EQ(part(2), sixth.rgb);
}

TEST_F(EpisodeVideo, RealTimeIsOneFramePerControlStep) {
  EXPECT_EQ(video_fps(*env, {}), 40);  // the walker's 0.025 s
  VideoOptions options;
  options.fps = 25;
  EXPECT_EQ(video_fps(*env, options), 25);
}

TEST_F(EpisodeVideo, TheReplayPassesThroughTheRecordedStates) {
  VideoOptions options;
  options.tile_width = options.tile_height = 32;
  Episode nudged = episodes[0];
  nudged.actions[0] += 0.5f;  // the first action as it was not recorded
  const auto reports = write_episode_video(*env, {{{"recorded", episodes[0]}, {"nudged", nudged}}}, options,
                                           (dir / "replay.mp4").string());
  EXPECT_EQ(reports[0].steps, 12);
  EXPECT_LT(reports[0].max_observation_error, 1e-6);
  EXPECT_GT(reports[1].max_observation_error, 1e-3);
}

TEST_F(EpisodeVideo, AnEpisodeThatDoesNotFitTheEnvironmentIsNamed) {
  Episode broken = episodes[0];
  broken.actions.pop_back();
  const std::string path = (dir / "broken.mp4").string();
  try {
    write_episode_video(*env, {{{"demonstration 3", broken}}}, {}, path);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("demonstration 3: actions"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(EpisodeVideo, AnUnfinishedVideoLeavesNoFile) {
  const std::string path = (dir / "unfinished.mp4").string();
  {
    Mp4Writer video(path, {64, 48, 10});
    const std::vector<std::uint8_t> grey(64 * 48 * 3, 128);
    video.write(grey.data());
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir));
  EXPECT_THROW(Mp4Writer((dir / "odd.mp4").string(), {63, 48, 10}), RenderError);
}

// A video on a full file system: FFmpeg's failure is one line naming the file and the cause, no
// temporary file is left and the video before stays as it was and plays.
TEST_F(EpisodeVideo, AVideoOnAFullDiskIsRefusedInOneLineAndTheOneBeforeKept) {
  SmallFileSystem small(1024 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("video.mp4");
  std::vector<std::uint8_t> noise(64 * 48 * 3);
  expect_refused_on_a_full_disk_then_saved(small, path, [&] {
    Mp4Writer video(path, {64, 48, 10});
    for (int frame = 0; frame < 20; ++frame) {
      for (auto& byte : noise) byte = static_cast<std::uint8_t>(std::rand());  // poorly compressible
      video.write(noise.data());
    }
    video.finish();
  });
  EXPECT_EQ(decode(path).frames, 20);
}

// The same for a still: the PNG before stays whole and decodes.
TEST_F(EpisodeVideo, AStillOnAFullDiskIsRefusedInOneLineAndTheOneBeforeKept) {
  SmallFileSystem small(256 * 1024);
  if (!small.mounted()) GTEST_SKIP() << small.why_not();
  const std::string path = small.path("still.png");
  std::vector<std::uint8_t> noise(64 * 48 * 3);
  expect_refused_on_a_full_disk_then_saved(small, path, [&] {
    for (auto& byte : noise) byte = static_cast<std::uint8_t>(std::rand());
    write_png(path, 64, 48, noise.data());
  });
  EXPECT_EQ(decode_png(path).rgb, noise);
}

}  // namespace
}  // namespace vaegail::render
