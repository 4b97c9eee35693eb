#pragma once
// The one error style of mrcloth: typed exceptions at module boundaries,
// each message naming the file, line or element and what was expected.
#include <stdexcept>
#include <string>

namespace mrcloth {

/// Base of every error mrcloth throws on purpose.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A file could not be read, or its contents are not what was expected.
struct InputError : Error {
  using Error::Error;
};

/// An argument is out of range or inconsistent with the mesh it refers to.
struct ArgumentError : Error {
  using Error::Error;
};

/// A file could not be written.
struct OutputError : Error {
  using Error::Error;
};

}  // namespace mrcloth
