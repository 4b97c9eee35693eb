#include "script_interface.h"

#include <QRegularExpression>

namespace mrcloth {

QString SlotDescription::slotName() const {
  const qsizetype open = signature.indexOf(QLatin1Char('('));
  return (open < 0 ? signature : signature.left(open)).trimmed();
}

namespace {

QString filledText(const QString& text, const QVariantMap& limits) {
  static const QRegularExpression token(QStringLiteral("@([A-Za-z]+)@"));
  QString filled;
  qsizetype done = 0;
  for (QRegularExpressionMatchIterator it = token.globalMatch(text); it.hasNext();) {
    const QRegularExpressionMatch match = it.next();
    filled += text.mid(done, match.capturedStart() - done);
    const QVariantList range = limits.value(match.captured(1)).toList();
    filled += range.size() == 2 ? QStringLiteral("%1..%2").arg(QString::number(range[0].toDouble(), 'g', 15),
                                                              QString::number(range[1].toDouble(), 'g', 15))
                                : QStringLiteral("@unknown limit %1@").arg(match.captured(1));
    done = match.capturedEnd();
  }
  return filled + text.mid(done);
}

}  // namespace

QList<SlotDescription> withLimits(QList<SlotDescription> descriptions, const QVariantMap& limits) {
  for (SlotDescription& slot : descriptions) {
    slot.description = filledText(slot.description, limits);
    for (QString& text : slot.parameterDescriptions) text = filledText(text, limits);
  }
  return descriptions;
}

QString scriptObjectName(const QString& displayName) {
  QString name = displayName.toLower();
  name.remove(QLatin1Char(' '));
  return name;
}

}  // namespace mrcloth
