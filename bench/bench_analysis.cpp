// Issue 5's benchmark: instance analysis of the embedded default skirt
// refined uniformly twice (12320 vertices; the shared skirt, 11088, when
// ../shared/data is there) over a 200-frame PC2 cache: bend pairs,
// streamed curvature features, k-means into 3 modes. One core; prints a
// table. The cache is synthetic (each vertex displaced by travelling
// waves, written once to a temporary file): the analysis costs the same
// per frame whatever the cloth did, and recording 200 frames of 11088
// vertices would take minutes.
//
// Usage: bench_analysis [--frames N] [--cache FILE]
//   --cache: time a recorded instance of the same mesh instead (e.g.
//   analyse_instance.js's skirthelper_instance.pc2: real cloth bends
//   harder than the synthetic waves, a different mix of inverse sincs).
#include "mesh_ops/garment_io.h"
#include "mesh_ops/uniform_refine.h"
#include "solver/deformation_modes.h"
#include "solver/instance_curvature.h"
#include "solver/point_cache.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

using namespace mrcloth;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 200;
  std::string recorded;
  for (int a = 1; a + 1 < argc; a += 2) {
    if (std::string(argv[a]) == "--frames") frames = std::atoi(argv[a + 1]);
    else if (std::string(argv[a]) == "--cache") recorded = argv[a + 1];
    else {
      std::fprintf(stderr, "unknown option %s\nusage: bench_analysis [--frames N] [--cache FILE]\n", argv[a]);
      return 2;
    }
  }
  if (frames < 1) {
    std::fprintf(stderr, "--frames must be >= 1\n");
    return 2;
  }
  const std::string shared = std::string(MRCLOTH_SHARED_DATA) + "/garments/makehuman/skirthelper.obj";
  const bool have_shared = std::filesystem::exists(shared);
  const std::string garment = have_shared ? shared : std::string(MRCLOTH_DEFAULT_SKIRT);
  QuadMesh mesh = load_garment(garment, {have_shared ? "dm" : "m"}).mesh;
  uniform_refine(mesh, 2);
  const int n = static_cast<int>(mesh.n_vertices());

  const std::filesystem::path cache_path =
      !recorded.empty() ? std::filesystem::path(recorded)
                        : std::filesystem::temp_directory_path() / ("mrcloth_bench_analysis_" + std::to_string(n) + ".pc2");
  if (recorded.empty()) {
    Pc2Writer writer(cache_path.string(), n);
    FramePositions frame(n, 3);
    for (int t = 0; t < frames; ++t) {
      for (const auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        const double wave = 0.01 * std::sin(25.0 * p[1] + 0.2 * t) * std::cos(17.0 * p[0] - 0.1 * t);
        frame.row(v.idx()) << p[0] + wave, p[1], p[2] + wave;
      }
      writer.add_frame(frame);
    }
    writer.finish();
  } else {
    frames = Pc2Reader(recorded).num_frames();
  }

  auto start = Clock::now();
  const CurvaturePairs pairs = curvature_pairs(mesh);
  const double pairs_ms = ms_since(start);
  start = Clock::now();
  const CurvatureFeatures features = analyse_curvature(cache_path.string(), pairs);
  const double features_ms = ms_since(start);
  start = Clock::now();
  const ModeReport modes = deformation_modes(features.mean, features.deviation);
  const double modes_ms = ms_since(start);
  if (recorded.empty()) std::filesystem::remove(cache_path);

  std::printf("instance analysis of %s refined twice: %d vertices, %zu bend pairs, %d frames (%s), one core\n\n",
              have_shared ? "the shared skirt" : "the default skirt (shared data absent)", n, pairs.i.size(), frames,
              recorded.empty() ? "synthetic cache" : recorded.c_str());
  std::printf("| stage | ms | ms per 100 frames |\n|---|---|---|\n");
  std::printf("| bend pairs | %.1f | |\n", pairs_ms);
  std::printf("| curvature features (streamed PC2) | %.1f | %.1f |\n", features_ms, 100.0 * features_ms / frames);
  std::printf("| k-means, 3 modes, 8 restarts | %.1f | |\n", modes_ms);
  std::printf("| total | %.1f | %.1f |\n", pairs_ms + features_ms + modes_ms,
              100.0 * (pairs_ms + features_ms + modes_ms) / frames);
  std::printf("\nmode sizes:");
  for (const int size : modes.sizes) std::printf(" %d", size);
  std::printf("\n");
  return 0;
}
