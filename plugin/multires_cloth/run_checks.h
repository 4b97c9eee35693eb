#pragma once
// What simulate and recordInstance say before a run, worded for the log:
// what a script author can act on before waiting for it (cloth-cloth
// contact on a fine mesh, a garment far from the origin, a waist far from
// the pelvis, a short pre-roll, jitter and glitches in the clip, a garment
// too narrow for the motion, a motion shorter than the frames). The plugin
// emits them; the numbers come from the solver's checks.
#include "character_options.h"
#include "log_line.h"
#include "simulation_options.h"
#include "solver/character_setup.h"
#include "solver/character_sim.h"
#include "solver/dynamics_model.h"
#include "solver/self_contact.h"

#include <QString>
#include <QVariantMap>

#include <vector>

namespace mrcloth {

/// A warning for cloth-cloth contact on a mesh whose edges are on average
/// shorter than its reach (thickness + gathering reach), empty otherwise.
/// `slot` starts the text ("simulate").
QString selfContactWarning(const QString& slot, const QuadMesh& mesh, const SelfContactOptions& contact);

/// A warning when the run writes a PC2 cache (float32) and the garment
/// lies so far from the origin that the file's steps pass 0.1 mm, empty otherwise.
QString cachePrecisionWarning(const QString& slot, const QuadMesh& mesh, const SimulationOptions& settings);

/// What reading the clip changed (axes turned, joints renamed), as log lines.
std::vector<LogLine> clipChangeLines(const QString& slot, const CharacterRequest& wanted, const ClipChanges& changes);

/// The checks before a run on a character, appended to `lines`; returns
/// the report's `fit` (empty for a garment that is not a tube). `garment`
/// is the mesh as placed on the character, `model` its dynamics.
QVariantMap checkBeforeCharacterRun(const QString& slot, const SimulationRequest& request, const Character& character,
                                    const CharacterRunOptions& run, const DynamicsModel& model,
                                    const QuadMesh& garment, std::vector<LogLine>& lines);

}  // namespace mrcloth
