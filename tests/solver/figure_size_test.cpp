// A clip's figure sized against an adult's or a body's legs: the legs
// measured exactly on a hand-made skeleton, the limits exact, every clip
// here plausible in its own units and refused in the usual wrong ones
// (the shared clips skipped without ../shared/data).
#include "solver/figure_size.h"

#include "solver/character_setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

constexpr double kCmuScale = 0.056444;

std::string resource(const std::string& relative) { return std::string(MRCLOTH_RESOURCES) + "/" + relative; }
std::string shared(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

Joint joint(const std::string& name, int parent, const Eigen::Vector3d& offset) {
  Joint j;
  j.name = name;
  j.parent = parent;
  j.offset = offset;
  return j;
}

/// Hips with a bent left leg (hip 0.1 m aside, knee forward, ankle back)
/// and, with `both`, a straight right leg of another length.
Skeleton legs(bool both) {
  Skeleton s;
  s.joints.push_back(joint("Hips", -1, {0, 1, 0}));
  s.joints.push_back(joint("LeftUpLeg", 0, {0.1, -0.05, 0}));
  s.joints.push_back(joint("LeftLeg", 1, {0, -0.4, 0.12}));
  s.joints.push_back(joint("LeftFoot", 2, {0, -0.44, -0.09}));
  if (both) {
    s.joints.push_back(joint("RightUpLeg", 0, {-0.1, -0.05, 0}));
    s.joints.push_back(joint("RightLeg", 4, {0, -0.42, 0}));
    s.joints.push_back(joint("RightFoot", 5, {0, -0.4, 0}));
  }
  return s;
}

TEST(FigureSize, LegsOfLengthZeroAreNotPlausible) {
  // Every joint at one point (offsets 0): measured, and no figure at all.
  Skeleton collapsed = legs(true);
  for (Joint& j : collapsed.joints) j.offset.setZero();
  const FigureScale scale = figure_scale(collapsed);
  EXPECT_TRUE(scale.measured);
  EXPECT_EQ(scale.legs, 0.0);
  EXPECT_EQ(scale.factor(), 0.0);
  EXPECT_FALSE(plausible(scale));
  // No leg joints at all: nothing to measure, nothing refused.
  Skeleton hips_only;
  hips_only.joints.push_back(joint("Hips", -1, {0, 1, 0}));
  EXPECT_FALSE(figure_scale(hips_only).measured);
  EXPECT_TRUE(plausible(figure_scale(hips_only)));
}

Motion clip(const std::string& path, double scale) {
  BvhReadOptions options;
  options.scale = scale;
  Motion motion = read_bvh(path, options);
  standardise_clip(motion);
  return motion;
}

TEST(FigureSize, LegsAreTheHipToAnkleDistanceMeanOverTheLegsFound) {
  const double left = std::sqrt(0.84 * 0.84 + 0.03 * 0.03);  // (0, -0.84, 0.03) from hip to ankle
  EXPECT_NEAR(figure_scale(legs(false)).legs, left, 1e-12);
  EXPECT_NEAR(figure_scale(legs(true)).legs, 0.5 * (left + 0.82), 1e-12);
  // Against a body's legs, or an adult's without one.
  const FigureScale against_body = figure_scale(legs(true), 0.5);
  EXPECT_TRUE(against_body.against_body);
  EXPECT_NEAR(against_body.factor(), 0.5 * (left + 0.82) / 0.5, 1e-12);
  EXPECT_FALSE(figure_scale(legs(true)).against_body);
  EXPECT_EQ(figure_scale(legs(true)).expected, kReferenceLegs);
  // No legs by CMU names: nothing to measure, and nothing refused.
  Skeleton none;
  none.joints.push_back(joint("Hips", -1, {0, 100, 0}));
  none.joints.push_back(joint("Thigh", 0, {0, -50, 0}));
  EXPECT_EQ(figure_scale(none).legs, 0.0);
  EXPECT_EQ(figure_scale(none).factor(), 1.0);
  EXPECT_TRUE(plausible(figure_scale(none)));
}

TEST(FigureSize, TheLimitsAreInclusiveAndExact) {
  FigureScale adult;
  adult.expected = kReferenceLegs;
  for (const auto& [factor, expected] : std::vector<std::pair<double, bool>>{
           {kReferenceFactorLow, true}, {kReferenceFactorHigh, true}, {1.0, true},
           {kReferenceFactorLow * (1 - 1e-9), false}, {kReferenceFactorHigh * (1 + 1e-9), false}}) {
    adult.legs = factor * adult.expected;
    EXPECT_EQ(plausible(adult), expected) << "factor " << factor << " against an adult";
  }
  FigureScale body;
  body.expected = 0.81;
  body.against_body = true;
  for (const auto& [factor, expected] : std::vector<std::pair<double, bool>>{
           {kBodyFactorLimit, true}, {1.0 / kBodyFactorLimit, true}, {0.5, false}, {1.6, false}}) {
    body.legs = factor * body.expected;
    EXPECT_EQ(plausible(body), expected) << "factor " << factor << " against the body";
  }
  body.legs = 4.63;
  EXPECT_EQ(describe(body), "the figure's legs are 4.63 m long (hip to ankle in its rest pose), 5.7 times the "
                            "MakeHuman body's 0.81 m");
  adult.legs = 82.05;
  EXPECT_EQ(describe(adult), "the figure's legs are 82.05 m long (hip to ankle in its rest pose), 104 times an "
                             "adult's 0.79 m");
}

TEST(FigureSize, TheEmbeddedClipsAreAdultsInMetresAndRefusedInCentimetres) {
  for (const char* name : {"walk_instance", "walk_new", "squat", "mannequin"}) {
    const std::string path = resource(std::string("characters/") + name + ".bvh");
    const FigureScale metres = figure_scale(clip(path, 1.0).skeleton);
    EXPECT_NEAR(metres.factor(), 1.0, 0.01) << name;  // the mannequin's legs are the reference
    EXPECT_TRUE(plausible(metres)) << name;
    EXPECT_FALSE(plausible(figure_scale(clip(path, 0.01).skeleton))) << name << " read in centimetres";
    EXPECT_FALSE(plausible(figure_scale(clip(path, 1 / kCmuScale).skeleton))) << name << " scaled as CMU to metres";
  }
}

TEST(FigureSize, TheSharedClipsArePlausibleOnlyInTheirOwnUnits) {
  const std::string daz = shared("motions/cmu_daz/16_15_daz.bvh");
  if (!std::filesystem::exists(daz)) GTEST_SKIP() << "shared data absent (" << daz << ")";
  for (const char* name : {"02_01", "07_03", "07_06", "08_03", "09_01", "13_29_squats_f3760-4580"}) {
    const std::string path = shared(std::string("motions/cmu_mb/") + name + ".bvh");
    const FigureScale cmu = figure_scale(clip(path, kCmuScale).skeleton);
    EXPECT_GT(cmu.legs, 0.78) << name;
    EXPECT_LT(cmu.legs, 0.90) << name;
    EXPECT_TRUE(plausible(cmu)) << name;
    EXPECT_FALSE(plausible(figure_scale(clip(path, 1.0).skeleton))) << name << " in metres";
    EXPECT_FALSE(plausible(figure_scale(clip(path, 0.01).skeleton))) << name << " in centimetres";
    // In inches a CMU figure is a toddler (0.36 m of leg): plausible alone,
    // refused against the MakeHuman body's legs.
    const Skeleton inches = clip(path, 0.0254).skeleton;
    EXPECT_TRUE(plausible(figure_scale(inches))) << name;
    EXPECT_FALSE(plausible(figure_scale(inches, 0.81))) << name;
  }
  const FigureScale centimetres = figure_scale(clip(daz, 0.01).skeleton);
  EXPECT_NEAR(centimetres.legs, 0.8205, 0.001);
  EXPECT_TRUE(plausible(centimetres));
  EXPECT_FALSE(plausible(figure_scale(clip(daz, kCmuScale).skeleton))) << "the DAZ clip in CMU units";
  EXPECT_FALSE(plausible(figure_scale(clip(daz, 0.0254).skeleton))) << "the DAZ clip in inches";
}

}  // namespace
}  // namespace mrcloth
