#pragma once
// Pieces of OBJ text both of mrcloth's OBJ readers need (the garment loader
// and the MakeHuman body reader): indices that may count back from the end,
// and the texture part of a face corner.
#include <string_view>

namespace mrcloth {

/// An OBJ index ("7"; "-2" counts back from the last element defined so
/// far) against `defined` elements: the 0-based index, or -1 when the text
/// is not an index of one of them.
long resolve_obj_index(std::string_view text, long defined);

/// The texture part of a face corner ("v", "v/vt", "v//vn", "v/vt/vn"): the
/// text between its first and second '/', empty when it names none.
std::string_view obj_corner_texture(std::string_view corner);

}  // namespace mrcloth
