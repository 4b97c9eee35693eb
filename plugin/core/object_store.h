#pragma once
// The host's objects: integer ids (from 1, never reused) mapped to refinable
// meshes. Scripts only ever hold ids; the store owns the meshes.
#include "mesh_ops/quad_mesh.h"

#include <QString>

#include <map>
#include <memory>
#include <vector>

namespace mrcloth {

struct StoredObject {
  int id = 0;
  QString name;  ///< shown to the user: the file's base name, or how the object was derived
  QString path;  ///< file it was loaded from or last saved to; empty for derived objects
  std::shared_ptr<QuadMesh> mesh;
};

class ObjectStore {
 public:
  /// Stores `mesh` under a fresh id and returns it. Throws ArgumentError for a null mesh.
  int add(std::shared_ptr<QuadMesh> mesh, const QString& name, const QString& path = {});

  /// The object with `id`. Throws ArgumentError "no object with id N" if there is none.
  const StoredObject& get(int id) const;

  /// Shortcut for *get(id).mesh.
  QuadMesh& mesh(int id) const;

  /// Records the file an object was last saved to. Throws like get().
  void setPath(int id, const QString& path);

  /// Forgets the object; its mesh lives on while someone else shares it. Throws like get().
  void remove(int id);

  bool contains(int id) const;
  std::size_t size() const { return objects_.size(); }

  /// Every object, by increasing id.
  std::vector<StoredObject> list() const;

 private:
  StoredObject& find(int id);
  std::map<int, StoredObject> objects_;
  int next_id_ = 1;
};

}  // namespace mrcloth
