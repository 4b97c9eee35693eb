#pragma once
// OpenFlipper vocabulary: a plugin that reads or creates objects gets the
// host's object store. Objects are addressed by integer ids in scripts.
#include <QtPlugin>

namespace mrcloth {

class ObjectStore;

class LoadSaveInterface {
 public:
  virtual ~LoadSaveInterface() = default;

  /// Called by the host before initializePlugin(); `store` outlives the plugin's use of it.
  virtual void setObjectStore(ObjectStore* store) = 0;
};

}  // namespace mrcloth

Q_DECLARE_INTERFACE(mrcloth::LoadSaveInterface, "mrcloth.LoadSaveInterface/1.0")
