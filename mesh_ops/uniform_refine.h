#pragma once
#include "quad_mesh.h"

namespace mrcloth {

/// Splits every active face `levels` times (Algorithm 1 on every face, level
/// by level). Coarse vertices keep their indices. levels >= 0, and the
/// result at most kMostFaces faces (quad_refiner.h); throws ArgumentError
/// otherwise.
void uniform_refine(QuadMesh& mesh, int levels);

}  // namespace mrcloth
