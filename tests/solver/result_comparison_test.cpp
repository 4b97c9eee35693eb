// compare_results on caches written here: a result against itself is 0, and
// caches whose frames are not at the same times (PC2 start frame or sample
// rate) are refused naming both, since frame k would compare two times.
#include "test_meshes.h"

#include "solver/point_cache.h"
#include "solver/result_comparison.h"

#include "mesh_ops/errors.h"
#include "mesh_ops/uniform_refine.h"

#include <gtest/gtest.h>

#include <string>

namespace mrcloth {
namespace {

/// `frames` frames of `mesh` swaying along x, to a PC2 with the given timing.
std::string write_cache(const QuadMesh& mesh, const std::string& path, int frames, double start, double rate) {
  Pc2Writer writer(path, static_cast<int>(mesh.n_vertices()), start, rate);
  for (int f = 0; f < frames; ++f) {
    FramePositions x(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
    for (const auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      x.row(v.idx()) << p[0] + 0.01 * f * p[1], p[1], p[2];
    }
    writer.add_frame(x);
  }
  writer.finish();
  return path;
}

TEST(CompareResults, AResultAgainstItselfIsZero) {
  QuadMesh mesh = test::make_grid(3, 2, 0.1);
  uniform_refine(mesh, 1);
  const auto dir = test::fresh_folder("result_comparison", "self");
  const std::string cache = write_cache(mesh, (dir / "a.pc2").string(), 4, 1.0, 1.0);
  const ComparisonReport report = compare_results(mesh, cache, mesh, cache);
  EXPECT_EQ(report.frames, 4);
  EXPECT_EQ(report.mean_rms, 0.0);
  EXPECT_EQ(report.max_distance, 0.0);
}

TEST(CompareResults, CachesSampledOtherwiseAreRefusedNamingBoth) {
  QuadMesh mesh = test::make_grid(3, 2, 0.1);
  uniform_refine(mesh, 1);
  const auto dir = test::fresh_folder("result_comparison", "timing");
  const std::string ours = write_cache(mesh, (dir / "ours.pc2").string(), 4, 1.0, 1.0);
  const std::string halved = write_cache(mesh, (dir / "every_second.pc2").string(), 4, 1.0, 2.0);
  const std::string later = write_cache(mesh, (dir / "from_ten.pc2").string(), 4, 10.0, 1.0);
  try {
    compare_results(mesh, halved, mesh, ours);
    ADD_FAILURE() << "a cache sampled every second frame against one sampled every frame";
  } catch (const ArgumentError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(halved + " starts at frame 1 with a sample every 2 frames, " + ours +
                           " starts at frame 1 with a sample every 1 frames: their frames are not at the same times"),
              std::string::npos)
        << message;
  }
  EXPECT_THROW(compare_results(mesh, ours, mesh, later), ArgumentError);
  EXPECT_NO_THROW(compare_results(mesh, halved, mesh, halved)) << "sampled alike, however";
}

}  // namespace
}  // namespace mrcloth
