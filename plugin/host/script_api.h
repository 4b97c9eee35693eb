#pragma once
// `mrcloth --api`: the scripting API as text, from the slot descriptions,
// and a consistency check between the descriptions and the real slots.
#include "plugin/interfaces/script_interface.h"

#include <QObject>
#include <QString>
#include <QStringList>

namespace mrcloth {

/// One section of the API listing: a heading, then per slot its signature, its
/// description and one line per parameter.
QString formatScriptApi(const QString& scriptName, const QString& heading, const QList<SlotDescription>& slots_);

/// Problems between an object's public slots and its descriptions: a slot
/// without description, a description without slot, parameter lists of different length.
QStringList checkSlotDescriptions(const QObject& object, const QString& scriptName,
                                  const QList<SlotDescription>& slots_);

}  // namespace mrcloth
