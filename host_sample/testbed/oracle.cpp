#include "oracle.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

namespace rrc_sample {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kLeafSize = 4;
constexpr size_t kMaxObjects = 64;  // the scenes have 17 objects
// The oracle's visibility tolerance (README.md, "Recall and false hits"): the previous ray must meet the point's own
// object within 1e-4 of the point's distance (t is in units of that distance).
constexpr double kVisibleTolerance = 1e-4;
// The straddling bound (docs/measurements/ACCURACY.md, "Hit test against true visibility"): a previous-depth tap counts when its bilinear
// weight exceeds this (docs/measurements/ACCURACY.md's strict false hits use the same bound).
constexpr double kTapWeight = 1e-3;
// Excluded beside the image border (README.md, "Recall and false hits"): 2^-20 in uv, 1e-3 px at 1024 wide, a few
// fp32 ulps of the clip position's x/w.
constexpr double kBorderRounding = 0x1p-20;

struct Triangle {
    glm::dvec3 a, e1, e2;  // vertex, two edges (Moller-Trumbore)
};

struct Node {
    glm::dvec3 lo{kInf}, hi{-kInf};
    uint32_t first = 0, count = 0;  // leaf: triangles [first, first + count); inner: children first, first + 1
};

glm::dvec3 dehomogenise(const glm::dvec4& p) { return glm::dvec3(p) / p.w; }

// The eye of a perspective view_proj: the point whose clip position is (0, 0, z, 0).
glm::dvec3 eye_of(const glm::dmat4& inv_vp) { return dehomogenise(inv_vp * glm::dvec4(0.0, 0.0, 1.0, 0.0)); }

// The direction from the eye through pixel (x, y)'s centre (docs/CONVENTIONS.md: uv = (ndc + 1)/2, y down).
glm::dvec3 pixel_ray(const glm::dmat4& inv_vp, const glm::dvec3& eye, uint32_t x, uint32_t y, uint32_t W, uint32_t H) {
    const glm::dvec2 ndc(2.0 * (x + 0.5) / W - 1.0, 2.0 * (y + 0.5) / H - 1.0);
    return dehomogenise(inv_vp * glm::dvec4(ndc, 0.5, 1.0)) - eye;
}

bool slab(const Node& n, const glm::dvec3& o, const glm::dvec3& inv_d, double t_max, double& t_entry) {
    const glm::dvec3 t0 = (n.lo - o) * inv_d, t1 = (n.hi - o) * inv_d;
    const glm::dvec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
    const double enter = std::max(std::max(near.x, near.y), std::max(near.z, 0.0));
    const double leave = std::min(std::min(far.x, far.y), std::min(far.z, t_max));
    t_entry = enter;
    return enter <= leave;
}

}  // namespace

struct VisibilityOracle::MeshBvh {
    std::vector<Triangle> tris;
    std::vector<Node> nodes;
    glm::dvec3 centre{0.0};  // bounding sphere, object space
    double radius = 0.0;

    explicit MeshBvh(const MeshData& m) {
        for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            const glm::dvec3 a(m.vertices[m.indices[i]].position), b(m.vertices[m.indices[i + 1]].position),
                c(m.vertices[m.indices[i + 2]].position);
            tris.push_back({a, b - a, c - a});
        }
        glm::dvec3 lo(kInf), hi(-kInf);
        for (const Vertex& v : m.vertices) lo = glm::min(lo, glm::dvec3(v.position)), hi = glm::max(hi, glm::dvec3(v.position));
        centre = 0.5 * (lo + hi);
        for (const Vertex& v : m.vertices) radius = std::max(radius, glm::length(glm::dvec3(v.position) - centre));
        radius *= 1.0 + 1e-9;
        nodes.reserve(2 * tris.size() / kLeafSize + 2);
        nodes.emplace_back();
        build(0, 0, (uint32_t)tris.size());
    }

    // Median split of the centroids along the node's widest axis.
    void build(uint32_t node, uint32_t first, uint32_t count) {
        Node n;
        glm::dvec3 clo(kInf), chi(-kInf);
        for (uint32_t i = first; i < first + count; ++i) {
            const Triangle& t = tris[i];
            for (const glm::dvec3& p : {t.a, t.a + t.e1, t.a + t.e2}) n.lo = glm::min(n.lo, p), n.hi = glm::max(n.hi, p);
            const glm::dvec3 c = t.a + (t.e1 + t.e2) / 3.0;
            clo = glm::min(clo, c), chi = glm::max(chi, c);
        }
        if (count <= kLeafSize) {
            n.first = first, n.count = count;
            nodes[node] = n;
            return;
        }
        const glm::dvec3 ext = chi - clo;
        const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
        const uint32_t mid = first + count / 2;
        std::nth_element(
            tris.begin() + first, tris.begin() + mid, tris.begin() + first + count,
            [axis](const Triangle& p, const Triangle& q) { return (3.0 * p.a + p.e1 + p.e2)[axis] < (3.0 * q.a + q.e1 + q.e2)[axis]; });
        n.first = (uint32_t)nodes.size();
        n.count = 0;
        nodes[node] = n;
        nodes.emplace_back();
        nodes.emplace_back();
        build(n.first, first, mid - first);
        build(n.first + 1, mid, first + count - mid);
    }

    // Nearest t in (0, t_max) where the ray meets a triangle (t_max if none).
    double intersect(const glm::dvec3& o, const glm::dvec3& d, double t_max) const {
        const glm::dvec3 inv_d = 1.0 / d;
        uint32_t stack[64];
        int top = 0;
        double entry;
        if (!slab(nodes[0], o, inv_d, t_max, entry)) return t_max;
        stack[top++] = 0;
        while (top) {
            const Node& n = nodes[stack[--top]];
            if (n.count) {
                for (uint32_t i = n.first; i < n.first + n.count; ++i) {
                    const Triangle& t = tris[i];
                    const glm::dvec3 p = glm::cross(d, t.e2);
                    const double det = glm::dot(t.e1, p);
                    if (det == 0.0) continue;
                    const double inv = 1.0 / det;
                    const glm::dvec3 s = o - t.a;
                    const double u = glm::dot(s, p) * inv;
                    if (u < 0.0 || u > 1.0) continue;
                    const glm::dvec3 q = glm::cross(s, t.e1);
                    const double v = glm::dot(d, q) * inv;
                    if (v < 0.0 || u + v > 1.0) continue;
                    const double tt = glm::dot(t.e2, q) * inv;
                    if (tt > 0.0 && tt < t_max) t_max = tt;
                }
                continue;
            }
            // Nearer child last on the stack, so it is opened first and shortens t_max for the other.
            double ea, eb;
            const bool ha = slab(nodes[n.first], o, inv_d, t_max, ea), hb = slab(nodes[n.first + 1], o, inv_d, t_max, eb);
            if (ha && hb) {
                const bool a_first = ea <= eb;
                stack[top++] = a_first ? n.first + 1 : n.first;
                stack[top++] = a_first ? n.first : n.first + 1;
            } else if (ha) {
                stack[top++] = n.first;
            } else if (hb) {
                stack[top++] = n.first + 1;
            }
        }
        return t_max;
    }
};

// A view ready for casting: per object its inverse model and world bounding sphere.
struct VisibilityOracle::Prepared {
    struct Object {
        glm::dmat4 inverse;
        glm::dvec3 centre;
        double radius;
    };
    std::vector<Object> objects;
};

VisibilityStats& VisibilityStats::operator+=(const VisibilityStats& o) {
    surface += o.surface, visible += o.visible, straddling += o.straddling, clean_visible += o.clean_visible;
    clean_hits += o.clean_hits, hits += o.hits, false_hits += o.false_hits, false_hits_straddling += o.false_hits_straddling;
    excluded += o.excluded, excluded_hits += o.excluded_hits;
    for (uint32_t m = 0; m < kMaterialCount; ++m) missed_by_material[m] += o.missed_by_material[m];
    return *this;
}

void oracle_views(const FrameState& st, OracleView& cur, OracleView& prev) {
    cur.view_proj = st.view_proj;
    prev.view_proj = st.prev_view_proj;
    cur.model.clear(), prev.model.clear();
    for (const GpuObject& o : st.objects) cur.model.emplace_back(o.model), prev.model.emplace_back(o.prev_model);
}

VisibilityOracle::VisibilityOracle(const Scene& scene) {
    if (scene.objects.size() > kMaxObjects) throw std::runtime_error("the visibility oracle takes at most 64 objects");
    for (const MeshData& m : scene.meshes) meshes_.push_back(std::make_unique<MeshBvh>(m));
    for (const SceneObject& o : scene.objects)
        object_mesh_.push_back(o.mesh), object_material_.push_back(std::min(o.material, kMaterialCount - 1));
}

VisibilityOracle::~VisibilityOracle() = default;

VisibilityOracle::Prepared VisibilityOracle::prepare(const OracleView& v) const {
    Prepared p;
    for (size_t i = 0; i < v.model.size(); ++i) {
        const glm::dmat4& m = v.model[i];
        const MeshBvh& mesh = *meshes_[object_mesh_[i]];
        const double scale = std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])), glm::length(glm::dvec3(m[2]))});
        p.objects.push_back({glm::inverse(m), dehomogenise(m * glm::dvec4(mesh.centre, 1.0)), mesh.radius * scale * (1.0 + 1e-9)});
    }
    return p;
}

// The objects whose bounding spheres the ray enters, nearest entry first; each
// object's BVH is searched in its own space (the ray's t is the same there:
// the direction is transformed, not renormalised).
VisibilityOracle::Hit VisibilityOracle::cast_prepared(const Prepared& prepared, const glm::dvec3& o, const glm::dvec3& d,
                                                      double t_max) const {
    // A small fixed array, not a vector: two casts a pixel must not allocate.
    std::pair<double, int> order[kMaxObjects];
    int n = 0;
    const double dd = glm::dot(d, d);
    for (size_t i = 0; i < prepared.objects.size(); ++i) {
        const Prepared::Object& ob = prepared.objects[i];
        const glm::dvec3 oc = o - ob.centre;
        const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - ob.radius * ob.radius, disc = b * b - dd * c;
        if (disc < 0.0) continue;
        const double sq = std::sqrt(disc);
        const double enter = (-b - sq) / dd;
        if ((-b + sq) / dd <= 0.0 || enter >= t_max) continue;  // behind the origin, or beyond t_max
        order[n++] = {std::max(enter, 0.0), (int)i};
    }
    std::sort(order, order + n);
    Hit h;
    double best = t_max;
    for (int k = 0; k < n; ++k) {
        const auto [entry, i] = order[k];
        if (entry >= best) break;
        const Prepared::Object& ob = prepared.objects[i];
        const glm::dvec3 lo = dehomogenise(ob.inverse * glm::dvec4(o, 1.0)), ld = glm::dmat3(ob.inverse) * d;
        const double t = meshes_[object_mesh_[i]]->intersect(lo, ld, best);
        if (t < best) best = t, h.object = i, h.t = t;
    }
    return h;
}

VisibilityOracle::Hit VisibilityOracle::cast(const OracleView& view, const glm::dvec3& origin, const glm::dvec3& direction) const {
    const Prepared p = prepare(view);
    return cast_prepared(p, origin, direction, kInf);
}

std::vector<uint16_t> VisibilityOracle::object_ids(const OracleView& view, uint32_t W, uint32_t H) const {
    const Prepared p = prepare(view);
    const glm::dmat4 inv_vp = glm::inverse(view.view_proj);
    const glm::dvec3 eye = eye_of(inv_vp);
    std::vector<uint16_t> ids((size_t)W * H);
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x)
            ids[(size_t)y * W + x] = (uint16_t)(cast_prepared(p, eye, pixel_ray(inv_vp, eye, x, y, W, H), kInf).object + 1);
    return ids;
}

namespace {

// X moved by its object's previous model matrix.
glm::dvec3 cur_to_prev(const glm::dmat4& inverse_model, const glm::dmat4& prev_model, const glm::dvec3& X) {
    return dehomogenise(prev_model * (inverse_model * glm::dvec4(X, 1.0)));
}

// X_prev projects outside the previous image, but by less than kBorderRounding
// in uv: rrc tests uv_prev from the G-buffer's fp32 clip position, whose
// rounding (and the rasteriser's interpolation) decides which side it falls.
bool beside_border(const glm::dmat4& prev_view_proj, const glm::dvec3& X_prev) {
    const glm::dvec4 c = prev_view_proj * glm::dvec4(X_prev, 1.0);
    if (!(c.w > 0.0)) return false;
    const glm::dvec2 uv = (glm::dvec2(c) / c.w + 1.0) * 0.5;
    const bool inside = uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0;
    const double r = kBorderRounding;
    return !inside && uv.x >= -r && uv.x <= 1.0 + r && uv.y >= -r && uv.y <= 1.0 + r;
}

}  // namespace

VisibilityStats VisibilityOracle::judge(const OracleView& cur, const OracleView& prev, uint32_t W, uint32_t H,
                                        const std::vector<uint8_t>& mask, const std::vector<uint16_t>& prev_object,
                                        std::vector<uint8_t>* verdict) const {
    if (verdict) verdict->assign((size_t)W * H, 0);
    const Prepared pc = prepare(cur), pp = prepare(prev);
    const glm::dmat4 inv_vp = glm::inverse(cur.view_proj);
    const glm::dvec3 eye = eye_of(inv_vp), prev_eye = eye_of(glm::inverse(prev.view_proj));
    const bool has_previous = !prev_object.empty();

    auto rows = [&](uint32_t y0, uint32_t step, VisibilityStats& s) {
        for (uint32_t y = y0; y < H; y += step)
            for (uint32_t x = 0; x < W; ++x) {
                const size_t i = (size_t)y * W + x;
                const bool background = (mask[i] & RRC_MASK_BACKGROUND) != 0, is_hit = (mask[i] & RRC_MASK_HIT) != 0;
                // The pixel's sample (the sample renders without jitter): its ray through the pixel centre.
                const glm::dvec3 d = pixel_ray(inv_vp, eye, x, y, W, H);
                const Hit h = cast_prepared(pc, eye, d, kInf);
                if ((h.object < 0) != background) {
                    ++s.excluded;
                    if (is_hit) ++s.excluded_hits;
                    if (verdict) (*verdict)[i] = kVerdictExcluded | (is_hit ? kVerdictHit : 0);
                    continue;
                }
                if (h.object < 0) continue;
                const glm::dvec3 X_prev = cur_to_prev(pc.objects[h.object].inverse, prev.model[h.object], eye + h.t * d);
                if (has_previous && beside_border(prev.view_proj, X_prev)) {
                    ++s.excluded;
                    if (is_hit) ++s.excluded_hits;
                    if (verdict) (*verdict)[i] = kVerdictExcluded | (is_hit ? kVerdictHit : 0);
                    continue;
                }
                ++s.surface;
                if (is_hit) ++s.hits;
                bool visible = false, straddles = false;
                if (has_previous) {
                    const glm::dvec4 c = prev.view_proj * glm::dvec4(X_prev, 1.0);
                    if (c.w > 0.0) {
                        const glm::dvec2 uv = (glm::dvec2(c) / c.w + 1.0) * 0.5;
                        if (uv.x >= 0.0 && uv.x <= 1.0 && uv.y >= 0.0 && uv.y <= 1.0) {
                            // Only hits up to X_prev (t = 1) and its tolerance decide: nothing farther is looked at.
                            const Hit hp = cast_prepared(pp, prev_eye, X_prev - prev_eye, 1.0 + 2.0 * kVisibleTolerance);
                            visible = hp.object == h.object && std::fabs(hp.t - 1.0) <= kVisibleTolerance;
                        }
                        // The bilinear previous-depth taps (docs/CONVENTIONS.md, prev_jitter = 0).
                        const glm::dvec2 p = uv * glm::dvec2(W, H) - 0.5, i0 = glm::floor(p), f = p - i0;
                        for (int t = 0; t < 4; ++t) {
                            const int dx = t & 1, dy = t >> 1;
                            const double w = (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y);
                            if (!(w > kTapWeight)) continue;
                            const int tx = std::clamp((int)i0.x + dx, 0, (int)W - 1), ty = std::clamp((int)i0.y + dy, 0, (int)H - 1);
                            if (prev_object[(size_t)ty * W + (size_t)tx] != (uint16_t)(h.object + 1)) straddles = true;
                        }
                    }
                }
                if (verdict)
                    (*verdict)[i] = kVerdictSurface | (visible ? kVerdictVisible : 0) | (straddles ? kVerdictStraddling : 0) |
                                    (is_hit ? kVerdictHit : 0);
                if (visible) ++s.visible;
                if (straddles) ++s.straddling;
                if (visible && !straddles) {
                    ++s.clean_visible;
                    if (is_hit)
                        ++s.clean_hits;
                    else
                        ++s.missed_by_material[object_material_[h.object]];
                }
                if (is_hit && !visible) {
                    ++s.false_hits;
                    if (straddles) ++s.false_hits_straddling;
                }
            }
    };
    const uint32_t threads = std::max(1u, std::min(std::thread::hardware_concurrency(), H));
    std::vector<VisibilityStats> part(threads);
    std::vector<std::thread> pool;
    for (uint32_t k = 1; k < threads; ++k) pool.emplace_back(rows, k, threads, std::ref(part[k]));
    rows(0, threads, part[0]);
    for (std::thread& t : pool) t.join();
    VisibilityStats total;
    for (const VisibilityStats& s : part) total += s;
    return total;
}

}  // namespace rrc_sample
