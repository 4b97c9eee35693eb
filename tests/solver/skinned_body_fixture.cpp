#include "skinned_body_fixture.h"

#include <filesystem>

namespace mrcloth::test {

namespace fs = std::filesystem;

bool have_body() {
  return fs::exists(test::shared_data("bodies/makehuman/base.obj")) &&
         fs::exists(test::shared_data("bodies/makehuman/rigs/cmu_mb.mhskel")) &&
         fs::exists(test::shared_data("bodies/makehuman/rigs/default_weights.mhw")) &&
         fs::exists(test::shared_data("motions/cmu_mb/07_06.bvh"));
}

Motion* SkinnedBodyTest::motion_ = nullptr;
SkinnedBody* SkinnedBodyTest::body_ = nullptr;

}  // namespace mrcloth::test
