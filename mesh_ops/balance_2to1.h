#pragma once
#include "quad_refiner.h"

namespace mrcloth {

/// Splits active faces until every two active faces sharing an edge segment
/// differ by at most one level (so an edge carries at most one hanging node).
/// New vertices get R = mean of their fathers' R (Algorithm 3 without the
/// decrement). Returns the number of faces split. Leaves faces stale: the
/// caller's refiner finishes.
std::size_t balance_2to1(QuadMesh& mesh, QuadRefiner& refiner);

}  // namespace mrcloth
