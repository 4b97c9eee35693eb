#include "object_store.h"

#include "mesh_ops/errors.h"

#include <string>

namespace mrcloth {

int ObjectStore::add(std::shared_ptr<QuadMesh> mesh, const QString& name, const QString& path) {
  if (!mesh) throw ArgumentError("cannot store a null mesh");
  const int id = next_id_++;
  objects_.emplace(id, StoredObject{id, name, path, std::move(mesh)});
  return id;
}

const StoredObject& ObjectStore::get(int id) const {
  const auto it = objects_.find(id);
  if (it == objects_.end()) throw ArgumentError("no object with id " + std::to_string(id));
  return it->second;
}

StoredObject& ObjectStore::find(int id) {
  return const_cast<StoredObject&>(static_cast<const ObjectStore&>(*this).get(id));
}

QuadMesh& ObjectStore::mesh(int id) const { return *get(id).mesh; }

void ObjectStore::setPath(int id, const QString& path) { find(id).path = path; }

void ObjectStore::remove(int id) {
  get(id);  // throws for an unknown id
  objects_.erase(id);
}

bool ObjectStore::contains(int id) const { return objects_.count(id) != 0; }

std::vector<StoredObject> ObjectStore::list() const {
  std::vector<StoredObject> objects;
  objects.reserve(objects_.size());
  for (const auto& entry : objects_) objects.push_back(entry.second);
  return objects;
}

}  // namespace mrcloth
