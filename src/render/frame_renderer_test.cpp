#include "render/frame_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "env/mujoco_env.h"
#include "env/registry.h"
#include "env/walker.h"

namespace vaegail::render {
namespace {

constexpr int kWidth = 160, kHeight = 120;

// The walker's body colour (rgba 0.7 0.5 0.3 and 0.6 0.4 0.3, shaded): red well above blue.
int body_pixels(const std::vector<std::uint8_t>& rgb) {
  int n = 0;
  for (size_t p = 0; p < rgb.size(); p += 3) n += rgb[p] > rgb[p + 2] + 40;
  return n;
}

double mean_abs_difference(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
  return sum / a.size();
}

class WalkerFrames : public ::testing::Test {
 protected:
  void SetUp() override { walker.reset(0); }
  // The walker's reset state with qpos[index] set to `value`.
  std::vector<std::uint8_t> frame_with(int index, double value) {
    mjData* d = mj_makeData(walker.model());
    mj_copyData(d, walker.model(), walker.data());
    d->qpos[index] = value;
    mj_forward(walker.model(), d);
    renderer.draw(0, 0, *d, "test");
    mj_deleteData(d);
    return renderer.read();
  }

  WalkerEnv walker;
  FrameRenderer renderer{walker.model(), {1, 1, kWidth, kHeight}};
};

TEST_F(WalkerFrames, AFrameShowsTheWalkerAgainstTheFloorAndSky) {
  renderer.draw(0, 0, *walker.data(), "");
  const auto& rgb = renderer.read();
  ASSERT_EQ(rgb.size(), static_cast<size_t>(kWidth * kHeight * 3));
  EXPECT_EQ(renderer.tracked_body(), 1);  // the torso, whose root joints slide
  // Not blank: a body of some hundreds of pixels in a frame of several colours.
  EXPECT_GT(body_pixels(rgb), 200);
  EXPECT_LT(body_pixels(rgb), kWidth * kHeight / 4);
  int differing = 0;
  for (size_t p = 0; p < rgb.size(); p += 3) differing += std::abs(rgb[p] - rgb[0]) + std::abs(rgb[p + 1] - rgb[1]) > 30;
  EXPECT_GT(differing, kWidth * kHeight / 5);
}

TEST_F(WalkerFrames, TheFrameChangesWhenThePoseChanges) {
  const int right_hip = 3, right_knee = 4;
  const auto straight = frame_with(right_knee, 0.0);
  const auto same = frame_with(right_knee, 0.0);
  const auto bent = frame_with(right_knee, -1.5);
  const auto lifted = frame_with(right_hip, 1.2);
  EXPECT_EQ(mean_abs_difference(straight, same), 0.0);  // rendering is deterministic
  EXPECT_GT(mean_abs_difference(straight, bent), 0.2);
  EXPECT_GT(mean_abs_difference(straight, lifted), 0.2);
  EXPECT_GT(mean_abs_difference(bent, lifted), 0.2);
}

TEST_F(WalkerFrames, TheCameraFollowsTheWalkerDownTheFloor) {
  const int rootx = 0;
  const auto home = frame_with(rootx, 0.0);
  const auto far = frame_with(rootx, 25.0);
  // Still in view and as large, while the floor lines slide by underneath.
  EXPECT_NEAR(body_pixels(far), body_pixels(home), 0.1 * body_pixels(home));
  const auto half_way = frame_with(rootx, 0.5);
  EXPECT_GT(mean_abs_difference(home, half_way), 0.05);
}

TEST(FrameRenderer, TilesAreDrawnApartAndCaptioned) {
  WalkerEnv walker;
  walker.reset(0);
  FrameRenderer renderer(walker.model(), {1, 2, 96, 64});
  renderer.draw(0, 0, *walker.data(), "");
  renderer.clear(0, 1);
  auto rgb = renderer.read();
  int left = 0, right = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 192; ++x) {
      const std::uint8_t* p = &rgb[(y * 192 + x) * 3];
      (x < 96 ? left : right) += p[0] + p[1] + p[2] > 0;
    }
  EXPECT_GT(left, 96 * 64 / 5);  // the floor and the body; the sky is black
  EXPECT_EQ(right, 0);  // a cleared tile is black
  renderer.draw(0, 1, *walker.data(), "caption");
  const auto captioned = renderer.read();
  renderer.draw(0, 1, *walker.data(), "");
  EXPECT_GT(mean_abs_difference(captioned, renderer.read()), 0.0);
  EXPECT_THROW(renderer.draw(1, 0, *walker.data(), ""), RenderError);
}

TEST(FrameRenderer, AnArmWithAFixedBaseIsWatchedByAStillCamera) {
  const auto arm = make_env({"arm"});
  const auto* mujoco = dynamic_cast<const MujocoEnv*>(arm.get());
  ASSERT_NE(mujoco, nullptr);
  FrameRenderer renderer(mujoco->model(), {1, 1, 64, 48});
  EXPECT_EQ(renderer.tracked_body(), -1);
  EXPECT_GT(renderer.camera_distance(), 0.5);
}

TEST(FrameRenderer, ATinyTileIsRefusedInOneLine) {
  WalkerEnv walker;
  try {
    FrameRenderer renderer(walker.model(), {1, 1, 8, 8});
    FAIL() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("16x16"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vaegail::render
