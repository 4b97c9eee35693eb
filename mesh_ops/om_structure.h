#pragma once
// The chunk structure of an OM file, checked before OpenMesh's reader sees
// it: on a file damaged inside, OpenMesh 9's reader asserts (aborting the
// whole host), writes out of bounds, or reads billions of elements past the
// end, with no error to catch.
#include <string>

namespace mrcloth {

/// Walks the chunks of an OM file as OpenMesh 9's reader will read them.
/// `bytes`: the whole file, read from `path` (named in the error).
/// Checks the header; every chunk whole inside the file and of an element
/// kind the reader knows; each built-in chunk of the shape the reader
/// asserts; vertices, faces and edges made once, before the chunks that
/// fill them; the stored next-halfedge links in range (the reader writes
/// through them); the sizes of mrcloth's list layers; and the end: OpenMesh
/// 9's closing chunk (in its own format and in every file holding
/// mrcloth's layers) or, in older formats, the last chunk's last byte. A
/// file of a newer format than the reader's is left to the reader, which
/// refuses it. Throws InputError naming `path`, the chunk's byte offset and
/// what was expected.
void check_om_structure(const std::string& path, const std::string& bytes);

}  // namespace mrcloth
