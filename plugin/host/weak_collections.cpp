#include "weak_collections.h"

#include <QJSEngine>
#include <QJSValue>

namespace mrcloth {
namespace {

// Each collection keeps its entries on the keys themselves, under a symbol
// of its own (as polyfills of WeakMap do): O(1), and an entry goes when its
// key does, as a weak one should. Keys that cannot take a property (frozen,
// sealed) go to a Map, held strongly. As the language's: only objects and
// functions are keys, anything else is a TypeError on set / add and absent
// on the queries.
const char kCollections[] = R"JS(
(function (global) {
  "use strict";
  const isKey = (key) => (typeof key === "object" && key !== null) || typeof key === "function";
  const refuse = (what, key) => { throw new TypeError("Invalid value used " + what + ": " + String(key)); };
  const own = Object.prototype.hasOwnProperty;
  class Entries {
    constructor() {
      this.slot = Symbol("entry");
      this.frozen = new Map();
    }
    get(key) { return own.call(key, this.slot) ? key[this.slot] : this.frozen.get(key); }
    set(key, value) {
      if (own.call(key, this.slot)) key[this.slot] = value;
      else if (Object.isExtensible(key))
        Object.defineProperty(key, this.slot, {value: value, writable: true, configurable: true});
      else this.frozen.set(key, value);
    }
    has(key) { return own.call(key, this.slot) || this.frozen.has(key); }
    delete(key) { return own.call(key, this.slot) ? delete key[this.slot] : this.frozen.delete(key); }
  }
  const entries = Symbol("entries");
  class WeakMap {
    constructor(pairs) {
      Object.defineProperty(this, entries, {value: new Entries()});
      if (pairs !== undefined && pairs !== null)
        for (const [key, value] of pairs) this.set(key, value);
    }
    get(key) { return isKey(key) ? this[entries].get(key) : undefined; }
    set(key, value) {
      if (!isKey(key)) refuse("as weak map key", key);
      this[entries].set(key, value);
      return this;
    }
    has(key) { return isKey(key) && this[entries].has(key); }
    delete(key) { return isKey(key) && this[entries].delete(key); }
  }
  class WeakSet {
    constructor(values) {
      Object.defineProperty(this, entries, {value: new Entries()});
      if (values !== undefined && values !== null)
        for (const value of values) this.add(value);
    }
    add(value) {
      if (!isKey(value)) refuse("in weak set", value);
      this[entries].set(value, true);
      return this;
    }
    has(value) { return isKey(value) && this[entries].has(value); }
    delete(value) { return isKey(value) && this[entries].delete(value); }
  }
  for (const C of [WeakMap, WeakSet])
    Object.defineProperty(C.prototype, Symbol.toStringTag, {value: C.name});
  global.WeakMap = WeakMap;
  global.WeakSet = WeakSet;
})
)JS";

}  // namespace

void replaceWeakCollections(QJSEngine& engine) {
  engine.evaluate(QString::fromLatin1(kCollections), QStringLiteral("mrcloth-weak-collections")).call({engine.globalObject()});
}

}  // namespace mrcloth
