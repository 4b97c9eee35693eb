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
#include "solver/joint_names.h"
#include "solver/motion_axes.h"
#include "solver/character_sim.h"
#include "solver/garment_fit.h"

#include <QString>
#include <QStringList>
#include <QVariantMap>

namespace mrcloth {

/// A character run's options: what solver/character_setup.h sets up, and
/// where the motion and the body's cache come from.
struct CharacterRequest {
  QString motionPath;
  double motionScale = 1.0;     ///< metres per BVH unit
  QString motionUnits;          ///< how the scale was given, for the report ("m", "cmu", "scale 0.01")
  bool autoJointNames = true;   ///< rename a known convention's joints onto CMU names (motion.joints "auto")
  JointRenaming jointRenaming;  ///< motion.joints given as {name in the file: CMU name}; used when !autoJointNames
  bool autoAxes = true;         ///< stand a clip recorded with other axes upright (motion.axes "auto")
  CharacterSetup setup;         ///< body, placement, pre-roll, step rate, skipFirst, motion start
  QString bodyOutput;           ///< PC2 cache of the body at the output frames (rest OBJ beside it); empty: none
};

/// The top-level keys only a character run accepts (each needs `motion`).
QStringList characterOptionKeys();

/// Reads motion, body, place, preroll, stepRate and skipFirst from the top
/// level of the options (`fields`); `fps` is the run's output rate (stepRate
/// must be at least that). Input files must exist (InputError naming the
/// option); errors name the option.
CharacterRequest parseCharacterOptions(const options::Fields& fields, double fps);

/// What loadCharacter did to the clip before building the character.
struct ClipChanges {
  JointRenaming renamed;  ///< joints renamed onto CMU names (motion.joints)
  AxisTurn turned;        ///< the axes turned to stand it upright (motion.axes)
};

/// Reads the BVH, renames its joints onto CMU names as motion.joints says,
/// turns its axes as motion.axes says (`changes`, if given, receives both)
/// and builds the character (make_character). Errors name the option they
/// come from ("option 'motion': <file>:<line>: ...").
Character loadCharacter(const CharacterRequest& request, const QuadMesh& garment, ClipChanges* changes = nullptr);

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
