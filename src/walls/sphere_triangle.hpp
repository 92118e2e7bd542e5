#pragma once
// Sphere against triangle mesh: the closest point of a triangle to a point,
// and the rule that turns the closest points of many triangles into contacts,
// each touching region of the mesh counted exactly once. Host and device code;
// no allocation, no recursion, no std:: containers.
//
// THE RULE (docs/MESHES.md has the derivation, the tests and the limits).
// A contact is a local minimum of the distance from the sphere centre x to
// the mesh surface, closer than the radius, counted once. Every triangle
// within reach reports its closest point q, the feature f holding it (face,
// edge or vertex) and the distance d. A face report is a local minimum. An
// edge or vertex report is one exactly when every other triangle containing f
// finds its closest point on f too; otherwise some triangle containing q
// reaches closer. A report (t, f, q, d) is dropped when another report
// (u, f', q', d') of a triangle u sharing a vertex with t says so:
//   S  |q' - q| <= tol and (rank f', u) < (rank f, t)      the same point seen twice (shared edge or
//                                                         vertex, or rounding): the face, else the
//                                                         lowest index, reports it;
//   F  (d', rank f', u) < (d, rank f, t) and the contact   a shallow concave crease of a tessellated
//      normals differ by less than the crease angle       curved surface: the nearer report stands
//                                                         for the smooth surface;
// and, for an edge or vertex report, when u contains f and q' is not q (S
// did not apply):
//   B1 f' is a face, or an edge through the vertex f      u reaches closer: q is no minimum;
//   B2 f' == f and u < t                                  the same feature: the lowest index reports;
//   B3 f' unrelated to f (neither contains the other)     u reaches closer elsewhere; exact ties
//      and (d', rank f', u) < (d, rank f, t)              broken by a total order;
//      (f' an end of the edge f: no objection; B1 drops u's report instead).
// rank: 0 face, 1 edge, 2 vertex. tol = 1e-6 radius + what coordinate
// rounding can hide (mesh_coincidence_tolerance). A triangle containing an
// edge or vertex within reach is itself within reach (its distance is at most
// d), so the rule needs only the triangles of the sphere's own cell.
//
// Properties (tests/walls/test_mesh_contacts.cpp): on a flat tessellated
// surface exactly one contact with the overlap and normal of the analytic
// plane, wherever the centre projects (inside a face, on a shared edge, on a
// shared vertex, within rounding of them); outside a convex body exactly one
// contact at the true distance; at a concave corner sharper than the crease
// angle one contact per face. The "owned" bits of walls/mesh.hpp name the
// reporter of B2 whenever all triangles classify the point alike; the rule
// does not rely on them, so a rounding disagreement at a feature boundary
// neither loses nor doubles a contact.
#include <cmath>
#include <cstdint>

#include "core/hd.hpp"
#include "core/types.hpp"
#include "core/vec3.hpp"
#include "walls/mesh.hpp"

namespace gs {

// Where on a triangle the closest point lies. Edge k joins corners k, (k+1)%3.
enum TriangleFeature : std::uint8_t {
  kFace = 0,
  kEdge0 = 1,
  kEdge1 = 2,
  kEdge2 = 3,
  kVertex0 = 4,
  kVertex1 = 5,
  kVertex2 = 6,
};
GS_HD GS_INLINE bool is_edge_feature(std::uint8_t f) { return f >= kEdge0 && f <= kEdge2; }
GS_HD GS_INLINE bool is_vertex_feature(std::uint8_t f) { return f >= kVertex0 && f <= kVertex2; }
// 0 face, 1 edge, 2 vertex.
GS_HD GS_INLINE int feature_rank(std::uint8_t f) { return f == kFace ? 0 : (f <= kEdge2 ? 1 : 2); }

struct ClosestPoint {
  Vec3d point;            // closest point of the triangle to the query point
  double distance;        // |query - point|
  std::uint8_t feature;   // TriangleFeature holding `point` in its relative interior
};

namespace detail {
// Closest point of the segment from corner k (u) to corner k+1 (w); replaces
// `best` when strictly closer, so on ties the lower edge index wins.
GS_HD GS_INLINE void closest_on_edge(const Vec3d& p, const Vec3d& u, const Vec3d& w, int k, ClosestPoint& best) {
  const Vec3d uw = w - u;
  const double along = dot(p - u, uw);
  const double length2 = norm2(uw);
  ClosestPoint c;
  if (along <= 0) {
    c.point = u;
    c.feature = std::uint8_t(kVertex0 + k);
  } else if (along >= length2) {
    c.point = w;
    c.feature = std::uint8_t(kVertex0 + (k + 1) % 3);
  } else {
    c.point = u + uw * (along / length2);
    c.feature = std::uint8_t(kEdge0 + k);
  }
  c.distance = norm(p - c.point);
  if (k == 0 || c.distance < best.distance) best = c;
}
}  // namespace detail

// Closest point of the triangle (a, b, c) to p, by regions: the face when the
// projection of p falls strictly inside (all three sub-areas of the projection
// positive); otherwise the nearest point of the three edges, clamped to their
// ends, which names an edge or a corner. A projection on an edge, to rounding,
// therefore reports the edge, and both triangles sharing the edge agree.
GS_HD GS_INLINE ClosestPoint closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d n = cross(b - a, c - a);  // |n| = twice the area
  const Vec3d pa = a - p, pb = b - p, pc = c - p;
  if (dot(n, cross(pa, pb)) > 0 && dot(n, cross(pb, pc)) > 0 && dot(n, cross(pc, pa)) > 0) {
    const double n2 = norm2(n);
    const double height = dot(n, p - a) / n2;  // signed, in units of |n|
    ClosestPoint r;
    r.point = p - n * height;
    r.distance = std::fabs(height) * std::sqrt(n2);
    r.feature = kFace;
    return r;
  }
  ClosestPoint best{Vec3d(), 0.0, kFace};
  detail::closest_on_edge(p, a, b, 0, best);
  detail::closest_on_edge(p, b, c, 1, best);
  detail::closest_on_edge(p, c, a, 2, best);
  return best;
}

// One contact of a sphere with a mesh, as the force kernel needs it.
struct MeshContact {
  std::int32_t triangle;     // the reporting triangle
  std::uint8_t feature;      // TriangleFeature of the contact in that triangle
  std::int32_t mesh;         // mesh id
  std::uint32_t feature_key; // mesh_feature_key: stable id of the touched face/edge/vertex
  double overlap;            // radius - distance > 0 [m]
  Vec3d normal;              // unit, from the surface towards the sphere centre
  Vec3d point;               // contact point on the surface (world frame)
  Vec3d wall_velocity;       // velocity of the mesh material at `point` (zero without poses)
};

// Key of a feature over the whole MeshSet: kind in the top two bits (0 face,
// 1 edge, 2 vertex), then the triangle, edge or vertex index. The same edge or
// vertex has the same key whichever triangle reports it.
GS_HD GS_INLINE std::uint32_t mesh_feature_key(const MeshView& m, std::int32_t t, std::uint8_t f) {
  if (f == kFace) return std::uint32_t(t);
  if (is_edge_feature(f)) return (1u << 30) | std::uint32_t(m.edges[t].e[f - kEdge0]);
  return (2u << 30) | std::uint32_t(m.corners[t].v[f - kVertex0]);
}

// History partner id of a mesh feature (core/types.hpp): the two kind bits of
// mesh_feature_key moved down to bits 28-29, under the mesh range's prefix.
// Feature indices are below kMaxMeshFeatures (checked by the Simulation).
GS_HD GS_INLINE ParticleId mesh_partner_id(std::uint32_t feature_key) {
  return kMeshPartnerBase | ((feature_key >> 30) << 28) | (feature_key & 0x0FFFFFFFu);
}

// The inverse, for a partner id in the mesh range.
GS_HD GS_INLINE std::uint32_t mesh_feature_key_of(ParticleId partner) {
  return (((partner >> 28) & 3u) << 30) | (partner & 0x0FFFFFFFu);
}

// The vertices of the feature named by a mesh_feature_key (3 for a face, 2
// for an edge, 1 for a vertex); returns how many.
GS_HD GS_INLINE int mesh_feature_vertices(const MeshView& m, std::uint32_t key, std::int32_t v[3]) {
  const std::uint32_t kind = key >> 30;
  const std::int32_t index = std::int32_t(key & 0x3FFFFFFFu);
  if (kind == 0) {
    for (int k = 0; k < 3; ++k) v[k] = m.corners[index].v[k];
    return 3;
  }
  if (kind == 1) {
    v[0] = m.edge_ends[index].v[0];
    v[1] = m.edge_ends[index].v[1];
    return 2;
  }
  v[0] = index;
  return 1;
}

// Whether two features share a vertex: a contact that moves from one to the
// other (rolling over a tessellated floor) is the same contact, so friction
// history can follow it (docs/MESHES.md, Integration).
GS_HD GS_INLINE bool mesh_features_adjacent(const MeshView& m, std::uint32_t a, std::uint32_t b) {
  std::int32_t va[3], vb[3];
  const int na = mesh_feature_vertices(m, a, va), nb = mesh_feature_vertices(m, b, vb);
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nb; ++j)
      if (va[i] == vb[j]) return true;
  return false;
}

// Whether a history partner is a feature adjacent to `key` (sharing a vertex,
// hence of the same mesh): the same contact, moved on across the surface.
struct SameMeshContact {
  const MeshView* meshes;
  std::uint32_t key;
  GS_HD bool operator()(ParticleId partner) const {
    return partner >= kMeshPartnerBase && partner < kWallPartnerBase &&
           mesh_features_adjacent(*meshes, key, mesh_feature_key_of(partner));
  }
};

GS_HD GS_INLINE ClosestPoint triangle_closest_point(const MeshView& m, std::int32_t t, const Vec3d& x) {
  const MeshCorners& c = m.corners[t];
  return closest_point_on_triangle(x, m.vertex[c.v[0]], m.vertex[c.v[1]], m.vertex[c.v[2]]);
}

// Unit normal of triangle t turned towards x (outwards when x lies on its plane).
GS_HD GS_INLINE Vec3d face_normal_towards(const MeshView& m, std::int32_t t, const Vec3d& x) {
  const MeshCorners& c = m.corners[t];
  const Vec3d& a = m.vertex[c.v[0]];
  const Vec3d n = cross(m.vertex[c.v[1]] - a, m.vertex[c.v[2]] - a);
  return n * ((dot(n, x - a) < 0 ? -1.0 : 1.0) / norm(n));
}

// Contact normal of the report r of triangle t: the face normal for a face,
// else the direction from the closest point to x (r.distance > 0).
GS_HD GS_INLINE Vec3d contact_normal(const MeshView& m, std::int32_t t, const ClosestPoint& r, const Vec3d& x) {
  if (r.feature == kFace) return face_normal_towards(m, t, x);
  return (x - r.point) * (1.0 / r.distance);
}

// Distance below which two reported points are one (rule S): 1e-6 radius,
// plus what rounding of coordinates of size |x| can hide: distances carry
// errors of about 1e-15 |x|, and a report whose distance is wrong by e can sit
// up to sqrt(2 radius e) along the surface from the true closest point.
GS_HD GS_INLINE double mesh_coincidence_tolerance(const Vec3d& x, double radius) {
  const double scale = std::fmax(std::fabs(x.x), std::fmax(std::fabs(x.y), std::fabs(x.z)));
  return 1e-6 * radius + 2e-7 * std::sqrt(radius * scale);
}

namespace detail {
// (d', rank', t') < (d, rank, t): a strict total order on reports.
GS_HD GS_INLINE bool precedes(double da, std::uint8_t fa, std::int32_t ta, double db, std::uint8_t fb,
                              std::int32_t tb) {
  if (da != db) return da < db;
  const int ra = feature_rank(fa), rb = feature_rank(fb);
  if (ra != rb) return ra < rb;
  return ta < tb;
}
GS_HD GS_INLINE bool report_precedes(const ClosestPoint& a, std::int32_t ta, const ClosestPoint& b, std::int32_t tb) {
  return precedes(a.distance, a.feature, ta, b.distance, b.feature, tb);
}

// The report r of triangle t as the rule weighs it: its feature's edge id (or
// -1) and its one or two vertices (unused for a face).
struct Report {
  std::int32_t t;
  ClosestPoint r;
  bool on_face, on_edge;
  std::int32_t v0, v1, edge;
  int rank;
};
GS_HD GS_INLINE Report make_report(const MeshView& m, std::int32_t t, const ClosestPoint& r) {
  Report p{t, r, r.feature == kFace, is_edge_feature(r.feature), 0, 0, -1, feature_rank(r.feature)};
  const MeshCorners& tc = m.corners[t];
  const int k0 = p.on_edge ? r.feature - kEdge0 : (p.on_face ? 0 : r.feature - kVertex0);
  p.v0 = tc.v[k0];
  p.v1 = p.on_edge ? tc.v[(k0 + 1) % 3] : p.v0;
  p.edge = p.on_edge ? m.edges[t].e[k0] : -1;
  return p;
}

// Whether triangle u's report drops the report p (the rule at the top of
// this file). Each triangle's objection stands alone: the rule keeps a report
// that no triangle objects to, in whatever order they are asked.
GS_HD GS_INLINE bool objects(const MeshView& m, const Vec3d& x, double radius, double tol2, const Report& p,
                             std::int32_t u) {
  const std::int32_t t = p.t;
  if (u == t || !m.shares_vertex(u, t)) return false;
  const ClosestPoint o = triangle_closest_point(m, u, x);
  if (!(o.distance < radius)) return false;
  const int other_rank = feature_rank(o.feature);
  // S: the same point, found again by a neighbour; the face, else the lowest index, reports it.
  if (norm2(o.point - p.r.point) <= tol2) return other_rank < p.rank || (other_rank == p.rank && u < t);
  // F: a nearer report of a neighbour whose contact normal is within the
  // crease angle (the sphere sits in a shallow concave crease of a
  // tessellated curved surface): one smooth surface, the nearer one reports.
  if (m.crease_cos && m.mesh && o.distance > 0 && report_precedes(o, u, p.r, t) &&
      dot(contact_normal(m, t, p.r, x), contact_normal(m, u, o, x)) > m.crease_cos[m.mesh[t]])
    return true;
  if (p.on_face || !(p.on_edge ? m.has_edge(u, p.edge) : m.has_vertex(u, p.v0))) return false;
  // u contains the edge or vertex of r, and its closest point is elsewhere.
  if (o.feature == kFace) return true;  // B1
  const MeshCorners& uc = m.corners[u];
  if (is_edge_feature(o.feature)) {
    const int j = o.feature - kEdge0;
    if (p.on_edge && m.edges[u].e[j] == p.edge) return u < t;                                   // B2
    if (!p.on_edge && (uc.v[j] == p.v0 || uc.v[(j + 1) % 3] == p.v0)) return true;  // B1: an edge through the vertex
  } else {
    const std::int32_t w = uc.v[o.feature - kVertex0];
    if (!p.on_edge && w == p.v0) return u < t;            // B2
    if (p.on_edge && (w == p.v0 || w == p.v1)) return false;  // an end of the edge: no objection
  }
  return report_precedes(o, u, p.r, t);  // B3
}

// The rule for the report r of triangle t: false when another report within
// reach makes it redundant. Triangle `first` of the list (-1: none) is asked
// before the others (NearestReport says why).
GS_HD GS_INLINE bool keep_mesh_report(const MeshView& m, const std::int32_t* list, std::int32_t count, const Vec3d& x,
                                      double radius, double tol2, std::int32_t t, const ClosestPoint& r,
                                      std::int32_t first) {
  const Report p = make_report(m, t, r);
  for (std::int32_t k = first >= 0 ? -1 : 0; k < count; ++k) {  // k = -1: `first`
    const std::int32_t u = k < 0 ? first : list[k];
    if ((k < 0 || u != first) && objects(m, x, radius, tol2, p, u)) return false;
  }
  return true;
}
}  // namespace detail

// The first of the reports within reach in the rule's total order (nearest,
// then face before edge before vertex, then lowest index), found while the
// triangles in reach are listed, which the rule asks first: it objects to most of the others (under a flat fan, the face
// report to every edge and vertex report around the centre), which are then
// dropped after one closest point instead of a scan of the list. A sphere
// under the centre of the mixer impeller's hub, 64 triangles in reach,
// scanned the cell's 64-100 for each report: a thread of 6,000 closest points
// per step, and mixer case b's step 4-5 times longer (docs/PERFORMANCE.md, "A
// sphere under the hub's centre").
struct NearestReport {
  double distance = 0;
  std::uint8_t feature = kFace;
  std::int32_t t = -1;  // none yet
  GS_HD void consider(double d, std::uint8_t f, std::int32_t u) {
    if (t >= 0 && !detail::precedes(d, f, u, distance, feature, t)) return;
    distance = d;
    feature = f;
    t = u;
  }
};

// How many triangles within reach for_each_mesh_contact_in lists apart; with
// more in reach it scans the whole list it was given.
constexpr int kMeshInReachCap = 16;

// Whether triangle t of list[0..count) reports a contact of the sphere (x,
// radius), r being its closest point: within reach, with a normal, and not
// made redundant by another report (the rule at the top of this file).
// `first`: the nearest report's triangle, a member of the list (any member,
// or -1, gives the same answer, sooner or later).
GS_HD GS_INLINE bool mesh_report_kept(const MeshView& m, const std::int32_t* list, std::int32_t count,
                                      const Vec3d& x, double radius, double tol2, std::int32_t t,
                                      const ClosestPoint& r, std::int32_t first) {
  if (!(r.distance < radius)) return false;
  if (r.feature != kFace && !(r.distance > 0)) return false;  // centre on an edge or corner: no normal
  return detail::keep_mesh_report(m, list, count, x, radius, tol2, t, r, first);
}

// The contact that triangle t reports at its closest point r to the sphere
// (x, radius), a report mesh_report_kept keeps.
GS_HD GS_INLINE MeshContact mesh_contact(const MeshView& m, std::int32_t t, const ClosestPoint& r, const Vec3d& x,
                                         double radius) {
  MeshContact c;
  c.normal = contact_normal(m, t, r, x);
  c.triangle = t;
  c.feature = r.feature;
  c.mesh = m.mesh ? m.mesh[t] : 0;
  c.feature_key = mesh_feature_key(m, t, r.feature);
  c.overlap = radius - r.distance;
  c.point = r.point;
  c.wall_velocity = m.pose ? mesh_point_velocity(m.pose[c.mesh], r.point) : Vec3d();
  return c;
}

// Calls visit(const MeshContact&) for each contact of the sphere (x, radius)
// with the triangles list[0..count), which must hold, ascending, every
// triangle within `radius` of x (a cell's list from bin_triangles does).
// Contacts come in ascending triangle order. (walls/sphere_triangle_group.hpp does
// the same with a group of GPU lanes; keep the two in step.)
template <class Visitor>
GS_HD void for_each_mesh_contact_in(const MeshView& m, const std::int32_t* list, std::int32_t count, const Vec3d& x,
                                    double radius, Visitor& visit) {
  // The rule weighs a report only against triangles within reach (it skips
  // the others), so those are listed first and it scans them alone. A cell
  // at the centre of a fan (a disc tessellated around its centre vertex)
  // holds a hundred triangles, of which a sphere touches a handful; scanning
  // the cell for each of its reports made such a sphere cost as much as a
  // warp of others (the mixer's particles wedged under the hub).
  std::int32_t in_reach[kMeshInReachCap];
  std::int32_t n_in_reach = 0;
  NearestReport nearest;
  for (std::int32_t k = 0; k < count; ++k) {
    const ClosestPoint r = triangle_closest_point(m, list[k], x);
    if (!(r.distance < radius)) continue;
    nearest.consider(r.distance, r.feature, list[k]);
    if (n_in_reach < kMeshInReachCap) in_reach[n_in_reach] = list[k];
    ++n_in_reach;
  }
  if (n_in_reach <= kMeshInReachCap) {
    list = in_reach;
    count = n_in_reach;
  }
  const double tol = mesh_coincidence_tolerance(x, radius);
  const double tol2 = tol * tol;
  for (std::int32_t k = 0; k < count; ++k) {
    const std::int32_t t = list[k];
    const ClosestPoint r = triangle_closest_point(m, t, x);
    if (mesh_report_kept(m, list, count, x, radius, tol2, t, r, nearest.t)) visit(mesh_contact(m, t, r, x, radius));
  }
}

// The same over the binned cell of x in each mesh (bins from bin_triangles
// with reach >= radius). Features never span two meshes, so each mesh's list
// is complete for the rules above; meshes come in order, so contacts stay in
// ascending triangle order.
template <class Visitor>
GS_HD void for_each_mesh_contact(const MeshView& m, const Vec3d& x, double radius, Visitor& visit) {
  for (std::int32_t k = 0; k < m.n_meshes; ++k) {
    if (!m.pose[k].active) continue;  // outside its active window (walls/timeline.hpp)
    std::int32_t begin, end;
    m.cell_range(k, x, begin, end);
    if (end > begin) for_each_mesh_contact_in(m, m.cell_triangles + begin, end - begin, x, radius, visit);
  }
}

}  // namespace gs
