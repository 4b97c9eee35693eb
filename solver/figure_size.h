#pragma once
// How big a clip's figure is: a check on the units it was read in. A
// centimetre clip read in CMU units (0.056444 m per unit) stands nine
// metres tall; skinned onto the MakeHuman body it blows the body up, and
// capsules and a garment in metres are lost on it, yet the run itself
// finishes and only its numbers are absurd. Runs on a character refuse such
// a clip before they start (make_character), and the scripting API's
// `units: "auto"` picks the units that give the figure a human size.
#include "skeleton.h"

#include "mesh_ops/errors.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mrcloth {

/// The legs, hip joint to ankle, of the figure the checks measure against
/// when no body is given, metres: the embedded mannequin's (1.65 m tall).
/// CMU's subjects measure 0.79-0.89 m, the DAZ clip 0.82 m, the MakeHuman
/// body 0.81 m.
constexpr double kReferenceLegs = 0.79;

/// The figure's size against what it should be.
struct FigureScale {
  double legs = 0.0;      ///< metres, hip joint to ankle in the rest pose, the mean of the legs found (CMU names); 0: none found
  bool measured = false;  ///< whether a leg was found (its joints by CMU names), even one of length 0
  double expected = 0.0;  ///< metres, the legs it is measured against: a body's own, or kReferenceLegs
  bool against_body = false;  ///< whether `expected` is a body's legs
  /// legs / expected (1 without legs: nothing to measure; 0 for legs of
  /// length 0, a skeleton whose joints all stand at one point).
  double factor() const { return (measured || legs > 0.0) && expected > 0.0 ? legs / expected : 1.0; }
};

/// The legs (metres; 0 if neither leg is found) of a skeleton whose joints
/// stand at `joints` (per joint, metres): the mean over LeftUpLeg-LeftFoot
/// and RightUpLeg-RightFoot of the distance between the two joints.
double leg_length(const Skeleton& skeleton, const std::vector<Eigen::Vector3d>& joints);

/// The skeleton's legs in its rest pose against `body_legs` (metres, a
/// body's own legs as leg_length measures them; 0: no body, the reference).
FigureScale figure_scale(const Skeleton& skeleton, double body_legs = 0.0);

/// The factor (legs / expected) within which a figure passes: a body
/// skinned by a skeleton half again as long or short is visibly torn, so
/// 1.5 against a body; without one, any person from a child (0.32 m of
/// leg) to a giant of 2 m, 0.4-2.0. Units that differ (CMU units and
/// inches, the closest pair) differ by 2.2 or more.
constexpr double kBodyFactorLimit = 1.5;
constexpr double kReferenceFactorLow = 0.4;
constexpr double kReferenceFactorHigh = 2.0;

/// Whether the figure is a plausible size for its units (see above).
bool plausible(const FigureScale& scale);

/// "the figure's legs are 4.63 m long (hip to ankle), 5.7 times the
/// MakeHuman body's 0.81 m" (or "an adult's 0.79 m"): what a refusal says.
std::string describe(const FigureScale& scale);

/// Thrown by make_character for a figure that is not plausible: callers
/// that know the clip's file and units say them, and which units would fit.
struct FigureSizeError : ArgumentError {
  FigureSizeError(const std::string& message, const FigureScale& figure) : ArgumentError(message), scale(figure) {}
  FigureScale scale;
};

}  // namespace mrcloth
