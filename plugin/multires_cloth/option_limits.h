#pragma once
// The bounds of multirescloth's numeric options in one place: the option
// parsers check them, and multirescloth.limits() hands them to scripts (the
// pipeline checks its flags against them before a run; a tool's UI can set
// its ranges from them). Each bounds a frame's or a call's work, so that
// progress reports and Ctrl-C come in reasonable time, or keeps a value
// where the solver's arithmetic holds.
#include "solver/character_sim.h"
#include "solver/worker_pool.h"

#include <QVariantMap>

namespace mrcloth::options {

constexpr int kMostSubsteps = kMostStepsPerFrame;  ///< implicit steps per output frame
constexpr int kMostIterations = 100;               ///< local/global iterations per step
/// Conjugate-gradient iterations per Newton step: 1000 converge any garment's (newtonCg stops once converged).
constexpr int kMostNewtonCg = 1000;
constexpr int kMostLimiterSweeps = 1000;    ///< strain-limiter sweeps per collision round
constexpr int kMostCollisionRounds = 100;   ///< rounds of limiting and checking per step
constexpr int kMostThreads = WorkerPool::kMostWorkers;
/// A pre-roll of 0 s is a jump to the first frame; otherwise 1 ms to 60 s
/// (1e8 s overflowed its frame count, 1e-300 s made steps so short the run
/// turned non-finite).
constexpr double kShortestPreroll = 1e-3;
constexpr double kLongestPreroll = 60.0;
constexpr double kMostSelfContactThickness = 0.02;  ///< metres of cloth-cloth contact thickness
/// extractModes' k-means restarts: each is a whole k-means run (a step of the clustering job).
constexpr int kMostRestarts = 10000;

/// Every numeric option's [least, most] as the calls check them, by name
/// ("fps", "substeps", ...): what multirescloth.limits() returns and what
/// the API's descriptions print (api_descriptions.cpp).
QVariantMap limitsMap();

}  // namespace mrcloth::options
