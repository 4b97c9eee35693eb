// Issue 4's benchmark: the shared MakeHuman skirt, unrefined (720 vertices)
// and refined uniformly twice (11088), on CMU walk 07_06 with each body kind
// (capsules along the bones, the skinned MakeHuman mesh): ms per output frame
// split into dynamics and collision, one core, set up as the plugin sets up
// a run by default (fitted capsules, leg bridges, the waist on the skin, arm
// clearance, the garment cleared of the skinned body). Prints a table (depth:
// the deepest vertex below the body's surface at an output frame; tear: the
// largest opening of an edge at least doubled, SimulationReport::
// max_tear_opening), then where each row's time went (solve, limiter, posing,
// first and later collision rounds, rounds per step).
//
// Usage: bench_character [--frames N] [--preroll S] [--garment coarse|refined|all] [--body capsules|mesh|all]
//                        [--self-contact METRES]
#include "mesh_ops/garment_io.h"
#include "mesh_ops/boundary_loops.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/character_sim.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace mrcloth;

struct BenchOptions {
  int frames = 60;         // output frames at 30 fps (2 s of walking)
  double preroll = 0.5;    // seconds, not timed in the table
  std::string garment = "all";  // coarse | refined | all: which rows to run (one row is handy under a profiler)
  std::string body = "all";     // capsules | mesh | all
  double self_contact = 0.0;    // cloth-cloth contact thickness, metres (0: off, the default)
};

std::string data(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

struct Row {
  std::string garment, body;
  std::size_t vertices = 0;
  CharacterRunReport report;
};

Row run(const std::string& name, const QuadMesh& garment, const Eigen::Vector3d& offset, const Motion& motion,
        PosedBody& body, const std::string& body_name, const BenchOptions& b, const Pose& garment_pose,
        const SkinnedBody* waist_skin = nullptr, std::shared_ptr<const ArmClearance> arms = nullptr) {
  QuadMesh placed = copy_mesh(garment);
  for (auto v : placed.vertices()) placed.point(v) += OpenMesh::Vec3d(offset.x(), offset.y(), offset.z());
  if (body_name == "mesh") {
    // As the plugin does on the skinned body: the garment starts clear of
    // it (these uniform meshes have no T-nodes).
    CharacterRunOptions start;
    start.garment_pose = garment_pose;
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(placed.n_vertices()), 3);
    for (auto v : placed.vertices()) points.row(v.idx()) << placed.point(v)[0], placed.point(v)[1], placed.point(v)[2];
    clear_garment_of_body(body, motion, start, points, {});
    for (auto v : placed.vertices()) placed.set_point(v, OpenMesh::Vec3d(points(v.idx(), 0), points(v.idx(), 1), points(v.idx(), 2)));
  }
  DynamicsOptions d;
  d.pinned = boundary_loop_by_name(placed, "top");
  const DynamicsModel model = build_dynamics(placed, d);
  ClothState state = rest_state(model);
  CharacterRunOptions o;
  o.frames = b.frames;
  o.preroll_seconds = b.preroll;
  o.garment_pose = garment_pose;  // the A-pose base.obj (and the skirt) were modelled in
  if (waist_skin) waist_follows_skin(o, *waist_skin, motion, model);  // as the plugin does with MakeHuman
  o.arm_clearance = std::move(arms);  // as the plugin does by default
  o.simulation.self_contact.thickness = b.self_contact;
  Row row;
  row.garment = name;
  row.body = body_name;
  row.vertices = placed.n_vertices();
  row.report = simulate_on_character(model, state, motion, body, o);
  return row;
}

void print(const Row& r) {
  const SimulationReport& m = r.report.motion;
  std::printf("| %-22s | %-8s | %8zu | %9.1f | %9.1f | %9.1f | %7.2f %% | %9.1f | %9.2f | %9d | %s |\n", r.garment.c_str(),
              r.body.c_str(), r.vertices, m.mean_frame.dynamics_ms, m.mean_frame.collision_ms, m.ms_per_frame_total,
              100.0 * m.max_stretch, 1000.0 * m.max_tear_opening, 1000.0 * m.max_depth, m.max_self_crossings,
              m.non_finite ? "NaN!" : "ok");
}

/// Where each row's time went, ms per output frame: the solve and the
/// strain limiter (dynamics), posing the body, each step's first collision
/// round and the later rounds (with cloth-cloth contact's gather).
void print_parts(const std::vector<Row>& rows) {
  std::printf("\nwhere the time goes, ms per frame (dynamics = solve + limiter; collision = posing + first round + later rounds)\n\n");
  std::printf("| %-22s | %-8s | %8s | %8s | %8s | %11s | %12s | %11s |\n", "garment", "body", "solve", "limiter", "posing",
              "first round", "later rounds", "rounds/step");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(24, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(10, '-').c_str(), std::string(10, '-').c_str(),
              std::string(13, '-').c_str(), std::string(14, '-').c_str(), std::string(13, '-').c_str());
  for (const Row& r : rows) {
    const SimulationReport& m = r.report.motion;
    const FrameTiming& t = m.mean_frame;
    std::printf("| %-22s | %-8s | %8.1f | %8.1f | %8.1f | %11.1f | %12.1f | %11.2f |\n", r.garment.c_str(),
                r.body.c_str(), t.dynamics_ms - t.limiter_ms, t.limiter_ms, t.posing_ms, t.first_round_ms,
                t.collision_ms - t.posing_ms - t.first_round_ms, m.mean_rounds);
  }
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions b;
  const char* usage =
      "usage: bench_character [--frames N] [--preroll S] [--garment coarse|refined|all] [--body capsules|mesh|all] "
      "[--self-contact METRES]\n";
  for (int a = 1; a < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--help" || key == "-h") {
      std::printf("%s", usage);
      return 0;
    }
    if (a + 1 == argc) {
      std::fprintf(stderr, "option %s needs a value\n%s", argv[a], usage);
      return 2;
    }
    if (key == "--frames") b.frames = std::atoi(argv[a + 1]);
    else if (key == "--preroll") b.preroll = std::atof(argv[a + 1]);
    else if (key == "--garment") b.garment = argv[a + 1];
    else if (key == "--body") b.body = argv[a + 1];
    else if (key == "--self-contact") b.self_contact = std::atof(argv[a + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n%s", argv[a], usage);
      return 2;
    }
  }
  const std::string skirt_path = data("garments/makehuman/skirthelper.obj");
  if (!std::filesystem::exists(skirt_path)) {
    std::printf("shared data absent (%s): nothing to measure\n", skirt_path.c_str());
    return 0;
  }
  BvhReadOptions bvh;
  bvh.scale = 0.056444;  // CMU units to metres
  bvh.skip_first_frame = true;
  const Motion motion = read_bvh(data("motions/cmu_mb/07_06.bvh"), bvh);
  MakeHumanOptions mh;
  mh.base_obj = data("bodies/makehuman/base.obj");
  mh.skeleton_file = data("bodies/makehuman/rigs/cmu_mb.mhskel");
  mh.weights_file = data("bodies/makehuman/rigs/default_weights.mhw");
  const SkinnedBody skinned = load_makehuman_body(mh, motion.skeleton);

  CapsuleRig rig = make_capsule_rig(motion.skeleton);
  fit_capsules_to_body(rig, motion.skeleton, skinned);  // as the plugin fits them

  const QuadMesh coarse = load_garment(skirt_path, {"dm"}).mesh;
  QuadMesh high = copy_mesh(coarse);
  uniform_refine(high, 2);

  // base.obj x 0.1 + obj_offset is the garment on the body bound to the rest
  // pose; garment_shift moves it to where the clip starts.
  CharacterRunOptions reference;
  const Eigen::Vector3d offset =
      skinned.obj_offset + garment_shift(motion, reference, rest_pose(motion.skeleton).position(0));
  const Pose a_pose = mesh_pose(skinned, motion.skeleton);
  // As the plugin does: shrink the capsules the skirt starts inside of.
  CharacterRunOptions start;
  start.garment_pose = a_pose;
  Eigen::MatrixX3d skirt_points(static_cast<Eigen::Index>(coarse.n_vertices()), 3);
  for (auto v : coarse.vertices())
    skirt_points.row(v.idx()) = (Eigen::Vector3d(coarse.point(v)[0], coarse.point(v)[1], coarse.point(v)[2]) + offset).transpose();
  clear_capsules_for_garment(rig, motion, start, skinned.joint_rest, skirt_points);
  // As the plugin does by default: bridges between the legs for a skirt
  // (to the ankles for this one), for both body kinds; judged, as there,
  // with the skirt where base.obj puts it in the skeleton's rest space.
  const Eigen::MatrixX3d rest_space = skirt_points.rowwise() - (offset - skinned.obj_offset).transpose();
  const double reach = automatic_leg_bridges(static_cast<int>(boundary_loops(coarse).size()), rest_space, motion.skeleton);
  CapsuleRig bridges = make_capsule_rig(motion.skeleton);
  if (reach > 0.0) {
    add_leg_bridges(rig, motion.skeleton, reach);
    add_leg_bridges(bridges, motion.skeleton, reach);
  }
  bridges.bones.clear();
  const auto arms = std::make_shared<const ArmClearance>(
      make_arm_clearance(motion.skeleton, {}, skinned.rest_vertices, skinned.weights, skinned.joint_rest));
  CapsulePosedBody capsules(rig, motion.skeleton, skinned.joint_rest);
  SkinnedPosedBody mesh(skinned, motion.skeleton, 0.004, 0.3, bridges);
  std::printf("skirt on CMU 07_06, %d frames at 30 fps after a %.1f s pre-roll, 120 Hz steps, one core, leg bridges %.0f, cloth-cloth contact %.1f mm\n\n",
              b.frames, b.preroll, reach, 1000.0 * b.self_contact);
  std::printf("| %-22s | %-8s | %8s | %9s | %9s | %9s | %9s | %9s | %9s | %9s |  |\n", "garment", "body", "vertices",
              "dyn ms/f", "coll ms/f", "total", "stretch", "tear mm", "depth mm", "crossings");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|%s|%s|----|\n", std::string(24, '-').c_str(), std::string(10, '-').c_str(),
              std::string(10, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str());
  const QuadMesh* garments[] = {&coarse, &high};
  std::vector<Row> rows;
  const auto keep = [&](Row row) {  // printed as soon as it is measured
    print(row);
    rows.push_back(std::move(row));
  };
  for (const QuadMesh* g : garments) {
    const std::string name = g == &coarse ? "skirt (coarse)" : "skirt (uniform x2)";
    if (b.garment != "all" && b.garment != (g == &coarse ? "coarse" : "refined")) continue;
    if (b.body == "all" || b.body == "capsules")
      keep(run(name, *g, offset, motion, capsules, "capsules", b, a_pose, &skinned, arms));
    if (b.body == "all" || b.body == "mesh") keep(run(name, *g, offset, motion, mesh, "mesh", b, a_pose, &skinned, arms));
  }
  print_parts(rows);
  return 0;
}
