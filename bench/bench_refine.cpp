// bench_refine: how long the one-off refinement stage takes on real garments.
//
// The paper's figure to compare with (its Table 2): 108 ms to refine its
// 792-vertex skirt adaptively, once, on an Intel Core 2 Duo E8400 (2008).
// Here: MakeHuman's skirthelper (720 vertices, the closest real match, from
// the shared data folder) and the embedded default skirt (800 vertices).
//
//   build/bin/bench_refine --benchmark_min_time=0.2
//
// Every refinement works on a fresh copy of the loaded (and painted) mesh;
// the copy is excluded with PauseTiming and timed on its own by copy_mesh/*
// so its cost is visible too.
#include "mesh_ops/adaptive_refine.h"
#include "mesh_ops/garment_io.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quad_mesh.h"
#include "mesh_ops/uniform_refine.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace {

/// A spherical mode brush placed relative to the garment's bounding box, so
/// the same brush lands on the same part of any skirt whatever its units.
struct Brush {
  OpenMesh::Vec3d where;          ///< position in the bbox, each coordinate in [0, 1] (x left-right, y hem-waist, z back-front)
  double radius_of_height = 0.0;  ///< radius as a fraction of the bbox height
  int mode = 1;                   ///< mode painted inside the sphere
};

/// What the adaptive benchmark paints and how it refines. Painted in order
/// (later brushes overwrite earlier ones). Fixed, so runs are comparable.
struct PaintedRefineOptions {
  std::vector<Brush> brushes = {
      {{0.5, 0.3, 1.0}, 0.45, 2},  // front below the hips: the thighs push it when walking
      {{0.5, 0.3, 0.0}, 0.45, 2},  // back below the hips: same, from behind
      {{0.5, 0.0, 1.0}, 0.25, 3},  // front hem: swings with the knees, the most folds
      {{0.5, 0.0, 0.0}, 0.25, 3},  // back hem: the same swing behind
  };
  mrcloth::AdaptiveRefineOptions refine{/*delta=*/8.0, /*max_level=*/3, /*balance=*/true};
};

struct GarmentSource {
  std::string name;   ///< benchmark name part
  std::string path;   ///< file to load
  std::string units;  ///< units of the file's coordinates
  bool shared = false;  ///< lives in the shared data folder (absent in a fresh clone)
};

/// A loaded garment, or why there is none.
struct Garment {
  std::string name;
  std::unique_ptr<mrcloth::QuadMesh> plain;    ///< as loaded: every vertex mode 1
  std::unique_ptr<mrcloth::QuadMesh> painted;  ///< with PaintedRefineOptions::brushes applied
  std::vector<std::size_t> painted_counts;     ///< vertices painted by each brush
  std::string error;                           ///< non-empty: benchmarks skip with this message
};

std::pair<OpenMesh::Vec3d, OpenMesh::Vec3d> bounding_box(const mrcloth::QuadMesh& mesh) {
  const double inf = std::numeric_limits<double>::infinity();
  OpenMesh::Vec3d lo(inf, inf, inf), hi(-inf, -inf, -inf);
  for (auto v : mesh.vertices()) {
    lo.minimize(mesh.point(v));
    hi.maximize(mesh.point(v));
  }
  return {lo, hi};
}

/// The mesh vertex nearest to `target`: brush centres sit on the cloth, not
/// inside the tube where a box-relative point would otherwise fall.
OpenMesh::Vec3d nearest_vertex(const mrcloth::QuadMesh& mesh, const OpenMesh::Vec3d& target) {
  OpenMesh::Vec3d best = mesh.point(mesh.vertex_handle(0));
  for (auto v : mesh.vertices())
    if ((mesh.point(v) - target).sqrnorm() < (best - target).sqrnorm()) best = mesh.point(v);
  return best;
}

std::vector<std::size_t> paint(mrcloth::QuadMesh& mesh, const std::vector<Brush>& brushes) {
  const auto [lo, hi] = bounding_box(mesh);
  const OpenMesh::Vec3d size = hi - lo;
  std::vector<std::size_t> counts;
  for (const Brush& brush : brushes) {
    const OpenMesh::Vec3d target = lo + OpenMesh::Vec3d(brush.where[0] * size[0], brush.where[1] * size[1], brush.where[2] * size[2]);
    counts.push_back(mrcloth::paint_modes_sphere(mesh, nearest_vertex(mesh, target), brush.radius_of_height * size[1], brush.mode));
  }
  return counts;
}

Garment load(const GarmentSource& source, const PaintedRefineOptions& options) {
  Garment garment;
  garment.name = source.name;
  if (!std::filesystem::exists(source.path)) {
    garment.error = source.shared ? "shared data absent: " + source.path + " (configure with -DMRCLOTH_SHARED_DATA=<folder>)"
                                  : "garment missing: " + source.path;
    return garment;
  }
  try {
    mrcloth::LoadOptions load_options;
    load_options.units = source.units;
    auto loaded = mrcloth::load_garment(source.path, load_options);
    garment.plain = std::make_unique<mrcloth::QuadMesh>(std::move(loaded.mesh));
    garment.painted = std::make_unique<mrcloth::QuadMesh>(mrcloth::copy_mesh(*garment.plain));
    garment.painted_counts = paint(*garment.painted, options.brushes);
  } catch (const std::exception& e) {
    garment.error = std::string("cannot load ") + source.path + ": " + e.what();
  }
  return garment;
}

void set_mesh_counters(benchmark::State& state, const mrcloth::QuadMesh& coarse, const mrcloth::QuadMesh& refined) {
  state.counters["coarse_vertices"] = double(coarse.n_vertices());
  state.counters["vertices"] = double(refined.n_vertices());
  state.counters["faces"] = double(refined.n_faces());
  state.counters["hanging_nodes"] = double(mrcloth::count_hanging(refined));
}

void bench_copy(benchmark::State& state, const Garment& garment) {
  if (!garment.error.empty()) {
    state.SkipWithError(garment.error.c_str());
    return;
  }
  for (auto _ : state) {
    mrcloth::QuadMesh copy = mrcloth::copy_mesh(*garment.plain);
    benchmark::DoNotOptimize(copy);
  }
  state.counters["vertices"] = double(garment.plain->n_vertices());
}

void bench_uniform(benchmark::State& state, const Garment& garment, int levels) {
  if (!garment.error.empty()) {
    state.SkipWithError(garment.error.c_str());
    return;
  }
  mrcloth::QuadMesh mesh;
  for (auto _ : state) {
    state.PauseTiming();
    mesh = mrcloth::copy_mesh(*garment.plain);
    state.ResumeTiming();
    mrcloth::uniform_refine(mesh, levels);
    benchmark::ClobberMemory();
  }
  set_mesh_counters(state, *garment.plain, mesh);
}

void bench_adaptive(benchmark::State& state, const Garment& garment, const PaintedRefineOptions& options) {
  if (!garment.error.empty()) {
    state.SkipWithError(garment.error.c_str());
    return;
  }
  mrcloth::QuadMesh mesh;
  mrcloth::AdaptiveRefineReport report;
  for (auto _ : state) {
    state.PauseTiming();
    mesh = mrcloth::copy_mesh(*garment.painted);
    state.ResumeTiming();
    report = mrcloth::adaptive_refine(mesh, options.refine);
    benchmark::ClobberMemory();
  }
  set_mesh_counters(state, *garment.painted, mesh);
  state.counters["passes"] = double(report.faces_refined_per_pass.size());
  state.counters["balance_splits"] = double(report.faces_refined_for_balance);
  for (std::size_t i = 0; i < garment.painted_counts.size(); ++i)
    state.counters["painted_brush" + std::to_string(i)] = double(garment.painted_counts[i]);
  state.SetLabel("paper Table 2: 108 ms once for its 792-vertex skirt (Core 2 Duo E8400)");
}

void register_benchmarks(const Garment& garment, const PaintedRefineOptions& options) {
  const std::string& g = garment.name;
  benchmark::RegisterBenchmark(("copy_mesh/" + g).c_str(), [&garment](benchmark::State& s) { bench_copy(s, garment); })
      ->Unit(benchmark::kMillisecond);
  for (int levels : {1, 2}) {
    benchmark::RegisterBenchmark(("uniform_refine/" + g + "/levels:" + std::to_string(levels)).c_str(),
                                 [&garment, levels](benchmark::State& s) { bench_uniform(s, garment, levels); })
        ->Unit(benchmark::kMillisecond);
  }
  const std::string adaptive_name = "adaptive_refine/" + g + "/delta:" + std::to_string(int(options.refine.delta)) +
                                    "/max_level:" + std::to_string(options.refine.max_level) +
                                    (options.refine.balance ? "/balanced" : "/unbalanced");
  benchmark::RegisterBenchmark(adaptive_name.c_str(),
                               [&garment, &options](benchmark::State& s) { bench_adaptive(s, garment, options); })
      ->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  const PaintedRefineOptions options;
  const std::vector<GarmentSource> sources = {
      {"skirthelper", std::string(MRCLOTH_SHARED_DATA) + "/garments/makehuman/skirthelper.obj", "dm", true},
      {"default_skirt", MRCLOTH_DEFAULT_SKIRT, "m", false},
  };
  // Loaded once, before any timing; they outlive the benchmarks that reference them.
  std::vector<Garment> garments;
  for (const GarmentSource& source : sources) garments.push_back(load(source, options));
  for (const Garment& garment : garments) register_benchmarks(garment, options);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
