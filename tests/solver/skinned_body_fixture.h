#pragma once
// The MakeHuman body of the shared data, loaded once for the SkinnedBodyTest
// suite (skinned_body_test.cpp, skinned_waist_test.cpp), and whether that
// data is there (the tests skip with a message when it is not).
#include "solver/body_skinned_mesh.h"
#include "test_meshes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mrcloth::test {

/// Metres per unit of the CMU clips (read_bvh's scale for motions/cmu_mb).
constexpr double kCmuScale = 0.056444;

/// Whether the shared data holds the MakeHuman body, its rig and weights,
/// and the CMU walk 07_06.
bool have_body();

#define SKIP_WITHOUT_BODY()                                                                                 \
  if (!have_body())                                                                                         \
  GTEST_SKIP() << "shared data absent under " << test::shared_data("")                                     \
               << " (set MRCLOTH_SHARED_DATA to the folder with bodies/makehuman and motions/cmu_mb)"

class SkinnedBodyTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!have_body()) return;
    motion_ = new Motion(read_bvh(test::shared_data("motions/cmu_mb/07_06.bvh"), {kCmuScale, false}));
    body_ = new SkinnedBody(load_makehuman_body(makehuman_files(test::shared_data("bodies/makehuman")), motion_->skeleton));
  }
  static void TearDownTestSuite() {
    delete body_;
    delete motion_;
    body_ = nullptr;
    motion_ = nullptr;
  }
  static const Skeleton& skeleton() { return motion_->skeleton; }
  static int joint(const std::string& name) {
    const int j = skeleton().find(name);
    EXPECT_GE(j, 0) << name;
    return j;
  }
  /// Body vertices whose largest weight is on `joint` and at least `at_least`.
  static std::vector<Eigen::Index> dominated_by(int j, double at_least) {
    std::vector<Eigen::Index> out;
    for (std::size_t v = 0; v < body_->weights.size(); ++v)
      for (const auto& [jj, w] : body_->weights[v])
        if (jj == j && w >= at_least) out.push_back(static_cast<Eigen::Index>(v));
    return out;
  }
  static Motion* motion_;
  static SkinnedBody* body_;
};

}  // namespace mrcloth::test
