#pragma once
// Brute-force oracles written apart from the library (distance to a triangle
// mesh, generalised winding number) and meshes built in code to check
// MeshBody against them: shared by the MeshBody tests on built meshes
// (mesh_body_test.cpp) and on the MakeHuman body (skinned_body_test.cpp).
// Lengths are in the meshes' units (metres in the tests).
#include "solver/mesh_body.h"

#include <Eigen/Core>

#include <random>
#include <string>
#include <vector>

namespace mrcloth::test {

// ---- independent brute force -----------------------------------------------

/// Distance from p to the segment a-b (to a when a == b).
double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Distance to a triangle, written differently from the library's Voronoi
/// region walk: the plane distance when the projection falls inside (by the
/// signs of three edge tests), else the nearest of the three edges.
double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& c);

/// A triangle mesh: one vertex a row (n x 3), triangles as row indices,
/// counter-clockwise seen from outside.
struct Mesh {
  Eigen::MatrixX3d vertices;
  std::vector<Eigen::Vector3i> triangles;
  Eigen::Vector3d vertex(int i) const { return vertices.row(i).transpose(); }
};

/// Unsigned distance from p to the mesh: the nearest of all its triangles.
double brute_distance(const Mesh& mesh, const Eigen::Vector3d& p);

/// Generalised winding number (sum of signed solid angles / 4 pi, Van
/// Oosterom and Strackee): about 1 inside a closed outward mesh, 0 outside.
double winding_number(const Mesh& mesh, const Eigen::Vector3d& p);

// ---- meshes ------------------------------------------------------------------

/// An icosahedron subdivided `levels` times, projected on the unit sphere.
Mesh icosphere(int levels);

/// The cube [-1, 1]^3 with n x n quads per face, each split in two: sharp
/// edges and corners, where edge and vertex pseudo-normals decide the sign.
Mesh subdivided_cube(int n);

/// Points near and inside a mesh: uniform in its padded box, plus surface
/// points (triangle samples, vertices, edge midpoints) pushed along random
/// directions by up to `spread`.
std::vector<Eigen::Vector3d> sample_points(const Mesh& mesh, std::mt19937& rng, int count, double spread);

/// query() against brute force: |d| to 1e-12 and the sign of the winding
/// number (points within 1e-9 of the surface have no reliable sign).
void expect_matches_brute_force(const MeshBody& body, const Mesh& mesh, const std::vector<Eigen::Vector3d>& points,
                                const std::string& label);

/// The mesh's vertices moved to a * x + t, one a row (n x 3).
Eigen::MatrixX3d transformed(const Mesh& mesh, const Eigen::Matrix3d& a, const Eigen::Vector3d& t);

}  // namespace mrcloth::test
