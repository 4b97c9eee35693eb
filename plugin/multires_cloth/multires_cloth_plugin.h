#pragma once
// The "Multires Cloth" plugin: the scripting face of mesh_ops and the solver.
// Every public slot is a thin adapter (check arguments, call mesh_ops or the
// solver, store the result, report); no geometry happens here. Slots never
// modify their input: refinements refine a copy and return the new object's
// id, a simulation writes a point cache (and, if asked, a new object), so a
// script can compare meshes and rerun a step with other options.
#include "plugin/interfaces/base_interface.h"
#include "plugin/interfaces/load_save_interface.h"
#include "plugin/interfaces/logging_interface.h"
#include "plugin/interfaces/process_interface.h"
#include "plugin/interfaces/script_interface.h"

#include <QObject>
#include <QVariant>
#include <QVariantList>
#include <QVariantMap>

#include <vector>

namespace mrcloth {

struct LogLine;
struct StoredObject;
struct SimulationRequest;

class MultiresClothPlugin : public QObject,
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
  // LoggingInterface and ProcessInterface, implemented by moc.
  void log(Logtype type, QString message) override;
  void startJob(QString jobId, QString description, int min, int max) override;
  void setJobState(QString jobId, int value) override;
  void finishJob(QString jobId) override;

 public:
  // BaseInterface
  QString name() const override { return QStringLiteral("Multires Cloth"); }
  QString description() const override;
  // LoadSaveInterface
  void setObjectStore(ObjectStore* store) override { store_ = store; }
  // ScriptInterface
  QList<SlotDescription> slotDescriptions() const override;

  // The scripting API. Parameters are QVariant so that wrong types are
  // reported by name (see plugin/core/script_values.h); slotDescriptions()
  // gives the types a script must pass.
 public slots:
  // Every argument defaults to undefined, so a call missing one reaches the
  // slot's own check ("levels must be an integer, got undefined"), not Qt's
  // "Unable to determine callable overload".
  int refineUniform(QVariant id = QVariant(), QVariant levels = QVariant());
  int setModes(QVariant id = QVariant(), QVariant vertexIds = QVariant(), QVariant mode = QVariant());
  int paintModes(QVariant id = QVariant(), QVariant brush = QVariant());
  QVariantList getModes(QVariant id = QVariant());
  int eraseModes(QVariant id = QVariant(), QVariant vertexIds = QVariant());
  QVariantList getLayer(QVariant id = QVariant(), QVariant name = QVariant());
  void saveLayers(QVariant id = QVariant(), QVariant path = QVariant());
  int loadModes(QVariant id = QVariant(), QVariant path = QVariant());
  int refineAdaptive(QVariant id = QVariant(), QVariant options = QVariant());
  QVariantMap lastReport();
  void exportSurface(QVariant id = QVariant(), QVariant path = QVariant(), QVariant options = QVariant());
  QVariantMap simulate(QVariant id = QVariant(), QVariant options = QVariant());
  QVariantMap recordInstance(QVariant id = QVariant(), QVariant options = QVariant());
  QVariantMap motionInfo(QVariant motion = QVariant());
  QVariantMap limits();
  QVariantMap extractModes(QVariant id = QVariant(), QVariant cachePath = QVariant(), QVariant options = QVariant());
  QVariantMap mapModes(QVariant refinedId = QVariant(), QVariant coarseId = QVariant(), QVariant options = QVariant());
  QVariantMap compareResults(QVariant id = QVariant(), QVariant cachePath = QVariant(), QVariant referenceId = QVariant(),
                             QVariant referenceCachePath = QVariant(), QVariant options = QVariant());

 private:
  ObjectStore& store() const;
  template <class Body>
  auto guarded(const char* slot, Body&& body) -> decltype(body());
  /// simulate or recordInstance with `motion`: the garment on a character.
  QVariantMap simulateOnCharacter(const QString& slot, const StoredObject& input, const SimulationRequest& request);
  /// Logs a warning of the running simulate / recordInstance and keeps it
  /// for its report's `warnings` (a batch script can act on them).
  void warn(const QString& text);
  /// Emits `lines` in order, the warnings through warn() so the run's
  /// report keeps them.
  void logLines(const std::vector<LogLine>& lines);
  /// A run stopped before its first frame, in its set-up (building the
  /// model, factorising its system: 5.5 s at 175k vertices, 45 s at 700k):
  /// says so as a warning and throws.
  [[noreturn]] void stopInSetUp(const QString& slot, int frames);
  /// Logs `text` as a warning (an interrupted script's error is not shown)
  /// and throws it: a long call stopped by Ctrl-C.
  [[noreturn]] void stopCancelled(const QString& text);

  ObjectStore* store_ = nullptr;
  QVariantMap last_report_;
  QStringList run_warnings_;  ///< the running simulate / recordInstance's warnings
};

}  // namespace mrcloth
