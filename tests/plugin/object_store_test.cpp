// Default-constructing a QuadMesh instantiates OpenMesh's PropertyT<Vec3d>::push_back,
// which pushes a deliberately uninitialised VectorT; GCC 12 flags that inside
// OpenMesh's header. Nothing here reads such a value.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "plugin/core/object_store.h"

#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <memory>

namespace mrcloth {
namespace {

std::shared_ptr<QuadMesh> emptyMesh() { return std::make_shared<QuadMesh>(); }

TEST(ObjectStore, IdsStartAtOneAndAreNeverReused) {
  ObjectStore store;
  EXPECT_EQ(store.add(emptyMesh(), "a"), 1);
  EXPECT_EQ(store.add(emptyMesh(), "b"), 2);
  store.remove(2);
  EXPECT_EQ(store.add(emptyMesh(), "c"), 3) << "a removed id must not come back";
  EXPECT_EQ(store.size(), 2u);
}

TEST(ObjectStore, GetReturnsWhatWasAdded) {
  ObjectStore store;
  auto mesh = emptyMesh();
  const int id = store.add(mesh, "skirt", "/data/skirt.obj");
  const StoredObject& object = store.get(id);
  EXPECT_EQ(object.id, id);
  EXPECT_EQ(object.name, QStringLiteral("skirt"));
  EXPECT_EQ(object.path, QStringLiteral("/data/skirt.obj"));
  EXPECT_EQ(object.mesh, mesh);
  EXPECT_EQ(&store.mesh(id), mesh.get());
  store.setPath(id, "/tmp/skirt.om");
  EXPECT_EQ(store.get(id).path, QStringLiteral("/tmp/skirt.om"));
}

TEST(ObjectStore, UnknownIdThrowsArgumentErrorNamingIt) {
  ObjectStore store;
  store.add(emptyMesh(), "a");
  for (const int id : {0, -1, 2, 99}) {
    try {
      store.get(id);
      FAIL() << "no exception for id " << id;
    } catch (const ArgumentError& error) {
      EXPECT_EQ(std::string(error.what()), "no object with id " + std::to_string(id));
    }
  }
  EXPECT_THROW(store.remove(5), ArgumentError);
  EXPECT_THROW(store.setPath(5, "x"), ArgumentError);
  EXPECT_THROW(store.mesh(5), ArgumentError);
  EXPECT_FALSE(store.contains(5));
  EXPECT_TRUE(store.contains(1));
}

TEST(ObjectStore, NullMeshIsRejected) {
  ObjectStore store;
  EXPECT_THROW(store.add(nullptr, "null"), ArgumentError);
  EXPECT_EQ(store.size(), 0u);
}

TEST(ObjectStore, ListIsOrderedById) {
  ObjectStore store;
  for (const char* name : {"a", "b", "c", "d"}) store.add(emptyMesh(), name);
  store.remove(2);
  const std::vector<StoredObject> objects = store.list();
  ASSERT_EQ(objects.size(), 3u);
  EXPECT_EQ(objects[0].id, 1);
  EXPECT_EQ(objects[1].id, 3);
  EXPECT_EQ(objects[2].id, 4);
  EXPECT_EQ(objects[2].name, QStringLiteral("d"));
}

TEST(ObjectStore, RemovedMeshLivesOnWhileShared) {
  ObjectStore store;
  const int id = store.add(emptyMesh(), "a");
  std::weak_ptr<QuadMesh> watched = store.get(id).mesh;
  std::shared_ptr<QuadMesh> held = store.get(id).mesh;
  store.remove(id);
  EXPECT_EQ(held.use_count(), 1) << "the store let go of its share";
  held.reset();
  EXPECT_TRUE(watched.expired()) << "and nothing else kept the mesh alive";
}

}  // namespace
}  // namespace mrcloth
