#pragma once
// Motion axes. The characters stand a clip's rest pose as the MakeHuman body
// and the CMU clips stand: Y up, the figure's left along +X (so facing +Z).
// A clip recorded with other axes (Z up, facing -Z or +X) is turned once,
// after reading, by a signed permutation of the axes: offsets and position
// channels move to the other axis, rotation channels are relabelled to the
// turned axis, values negated where an axis flips. Nothing is recomputed,
// so turning and turning back gives the clip again to the bit.
#include "skeleton.h"

#include <array>
#include <string>

namespace mrcloth {

/// A proper signed axis permutation: new coordinate k = sign[k] * old
/// coordinate axis[k] (a rotation by multiples of 90 degrees).
struct AxisTurn {
  std::array<int, 3> axis{0, 1, 2};
  std::array<double, 3> sign{1.0, 1.0, 1.0};
  bool identity() const;
  /// The turn undone.
  AxisTurn inverse() const;
  /// Where each new axis comes from, e.g. "x = x, y = z, z = -y"; "" for the identity.
  std::string describe() const;
};

/// The turn that stands the skeleton's rest pose upright: up (Hips to
/// Head) onto +Y and left (RightUpLeg to LeftUpLeg) onto +X, each snapped
/// to its nearest signed axis; without a Head, up to the neck or spine,
/// and without the legs, left across the shoulders, arms or feet (CMU
/// names; see joint_names.h). The identity when none of those is there or
/// both snap to one axis; then `undecided`, if given, says why (else it is
/// cleared).
AxisTurn upright_turn(const Skeleton& skeleton, std::string* undecided = nullptr);

/// Turns the motion in place: offsets, position channels and rotation
/// channels as the header says. Throws ArgumentError for a turn that is not
/// a proper signed permutation.
void turn_axes(Motion& motion, const AxisTurn& turn);

}  // namespace mrcloth
