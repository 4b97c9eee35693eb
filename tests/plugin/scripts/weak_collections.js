// WeakMap and WeakSet: Qt 6.4's own crash the host once the collector runs
// over dead keys (mrcloth replaces them; plugin/host/weak_collections.h).
// Exit 0 and "ok" (checked by run_and_check.cmake); any failed check throws.
"use strict";
core.include("test_asserts.js");
const map = new WeakMap(), set = new WeakSet();
const kept = [];
for (let i = 0; i < 200000; ++i) {
  const key = {i: i};
  map.set(key, i);
  set.add(key);
  if (map.get(key) !== i || !set.has(key)) throw new Error("lost key " + i);
  if (i % 50000 === 0) kept.push(key);
}
expectEqual(kept.map((key) => map.get(key)), [0, 50000, 100000, 150000], "kept keys' values");
expectEqual([map.has({}), set.has({}), map.has(1), set.has("a"), map.get(2)], [false, false, false, false, undefined],
            "absent keys");
expectEqual([map.delete(kept[0]), map.has(kept[0]), set.delete(kept[1]), set.has(kept[1]), set.delete(kept[1])],
            [true, false, true, false, false], "delete");
expectThrows(() => map.set(1, 2), "TypeError", "weak map key");
expectThrows(() => set.add("text"), "TypeError", "weak set");
const frozen = Object.freeze({}), other = new WeakMap();
map.set(frozen, "cold");
expectEqual([map.get(frozen), map.has(frozen), other.has(frozen), set.has(frozen), map.delete(frozen), map.has(frozen)],
            ["cold", true, false, false, true, false], "a frozen key");
const shared = {};
map.set(shared, 1);
other.set(shared, 2);
expectEqual([map.get(shared), other.get(shared), Object.keys(shared).length, JSON.stringify(shared)], [1, 2, 0, "{}"],
            "two maps, one key; the entries are not the key's own visible properties");
const f = () => 0;
expectEqual([new WeakMap([[f, 3]]).get(f), new WeakSet([f]).has(f), map.set(f, 1) === map], [3, true, true],
            "functions are keys; constructors take entries; set returns the map");
expectEqual([Object.prototype.toString.call(map), Object.prototype.toString.call(set)],
            ["[object WeakMap]", "[object WeakSet]"], "toStringTag");
print("ok");
