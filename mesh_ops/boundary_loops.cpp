#include "boundary_loops.h"

#include "errors.h"

#include <algorithm>
#include <cctype>

namespace mrcloth {
namespace {

// Follows next_halfedge from a boundary halfedge until it comes back,
// collecting each halfedge's start vertex and marking the halfedges seen.
std::vector<int> walk_loop(const QuadMesh& mesh, QuadMesh::HalfedgeHandle start, std::vector<char>& seen) {
  std::vector<int> loop;
  QuadMesh::HalfedgeHandle h = start;
  do {
    seen[static_cast<std::size_t>(h.idx())] = 1;
    loop.push_back(mesh.from_vertex_handle(h).idx());
    h = mesh.next_halfedge_handle(h);
  } while (h != start && !seen[static_cast<std::size_t>(h.idx())]);
  return loop;
}

// Starts the loop at its lowest vertex index, so the result does not depend
// on how OpenMesh happened to number the boundary halfedges.
void rotate_to_lowest(std::vector<int>& loop) {
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
}

double mean_height(const QuadMesh& mesh, const std::vector<int>& loop) {
  double sum = 0.0;
  for (int v : loop) sum += mesh.point(mesh.vertex_handle(v))[1];
  return sum / static_cast<double>(loop.size());
}

// "loop:N" -> N, or -1 when `name` is not of that form.
long parse_loop_index(const std::string& name) {
  const std::string prefix = "loop:";
  if (name.compare(0, prefix.size(), prefix) != 0 || name.size() == prefix.size() || name.size() > prefix.size() + 9)
    return -1;
  long n = 0;
  for (std::size_t i = prefix.size(); i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return -1;
    n = n * 10 + (name[i] - '0');
  }
  return n;
}

std::string loop_count_text(std::size_t n) {
  return "the mesh has " + std::to_string(n) + (n == 1 ? " boundary loop" : " boundary loops");
}

}  // namespace

std::vector<std::vector<int>> boundary_loops(const QuadMesh& mesh) {
  std::vector<char> seen(mesh.n_halfedges(), 0);
  std::vector<std::vector<int>> loops;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[static_cast<std::size_t>(h.idx())]) continue;
    loops.push_back(walk_loop(mesh, h, seen));
    rotate_to_lowest(loops.back());
  }
  std::vector<double> height(loops.size());
  std::vector<std::size_t> order(loops.size());
  for (std::size_t i = 0; i < loops.size(); ++i) {
    height[i] = mean_height(mesh, loops[i]);
    order[i] = i;
  }
  // Stable, so loops of equal height keep the order in which they were found.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return height[a] > height[b]; });
  std::vector<std::vector<int>> sorted;
  sorted.reserve(loops.size());
  for (std::size_t i : order) sorted.push_back(std::move(loops[i]));
  return sorted;
}

std::vector<int> boundary_loop_by_name(const QuadMesh& mesh, const std::string& name) {
  const bool named_end = name == "top" || name == "bottom";
  const long index = parse_loop_index(name);
  if (!named_end && index < 0)
    throw ArgumentError("unknown boundary loop \"" + name + "\"; use \"top\", \"bottom\" or \"loop:N\" (" +
                        loop_count_text(boundary_loops(mesh).size()) + ")");
  std::vector<std::vector<int>> loops = boundary_loops(mesh);
  if (loops.empty() || (index >= 0 && static_cast<std::size_t>(index) >= loops.size()))
    throw ArgumentError("no boundary loop \"" + name + "\": " + loop_count_text(loops.size()) +
                        (loops.empty() ? "" : " (loop:0 to loop:" + std::to_string(loops.size() - 1) + ")"));
  if (name == "top") return std::move(loops.front());
  if (name == "bottom") return std::move(loops.back());
  return std::move(loops[static_cast<std::size_t>(index)]);
}

}  // namespace mrcloth
