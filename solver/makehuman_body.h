#pragma once
// Reading a MakeHuman body into a SkinnedBody (body_skinned_mesh.h): the
// `body` group of base.obj, the CMU rig of a .mhskel and the skin weights of
// a .mhw, bound to a BVH skeleton. Posing the body once read is
// body_skinned_mesh.h's.
#include "skeleton.h"

#include <string>

namespace mrcloth {

// Declared, not included: body_skinned_mesh.h defines it and includes this
// header (its callers see the loader there), so including it back would be
// a cycle. Calling load_makehuman_body needs body_skinned_mesh.h.
struct SkinnedBody;

struct MakeHumanOptions {
  std::string base_obj;        ///< path of bodies/makehuman/base.obj (group "body" is the body)
  std::string skeleton_file;   ///< path of rigs/cmu_mb.mhskel (JSON)
  std::string weights_file;    ///< path of rigs/default_weights.mhw (JSON)
  double metres_per_unit = 0.1;  ///< base.obj's units (MakeHuman exports decimetres)
};

/// The three files of a MakeHuman folder laid out as the shared data's
/// bodies/makehuman: `folder`/base.obj, rigs/cmu_mb.mhskel and
/// rigs/default_weights.mhw (not checked for existence).
MakeHumanOptions makehuman_files(const std::string& folder);

/// Loads the MakeHuman body and binds it to `skeleton` (a CMU skeleton in
/// metres, rest pose = T-pose): a CMU bone's weight is the sum of its
/// mhskel `weights_reference` bones' weights (`reference` when it has none);
/// default bones no CMU bone lists go to the CMU bone whose weights overlap
/// theirs most. The mesh is translated so its hip joints' midpoint meets the
/// skeleton's, and every bone with a direction in the skeleton gets a rest
/// correction rotation taking its mesh (A-pose) direction to the skeleton's
/// rest direction, applied once, so the bound rest mesh is in T-pose with
/// the mesh's own bone lengths. Names the file and the problem on failure
/// (InputError); a body not 0.5-3 m tall is refused as one read in other
/// units, with the units it would have in.
SkinnedBody load_makehuman_body(const MakeHumanOptions& files, const Skeleton& skeleton);

}  // namespace mrcloth
