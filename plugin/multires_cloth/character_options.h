#pragma once
// The character side of multirescloth.simulate and recordInstance: the
// `motion`, `body`, `place`, `preroll`, `stepRate` and `skipFirst` options
// checked strictly, then the BVH motion, the collision body and the garment
// placement they ask for, loaded for solver/character_sim.h. The waist
// (`waist` / `pins`) is parsed with the other pins in simulation_options.cpp.
#include "plugin/core/option_fields.h"
#include "mesh_ops/quad_mesh.h"
#include "solver/body_skinned_mesh.h"
#include "solver/character_sim.h"
#include "solver/skeleton.h"

#include <Eigen/Geometry>

#include <QString>
#include <QStringList>
#include <QVariantMap>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace mrcloth {

/// What the pinned waist of a garment on a character follows.
enum class WaistFollows { automatic, pelvis, skin };
enum class CharacterBodyType { capsules, mesh };

/// Where the garment's rest positions are, relative to the skeleton's rest
/// pose (which simulate_on_character needs them in).
enum class GarmentPlacement {
  none,        ///< already in the skeleton's rest space
  makehuman,   ///< modelled on MakeHuman's base.obj (loaded in dm): + SkinnedBody::obj_offset
  firstFrame,  ///< modelled on the clip's frame 0 (CMU's added T-pose, the embedded walks' T-pose)
};

struct CharacterRequest {
  QString motionPath;
  double motionScale = 1.0;     ///< metres per BVH unit
  QString motionUnits;          ///< how the scale was given, for the report ("m", "cmu", "scale 0.01")
  bool skipFirst = true;        ///< drop frame 0 (CMU's added T-pose)
  double motionStart = 0.0;     ///< seconds into the clip (after skipFirst)
  CharacterBodyType body = CharacterBodyType::capsules;
  bool hasMakeHuman = false;    ///< the three MakeHuman files were given
  MakeHumanOptions makehuman;
  double thickness = 0.004;     ///< body thickness, metres
  double friction = 0.3;
  /// Capsule radius overrides by joint name (head, tail), metres; 0 removes the capsule.
  std::map<std::string, std::pair<double, double>> radii;
  /// Bridges between the legs (add_leg_bridges): < 0 automatic (down to the
  /// knees, or the ankles if the garment reaches below them, for a garment
  /// that is one tube with two boundary loops, none otherwise), 0 none,
  /// else the reach in bones from the hips (0.5 .. 2).
  double legBridges = -1.0;
  /// How the pinned waist moves: rigidly with the pelvis, or skinned like
  /// the MakeHuman body under it (CharacterRunOptions::waist_weights).
  /// Automatic: with the skin whenever the MakeHuman body is given (its
  /// mesh, or capsules fitted to it), else with the pelvis.
  WaistFollows waistFollows = WaistFollows::automatic;
  /// Arms opened just enough to keep the hands this far (metres) from the
  /// hips and thighs (solver/arm_clearance.h); < 0: the clip's arms as they are.
  double armClearance = ArmClearanceOptions{}.clearance;
  GarmentPlacement place = GarmentPlacement::none;
  double prerollSeconds = 1.0;
  double stepRate = 120.0;      ///< time steps per second
  QString bodyOutput;           ///< PC2 cache of the body at the output frames (rest OBJ beside it); empty: none
};

/// The top-level keys only a character run accepts (each needs `motion`).
QStringList characterOptionKeys();

/// Reads motion, body, place, preroll, stepRate and skipFirst from the top
/// level of the options (`fields`); `fps` is the run's output rate (stepRate
/// must be at least that). Input files must exist (InputError naming the
/// option); errors name the option.
CharacterRequest parseCharacterOptions(const options::Fields& fields, double fps);

/// A loaded character: the motion (kept at a fixed address: the posed body
/// refers to its skeleton), the collision body, and the rigid transform
/// taking the garment's rest positions into the skeleton's rest space.
struct LoadedCharacter {
  std::unique_ptr<Motion> motion;
  std::unique_ptr<PosedBody> body;
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  Pose garmentPose;             ///< the pose the garment was modelled on (empty: the rest pose)
  int bodyVertices = 0;         ///< skinned mesh vertices (0 for capsules)
  int bodyCapsules = 0;         ///< capsules (0 for a mesh)
  double legBridges = 0.0;      ///< the reach of the bridges between the legs, bones (0: none)
  bool fittedCapsules = false;  ///< capsule radii fitted to the MakeHuman body
  int capsulesShrunk = 0;       ///< capsules shrunk so the garment starts outside them (clear_capsules_of)
  /// The MakeHuman body whose skin the waist follows; null: the waist follows the pelvis.
  std::shared_ptr<const SkinnedBody> waistSkin;
  /// The hands kept out of the hips (on the body's own proportions); null: off.
  std::shared_ptr<const ArmClearance> armClearance;
};

/// Reads the BVH, finds the placement, builds the body (with bridges between
/// the legs as the request and the garment ask). Errors name the option
/// they come from ("option 'motion': <file>:<line>: ...").
LoadedCharacter loadCharacter(const CharacterRequest& request, const QuadMesh& garment);

/// Settings for simulate_on_character from the request, the loaded
/// character (its garment pose, the skin the waist follows), the garment's
/// model (its pinned waist) and the run's frames, fps and solver settings
/// (iterations, gravity, colliders, cache).
CharacterRunOptions characterRunOptions(const CharacterRequest& request, const LoadedCharacter& character,
                                        const DynamicsModel& model, const SimulationOptions& simulation);

QString bodyTypeName(CharacterBodyType type);
QString placementName(GarmentPlacement place);

/// What a character run adds to simulate's report: preroll {frames, steps,
/// msPerFrame {dynamics, collision, total}, initialPenetration, maxPenetration,
/// nonFinite}, maxWaistError, body, motion, motionUnits, motionStart,
/// motionDuration, skipFirst, place, stepRate, placement [dx, dy, dz], legBridges,
/// capsulesShrunk, waistFollows ("pelvis" | "skin"); with bodyOutput,
/// bodyCache and bodyMesh (added by the caller once written).
QVariantMap characterReportMap(const CharacterRunReport& report, const CharacterRequest& request,
                               const LoadedCharacter& character, const CharacterRunOptions& run);

}  // namespace mrcloth
