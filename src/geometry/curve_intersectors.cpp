// The reference curve intersectors (curve_math.h): slow, in double, written
// from the surface definitions of curve_set.h rather than from Embree's code,
// so that the agreement tests compare two independent implementations.

#include <algorithm>
#include <cmath>

#include "curve_math.h"
#include "double_triangle.h"

namespace strahl::curve {

namespace {

DVec3 xyz(const DVec4& v) { return DVec3(v.x, v.y, v.z); }

// Both roots of |o + t d − c|² = R² (t0 <= t1); false if the ray misses.
bool raySphere(const DRay& ray, const DVec3& c, double R, double& t0, double& t1) {
    const DVec3 oc = ray.origin - c;
    const double a = glm::dot(ray.dir, ray.dir);
    const double halfB = glm::dot(oc, ray.dir);
    // c' = |oc|² − R², written through the distance of c from the ray's line
    // to avoid cancelling |oc|² against R² when the ray starts far away.
    const DVec3 perp = oc - (halfB / a) * ray.dir;
    const double disc = a * (R * R - glm::dot(perp, perp));
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    t0 = (-halfB - root) / a;
    t1 = (-halfB + root) / a;
    return true;
}

// ---- round cubic ------------------------------------------------------------
//
// Unknowns (u, t). With X = o + t d, R = X − C(u), T = C'/|C'|:
//     f(u, t) = R·T = 0                   (X lies in the normal plane at u)
//     g(u, t) = sqrt(|R|² − f²) − r(u) = 0 (at distance r from the axis)
// Derivatives: ∂R/∂u = −C', ∂R/∂t = d, ∂T/∂u = (C'' − T (T·C''))/|C'|,
//     ∂f/∂u = −|C'| + R·∂T/∂u,   ∂f/∂t = d·T,
//     K = |R|² − f²,  ∂K/∂u = 2(−R·C' − f ∂f/∂u),  ∂K/∂t = 2(R·d − f ∂f/∂t),
//     ∂g/∂u = ∂K/∂u / (2√K) − r',  ∂g/∂t = ∂K/∂t / (2√K).
// Newton converges from seeds on a nearly straight piece of the curve, where
// the tube is locally a cylinder whose two ray roots are the seeds.

bool newtonRound(const DRay& ray, const DVec4 b[4], double u, double t, double tolerance, RefHit& hit) {
    for (int iteration = 0; iteration < 40; ++iteration) {
        const Eval e = evalBezier(b, u);
        const DVec3 C = xyz(e.p), C1 = xyz(e.dp), C2 = xyz(e.ddp);
        const double len1 = glm::length(C1);
        if (!(len1 > 0.0)) return false;
        const DVec3 T = C1 / len1;
        const DVec3 X = ray.origin + t * ray.dir;
        const DVec3 R = X - C;
        const DVec3 dTdu = (C2 - T * glm::dot(T, C2)) / len1;
        const double f = glm::dot(R, T);
        const double dfdu = -len1 + glm::dot(R, dTdu);
        const double dfdt = glm::dot(ray.dir, T);
        const double K = glm::dot(R, R) - f * f;
        if (!(K > 0.0)) return false;  // on the axis: no normal plane distance
        const double sK = std::sqrt(K);
        const double g = sK - e.p.w;
        const double dgdu = (-glm::dot(R, C1) - f * dfdu) / sK - e.dp.w;
        const double dgdt = (glm::dot(R, ray.dir) - f * dfdt) / sK;
        const double det = dfdu * dgdt - dfdt * dgdu;
        if (!(std::abs(det) > 0.0)) return false;
        const double du = (f * dgdt - dfdt * g) / det;
        const double dt = (dfdu * g - f * dgdu) / det;
        u = std::clamp(u - du, -0.5, 1.5);
        t -= dt;
        if (std::abs(f) < tolerance && std::abs(g) < tolerance && std::abs(du) < 1e-12) {
            if (!(u >= 0.0 && u <= 1.0) || !(t > ray.tnear && t < ray.tfar)) return false;
            const Eval s = evalBezier(b, u);
            const DVec3 S1 = xyz(s.dp);
            DVec3 Rp = ray.origin + t * ray.dir - xyz(s.p);
            Rp -= S1 * (glm::dot(Rp, S1) / glm::dot(S1, S1));
            const double rl = glm::length(Rp);
            if (!(rl > 0.0)) return false;
            const DVec3 Rn = Rp / rl;
            hit.t = t;
            hit.u = u;
            hit.v = 0.0;
            // The swept circle's normal: ∂X/∂u × ∂X/∂φ ∝ |C'|² Rn − r' C'.
            hit.Ng = glm::dot(S1, S1) * Rn - s.dp.w * S1;
            return true;
        }
    }
    return false;
}

struct CubicSearch {
    const DRay& ray;
    double tolerance;
    RefHit best;
    bool found = false;

    void consider(const RefHit& h) {
        if (!found || h.t < best.t) {
            best = h;
            found = true;
        }
    }

    void piece(const DVec4 b[4], const DVec4 whole[4], double u0, double u1, int depth) {
        const DVec3 centre = 0.5 * (xyz(b[0]) + xyz(b[3]));
        double reach = 0.0, rMax = 0.0;
        for (int i = 0; i < 4; ++i) {
            reach = std::max(reach, glm::length(xyz(b[i]) - centre));
            rMax = std::max(rMax, b[i].w);
        }
        double t0, t1;
        if (!raySphere(ray, centre, reach + rMax, t0, t1)) return;
        const double tLimit = found ? best.t : ray.tfar;
        if (t1 <= ray.tnear || t0 >= tLimit) return;
        // How far the inner control points stray from the chord: split until
        // the piece is straight to a tenth of its radius (and its length is
        // at most a few radii), so that the cylinder seeds below are close.
        const DVec3 chord = xyz(b[3]) - xyz(b[0]);
        const double chordLength = glm::length(chord);
        double stray = 0.0;
        for (int i = 1; i <= 2; ++i) {
            const DVec3 q = xyz(b[i]) - xyz(b[0]);
            const DVec3 off = chordLength > 0.0 ? q - chord * (glm::dot(q, chord) / (chordLength * chordLength)) : q;
            stray = std::max(stray, glm::length(off));
        }
        const double rMean = 0.25 * (b[0].w + b[1].w + b[2].w + b[3].w);
        const bool straight = stray <= 0.1 * rMean && chordLength <= 4.0 * rMean;
        if (depth < 14 && (depth < 2 || !straight)) {
            DVec4 left[4], right[4];
            splitBezier(b, left, right);
            const double um = 0.5 * (u0 + u1);
            piece(left, whole, u0, um, depth + 1);
            piece(right, whole, um, u1, depth + 1);
            return;
        }
        // Seeds: the roots of the cylinder around the chord (radius rMean),
        // or the sphere's roots when the ray misses that cylinder.
        double seeds[2] = {t0, t1};
        if (chordLength > 0.0) {
            const DVec3 a = chord / chordLength;
            const DVec3 oc = ray.origin - xyz(b[0]);
            const DVec3 dPerp = ray.dir - a * glm::dot(ray.dir, a);
            const DVec3 oPerp = oc - a * glm::dot(oc, a);
            const double A = glm::dot(dPerp, dPerp), B = glm::dot(oPerp, dPerp);
            const double Cc = glm::dot(oPerp, oPerp) - rMean * rMean;
            const double disc = B * B - A * Cc;
            if (A > 0.0 && disc >= 0.0) {
                seeds[0] = (-B - std::sqrt(disc)) / A;
                seeds[1] = (-B + std::sqrt(disc)) / A;
            }
        }
        for (double ts : seeds) {
            const DVec3 x = ray.origin + ts * ray.dir;
            double s = chordLength > 0.0 ? glm::dot(x - xyz(b[0]), chord) / (chordLength * chordLength) : 0.5;
            s = std::clamp(s, 0.0, 1.0);
            RefHit h;
            if (newtonRound(ray, whole, u0 + s * (u1 - u0), ts, tolerance, h)) consider(h);
        }
    }
};

}  // namespace

Eval evalBezier(const DVec4 b[4], double u) {
    const double s = 1.0 - u;
    Eval e;
    e.p = s * s * s * b[0] + 3.0 * s * s * u * b[1] + 3.0 * s * u * u * b[2] + u * u * u * b[3];
    e.dp = 3.0 * (s * s * (b[1] - b[0]) + 2.0 * s * u * (b[2] - b[1]) + u * u * (b[3] - b[2]));
    e.ddp = 6.0 * (s * (b[2] - 2.0 * b[1] + b[0]) + u * (b[3] - 2.0 * b[2] + b[1]));
    return e;
}

void splitBezier(const DVec4 b[4], DVec4 left[4], DVec4 right[4]) {
    const DVec4 ab = 0.5 * (b[0] + b[1]), bc = 0.5 * (b[1] + b[2]), cd = 0.5 * (b[2] + b[3]);
    const DVec4 abc = 0.5 * (ab + bc), bcd = 0.5 * (bc + cd);
    const DVec4 mid = 0.5 * (abc + bcd);
    left[0] = b[0], left[1] = ab, left[2] = abc, left[3] = mid;
    right[0] = mid, right[1] = bcd, right[2] = cd, right[3] = b[3];
}

bool intersectRoundCubic(const DRay& ray, const DVec4 b[4], RefHit& hit) {
    // Newton's bound on |f| and |g|: 1e-10 of the scale of the coordinates.
    double scale = glm::length(ray.origin);
    for (int i = 0; i < 4; ++i) scale = std::max(scale, glm::length(xyz(b[i])) + b[i].w);
    CubicSearch search{ray, 1e-10 * std::max(scale, 1e-30), {}, false};
    search.piece(b, b, 0.0, 1.0, 0);
    if (!search.found) return false;
    hit = search.best;
    return true;
}

// ---- round linear -----------------------------------------------------------
//
// The hull of two balls is the union of the balls B(s) = ball(c(s), r(s)),
// c and r linear in s ∈ [0, 1] (a point λx0 + (1−λ)x1 of the hull lies in
// B(1−λ)). Its distance-like function F(x) = min_s |x − c(s)| − r(s) is
// convex (|x − c(s)| − r(s) is jointly convex in x and s), so along a ray it
// has at most two roots, around one minimum: golden-section search finds the
// minimum, bisection the roots.
//
// The inner minimum in closed form: with p = x − c0, D = c1 − c0, L = |D|,
// δ = r1 − r0, h = p·D / L² and q the distance of x from the axis, the
// derivative −(p − sD)·D / |p − sD| − δ vanishes where (s − h) L = q k / √(1 − k²),
// k = δ / L; then s is clamped to [0, 1] (convex in s). For |k| >= 1 one ball
// contains the other and the minimum is at the bigger one.

double roundLinearDistance(const DVec3& x, const DVec4& p0, const DVec4& p1, double& s) {
    const DVec3 c0 = xyz(p0), D = xyz(p1) - c0, p = x - c0;
    const double L2 = glm::dot(D, D);
    const double delta = p1.w - p0.w;
    if (!(L2 > 0.0)) {
        s = p1.w > p0.w ? 1.0 : 0.0;
        return glm::length(p) - std::max(p0.w, p1.w);
    }
    const double L = std::sqrt(L2), k = delta / L;
    if (k >= 1.0) {
        s = 1.0;
    } else if (k <= -1.0) {
        s = 0.0;
    } else {
        const double h = glm::dot(p, D) / L2;
        const double q = std::sqrt(std::max(0.0, glm::dot(p, p) - h * h * L2));
        s = std::clamp(h + q * k / (L * std::sqrt(1.0 - k * k)), 0.0, 1.0);
    }
    return glm::length(p - s * D) - (p0.w + s * delta);
}

bool intersectRoundLinear(const DRay& ray, const DVec4& p0, const DVec4& p1, RefHit& hit) {
    const DVec3 centre = 0.5 * (xyz(p0) + xyz(p1));
    const double R = 0.5 * glm::length(xyz(p1) - xyz(p0)) + std::max(p0.w, p1.w);
    double ta, tb;
    if (!raySphere(ray, centre, R, ta, tb)) return false;
    if (tb <= ray.tnear || ta >= ray.tfar) return false;
    double s;
    const auto F = [&](double t) { return roundLinearDistance(ray.origin + t * ray.dir, p0, p1, s); };
    // Golden-section search for the minimum of the convex F on [ta, tb]; 90
    // steps shrink the bracket by 0.618^90 ≈ 1e-19, below double's resolution.
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = ta, hi = tb;
    double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    double f1 = F(m1), f2 = F(m2);
    for (int i = 0; i < 90 && f1 > 0.0 && f2 > 0.0; ++i) {
        if (f1 < f2) {
            hi = m2, m2 = m1, f2 = f1;
            m1 = hi - g * (hi - lo), f1 = F(m1);
        } else {
            lo = m1, m1 = m2, f1 = f2;
            m2 = lo + g * (hi - lo), f2 = F(m2);
        }
    }
    const double tMin = f1 <= f2 ? m1 : m2;
    if (F(tMin) > 0.0) return false;
    // F >= 0 on the bounding sphere, <= 0 at tMin: one root on each side.
    const auto bisect = [&](double outside, double inside) {
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (outside + inside);
            if (mid == outside || mid == inside) break;
            (F(mid) > 0.0 ? outside : inside) = mid;
        }
        return outside;
    };
    const double roots[2] = {bisect(ta, tMin), bisect(tb, tMin)};
    for (double t : roots) {
        if (!(t > ray.tnear && t < ray.tfar)) continue;
        const DVec3 x = ray.origin + t * ray.dir;
        roundLinearDistance(x, p0, p1, s);
        const DVec3 n = x - (xyz(p0) + s * (xyz(p1) - xyz(p0)));
        hit.t = t;
        hit.u = s;
        hit.v = 0.0;
        hit.Ng = n;
        return true;
    }
    return false;
}

// ---- flat -----------------------------------------------------------------------
//
// A piece [ua, ub] of the curve becomes the quad lp0 lp1 up1 up0 with
// lp = C + r n, up = C − r n, n = normalize(C' × d): perpendicular to the ray
// and to the curve as the ray sees it. The quad is the two triangles
// (lp0, lp1, up0) and (up1, up0, lp1); (U, V) ∈ [0, 1]² run along the piece
// and from lp to up, so v = 2V − 1 is −1 on the lp side.

namespace {

// Möller–Trumbore (double_triangle.h) on the ray's origin and direction.
bool rayTriangle(const DRay& ray, const DVec3& v0, const DVec3& v1, const DVec3& v2, double& t, double& b1,
                 double& b2) {
    return geometry_detail::rayTriangle(ray.origin, ray.dir, v0, v1, v2, t, b1, b2);
}

// Embree ignores flat-curve hits nearer to the ray's origin than twice the
// radius (its default self-intersection avoidance factor, 2).
bool beyondSelf(const DRay& ray, double t, double r) { return t * glm::length(ray.dir) > 2.0 * r; }

}  // namespace

bool intersectFlatCubic(const DRay& ray, const DVec4 b[4], int pieces, RefHit& hit) {
    bool found = false;
    double tBest = ray.tfar;
    Eval a = evalBezier(b, 0.0);
    for (int i = 0; i < pieces; ++i) {
        const Eval e = evalBezier(b, double(i + 1) / pieces);
        const DVec3 na = glm::cross(xyz(a.dp), ray.dir), ne = glm::cross(xyz(e.dp), ray.dir);
        const double la = glm::length(na), le = glm::length(ne);
        if (la > 0.0 && le > 0.0) {
            const DVec3 lp0 = xyz(a.p) + (a.p.w / la) * na, up0 = xyz(a.p) - (a.p.w / la) * na;
            const DVec3 lp1 = xyz(e.p) + (e.p.w / le) * ne, up1 = xyz(e.p) - (e.p.w / le) * ne;
            double t, b1, b2, U = 0.0, V = 0.0;
            bool hitPiece = false;
            if (rayTriangle(ray, lp0, lp1, up0, t, b1, b2) && t > ray.tnear && t < tBest) {
                U = b1, V = b2, hitPiece = true;
            } else if (rayTriangle(ray, up1, up0, lp1, t, b1, b2) && t > ray.tnear && t < tBest) {
                U = 1.0 - b1, V = 1.0 - b2, hitPiece = true;
            }
            if (hitPiece && beyondSelf(ray, t, a.p.w + U * (e.p.w - a.p.w))) {
                tBest = t;
                found = true;
                hit.t = t;
                hit.u = (i + U) / pieces;
                hit.v = 2.0 * V - 1.0;
                hit.Ng = xyz(evalBezier(b, hit.u).dp);
            }
        }
        a = e;
    }
    return found;
}

bool intersectFlatLinear(const DRay& ray, const DVec4& p0, const DVec4& p1, RefHit& hit) {
    // Project onto the plane through the origin normal to the ray.
    const double dd = glm::dot(ray.dir, ray.dir);
    const auto flatten = [&](const DVec3& x) {
        const DVec3 q = x - ray.origin;
        return q - ray.dir * (glm::dot(q, ray.dir) / dd);
    };
    const DVec3 q0 = flatten(xyz(p0)), q1 = flatten(xyz(p1));
    const DVec3 v = q1 - q0;
    const double vv = glm::dot(v, v);
    const double u = vv > 0.0 ? std::clamp(-glm::dot(q0, v) / vv, 0.0, 1.0) : 0.0;
    const DVec4 p = p0 + u * (p1 - p0);
    const DVec3 q = q0 + u * v;
    if (glm::dot(q, q) > p.w * p.w) return false;
    const double t = glm::dot(xyz(p) - ray.origin, ray.dir) / dd;
    if (!(t > ray.tnear && t < ray.tfar) || !beyondSelf(ray, t, p.w)) return false;
    hit.t = t;
    hit.u = u;
    hit.v = 0.0;
    hit.Ng = xyz(p1 - p0);
    return true;
}

// ---- oriented ------------------------------------------------------------------

bool orientedFrame(const DVec4 b[4], const DVec4 nb[4], OrientedFrame& frame) {
    // r k and its derivative at one end, from the curve and the normal there.
    const auto across = [](const Eval& c, const Eval& n, DVec3& rk, DVec3& drk) {
        const DVec3 bt = glm::cross(xyz(n.p), xyz(c.dp));
        // Embree takes C'' as zero here (its documentation: large
        // curvatures would otherwise thicken the ribbon).
        const DVec3 dbt = glm::cross(xyz(n.dp), xyz(c.dp));
        const double len = glm::length(bt);
        if (!(len > 0.0)) return false;
        const DVec3 k = bt / len;
        const DVec3 dk = (dbt - k * glm::dot(k, dbt)) / len;
        rk = c.p.w * k;
        drk = c.dp.w * k + c.p.w * dk;
        return true;
    };
    DVec3 rk0, drk0, rk1, drk1;
    if (!across(evalBezier(b, 0.0), evalBezier(nb, 0.0), rk0, drk0) ||
        !across(evalBezier(b, 1.0), evalBezier(nb, 1.0), rk1, drk1))
        return false;
    frame.w[0] = rk0;
    frame.w[1] = rk0 + drk0 / 3.0;
    frame.w[2] = rk1 - drk1 / 3.0;
    frame.w[3] = rk1;
    return true;
}

DVec3 orientedWidth(const OrientedFrame& frame, double u, DVec3* derivative) {
    const double v = 1.0 - u;
    const DVec3* w = frame.w;
    if (derivative)
        *derivative = 3.0 * (v * v * (w[1] - w[0]) + 2.0 * u * v * (w[2] - w[1]) + u * u * (w[3] - w[2]));
    return v * v * v * w[0] + 3.0 * u * v * v * w[1] + 3.0 * u * u * v * w[2] + u * u * u * w[3];
}

bool intersectOrientedCubic(const DRay& ray, const DVec4 b[4], const OrientedFrame& frame, RefHit& hit) {
    // f(u) = (C(u) - o) . (W(u) x d): zero where the ray meets the line across.
    const auto f = [&](double u) {
        return glm::dot(xyz(evalBezier(b, u).p) - ray.origin, glm::cross(orientedWidth(frame, u), ray.dir));
    };
    constexpr int kIntervals = 128;  // a degree-6 polynomial: two roots closer than 1/128 are a graze
    bool found = false;
    double tBest = ray.tfar;
    double u0 = 0.0, f0 = f(0.0);
    for (int i = 1; i <= kIntervals; ++i) {
        const double u1 = double(i) / kIntervals, f1 = f(u1);
        if ((f0 <= 0.0) != (f1 <= 0.0) || f0 == 0.0) {
            double lo = u0, hi = u1, flo = f0;
            for (int k = 0; k < 60 && flo != 0.0; ++k) {
                const double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm <= 0.0) == (flo <= 0.0)) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            const double u = flo == 0.0 ? lo : 0.5 * (lo + hi);
            const Eval e = evalBezier(b, u);
            DVec3 dW;
            const DVec3 W = orientedWidth(frame, u, &dW);
            const DVec3 q = xyz(e.p) - ray.origin, wd = glm::cross(W, ray.dir);
            const double wd2 = glm::dot(wd, wd);
            if (wd2 > 0.0) {
                // o + t d = C + s W: cross with W gives t, with d gives s.
                const double t = glm::dot(glm::cross(q, W), glm::cross(ray.dir, W)) / wd2;
                const double s = -glm::dot(glm::cross(q, ray.dir), wd) / wd2;
                if (std::abs(s) <= 1.0 && t > ray.tnear && t < tBest) {
                    tBest = t;
                    found = true;
                    hit.t = t;
                    hit.u = u;
                    hit.v = s;
                    hit.Ng = glm::cross(xyz(e.dp) + s * dW, W);
                }
            }
        }
        u0 = u1;
        f0 = f1;
    }
    return found;
}

}  // namespace strahl::curve
