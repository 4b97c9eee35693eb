// Whether the shared skirts can go round the walking body at all: at eight
// heights of each skirt (top to hem), the strain a level loop of it needs to go
// round the skinned MakeHuman body's section over a walk (character_fit.h;
// arms and hands not counted: they hang beside a skirt, not in it). Where
// this exceeds the cloth's stretch limit (cotton's 3 %), the stride asks for
// cloth that is not there, and no solver keeps the skirt whole and within
// its limit: the strain limiter spends every round it has.
//
// Usage: bench_fit [--frames N] [--preroll S] [--flare AMOUNT]  (N output
//        frames at 30 fps after the pre-roll, as bench_character and
//        bench_walks run, at most 100 of them sectioned as simulate does;
//        --flare widens the skirts toward their hems,
//        bench::flare_skirt)
#include "mesh_ops/garment_io.h"
#include "garment_on_character.h"
#include "solver/character_fit.h"
#include "solver/material.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace mrcloth;

std::string data(const std::string& relative) { return std::string(MRCLOTH_SHARED_DATA) + "/" + relative; }

}  // namespace

int main(int argc, char** argv) {
  int frames = 60;
  double preroll = 0.5;
  double flare = 0.0;  // the skirts widened toward their hems by this (bench::flare_skirt)
  for (int a = 1; a < argc; a += 2) {
    const std::string key = argv[a];
    if (key == "--help" || key == "-h" || a + 1 == argc) {
      std::printf("usage: bench_fit [--frames N] [--preroll S] [--flare AMOUNT]\n");
      return key == "--help" || key == "-h" ? 0 : 2;
    }
    if (key == "--frames") frames = std::atoi(argv[a + 1]);
    else if (key == "--preroll") preroll = std::atof(argv[a + 1]);
    else if (key == "--flare") flare = std::atof(argv[a + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\nusage: bench_fit [--frames N] [--preroll S] [--flare AMOUNT]\n", argv[a]);
      return 2;
    }
  }
  const std::string garments[] = {"skirthelper.obj", "female_elegantsuit01_skirt_on_base.obj"};
  const std::string walks[] = {"07_06", "07_03", "08_03", "02_01"};
  if (!std::filesystem::exists(data("garments/makehuman/" + garments[0]))) {
    std::printf("shared data absent (%s): nothing to measure\n", data("garments/makehuman").c_str());
    return 0;
  }
  const HoopDemandOptions levels;
  std::printf("strain a level loop of the skirt needs to go round the walking body (arms not counted), at %d levels from the "
              "waist (level 1) to the hem, over %d frames at 30 fps after a %.1f s pre-roll; the cloth's "
              "stretch limit is %.0f %% (cotton)\n\n",
              levels.levels, frames, preroll, 100.0 * material_preset("cotton").stretch_limit);
  std::printf("| skirt | walk |");
  for (int k = 1; k <= levels.levels; ++k) std::printf(" level %d |", k);
  std::printf(" lowest level's girth, m |\n|---|---|");
  for (int k = 1; k <= levels.levels; ++k) std::printf("---|");
  std::printf("---|\n");
  for (const std::string& garment_file : garments) {
    QuadMesh garment = load_garment(data("garments/makehuman/" + garment_file), {"dm"}).mesh;
    bench::flare_skirt(garment, flare);
    for (const std::string& walk : walks) {
      BvhReadOptions bvh;
      bvh.scale = 0.056444;          // CMU units to metres
      bvh.skip_first_frame = false;  // make_character drops CMU's added T-pose
      const Motion clip = read_bvh(data("motions/cmu_mb/" + walk + ".bvh"), bvh);
      bench::GarmentRunOptions run;
      run.makehuman_folder = data("bodies/makehuman");
      run.preroll = preroll;
      run.simulation.frames = frames;
      const std::vector<HoopLevel> result = bench::garment_fit(bench::prepare_garment_on_character(garment, clip, run));
      std::printf("| %s | %s |", garment_file.substr(0, garment_file.find('.')).c_str(), walk.c_str());
      for (const HoopLevel& level : result) std::printf(" %+.0f %% |", 100.0 * level.demand());
      std::printf(" %.3f |\n", result.back().garment_girth);
    }
  }
  return 0;
}
