#pragma once
#include "quad_mesh.h"

namespace mrcloth {

/// The most faces a uniform refinement may make (a garment of 800 coarse
/// faces refined 8 times has 52 million; each takes about half a kilobyte).
constexpr double kMostUniformFaces = 5e7;

/// Splits every active face `levels` times (Algorithm 1 on every face, level
/// by level). Coarse vertices keep their indices. levels >= 0, and the
/// result at most kMostUniformFaces faces; throws ArgumentError otherwise.
void uniform_refine(QuadMesh& mesh, int levels);

}  // namespace mrcloth
