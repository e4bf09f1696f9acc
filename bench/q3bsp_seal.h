// A Quake III brush (the intersection of its sides' half-spaces) as a closed triangle mesh, for the seal
// the converter writes beside the drawn faces (q3bsp_to_obj.cpp, q3bsp::sealBrushes). Apart from q3bsp.h
// because it needs CGAL (compile with -lgmp): the corners are where three sides' planes meet inside every
// other side, and CGAL's convex_hull_3 makes the closed, outward-facing surface through them.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include "q3bsp.h"

namespace q3bsp {

/// Closed triangle meshes (outward-facing), metres, y up, as Mesh holds the drawn faces.
struct Solids {
  std::vector<V3> points;
  std::vector<std::array<size_t, 3>> triangles;
  size_t brushes = 0;     ///< brushes made into solids
  size_t degenerate = 0;  ///< brushes with no volume (fewer than four corners off one plane), left out
};

namespace detail {

// The corners of the convex brush bounded by `planes` (outward normals, n·p ≤ dist inside), Quake units:
// each point where three planes meet that no plane has further out than `slack` units.
inline std::vector<V3> brushCorners(const std::vector<Plane>& planes, double slack = 0.01) {
  std::vector<V3> corners;
  const size_t n = planes.size();
  auto normal = [&](size_t i) { return V3{planes[i].normal[0], planes[i].normal[1], planes[i].normal[2]}; };
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b)
      for (size_t c = b + 1; c < n; ++c) {
        const V3 na = normal(a), nb = normal(b), nc = normal(c);
        const V3 bc = cross(nb, nc);
        const double det = dot(na, bc);
        if (std::abs(det) < 1e-9) continue;  // two of them parallel, or all three through one line
        const V3 ca = cross(nc, na), ab = cross(na, nb);
        V3 p;
        for (int k = 0; k < 3; ++k)
          p[k] = (planes[a].dist * bc[k] + planes[b].dist * ca[k] + planes[c].dist * ab[k]) / det;
        bool inside = true;
        for (size_t i = 0; i < n && inside; ++i) inside = dot(normal(i), p) - planes[i].dist <= slack;
        if (inside) corners.push_back(p);
      }
  return corners;
}

}  // namespace detail

/// The brushes `planes` (Quake units, as sealBrushes gives them) as closed solids scaled by `scale`
/// metres per unit and turned y up as convert turns the faces.
inline Solids brushSolids(const std::vector<std::vector<Plane>>& brushes, double scale) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
  Solids out;
  for (const std::vector<Plane>& planes : brushes) {
    std::vector<K::Point_3> corners;
    for (const V3& p : detail::brushCorners(planes)) corners.emplace_back(p[0], p[1], p[2]);
    if (corners.size() < 4) {
      ++out.degenerate;
      continue;
    }
    SurfaceMesh hull;
    CGAL::convex_hull_3(corners.begin(), corners.end(), hull);
    if (hull.number_of_faces() < 4) {  // the corners lie in one plane: a brush without volume
      ++out.degenerate;
      continue;
    }
    std::vector<size_t> pointOf(hull.num_vertices());  // by the mesh's vertex index, removed ones too
    for (const SurfaceMesh::Vertex_index v : hull.vertices()) {
      const K::Point_3& q = hull.point(v);
      pointOf[size_t(v)] = out.points.size();
      // Quake: z up. Ours: y up; (x, y, z) -> (x, z, -y) is a rotation, so the outward winding survives.
      out.points.push_back({q.x() * scale, q.z() * scale, -q.y() * scale});
    }
    for (const SurfaceMesh::Face_index f : hull.faces()) {
      std::array<size_t, 3> t{};
      int k = 0;
      for (const SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(hull.halfedge(f), hull))
        if (k < 3) t[size_t(k++)] = pointOf[size_t(v)];
      if (k == 3) out.triangles.push_back(t);
    }
    ++out.brushes;
  }
  return out;
}

}  // namespace q3bsp
