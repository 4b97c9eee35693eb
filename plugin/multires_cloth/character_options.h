#pragma once
// The character side of multirescloth.simulate and recordInstance: the
// `motion`, `body`, `place`, `preroll`, `stepRate` and `skipFirst` options
// checked strictly, then the BVH motion read and the character built by
// solver/character_setup.h (the same calls bench_character makes). The
// waist (`waist` / `pins`) is parsed with the other pins in
// simulation_options.cpp.
#include "plugin/core/option_fields.h"
#include "mesh_ops/quad_mesh.h"
#include "solver/character_setup.h"
#include "solver/character_sim.h"
#include "solver/figure_size.h"
#include "solver/garment_fit.h"

#include <QString>
#include <QStringList>
#include <QVariantMap>

namespace mrcloth {

/// A character run's options: what solver/character_setup.h sets up, and
/// where the motion and the body's cache come from.
struct CharacterRequest {
  QString motionPath;
  double motionScale = 1.0;     ///< metres per BVH unit (0 while the units are "auto": loadCharacter resolves them)
  QString motionUnits;          ///< how the scale was given, for the report ("m", "cmu", "scale 0.01", "auto" / resolved "auto: cm")
  double motionSmoothing = 0.0; ///< motion.smoothing: seconds, the Gaussian's standard deviation (smooth_motion); 0: as recorded
  ClipConventions conventions;  ///< motion.joints and motion.axes
  PositionChannels positionChannels = PositionChannels::absolute;  ///< motion.positions
  CharacterSetup setup;         ///< body, placement, pre-roll, step rate, skipFirst, motion start
  QString bodyOutput;           ///< PC2 cache of the body at the output frames (rest OBJ beside it); empty: none
  bool fitWarning = true;       ///< log a warning when the fit check finds the garment too narrow (the report's fit has it either way)
};

/// motion.smoothing's largest (seconds): beyond it the filter erases the motion itself.
constexpr double kLongestMotionSmoothing = 1.0;

/// The largest side (metres) a garment worn by a person may span on a
/// character run: outside it the garment was loaded in the wrong units
/// (resources/scripts/pipeline.js checks the same before any work).
constexpr double kGarmentSpanLow = 0.1;
constexpr double kGarmentSpanHigh = 4.0;

/// The top-level keys only a character run accepts (each needs `motion`).
QStringList characterOptionKeys();

/// Reads motion, body, place, preroll, stepRate, skipFirst and fitWarning from the top
/// level of the options (`fields`); `fps` is the run's output rate (stepRate
/// must be at least that). Input files must exist (InputError naming the
/// option); errors name the option.
CharacterRequest parseCharacterOptions(const options::Fields& fields, double fps);

/// A clip read on its own (multirescloth.motionInfo), as a run on a
/// character reads it.
struct MotionReading {
  CharacterRequest request;  ///< the motion's options, units resolved
  Motion clip;               ///< read in metres, joints renamed and axes turned; frame 0 kept
  ClipChanges changes;       ///< what standardise_clip did
  FigureScale figure;        ///< its legs against an adult's
};

/// Reads `motion` (simulate's `motion` option: a path or {path, units or
/// scale, skipFirst, start, joints, axes, positions, smoothing}) and checks its figure against an
/// adult's (figure_size.h). Errors name the option; a figure too big or
/// small for its units is an InputError saying which units would fit.
MotionReading readMotion(const QVariant& motion);

/// What a figure too big or small for the units it was read in is told:
/// the option, file, units, its legs against the expected ones, and the
/// units that would fit.
QString figureRefusal(const CharacterRequest& request, const FigureScale& figure);

/// Reads the BVH, renames its joints and turns its axes as motion.joints
/// and motion.axes say (standardise_clip; `changes`, if given, receives what
/// it did) and builds the character (make_character). Errors name the option they
/// come from ("option 'motion': <file>:<line>: ..."); a figure too big or
/// small for its units is an InputError naming the file, its units and the
/// units that would fit. Units "auto" are resolved in `request` (its
/// motionUnits then say "auto: cm", as the report shows them).
Character loadCharacter(CharacterRequest& request, const QuadMesh& garment, ClipChanges* changes = nullptr);

QString bodyTypeName(CharacterBodyKind type);
QString placementName(GarmentPlacement place);

/// What a character run adds to simulate's report: preroll {frames, steps,
/// msPerFrame {dynamics, collision, total}, initialPenetration, maxPenetration,
/// nonFinite}, maxWaistError, body, motion, motionUnits, motionStart,
/// motionDuration, skipFirst, place, stepRate, placement [dx, dy, dz], legBridges,
/// capsulesShrunk, waistFollows ("pelvis" | "skin"); with bodyOutput,
/// bodyCache and bodyMesh (added by the caller once written).
QVariantMap characterReportMap(const CharacterRunReport& report, const CharacterRequest& request,
                               const Character& character, const CharacterRunOptions& run);

/// The report's `fit` for a tube garment (run_hoop_demand): levels [{height
/// (m, up axis), garmentGirth, bodyGirth (m), demand (strain, null without a
/// garment section), frame (output frame, -1: no body section)}] from the
/// garment's top down, largestDemand, and stretchLimit (the material's).
QVariantMap hoopDemandMap(const std::vector<HoopLevel>& levels, double stretch_limit);

}  // namespace mrcloth
