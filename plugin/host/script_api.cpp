#include "script_api.h"

#include <QMetaMethod>
#include <QSet>

#include <algorithm>

namespace mrcloth {

QString formatScriptApi(const QString& scriptName, const QString& heading, const QList<SlotDescription>& slots_) {
  QString text = QStringLiteral("%1 - %2\n").arg(scriptName, heading);
  for (const SlotDescription& slot : slots_) {
    text += QStringLiteral("\n  %1.%2\n      %3\n").arg(scriptName, slot.signature, slot.description);
    qsizetype width = 0;
    for (const QString& name : slot.parameterNames) width = std::max(width, name.size());
    for (qsizetype i = 0; i < slot.parameterNames.size(); ++i)
      text += QStringLiteral("      %1  %2\n")
                  .arg(slot.parameterNames[i].leftJustified(width), slot.parameterDescriptions.value(i));
  }
  return text;
}

QStringList checkSlotDescriptions(const QObject& object, const QString& scriptName,
                                  const QList<SlotDescription>& slots_) {
  QStringList problems;
  QSet<QString> public_slots;
  const QMetaObject* meta = object.metaObject();
  // Only the object's own class: QObject's deleteLater is not part of the API.
  for (int i = meta->methodOffset(); i < meta->methodCount(); ++i) {
    const QMetaMethod method = meta->method(i);
    if (method.methodType() == QMetaMethod::Slot && method.access() == QMetaMethod::Public)
      public_slots.insert(QString::fromLatin1(method.name()));
  }
  QSet<QString> described;
  for (const SlotDescription& slot : slots_) {
    const QString name = slot.slotName();
    described.insert(name);
    if (!public_slots.contains(name))
      problems << QStringLiteral("%1: described slot '%2' is not a public slot").arg(scriptName, name);
    if (slot.parameterNames.size() != slot.parameterDescriptions.size())
      problems << QStringLiteral("%1.%2: %3 parameter names but %4 parameter descriptions")
                      .arg(scriptName, name).arg(slot.parameterNames.size()).arg(slot.parameterDescriptions.size());
  }
  QStringList undocumented;
  for (const QString& name : public_slots)
    if (!described.contains(name)) undocumented << name;
  undocumented.sort();
  for (const QString& name : undocumented)
    problems << QStringLiteral("%1: public slot '%2' has no description").arg(scriptName, name);
  return problems;
}

}  // namespace mrcloth
