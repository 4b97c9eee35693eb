#pragma once
#include "quad_mesh.h"

#include <functional>

namespace mrcloth {

/// Called as a refinement goes, with the steps done and the steps in all
/// (uniform_refine_steps): after every level's splits and every
/// kRefineProgressSteps steps within one, and as often while the refined
/// faces are built. Return false to stop.
using RefineProgress = std::function<bool(int steps_done, int steps_total)>;
constexpr int kRefineProgressSteps = 65536;

/// The steps of uniform_refine(mesh, levels) for its progress: one per face
/// split (the active faces times 1 + 4 + ... + 4^(levels - 1)), then one per
/// face of the result built (the active faces times 4^levels), which takes
/// as long as the splits or longer. A double: levels that would pass
/// kMostFaces are refused by uniform_refine, not counted here; 0 for none.
double uniform_refine_steps(const QuadMesh& mesh, int levels);

/// Splits every active face `levels` times (Algorithm 1 on every face, level
/// by level). Coarse vertices keep their indices. levels >= 0, and the
/// result at most kMostFaces faces (quad_refiner.h); throws ArgumentError
/// otherwise (before any work). Returns false when `progress` stopped it:
/// the mesh is then half refined, its faces stale, and must be discarded.
/// The callback changes nothing in a refinement it lets finish.
bool uniform_refine(QuadMesh& mesh, int levels, const RefineProgress& progress = {});

}  // namespace mrcloth
