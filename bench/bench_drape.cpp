// The drape scene of issue 3, timed on one core and printed as a table:
// a 1 m x 1 m sheet of n x n vertices, flat at height 0, centred over a
// static sphere of radius 0.25 m whose centre is 0.3 m below it; gravity
// 9.8 m/s^2, 25 frames per second, 50 frames, time step 5 ms. Plus the same
// sheet refined adaptively around the contact region against the uniform
// sheet of the same finest resolution.
//
// Usage: bench_drape [--frames N] [--sizes 28,64,110] [--iterations K] [--sweeps S]
#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quadtree_forest.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/simulate.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace mrcloth;

struct BenchOptions {
  int frames = 50;                          // output frames at 25 fps
  std::vector<int> sizes{28, 64, 110};      // vertices per side of the uniform sheets
  int iterations = 2;                       // local/global iterations per step (the library default)
  int sweeps = 6;                           // strain-limiting sweeps per round (the library default)
};

QuadMesh make_sheet(int n, double side = 1.0) {
  QuadMesh mesh;
  const double step = side / (n - 1);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) mesh.add_vertex(QuadMesh::Point(-0.5 * side + i * step, 0.0, -0.5 * side + k * step));
  const auto vid = [&](int i, int k) { return mesh.vertex_handle(k * n + i); };
  for (int k = 0; k + 1 < n; ++k)
    for (int i = 0; i + 1 < n; ++i) mesh.add_face(vid(i, k), vid(i, k + 1), vid(i + 1, k + 1), vid(i + 1, k));
  init_forest(mesh);
  return mesh;
}

struct Row {
  std::string model;
  std::size_t vertices = 0;
  SimulationReport report;
};

Row run(const std::string& name, const QuadMesh& mesh, const BenchOptions& b) {
  DynamicsOptions d;  // cotton, default alpha
  const DynamicsModel model = build_dynamics(mesh, d);
  SimulationOptions s;
  s.frames = b.frames;
  s.fps = 25.0;
  s.substeps = 8;  // 5 ms
  s.iterations = b.iterations;
  s.strain_limit_sweeps = b.sweeps;
  s.gravity = Eigen::Vector3d(0.0, -9.8, 0.0);
  Collider sphere;
  sphere.shape = SphereCollider{{0.0, -0.3, 0.0}, 0.25};
  s.colliders = {sphere};
  ClothState state = rest_state(model);
  Row row;
  row.model = name;
  row.vertices = mesh.n_vertices();
  row.report = simulate(model, state, s);
  return row;
}

// Coarse 28 x 28 sheet refined to level 3 (109 x 109 at the finest) where
// it lies on the sphere and where it starts to fold over its rim.
QuadMesh adaptive_sheet(const AdaptiveRefineOptions& refine, double inner_radius, double outer_radius) {
  QuadMesh mesh = make_sheet(28);
  paint_modes_sphere(mesh, {0, 0, 0}, outer_radius, 2);
  paint_modes_sphere(mesh, {0, 0, 0}, inner_radius, 3);
  adaptive_refine(mesh, refine);
  return mesh;
}

std::vector<int> parse_sizes(const std::string& text) {
  std::vector<int> sizes;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) sizes.push_back(std::stoi(item));
  return sizes;
}

void print(const Row& r) {
  const SimulationReport& p = r.report;
  std::printf("| %-34s | %8zu | %9.1f | %9.1f | %9.1f | %7.2f %% | %9.2e | %s |\n", r.model.c_str(), r.vertices,
              p.mean_frame.dynamics_ms, p.mean_frame.collision_ms, p.mean_frame.total_ms(), 100.0 * p.max_stretch,
              p.max_penetration, p.non_finite ? "NaN!" : "ok");
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions b;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--frames") b.frames = std::atoi(argv[a + 1]);
    else if (key == "--sizes") b.sizes = parse_sizes(argv[a + 1]);
    else if (key == "--iterations") b.iterations = std::atoi(argv[a + 1]);
    else if (key == "--sweeps") b.sweeps = std::atoi(argv[a + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\nusage: bench_drape [--frames N] [--sizes 28,64,110] [--iterations K] [--sweeps S]\n", argv[a]);
      return 2;
    }
  }
  std::printf("drape: 1 m sheet over a 0.25 m sphere, 25 fps, %d frames, h = 5 ms, %d iterations, one core\n\n",
              b.frames, b.iterations);
  std::printf("| %-34s | %8s | %9s | %9s | %9s | %9s | %9s | %s |\n", "model", "vertices", "dyn ms/f", "coll ms/f",
              "total", "stretch", "penetr. m", "");
  std::printf("|%s|%s|%s|%s|%s|%s|%s|%s|\n", std::string(36, '-').c_str(), std::string(10, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str(), std::string(11, '-').c_str(),
              std::string(11, '-').c_str(), std::string(11, '-').c_str(), std::string(6, '-').c_str());
  Row largest;
  for (int n : b.sizes) {
    const Row row = run("uniform " + std::to_string(n) + " x " + std::to_string(n), make_sheet(n), b);
    print(row);
    if (row.vertices > largest.vertices) largest = row;
  }

  QuadMesh uniform = make_sheet(28);
  uniform_refine(uniform, 2);
  const Row high = run("uniform 28 refined x2 (109 x 109)", uniform, b);
  print(high);
  const Row adaptive = run("adaptive 28 -> level 3 at contact", adaptive_sheet({8.0, 3, true}, 0.22, 0.32), b);
  print(adaptive);
  std::printf("\nadaptive vs uniform 109 x 109: %.2f x faster per frame, %.1f %% of its vertices\n",
              high.report.mean_frame.total_ms() / adaptive.report.mean_frame.total_ms(),
              100.0 * adaptive.vertices / high.vertices);
  if (largest.vertices > 0)
    std::printf("adaptive vs %s: %.2f x faster per frame\n", largest.model.c_str(),
                largest.report.mean_frame.total_ms() / adaptive.report.mean_frame.total_ms());
  return 0;
}
