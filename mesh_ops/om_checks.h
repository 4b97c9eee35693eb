#pragma once
// A .om file held to what save_mesh wrote, beyond the chunk structure
// om_structure.h walks: the checksum save_mesh writes into it, the counts
// its header declares, the halfedge links and refinement hierarchy it
// stores, and only the analysis layers it stores. `path` names the file in
// every error; `bytes` is the whole file as read from it.
#include "quad_mesh.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace mrcloth {

/// Where a .om file's checksum layer keeps its eight bytes: after the
/// chunk's name, its type's name (a length byte, then the text) and its
/// block size (4 bytes, which must be 8).
struct ChecksumPlace {
  bool present = false;  ///< the file names the layer (one written before it, or by another program, does not)
  bool damaged = false;  ///< named, but its frame is not as save_mesh writes it
  std::size_t offset = 0;
};
/// Where the checksum layer's eight bytes stand in the OM file `bytes`.
ChecksumPlace checksum_place(const std::string& bytes);

/// FNV-1a (64 bits) of `bytes` with the eight at `skip` taken as zero.
std::uint64_t file_checksum(const std::string& bytes, std::size_t skip);

/// A .om file with a checksum layer must match it (any byte changed or cut
/// off): checked before OpenMesh reads, whose reader asserts (aborting the
/// host) on some damaged chunks.
/// Throws InputError naming `path` when it does not.
void check_om_checksum(const std::string& path, const std::string& bytes);

/// An OM file cut short in its vertex or face chunks reads fewer elements
/// than its header counts (or garbage faces): refused before the faces are
/// looked at. The header: "OM", mesh kind, version, then the vertex, face
/// and edge counts as 32-bit integers in the writer's (little-endian) order.
/// `mesh`: what OpenMesh's reader made of `bytes`. Throws InputError naming
/// `path`.
void check_om_counts(const std::string& path, const std::string& bytes, const QuadMesh& mesh);

/// The refinement hierarchy of a `.om` file, checked before anything reads
/// it: a truncated or damaged file can hold records that point anywhere.
/// `mesh`: the file's, read, with a forest. Throws InputError naming `path`
/// and the record, face or vertex found damaged.
void check_stored_forest(const std::string& path, const QuadMesh& mesh);

/// The OM reader fills only layers that exist before it reads, so every
/// analysis layer was made first; those the file does not store (a mesh
/// saved before any analysis) are removed again, so that a save and load
/// adds no layers of zeros. An OM file stores each property's name as
/// plain text.
/// `bytes`: the file `mesh` was read from.
void drop_analysis_layers_not_stored(const std::string& bytes, QuadMesh& mesh);

}  // namespace mrcloth
