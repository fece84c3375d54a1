// Checks and orientation of a boundary triangulation with CGAL's Polygon
// Mesh Processing (PMP) package.
//
// The triangles are a polygon soup until they are known to bound a solid.
// orient_polygon_soup orients them consistently across every edge shared by
// two triangles, walking each connected shell, and cuts the soup (it
// duplicates vertices) where no surface mesh can be made: at edges of more
// than two triangles (reported to the visitor), along seams where the
// orientations cannot agree (a non-orientable surface) and at vertices where
// surfaces touch at a point only. On the mesh made from the cut soup every
// such defect shows as border edges: an edge of one triangle once, a seam
// twice. orient_to_bound_a_volume then turns each shell outward, or inward
// when it lies inside an odd number of others (a cavity), with exact
// predicates; it requires a mesh that does not intersect itself.
//
// Only the orientation is taken back from CGAL: a flipped triangle (a, b, c)
// becomes (a, c, b), and the vertices keep the order of their first use, so
// the written mesh does not depend on how CGAL stores it.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <map>
#include <new>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "lib/err.h"
#include "pack/trimesh.h"

namespace
{

namespace PMP = CGAL::Polygon_mesh_processing;
typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef std::array<std::size_t, 3> Triangle;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef std::pair<std::size_t, std::size_t> Edge;

Edge undirected(std::size_t a, std::size_t b) { return a < b ? Edge(a, b) : Edge(b, a); }

// What orient_polygon_soup cut. It copies its visitor: the results live
// outside.
struct Cuts {
	std::set<Edge> nonmanifold;
	std::vector<std::size_t> original; // of every vertex, duplicated or not
	std::size_t pinched = 0;
};

struct Cut_visitor : PMP::Default_orientation_visitor {
	Cuts *cuts;
	void non_manifold_edge(std::size_t a, std::size_t b, std::size_t)
	{
		cuts->nonmanifold.insert(undirected(a, b));
	}
	void non_manifold_vertex(std::size_t, std::size_t) { cuts->pinched++; }
	void duplicated_vertex(std::size_t v, std::size_t copy)
	{
		cuts->original.resize(copy + 1);
		cuts->original[copy] = v;
	}
};

// Merge vertices with identical coordinates and number the rest in order of
// first use, so that the mesh does not depend on how the input numbered
// unused vertices.
void weld(trimesh *m, std::vector<Point> &points, std::vector<Triangle> &tris)
{
	for (size_t i = 0; i < m->nvert; i++)
		points.emplace_back(m->vert[3 * i], m->vert[3 * i + 1], m->vert[3 * i + 2]);
	tris.resize(m->ntri);
	for (size_t t = 0; t < m->ntri; t++)
		for (int k = 0; k < 3; k++)
			tris[t][k] = (std::size_t)m->tri[3 * t + k];
	PMP::merge_duplicate_points_in_polygon_soup(points, tris);
	std::vector<std::size_t> id(points.size(), SIZE_MAX);
	std::vector<Point> used;
	for (size_t t = 0; t < m->ntri; t++)
		for (int k = 0; k < 3; k++) {
			std::size_t &v = tris[t][k];
			if (id[v] == SIZE_MAX) {
				id[v] = used.size();
				used.push_back(points[v]);
			}
			v = id[v];
			m->tri[3 * t + k] = (int32_t)v;
		}
	points.swap(used);
	m->nvert = points.size();
	for (size_t i = 0; i < m->nvert; i++)
		for (int k = 0; k < 3; k++)
			m->vert[3 * i + k] = points[i][k];
}

// Report what orient_polygon_soup cut in a mesh that is not a closed
// manifold surface, in the order: open, non-manifold edges, non-orientable,
// pinched vertices.
int report_cuts(const Mesh &mesh, const Cuts &cuts, const char *source)
{
	std::map<Edge, int> border; // its halfedges on the border
	for (Mesh::Halfedge_index h : mesh.halfedges())
		if (mesh.is_border(h))
			border[undirected(cuts.original[mesh.source(h)],
			                  cuts.original[mesh.target(h)])]++;
	size_t open = 0, seams = 0, n = cuts.nonmanifold.size();
	for (const auto &e : border)
		if (!cuts.nonmanifold.count(e.first))
			(e.second == 1 ? open : seams)++;
	if (open)
		return err_set("%s: the boundary is not a closed surface: %zu edge%s to only one "
		               "triangle (an open surface encloses no volume to fill)",
		               source, open, open == 1 ? " belongs" : "s belong");
	if (n)
		return err_set("%s: the boundary is not a manifold surface: %zu edge%s shared by "
		               "more than two triangles",
		               source, n, n == 1 ? " is" : "s are");
	if (seams)
		return err_set("%s: the boundary surface is not orientable", source);
	n = cuts.pinched;
	return err_set("%s: the boundary is not a manifold surface: %zu vert%s shared by "
	               "surfaces that meet only there",
	               source, n, n == 1 ? "ex is" : "ices are");
}

// Flip the triangles that CGAL's mesh runs the other way.
void take_orientation(const Mesh &mesh, trimesh *m)
{
	for (Mesh::Face_index f : mesh.faces()) {
		int32_t *t = m->tri + 3 * (size_t)f;
		bool same = false;
		for (Mesh::Halfedge_index h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
			if ((int32_t)mesh.source(h) == t[0])
				same = (int32_t)mesh.target(h) == t[1];
		if (!same)
			std::swap(t[1], t[2]);
	}
}

int check_and_orient(trimesh *m, const char *source)
{
	std::vector<Point> points;
	std::vector<Triangle> tris;
	weld(m, points, tris);
	size_t n = 0;
	for (const Triangle &t : tris)
		n += t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
	if (n)
		return err_set("%s: the boundary has %zu degenerate triangle%s (two corners at one "
		               "point)",
		               source, n, n == 1 ? "" : "s");
	Cuts cuts;
	cuts.original.resize(points.size());
	std::iota(cuts.original.begin(), cuts.original.end(), 0);
	Cut_visitor visitor;
	visitor.cuts = &cuts;
	bool cut = !PMP::orient_polygon_soup(points, tris, CGAL::parameters::visitor(visitor));
	Mesh mesh;
	PMP::polygon_soup_to_polygon_mesh(points, tris, mesh);
	if (cut || !CGAL::is_closed(mesh))
		return report_cuts(mesh, cuts, source);
	if (PMP::does_self_intersect(mesh))
		return err_set("%s: the boundary surface intersects itself (triangles that cross, "
		               "or of zero area): its inside is not defined",
		               source);
	PMP::orient_to_bound_a_volume(mesh);
	take_orientation(mesh, m);
	return 0;
}

} // namespace

extern "C" int trimesh_close(trimesh *m, const char *source)
{
	if (m->ntri == 0)
		return err_set("%s: no surface triangles: the geometry has no closed boundary",
		               source);
	try {
		return check_and_orient(m, source);
	} catch (const std::bad_alloc &) {
		return err_set("%s: out of memory while checking the boundary", source);
	}
}
