#pragma once
// The "Preview" plugin: pictures a garment artist can look at, made
// headless. Renders of a mesh or of any frame of its cache (shaded, with the
// quad wireframe, coloured by mode, level or curvature with a legend, on its
// body), frame sequences, contact sheets and report charts, as PNG (JPEG,
// BMP or PPM where the path's suffix says so), written atomically. Every
// slot is a thin adapter over plugin/render and preview_scene.h.
#include "plugin/interfaces/base_interface.h"
#include "plugin/interfaces/load_save_interface.h"
#include "plugin/interfaces/logging_interface.h"
#include "plugin/interfaces/process_interface.h"
#include "plugin/interfaces/script_interface.h"

#include <QObject>
#include <QVariant>
#include <QVariantList>
#include <QVariantMap>

namespace mrcloth {

class PreviewPlugin : public QObject,
                      public BaseInterface,
                      public LoggingInterface,
                      public LoadSaveInterface,
                      public ProcessInterface,
                      public ScriptInterface {
  Q_OBJECT
  Q_PLUGIN_METADATA(IID "mrcloth.BaseInterface/1.0")
  Q_INTERFACES(mrcloth::BaseInterface mrcloth::LoggingInterface mrcloth::LoadSaveInterface
                   mrcloth::ProcessInterface mrcloth::ScriptInterface)

 signals:
  void log(Logtype type, QString message) override;
  void startJob(QString jobId, QString description, int min, int max) override;
  void setJobState(QString jobId, int value) override;
  void finishJob(QString jobId) override;

 public:
  QString name() const override { return QStringLiteral("Preview"); }
  QString description() const override;
  void setObjectStore(ObjectStore* store) override { store_ = store; }
  QList<SlotDescription> slotDescriptions() const override;

 public slots:
  // Every argument defaults to undefined, so a call missing one reaches the
  // slot's own check ("levels must be an integer, got undefined"), not Qt's
  // "Unable to determine callable overload".
  QVariantMap render(QVariant id = QVariant(), QVariant path = QVariant(), QVariant options = QVariant());
  QVariantList renderSequence(QVariant id = QVariant(), QVariant prefix = QVariant(), QVariant options = QVariant());
  QVariantMap contactSheet(QVariant images = QVariant(), QVariant path = QVariant(), QVariant options = QVariant());
  void lineChart(QVariant path = QVariant(), QVariant chart = QVariant());
  void barChart(QVariant path = QVariant(), QVariant chart = QVariant());
  QVariantMap limits();

 private:
  /// Says (as a warning: an interrupted script's error is not shown) and
  /// throws that `slot` stopped on Ctrl-C, and what it left.
  [[noreturn]] void stopCancelled(const char* slot, const std::string& what);
  template <class Body>
  auto guarded(const char* slot, Body&& body) -> decltype(body());
  void writeAnimation(const QVariantList& frames, const QString& path, double fps);

  ObjectStore* store_ = nullptr;
};

}  // namespace mrcloth
