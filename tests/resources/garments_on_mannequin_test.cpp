// The default garments start outside the default mannequin's capsule body
// (T-pose, frame 0 of mannequin.bvh) and the skirt's waist lies close to
// the pelvis, so pinning it there holds it where it was modelled.
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/garment_io.h"
#include "solver/body_capsules.h"
#include "solver/skeleton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace mrcloth {
namespace {

using Eigen::Vector3d;

class GarmentsOnMannequin : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mannequin_ = new Motion(read_bvh(std::string(MRCLOTH_DEFAULT_CHARACTER_DIR) + "/mannequin.bvh"));
    rig_ = new CapsuleRig(make_capsule_rig(mannequin_->skeleton));
    body_ = new CapsuleBody(*rig_, mannequin_->skeleton);
    body_->pose(frame_pose(*mannequin_, 0));
    skirt_ = new LoadResult(load_garment(MRCLOTH_DEFAULT_SKIRT));
    trousers_ = new LoadResult(load_garment(MRCLOTH_DEFAULT_TROUSERS));
  }
  static void TearDownTestSuite() {
    delete trousers_;
    delete skirt_;
    delete body_;
    delete rig_;
    delete mannequin_;
  }
  /// Distance from p to the nearest capsule surface (ignoring thickness)
  /// and the name of that capsule's joint.
  static std::pair<double, std::string> nearest(const Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    std::string name;
    for (std::size_t i = 0; i < body_->colliders().size(); ++i) {
      const double d = query_surface(body_->colliders()[i], p).distance;
      if (d < best) {
        best = d;
        name = mannequin_->skeleton.joints[rig_->bones[i].joint].name;
      }
    }
    return {best, name};
  }
  static Vector3d point(const QuadMesh& mesh, int v) {
    const auto p = mesh.point(mesh.vertex_handle(v));
    return Vector3d(p[0], p[1], p[2]);
  }
  static Motion* mannequin_;
  static CapsuleRig* rig_;
  static CapsuleBody* body_;
  static LoadResult* skirt_;
  static LoadResult* trousers_;
};
Motion* GarmentsOnMannequin::mannequin_ = nullptr;
CapsuleRig* GarmentsOnMannequin::rig_ = nullptr;
CapsuleBody* GarmentsOnMannequin::body_ = nullptr;
LoadResult* GarmentsOnMannequin::skirt_ = nullptr;
LoadResult* GarmentsOnMannequin::trousers_ = nullptr;

TEST_F(GarmentsOnMannequin, TheBodyIsTheDefaultRig) {
  EXPECT_EQ(rig_->thickness, CapsuleRigOptions{}.thickness);
  // Legs, pelvis, torso, arms, neck and head; no hands, fingers or toes.
  std::set<std::string> names;
  for (const BoneCapsule& bone : rig_->bones) names.insert(mannequin_->skeleton.joints[bone.joint].name);
  for (const char* name : {"Hips", "LHipJoint", "RHipJoint", "LeftUpLeg", "RightUpLeg", "LeftLeg", "RightLeg",
                           "LeftFoot", "RightFoot", "LowerBack", "Spine", "Spine1", "Neck", "Neck1", "Head",
                           "LeftShoulder", "RightShoulder", "LeftArm", "RightArm", "LeftForeArm", "RightForeArm"})
    EXPECT_TRUE(names.count(name)) << name;
  EXPECT_EQ(names.size(), 21u);
}

TEST_F(GarmentsOnMannequin, GarmentsStartOutsideTheBody) {
  for (const auto& [label, loaded] : {std::pair{"skirt", skirt_}, std::pair{"trousers", trousers_}}) {
    const QuadMesh& mesh = loaded->mesh;
    double clearance = std::numeric_limits<double>::infinity();
    std::string where;
    for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) {
      const Vector3d p = point(mesh, v);
      ASSERT_EQ(body_->penetration(p), 0.0) << label << " vertex " << v << " at " << p.transpose()
                                            << " is inside the body (nearest: " << nearest(p).second << ")";
      const auto [d, name] = nearest(p);
      if (d < clearance) {
        clearance = d;
        where = name;
      }
    }
    EXPECT_GE(clearance, rig_->thickness) << label;
    std::printf("%s: closest vertex %.4f m from the capsules (%s)\n", label, clearance, where.c_str());
  }
}

TEST_F(GarmentsOnMannequin, SkirtWaistLiesOnThePelvis) {
  const QuadMesh& mesh = skirt_->mesh;
  const std::vector<int> waist = boundary_loops(mesh).front();
  double sum = 0.0, largest = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (int v : waist) {
    const auto [d, name] = nearest(point(mesh, v));
    EXPECT_TRUE(name == "LowerBack" || name == "Spine") << "waist vertex " << v << " is nearest to " << name;
    sum += d;
    largest = std::max(largest, d);
    smallest = std::min(smallest, d);
  }
  const double mean = sum / static_cast<double>(waist.size());
  std::printf("skirt waist to the torso capsules: mean %.4f, min %.4f, max %.4f m\n", mean, smallest, largest);
  // The waist is an ellipse 0.26 m wide and 0.18 m deep, the capsules are
  // round: close at the front and back, 4 cm off at the sides.
  EXPECT_LT(mean, 0.025) << "mean distance of the waist loop to the torso, m";
  EXPECT_LT(smallest, 0.01) << "the waist touches the body at the front and back";
  EXPECT_LT(largest, 0.045);
}

TEST_F(GarmentsOnMannequin, TrousersWaistLiesOnThePelvis) {
  const QuadMesh& mesh = trousers_->mesh;
  const std::vector<int> waist = boundary_loops(mesh).front();
  double sum = 0.0, largest = 0.0;
  for (int v : waist) {
    const double d = nearest(point(mesh, v)).first;
    sum += d;
    largest = std::max(largest, d);
  }
  const double mean = sum / static_cast<double>(waist.size());
  std::printf("trousers waist to the torso capsules: mean %.4f, max %.4f m\n", mean, largest);
  EXPECT_LT(mean, 0.04);
  EXPECT_LT(largest, 0.06);
}

}  // namespace
}  // namespace mrcloth
