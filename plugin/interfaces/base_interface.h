#pragma once
// OpenFlipper vocabulary: every plugin implements BaseInterface; the other
// interfaces are optional capabilities the host discovers with qobject_cast
// and wires up (signals connected, object store handed over) before it calls
// initializePlugin().
#include <QString>
#include <QtPlugin>

namespace mrcloth {

class BaseInterface {
 public:
  virtual ~BaseInterface() = default;

  /// Human-readable plugin name, e.g. "Multires Cloth". Scripts reach the
  /// plugin under this name lower-cased without spaces ("multirescloth").
  virtual QString name() const = 0;
  /// One line saying what the plugin is for (shown by `mrcloth --api`).
  virtual QString description() const = 0;
  /// Plugin version, "major.minor.patch".
  virtual QString version() const { return QStringLiteral("0.1.0"); }

  /// Called once after the host connected every interface of this plugin.
  virtual void initializePlugin() {}
  /// Called once after every plugin was initialised (plugins may look at each other here).
  virtual void pluginsInitialized() {}
};

}  // namespace mrcloth

#define MRCLOTH_BASE_INTERFACE_IID "mrcloth.BaseInterface/1.0"
Q_DECLARE_INTERFACE(mrcloth::BaseInterface, MRCLOTH_BASE_INTERFACE_IID)
