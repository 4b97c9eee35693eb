#pragma once
// Smoothing a clip in time: raw motion capture jitters by a fraction of a
// degree from frame to frame, which moves the shins through trouser cuffs
// at 120 frames a second (README, Motions unlike a clean walk).
#include "skeleton.h"

namespace mrcloth {

/// Smooths every channel of frames first_frame.. of `motion` in time with a
/// Gaussian of standard deviation `sigma_seconds` (truncated at 3 sigma),
/// in place; frames before first_frame (a CMU clip's added T-pose) are left
/// as they are and not read. A joint's three rotation channels about three
/// axes are smoothed as one rotation (unit quaternions, signs aligned,
/// averaged and normalised) and written back as the Euler triple nearest
/// the frame's own, so a clip whose angles jump to the other triple of the
/// same rotation is smoothed as the rotation it is; other rotation channels
/// are unwrapped (a turn from 179 to -179 degrees is 2 degrees) and
/// smoothed one by one, as positions are. At the ends every channel is
/// continued by point reflection through the end frame (again and again
/// for a window longer than the clip), so a constant rate or angular
/// velocity keeps every value to rounding. sigma_seconds <= 0: nothing
/// changes.
void smooth_motion(Motion& motion, double sigma_seconds, int first_frame = 0);

}  // namespace mrcloth
