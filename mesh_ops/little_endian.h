#pragma once
// Unsigned integers stored little-endian, as OpenMesh's .om files and
// binary OFF (on every machine mrcloth runs on) hold them; the readers'
// own checks say why a file is refused, so this only assembles bytes.
#include <cstddef>
#include <cstdint>
#include <string>

namespace mrcloth {

/// The unsigned integer of `width` bytes (1 .. 8) at `at` in `bytes`, least
/// significant first; the caller has checked that at + width <= bytes.size().
inline std::uint64_t little_endian_at(const std::string& bytes, std::size_t at, std::size_t width) {
  std::uint64_t value = 0;
  for (std::size_t k = 0; k < width; ++k) value |= std::uint64_t{static_cast<unsigned char>(bytes[at + k])} << (8 * k);
  return value;
}

}  // namespace mrcloth
