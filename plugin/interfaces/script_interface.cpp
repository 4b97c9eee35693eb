#include "script_interface.h"

namespace mrcloth {

QString SlotDescription::slotName() const {
  const qsizetype open = signature.indexOf(QLatin1Char('('));
  return (open < 0 ? signature : signature.left(open)).trimmed();
}

QString scriptObjectName(const QString& displayName) {
  QString name = displayName.toLower();
  name.remove(QLatin1Char(' '));
  return name;
}

}  // namespace mrcloth
