#pragma once
// Smoothing a clip in time: raw motion capture jitters by a fraction of a
// degree from frame to frame, which moves the shins through trouser cuffs
// at 120 frames a second (README, Motions unlike a clean walk).
#include "skeleton.h"

namespace mrcloth {

/// Smooths every channel of frames first_frame.. of `motion` in time with a
/// Gaussian of standard deviation `sigma_seconds` (truncated at 3 sigma),
/// in place; frames before first_frame (a CMU clip's added T-pose) are left
/// as they are and not read. Rotation channels are unwrapped first (a turn
/// from 179 to -179 degrees is 2 degrees), so their values may leave
/// [-180, 180]. At the ends the channels are continued by point reflection
/// through the end frame, so a channel changing at a constant rate keeps
/// every value (to rounding) and the clip keeps its first and last poses'
/// trend. sigma_seconds <= 0: nothing changes.
void smooth_motion(Motion& motion, double sigma_seconds, int first_frame = 0);

}  // namespace mrcloth
