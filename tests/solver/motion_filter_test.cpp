// smooth_motion: the Gaussian against its closed form (an impulse gives the
// weights), channels changing at a constant rate kept at every frame (the
// ends reflected through their points), rotations unwrapped, and the frames
// before first_frame neither changed nor read.
#include "solver/motion_filter.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace mrcloth {
namespace {

/// One joint with an x position and a z rotation channel, `frames` frames at 100 Hz, all zero.
Motion two_channels(int frames) {
  Motion motion;
  Joint root;
  root.name = "Hips";
  root.channels = {Channel::x_position, Channel::z_rotation};
  motion.skeleton.joints.push_back(root);
  motion.frame_time = 0.01;
  motion.frames = Eigen::MatrixXd::Zero(frames, 2);
  return motion;
}

TEST(MotionFilter, AnImpulseBecomesTheGaussianWeights) {
  Motion motion = two_channels(41);
  motion.frames(20, 0) = 1.0;
  const double sigma = 0.02;  // 2 frames: the kernel reaches 6
  smooth_motion(motion, sigma);
  double sum = 0.0;
  for (int k = -6; k <= 6; ++k) sum += std::exp(-0.5 * (k / 2.0) * (k / 2.0));
  for (int f = 0; f < 41; ++f) {
    const int k = f - 20;
    const double expected = std::abs(k) <= 6 ? std::exp(-0.5 * (k / 2.0) * (k / 2.0)) / sum : 0.0;
    EXPECT_NEAR(motion.frames(f, 0), expected, 1e-15) << "frame " << f;
    EXPECT_EQ(motion.frames(f, 1), 0.0);
  }
}

TEST(MotionFilter, AConstantRateIsKeptToTheEnds) {
  Motion motion = two_channels(30);
  for (int f = 0; f < 30; ++f) {
    motion.frames(f, 0) = 0.3 + 0.004 * f;  // metres
    motion.frames(f, 1) = -40.0 + 2.5 * f;  // degrees
  }
  const Motion before = motion;
  smooth_motion(motion, 0.05);  // the kernel (15 frames each way) reaches past both ends
  for (int f = 0; f < 30; ++f)
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(motion.frames(f, c), before.frames(f, c), 1e-12) << f << ", " << c;
  const Motion smoothed = motion;
  smooth_motion(motion, 0.0);
  EXPECT_TRUE(motion.frames == smoothed.frames) << "sigma 0 changes nothing";
}

TEST(MotionFilter, RotationsAreUnwrappedPositionsAreNot) {
  // A turn at 3 degrees a frame through +-180: read as it is written, a jump of 354.
  Motion motion = two_channels(20);
  for (int f = 0; f < 20; ++f) {
    const double angle = 160.0 + 3.0 * f;
    motion.frames(f, 1) = angle > 180.0 ? angle - 360.0 : angle;
    motion.frames(f, 0) = motion.frames(f, 1);  // the same numbers as a position: filtered as they are
  }
  Motion smoothed = motion;
  smooth_motion(smoothed, 0.02);
  for (int f = 0; f < 20; ++f) EXPECT_NEAR(smoothed.frames(f, 1), 160.0 + 3.0 * f, 1e-9) << "frame " << f;
  EXPECT_GT(std::abs(smoothed.frames(10, 0) - motion.frames(10, 0)), 10.0) << "a position is not unwrapped";
}

TEST(MotionFilter, FramesBeforeTheFirstAreNeitherChangedNorRead) {
  Motion motion = two_channels(25);
  for (int f = 0; f < 25; ++f) motion.frames(f, 0) = std::sin(0.7 * f);
  Motion without_first = two_channels(24);
  without_first.frames = motion.frames.bottomRows(24);
  motion.frames(0, 0) = 1e6;  // CMU's added T-pose, far from the motion
  smooth_motion(motion, 0.015, 1);
  smooth_motion(without_first, 0.015);
  EXPECT_EQ(motion.frames(0, 0), 1e6);
  for (int f = 0; f < 24; ++f) EXPECT_EQ(motion.frames(f + 1, 0), without_first.frames(f, 0)) << "frame " << f;
}

/// One joint with Z, Y, X rotation channels (degrees), all zero.
Motion one_rotation(int frames) {
  Motion motion;
  Joint root;
  root.name = "Hips";
  root.channels = {Channel::z_rotation, Channel::y_rotation, Channel::x_rotation};
  motion.skeleton.joints.push_back(root);
  motion.frame_time = 0.01;
  motion.frames = Eigen::MatrixXd::Zero(frames, 3);
  return motion;
}

Eigen::Matrix3d rotation_at(const Motion& motion, Eigen::Index f) {
  const double degree = 3.14159265358979323846 / 180.0;
  return (Eigen::AngleAxisd(motion.frames(f, 0) * degree, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(motion.frames(f, 1) * degree, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(motion.frames(f, 2) * degree, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// Writes rotation `r` into frame f as Z, Y, X angles, or as the other triple of the same rotation.
void set_rotation(Motion& motion, Eigen::Index f, const Eigen::Matrix3d& r, bool other_triple) {
  const Eigen::Vector3d zyx = r.eulerAngles(2, 1, 0) * (180.0 / 3.14159265358979323846);
  motion.frames.row(f) << zyx[0], zyx[1], zyx[2];
  if (other_triple) motion.frames.row(f) << zyx[0] + 180.0, 180.0 - zyx[1], zyx[2] + 180.0;
}

// A turn at a constant angular velocity about a tilted axis is kept at
// every frame, also where its Euler angles switch to the other triple of
// the same rotations (channel by channel that blurred into a glitch: a foot
// at 80 m/s), and with a window far longer than the clip.
TEST(MotionFilter, AConstantAngularVelocityIsKeptWhateverItsEulerAngles) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, -0.4).normalized();
  const Eigen::Matrix3d start = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 0.2, 0.1).normalized()).toRotationMatrix();
  for (const double sigma : {0.03, 1.0}) {
    Motion motion = one_rotation(40);
    for (Eigen::Index f = 0; f < 40; ++f)
      set_rotation(motion, f, Eigen::AngleAxisd(0.05 * static_cast<double>(f), axis).toRotationMatrix() * start, f >= 20);
    const Motion before = motion;
    smooth_motion(motion, sigma);
    for (Eigen::Index f = 0; f < 40; ++f) {
      EXPECT_LT((rotation_at(motion, f) - rotation_at(before, f)).norm(), 1e-9) << "sigma " << sigma << ", frame " << f;
      EXPECT_LT((motion.frames.row(f) - before.frames.row(f)).cwiseAbs().maxCoeff(), 1e-6)
          << "the triple nearest the frame's own, frame " << f;
    }
  }
}

// A window far longer than the clip (radius 300 frames on 5): positions at a
// constant rate are kept, reflected again and again through both ends.
TEST(MotionFilter, AWindowLongerThanTheClipKeepsAConstantRate) {
  Motion motion = two_channels(5);
  for (int f = 0; f < 5; ++f) motion.frames(f, 0) = 1.0 + 0.01 * f;
  const Motion before = motion;
  smooth_motion(motion, 1.0);
  for (int f = 0; f < 5; ++f) EXPECT_NEAR(motion.frames(f, 0), before.frames(f, 0), 1e-12) << "frame " << f;
}

}  // namespace
}  // namespace mrcloth
