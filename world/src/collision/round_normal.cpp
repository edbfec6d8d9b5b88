// The normal of least overlap of two round shapes by Newton's method. The overlap along
// a unit n is hA(n) + hB(-n), h being a shape's support function; for these shapes h is
// the centre's projection plus two closed-form terms:
//
//     sphere    c.n + r |n|
//     capsule   c.n + half |a.n| + r |n|
//     cylinder  c.n + half |a.n| + r |n - (a.n) a|
//
// (a the unit axis, half the half length). Their gradient is the support point and their
// Hessians are the curvature of the surfaces' round parts: r (I - n n') for a sphere's,
// r / |Pn| (P - q q') for a cylinder's (P = I - a a', q = Pn / |Pn|). On the unit sphere of
// normals, a minimum has the support points' difference along n, and Newton's step solves
// (B'HB - f I) u = -B'x in a basis B of the tangent plane (f the overlap, x its gradient).
//
// The Hessian is not positive where the overlap exceeds the surfaces' curvature; there
// Levenberg's damping makes the step one of descent, and each step is halved until the
// overlap falls.
//
// Where a.n changes sign, |a.n| has a crease: the normals across a capsule's or a
// cylinder's side. Many minima lie on it (a rim on a side), so a step that would cross
// it stops on it, and the descent goes on along the crease (its tangent the one basis
// vector) until the crease's multiplier (what half |a.n| must add along a to make the
// gradient lie along n) exceeds half; parallel axes share one crease. Where Pn vanishes
// (n along a cylinder's axis: its cap) r |Pn| is a cone: n is a minimum unless the other
// terms' gradient across the axis is steeper than r.
#include "collision/round_normal.h"

#include <cmath>

namespace cyclone::detail {
namespace {

// Newton steps at most: from a candidate's normal 2.9 on average (mixed1000).
constexpr int kMaxNewtonSteps = 12;
// Halvings of a step that does not lower the overlap.
constexpr int kMaxNewtonHalvings = 8;
// A cylinder whose |Pn| is below this shows its cap.
constexpr real kNewtonCapTilt = 1e-9;
// n lies on a crease when |a.n| is below this.
constexpr real kOnCrease = 1e-12;
// How far n moves off a cap's normal that is no minimum, rad.
constexpr real kCapLeave = 1e-3;
// A step shorter than this (rad) ends the descent: rounding.
constexpr real kMinNewtonStep = 1e-12;
// The least curvature (m per rad^2) of the damped model: below, Levenberg's damping.
constexpr real kMinNewtonCurvature = 1e-9;
// Damped steps are no longer than this, rad.
constexpr real kMaxNewtonTurn = 0.5;
// Times the damping grows to leave a crease on the falling side.
constexpr int kMaxNewtonDampings = 8;
// A step found no lower when shorter than this (rad) is rounding, not a stuck descent.
constexpr real kRoundingTurn = 1e-7;

// One shape's support function along n, for A, or along -n, for B (its centre negated:
// the other terms are even in n).
struct RoundTerm {
    Vector3 centre;
    Vector3 axis;
    real half;
    real radius;
    bool cylinder;
};

RoundTerm roundTerm(const CollisionShape &shape, const Matrix4 &pose, real side) {
    const Shape &s = shape.shape();
    return RoundTerm{side * pose.translation(), pose.linear().col(2), s.type == ShapeType::Sphere ? 0 : s.length / 2,
                     s.radius, s.type == ShapeType::Cylinder};
}

real overlapOf(const RoundTerm (&terms)[2], const Vector3 &n) {
    real sum = 0;
    for (const RoundTerm &t : terms) {
        const real along = t.axis.dot(n);
        sum += t.centre.dot(n) + t.half * std::abs(along) + t.radius * (t.cylinder ? (n - along * t.axis).norm() : 1);
    }
    return sum;
}

// The overlap's gradient and its Hessian at unit n. A term on its crease leaves out
// its half |a.n| part, whose gradient lies along a (off the crease); a cylinder's term
// at its cap's normal (`cap`, its index) leaves out its round part, which has no
// gradient there.
struct Slope {
    Vector3 gradient = Vector3::Zero();
    Matrix3 hessian = Matrix3::Zero();
    int cap = -1;
};

Slope slopeAt(const RoundTerm (&terms)[2], const bool (&crease)[2], const real (&side)[2], const Vector3 &n) {
    Slope s;
    for (int k = 0; k < 2; ++k) {
        const RoundTerm &t = terms[k];
        s.gradient += t.centre;
        if (!crease[k]) s.gradient += side[k] * t.half * t.axis;
        if (!t.cylinder) {
            s.gradient += t.radius * n;
            s.hessian += t.radius * (Matrix3::Identity() - n * n.transpose());
            continue;
        }
        const Vector3 across = n - t.axis.dot(n) * t.axis;
        const real tilt = across.norm();
        if (tilt < kNewtonCapTilt) {
            s.cap = k;
            continue;
        }
        const Vector3 q = across / tilt;
        s.gradient += t.radius * q;
        s.hessian += (t.radius / tilt) * (Matrix3::Identity() - t.axis * t.axis.transpose() - q * q.transpose());
    }
    return s;
}

// The overlap's second-order model in the tangent plane of n: its Hessian M and gradient
// g in the basis t1, t2, or along the crease of `creaseAxis` (if not zero) in t1 alone.
struct Model {
    Vector3 t1, t2;
    bool crease;
    real m11, m12, m22, g1, g2;

    Model(const Slope &slope, real f, const Vector3 &n, const Vector3 &creaseAxis) : crease(creaseAxis != Vector3::Zero()) {
        t1 = crease ? Vector3(n.cross(creaseAxis).normalized()) : n.unitOrthogonal();
        t2 = crease ? Vector3::Zero() : Vector3(n.cross(t1));
        m11 = t1.dot(slope.hessian * t1) - f;
        m12 = t1.dot(slope.hessian * t2);
        m22 = crease ? 1 : t2.dot(slope.hessian * t2) - f;
        g1 = t1.dot(slope.gradient);
        g2 = t2.dot(slope.gradient);
    }

    real leastEigenvalue() const {
        if (crease) return m11;
        const real mean = (m11 + m22) / 2, spread = std::hypot((m11 - m22) / 2, m12);
        return mean - spread;
    }

    // The damped Newton step -(M + mu I)^-1 g (Levenberg's; mu makes M + mu I positive
    // definite), no longer than kMaxNewtonTurn.
    Vector3 step(real mu) const {
        Vector3 s;
        if (crease) {
            s = -(g1 / (m11 + mu)) * t1;
        } else {
            const real a = m11 + mu, d = m22 + mu, det = a * d - m12 * m12;
            s = -((d * g1 - m12 * g2) / det) * t1 - ((a * g2 - m12 * g1) / det) * t2;
        }
        const real length = s.norm();
        return length > kMaxNewtonTurn ? Vector3(s * (kMaxNewtonTurn / length)) : s;
    }
};

// The descent's state: the terms, which creases n lies on, the sign of a.n taken for
// each term off its crease, and n with its overlap f.
struct Descent {
    RoundTerm terms[2];
    bool crease[2];
    real side[2];
    Vector3 n;
    real f;
};

// Moves n to `to` (overlap `value`): a term is on its crease where `to` lies on it, and
// takes its side off the crease from `to`.
void moveTo(Descent &d, const Vector3 &to, real value) {
    d.n = to;
    d.f = value;
    for (int k = 0; k < 2; ++k) {
        const real along = d.terms[k].axis.dot(to);
        d.crease[k] = d.terms[k].half > 0 && std::abs(along) < kOnCrease;
        if (along != 0) d.side[k] = along > 0 ? 1 : -1;
    }
}

enum class Move {
    Moved,    ///< n moved to a lower overlap.
    Settled,  ///< At a minimum, a cap, two creases, or rounding.
    Stuck     ///< No lower overlap along a step longer than rounding.
};

// Whether the two terms' axes are parallel (within about 3e-5 rad).
bool parallelAxes(const Descent &d) {
    const real c = d.terms[0].axis.dot(d.terms[1].axis);
    return !(1 - c * c > kMinNewtonCurvature);
}

// Two parallel axes have one crease, whose multiplier the two halves share: both are
// left together when it exceeds their sum. Returns 0 when they are left, or -1.
int leaveParallelCreases(Descent &d, Slope &slope) {
    const Vector3 &a = d.terms[0].axis;
    const real lambda = -slope.gradient.dot(a);
    if (!(std::abs(lambda) > d.terms[0].half + d.terms[1].half)) return -1;
    for (int k = 0; k < 2; ++k) {
        d.crease[k] = false;
        d.side[k] = lambda * a.dot(d.terms[k].axis) > 0 ? 1 : -1;
        slope.gradient += d.side[k] * d.terms[k].half * d.terms[k].axis;
    }
    return 0;
}

// Leaves a crease whose multiplier exceeds its half, towards the side the overlap falls,
// adding that side's gradient. On its crease a term's half |a.n| adds lambda a to the
// gradient, |lambda| <= half, and n is a minimum when those make the gradient lie along
// n: lambda = -(gradient . a) for one crease, a 2 x 2 system for two (a0 and a1 both
// across n). A multiplier beyond the half means the overlap falls off the crease towards
// its sign. Returns the crease left, or -1.
int leaveCrease(Descent &d, Slope &slope) {
    real lambda[2] = {0, 0};
    if (d.crease[0] && d.crease[1]) {
        if (parallelAxes(d)) return leaveParallelCreases(d, slope);
        const real c = d.terms[0].axis.dot(d.terms[1].axis), det = 1 - c * c;
        const real r0 = -slope.gradient.dot(d.terms[0].axis), r1 = -slope.gradient.dot(d.terms[1].axis);
        lambda[0] = (r0 - c * r1) / det;
        lambda[1] = (r1 - c * r0) / det;
    } else {
        for (int k = 0; k < 2; ++k)
            if (d.crease[k]) lambda[k] = -slope.gradient.dot(d.terms[k].axis);
    }
    const real excess0 = std::abs(lambda[0]) - d.terms[0].half, excess1 = std::abs(lambda[1]) - d.terms[1].half;
    const int k = excess0 >= excess1 ? 0 : 1;
    if (!d.crease[k] || !(std::max(excess0, excess1) > 0)) return -1;
    d.crease[k] = false;
    d.side[k] = lambda[k] > 0 ? 1 : -1;
    slope.gradient += d.side[k] * d.terms[k].half * d.terms[k].axis;
    return k;
}

// Whether a step that carries n past a cylinder's axis reaches its cap's normal at a lower
// overlap; if so n moves there.
bool reachCap(Descent &d, const Vector3 &step) {
    for (const RoundTerm &t : d.terms) {
        if (!t.cylinder) continue;
        const real along = t.axis.dot(d.n);
        const Vector3 across = d.n - along * t.axis;
        if (!(step.dot(across) < -across.squaredNorm())) continue;
        const Vector3 cap = along >= 0 ? t.axis : Vector3(-t.axis);
        const real value = overlapOf(d.terms, cap);
        if (!(value < d.f)) continue;
        moveTo(d, cap, value);
        return true;  // leaveCap decides there whether it is a minimum
    }
    return false;
}

// Moves n along `step` to a lower overlap, stopping on the first crease the step crosses
// and halving it while the overlap does not fall.
Move lineSearch(Descent &d, const Vector3 &step) {
    real reach = 1;
    int hit = -1;
    for (int k = 0; k < 2; ++k) {
        if (d.crease[k] || d.terms[k].half <= 0) continue;
        // A crease just left (n on it within rounding) is not crossed.
        const real before = d.terms[k].axis.dot(d.n), after = d.terms[k].axis.dot(d.n + step);
        if (std::abs(before) < kOnCrease || before * after >= 0 || after == 0) continue;
        const real t = before / (before - after);
        if (t < reach) reach = t, hit = k;
    }
    for (int halving = 0; halving <= kMaxNewtonHalvings; ++halving, reach /= 2, hit = -1) {
        Vector3 candidate = d.n + reach * step;
        if (hit >= 0) candidate -= d.terms[hit].axis.dot(candidate) * d.terms[hit].axis;
        candidate.normalize();
        const real value = overlapOf(d.terms, candidate);
        if (!(value < d.f)) continue;
        const real moved = (candidate - d.n).norm();
        moveTo(d, candidate, value);
        return moved < kMinNewtonStep ? Move::Settled : Move::Moved;
    }
    return 2 * reach * step.norm() < kRoundingTurn ? Move::Settled : Move::Stuck;
}

// At a cylinder's cap's normal its round part r |Pn| is a cone: n is a minimum if the
// other terms' gradient across the axis is no steeper than r; else the overlap falls
// along that gradient's negative, and n moves off the cap a little that way.
Move leaveCap(Descent &d, const Slope &slope) {
    const RoundTerm &t = d.terms[slope.cap];
    const Vector3 across = slope.gradient - slope.gradient.dot(t.axis) * t.axis;
    const real steepness = across.norm();
    if (steepness <= t.radius) return Move::Settled;
    // Shorter moves where a crease lies close by.
    for (real turn = kCapLeave; turn > kRoundingTurn; turn /= 10) {
        const Vector3 candidate = (d.n - turn * across / steepness).normalized();
        const real value = overlapOf(d.terms, candidate);
        if (!(value < d.f)) continue;
        moveTo(d, candidate, value);
        return Move::Moved;
    }
    return Move::Settled;
}

Move stepOnce(Descent &d) {
    Slope slope = slopeAt(d.terms, d.crease, d.side, d.n);
    if (slope.cap >= 0) return leaveCap(d, slope);
    const int left = leaveCrease(d, slope);
    // Two creases meet in two normals, where n then is, unless the axes are parallel.
    if (d.crease[0] && d.crease[1] && !parallelAxes(d)) return Move::Settled;
    const Vector3 creaseAxis = d.crease[0] ? d.terms[0].axis : d.crease[1] ? d.terms[1].axis : Vector3::Zero();
    const Model model(slope, d.f, d.n, creaseAxis);
    real mu = std::max<real>(0, kMinNewtonCurvature - model.leastEigenvalue());
    Vector3 step = model.step(mu);
    // A crease just left must be left on the side the overlap falls: more damping turns
    // the step towards the gradient's, which does.
    const real scale = std::abs(model.m11) + std::abs(model.m12) + std::abs(model.m22) + kMinNewtonCurvature;
    for (int k = 0; k < kMaxNewtonDampings && left >= 0 && d.side[left] * d.terms[left].axis.dot(step) <= 0; ++k)
        step = model.step(mu = 4 * mu + scale);
    if (left >= 0 && d.side[left] * d.terms[left].axis.dot(step) <= 0) return Move::Stuck;
    if (reachCap(d, step)) return Move::Moved;
    return lineSearch(d, step);
}

}  // namespace

bool roundNormalPair(ShapeType a, ShapeType b) {
    auto round = [](ShapeType t) {
        return t == ShapeType::Sphere || t == ShapeType::Capsule || t == ShapeType::Cylinder;
    };
    return round(a) && round(b) && (a == ShapeType::Cylinder || b == ShapeType::Cylinder);
}

bool roundNormal(const Pair &pair, Vector3 &normal, real &overlap) {
    Descent d{{roundTerm(pair.a, pair.poseA, 1), roundTerm(pair.b, pair.poseB, -1)}, {false, false}, {1, 1}, normal, 0};
    moveTo(d, normal, overlapOf(d.terms, normal));
    Move move = Move::Moved;
    for (int iteration = 0; iteration < kMaxNewtonSteps && move == Move::Moved; ++iteration) move = stepOnce(d);
    const real exact = pair.overlap(d.n);
    if (exact < overlap) normal = d.n, overlap = exact;
    return move == Move::Settled;
}

}  // namespace cyclone::detail
