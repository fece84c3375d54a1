// Signed distance to a closed triangulated boundary with a CGAL AABB tree.
//
// The tree answers the closest point q on the surface to a query p. The sign
// comes from the angle-weighted pseudo-normal n of the feature (face, edge
// or vertex) that q lies on: p is outside iff (p - q).n > 0 (Baerentzen &
// Aanaes 2005, Theorem 1), exact for a closed, consistently oriented mesh
// where a plain face normal fails at edges and vertices.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <new>
#include <vector>

#include <algorithm>
#include <iterator>

#include "pack/surface.h"

namespace
{

typedef CGAL::Simple_cartesian<double> Kernel;
typedef Kernel::Point_3 Point;
typedef Kernel::Triangle_3 Triangle;
typedef std::vector<Triangle>::const_iterator TriangleIt;
typedef CGAL::AABB_triangle_primitive<Kernel, TriangleIt> Primitive;
typedef CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> Tree;

struct Vec {
	double x, y, z;
};
Vec operator-(const Vec &a, const Vec &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator+(const Vec &a, const Vec &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator*(double s, const Vec &a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(const Vec &a, const Vec &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(const Vec &a, const Vec &b)
{
	return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec unit(const Vec &a)
{
	double n = std::sqrt(dot(a, a));
	return n > 0 ? (1.0 / n) * a : a;
}

} // namespace

struct surface {
	std::vector<Vec> vert;
	std::vector<int32_t> tri;
	std::vector<Triangle> triangles;
	std::vector<Vec> face_normal;   // per triangle
	std::vector<Vec> edge_normal;   // per triangle and local edge k (vertices k, k+1)
	std::vector<Vec> vertex_normal; // per vertex, angle-weighted
	Tree tree;
};

static void build_normals(surface *s)
{
	size_t nt = s->tri.size() / 3;
	s->face_normal.resize(nt);
	s->vertex_normal.assign(s->vert.size(), Vec{0, 0, 0});
	for (size_t t = 0; t < nt; t++) {
		const int32_t *v = &s->tri[3 * t];
		Vec a = s->vert[v[0]], b = s->vert[v[1]], c = s->vert[v[2]];
		Vec n = unit(cross(b - a, c - a));
		s->face_normal[t] = n;
		Vec p[3] = {a, b, c};
		for (int k = 0; k < 3; k++) {
			Vec e1 = unit(p[(k + 1) % 3] - p[k]), e2 = unit(p[(k + 2) % 3] - p[k]);
			double angle = std::acos(std::fmax(-1.0, std::fmin(1.0, dot(e1, e2))));
			s->vertex_normal[v[k]] = s->vertex_normal[v[k]] + angle * n;
		}
	}
	// An edge's pseudo-normal is the sum of its two faces' normals: find the
	// twin of each directed edge through a map keyed by (min, max) vertex.
	std::vector<std::pair<std::pair<int32_t, int32_t>, size_t>> edges(3 * nt);
	for (size_t t = 0; t < nt; t++)
		for (int k = 0; k < 3; k++) {
			int32_t u = s->tri[3 * t + k], w = s->tri[3 * t + (k + 1) % 3];
			edges[3 * t + k] = {{std::min(u, w), std::max(u, w)}, 3 * t + k};
		}
	std::sort(edges.begin(), edges.end());
	s->edge_normal.assign(3 * nt, Vec{0, 0, 0});
	for (size_t i = 0; i + 1 < edges.size(); i++)
		if (edges[i].first == edges[i + 1].first) {
			size_t e = edges[i].second, f = edges[i + 1].second;
			Vec n = s->face_normal[e / 3] + s->face_normal[f / 3];
			s->edge_normal[e] = s->edge_normal[f] = n;
		}
}

extern "C" surface *surface_new(const double *vert, size_t nvert, const int32_t *tri, size_t ntri)
{
	if (ntri == 0)
		return nullptr;
	surface *s = nullptr;
	try {
		s = new surface;
		s->vert.resize(nvert);
		for (size_t i = 0; i < nvert; i++)
			s->vert[i] = Vec{vert[3 * i], vert[3 * i + 1], vert[3 * i + 2]};
		s->tri.assign(tri, tri + 3 * ntri);
		s->triangles.reserve(ntri);
		for (size_t t = 0; t < ntri; t++) {
			const Vec &a = s->vert[tri[3 * t]], &b = s->vert[tri[3 * t + 1]],
			          &c = s->vert[tri[3 * t + 2]];
			s->triangles.emplace_back(Point(a.x, a.y, a.z), Point(b.x, b.y, b.z),
			                          Point(c.x, c.y, c.z));
		}
		build_normals(s);
		s->tree.insert(s->triangles.begin(), s->triangles.end());
		s->tree.build();
		s->tree.accelerate_distance_queries();
	} catch (const std::bad_alloc &) {
		delete s;
		return nullptr;
	}
	return s;
}

extern "C" void surface_free(surface *s) { delete s; }

// Barycentric coordinates of q in triangle t (q lies on it).
static void barycentric(const surface *s, size_t t, const Vec &q, double l[3])
{
	const int32_t *v = &s->tri[3 * t];
	Vec a = s->vert[v[0]], e1 = s->vert[v[1]] - a, e2 = s->vert[v[2]] - a, d = q - a;
	double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
	double p1 = dot(d, e1), p2 = dot(d, e2), den = d11 * d22 - d12 * d12;
	l[1] = (d22 * p1 - d12 * p2) / den;
	l[2] = (d11 * p2 - d12 * p1) / den;
	l[0] = 1 - l[1] - l[2];
}

// The pseudo-normal of the feature of triangle t that q lies on.
static Vec pseudo_normal(const surface *s, size_t t, const Vec &q)
{
	const double eps = 1e-7;
	double l[3];
	barycentric(s, t, q, l);
	int zero = 0, k0 = -1;
	for (int k = 0; k < 3; k++)
		if (l[k] < eps) {
			zero++;
			k0 = k;
		}
	if (zero == 0)
		return s->face_normal[t];
	if (zero == 1) // on the edge opposite vertex k0: local edge k0 + 1
		return s->edge_normal[3 * t + (k0 + 1) % 3];
	for (int k = 0; k < 3; k++) // on the vertex whose coordinate is not zero
		if (l[k] >= eps)
			return s->vertex_normal[s->tri[3 * t + k]];
	return s->face_normal[t];
}

// Signed distance from x given its closest point q on triangle t.
static double signed_distance(const surface *s, size_t t, const Vec &q, const double p[3],
                              double normal[3])
{
	Vec x{p[0], p[1], p[2]};
	Vec d = x - q;
	double dist = std::sqrt(dot(d, d));
	double outside = dot(d, pseudo_normal(s, t, q));
	if (normal) {
		Vec n = dist > 0 ? (outside > 0 ? (1.0 / dist) * d : (-1.0 / dist) * d)
		                 : unit(pseudo_normal(s, t, q));
		normal[0] = n.x;
		normal[1] = n.y;
		normal[2] = n.z;
	}
	return outside > 0 ? -dist : dist;
}

extern "C" double surface_distance(const surface *s, const double p[3], double normal[3],
                                   int32_t *hint)
{
	Point query(p[0], p[1], p[2]);
	Tree::Point_and_primitive_id pp;
	if (hint && *hint >= 0) {
		const Triangle &h = s->triangles[*hint];
		Point c = CGAL::centroid(h);
		pp = s->tree.closest_point_and_primitive(
		    query, Tree::Point_and_primitive_id(c, s->triangles.begin() + *hint));
	} else {
		pp = s->tree.closest_point_and_primitive(query);
	}
	size_t t = (size_t)(pp.second - s->triangles.begin());
	if (hint)
		*hint = (int32_t)t;
	return signed_distance(s, t, Vec{pp.first.x(), pp.first.y(), pp.first.z()}, p, normal);
}

extern "C" double surface_distance_among(const surface *s, const double p[3], const int32_t *tri,
                                         size_t n)
{
	if (n == 0)
		return INFINITY;
	Point query(p[0], p[1], p[2]), bq(0, 0, 0);
	double best = INFINITY;
	size_t bt = 0;
	Kernel::Construct_projected_point_3 project;
	for (size_t k = 0; k < n; k++) {
		Point q = project(s->triangles[tri[k]], query);
		double d2 = CGAL::squared_distance(query, q);
		if (d2 < best) {
			best = d2;
			bt = (size_t)tri[k];
			bq = q;
		}
	}
	return signed_distance(s, bt, Vec{bq.x(), bq.y(), bq.z()}, p, NULL);
}

extern "C" size_t surface_near(const surface *s, const double p[3], double radius, int32_t *out,
                               size_t max_out)
{
	std::vector<Primitive::Id> hits;
	CGAL::Bbox_3 box(p[0] - radius, p[1] - radius, p[2] - radius, p[0] + radius, p[1] + radius,
	                 p[2] + radius);
	s->tree.all_intersected_primitives(box, std::back_inserter(hits));
	Point c(p[0], p[1], p[2]);
	std::vector<int32_t> ids;
	ids.reserve(hits.size());
	for (const Primitive::Id &h : hits)
		if (CGAL::squared_distance(c, *h) <= radius * radius)
			ids.push_back((int32_t)(h - s->triangles.begin()));
	std::sort(ids.begin(), ids.end());
	for (size_t k = 0; k < ids.size() && k < max_out; k++)
		out[k] = ids[k];
	return ids.size();
}
