#pragma once
#include "quad_mesh.h"

#include <vector>

namespace mrcloth {

/// Rest area of each active face in m^2, indexed by face. The garment's area
/// is defined on the coarse mesh (each coarse quad's vector-area magnitude);
/// refinement shares a coarse quad's area among its active descendants in
/// proportion to their own vector-area magnitudes, so the total never depends
/// on the refinement (and equals the true areas on planar quads).
std::vector<double> rest_face_areas(const QuadMesh& mesh);

/// Garment area in m^2 (sum of the coarse quads' areas).
double garment_area(const QuadMesh& mesh);

/// Lumped mass per vertex in kg (indexed by vertex) for areal density in
/// kg/m^2: each active face gives a quarter of density * rest area to each of
/// its four corners; a hanging vertex gets no mass, which goes half to each of
/// its parents (recursively along T-node chains). Sum = density * garment_area.
std::vector<double> lumped_mass(const QuadMesh& mesh, double areal_density);

}  // namespace mrcloth
