#pragma once
// What simulate and recordInstance say and report after a run: the
// warnings a finished, cancelled or non-finite run ends with and its last
// log line (log_line.h: the plugin emits them), and the report keys beside
// the solver's numbers (simulationReportMap, characterReportMap): what the
// run wrote and, on a character, what reading the clip and placing the
// garment did. The wording before a run is run_checks.h's.
#include "character_options.h"
#include "log_line.h"
#include "simulation_options.h"
#include "solver/character_setup.h"
#include "solver/character_sim.h"
#include "solver/simulate.h"

#include <QString>
#include <QStringList>
#include <QVariantMap>

#include <vector>

namespace mrcloth {

/// What a run wrote; all empty (0) for an incomplete run, whose outputs
/// are not written.
struct RunOutputs {
  QStringList obj_files;  ///< the OBJ sequence's files; none without objSequence
  QString rest_mesh;      ///< the cache's rest mesh (OBJ beside it); empty: none
  QString body_mesh;      ///< the body cache's rest mesh (a run on a character with bodyOutput); empty: none
  int result = 0;         ///< the object stored with the last frame (updateObject); 0: none
};

/// The report keys every simulate and recordInstance run has beside the
/// solver's numbers: operation (`slot`), source (`source`, the input
/// object's id), material (`request`'s), objFiles and restMesh
/// (`outputs`), and resultId when an object was stored.
QVariantMap runOutputsReportMap(const QString& slot, int source, const SimulationRequest& request,
                                const RunOutputs& outputs);

/// What a run on a character adds to its report beside characterReportMap:
/// jointsRenamed and axesTurned (`changes`, what reading the clip did), fit
/// (`fit`, checkBeforeCharacterRun's; left out when empty), garmentCleared
/// (`clearance`, what placing the garment moved), and bodyCache (`wanted`'s
/// bodyOutput) with bodyMesh (`outputs`) when the body's cache was written.
QVariantMap characterRunReportMap(const CharacterRequest& wanted, const ClipChanges& changes, const QVariantMap& fit,
                                  const GarmentClearance& clearance, const RunOutputs& outputs);

/// What simulate (without a character) says after its run, in order:
/// penetration at the start, pins deep in a collider, then cancelled,
/// non-finite or the run's summary. `source` is the input object's id,
/// `request` the run's options, `report` the solver's.
std::vector<LogLine> simulationOutcomeLines(int source, const SimulationRequest& request,
                                            const SimulationReport& report);

/// What a run on a character says after it, in order: pins deep in the
/// body, the cloth starting inside it (both only with fitWarning), then
/// cancelled, non-finite or the run's summary. `slot` starts each line,
/// `source` is the input object's id, `request` the run's options,
/// `wanted` its character options with the units resolved (loadCharacter),
/// `report` and `run` the solver's report and options, `rest_mesh` the
/// rest mesh written (empty: none).
std::vector<LogLine> characterOutcomeLines(const QString& slot, int source, const SimulationRequest& request,
                                           const CharacterRequest& wanted, const CharacterRunReport& report,
                                           const CharacterRunOptions& run, const QString& rest_mesh);

}  // namespace mrcloth
