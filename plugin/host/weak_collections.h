#pragma once
// Qt 6.4's script engine (Debian 12's) crashes the host with a segmentation
// fault once its garbage collector runs over a WeakMap or WeakSet whose
// keys died (200,000 short-lived keys do it in a fraction of a second).
#include <QString>

class QJSEngine;

namespace mrcloth {

/// Replaces the engine's global WeakMap and WeakSet with classes of the same
/// methods (get / set / has / delete; add / has / delete) that keep each
/// entry on its key, under a symbol of the collection's own: an entry goes
/// with its key, and lookups stay O(1) (Qt 6.4's Map searches linearly).
/// Frozen keys are held strongly. Call before the script runs.
void replaceWeakCollections(QJSEngine& engine);

}  // namespace mrcloth
