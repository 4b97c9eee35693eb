#pragma once
// multirescloth.simulate's (and recordInstance's) script side: the options
// object a script passes, checked strictly and turned into solver settings,
// and the solver's report turned into the object the script gets back. No
// simulation happens here. The character options (motion, body, ...) are
// read by character_options.h.
#include "character_options.h"
#include "mesh_ops/quad_mesh.h"
#include "solver/dynamics_model.h"
#include "solver/simulate.h"

#include <QHash>
#include <QString>
#include <QStringList>
#include <QVariant>
#include <QVariantMap>

#include <optional>

namespace mrcloth {

/// The slot whose options are parsed: recordInstance requires motion and
/// output and records 200 frames by default.
enum class SimulationCall { simulate, recordInstance };

/// Everything one simulate call asks for.
struct SimulationRequest {
  DynamicsOptions dynamics;      ///< material, alpha, alphaBend, pinned vertex ids
  SimulationOptions simulation;  ///< frames, fps, substeps, iterations, gravity, colliders, cache_path (= output)
  QString pinsText;              ///< how the pins were given, for messages ("\"top\"", "4 vertex ids", "none")
  QString objSequence;           ///< OBJ sequence prefix; empty: none
  bool updateObject = false;     ///< store the last frame as a new object
  std::optional<CharacterRequest> character;  ///< set when `motion` is given: a run on a character
  /// optionNames: how the run's warnings name its options, for a tool that
  /// takes them under names of its own (the pipeline's flags); "" for one
  /// the tool does not offer (advice to set it is left out).
  QHash<QString, QString> optionNames;
};

/// How `request`'s warnings name option `key`: "option 'key'", or the name
/// optionNames gives it ("" when the caller offers no such option).
QString optionCalled(const SimulationRequest& request, const QString& key);

/// The keys simulate's options object accepts, in the order the errors list
/// them: the plain simulation's, then the character's (characterOptionKeys).
QStringList simulationOptionKeys();

/// `<folder>/<name>.obj` for a cache `<folder>/<name>.pc2`: where a cache's rest mesh goes.
QString restMeshPath(const QString& cache_path);

/// Checks a script's options object against `mesh` (loop names in "pins" are
/// resolved on it) and fills a request; every field absent keeps its solver
/// default. Throws ArgumentError naming the option for an unknown key, a wrong
/// type or a value out of range, and OutputError when the folder of `output`
/// or `objSequence` does not exist. Pinned ids are range-checked later, by
/// build_dynamics, which also rejects hanging vertices.
/// With `motion`, the character options are read too (see
/// parseCharacterOptions), the waist ("waist" or "pins", not both) defaults
/// to "top", and "substeps" is refused (the rate is "stepRate"); without it
/// every character option is refused.
SimulationRequest parseSimulationOptions(const QVariant& options, const QuadMesh& mesh,
                                         SimulationCall call = SimulationCall::simulate);

/// Refuses (OutputError, naming both) an output of the run (output,
/// bodyOutput, their rest meshes, a frame of objSequence) that is one of its
/// input files: the garment's (`garmentFile`, the object's file; empty:
/// none), the motion, the MakeHuman body's. Such an output replaced the
/// body or garment it was made from.
void requireOutputsSpareInputs(const SimulationRequest& request, const QString& garmentFile);

/// The script's view of a finished (or cancelled) run: frames, steps,
/// timeStep, precomputeMs, msPerFrame {dynamics, collision, total, limiter,
/// posing, firstRound},
/// maxStretch, maxTearOpening, maxPenetration (maxClothPenetration, maxClothDepth,
/// maxPinnedDepth, maxPinYield), nonFinite, cancelled, output, vertices,
/// freeVertices, pinnedVertices, hangingVertices, springs {stretch, shear,
/// bend}, perFrameMs [{dynamics, collision}].
QVariantMap simulationReportMap(const SimulationReport& report, const DynamicsModel& model);

/// "max stretch X %" for log lines, saying when the most stretched spring
/// lies between pinned vertices (then with the cloth's own largest stretch).
QString stretchSummary(const SimulationReport& report);

/// "max penetration X mm", with the cloth's own when the deepest vertex is a
/// pinned one (for the run's log line).
QString penetrationSummary(const SimulationReport& report);

/// The warning for pins a collider overlapped by more than a millimetre:
/// below its surface (pinsYield false) or moved out onto it, off their
/// targets; or an empty string. `slot` starts the message.
QString pinnedDepthWarning(const QString& slot, const SimulationReport& report, const SimulationRequest& request);

}  // namespace mrcloth
