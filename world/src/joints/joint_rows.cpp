// Each joint type's rows at the bodies' current poses.
//
// Conventions: a row's value is a function C of the two poses whose rate is
// J v = linA.v_a + angA.w_a + linB.v_b + angB.w_b. Positions are a's relative to b's
// frame (the world without b): the anchors' gap is p_a - p_b, a hinge's angle is a's
// turn about b's axis, a slider's offset is (p_a - p_b).n with n turning with b.
//  - A direction t fixed in b, C = t.(p_a - p_b): d/dt gives linA = t, angA = r_a x t,
//    linB = -t and angB = -((p_a - x_b) x t), since t turns with w_b.
//  - A rotation lock about e: angA = e, angB = -e, C the component of the rotation
//    from a's reference orientation to its current one (2 vec(q_e), w >= 0).
//  - A hinge's axis lock: t perpendicular to b's axis n_b, C = (n_b x n_a).t, whose rate
//    is (w_a - w_b).t while the axes agree.
#include <algorithm>
#include <cmath>

#include "joints/joint_set.h"

namespace cyclone::detail {
namespace {

// Two unit vectors completing the unit `n` to an orthonormal basis.
void perpendiculars(const Vector3 &n, Vector3 *t1, Vector3 *t2) {
    const Vector3 helper = std::abs(n.x()) < 0.57 ? Vector3::UnitX() : Vector3::UnitY();
    *t1 = n.cross(helper).normalized();
    *t2 = n.cross(*t1);
}

// The poses a joint's rows are made from.
struct JointFrame {
    Vector3 xa, xb;          ///< Centres of mass (x_b: zero without b), m.
    Quaternion qa, qb;       ///< Orientations (q_b: identity without b).
    Vector3 pa, pb;          ///< The anchors in world space, m.
    Vector3 axis;            ///< b's axis in world space.
};

JointFrame frameOf(const BodyStore &bodies, const JointRecord &j) {
    JointFrame f;
    const RigidBody &a = bodies[j.settings.a.index].body;
    f.xa = a.getPosition();
    f.qa = a.getOrientation();
    f.pa = a.getPointInWorldSpace(j.localA);
    if (j.settings.b) {
        const RigidBody &b = bodies[j.settings.b->index].body;
        f.xb = b.getPosition();
        f.qb = b.getOrientation();
        f.pb = b.getPointInWorldSpace(j.localB);
        f.axis = b.getDirectionInWorldSpace(j.axisB);
    } else {
        f.xb = Vector3::Zero();
        f.qb = Quaternion::Identity();
        f.pb = j.localB;
        f.axis = j.axisB;
    }
    return f;
}

// The rotation that takes a from its reference orientation (relative to b) to its
// current one, as a world-space rotation vector (small-angle: 2 vec(q)).
Vector3 rotationError(const JointFrame &f, const JointRecord &j) {
    Quaternion e = f.qa * j.reference.conjugate() * f.qb.conjugate();
    if (e.w() < 0) e.coeffs() = -e.coeffs();
    return 2 * e.vec();
}

// a's turn about b's axis since creation, rad, in (-pi, pi].
real hingeAngle(const JointFrame &f, const JointRecord &j) {
    const Quaternion delta = f.qb.conjugate() * f.qa * j.reference.conjugate();
    real angle = 2 * std::atan2(delta.vec().dot(j.axisB), delta.w());
    if (angle > M_PI) angle -= 2 * M_PI;
    if (angle <= -M_PI) angle += 2 * M_PI;
    return angle;
}

// Appends rows to `out` and fills their Jacobians; the caller completes them.
class RowMaker {
public:
    RowMaker(std::vector<JointRow> &out, const JointFrame &f, int a, int b, std::uint32_t joint)
        : out_(out), f_(f), a_(a), b_(b), joint_(joint) {}

    // C = t.(p_a - p_b), t fixed in b.
    JointRow &linear(int slot, const Vector3 &t) {
        JointRow &r = add(slot);
        r.linA = t;
        r.angA = (f_.pa - f_.xa).cross(t);
        r.linB = -t;
        r.angB = -(f_.pa - f_.xb).cross(t);
        r.error = t.dot(f_.pa - f_.pb);
        return r;
    }
    // A rotation row about e with the value `error`.
    JointRow &angular(int slot, const Vector3 &e, real error) {
        JointRow &r = add(slot);
        r.angular = true;
        r.angA = e;
        r.angB = -e;
        r.error = error;
        return r;
    }

private:
    JointRow &add(int slot) {
        out_.emplace_back();
        JointRow &r = out_.back();
        r.a = a_;
        r.b = b_;
        r.joint = joint_;
        r.slot = slot;
        return r;
    }
    std::vector<JointRow> &out_;
    const JointFrame &f_;
    int a_, b_;
    std::uint32_t joint_;
};

// Makes a limit row a spring of `spring` (none: rigid).
void springOf(JointRow &r, const std::optional<JointSpring> &spring) {
    if (!spring) return;
    r.frequency = spring->frequency;
    r.dampingRatio = spring->dampingRatio;
}

// The limit rows of a value (hinge angle, slider offset, twist); `row(slot)` makes a row
// whose rate is the value's. In the position pass only a violated rigid limit has a row
// (a soft one is a spring: it has none).
template <class MakeRow>
void addLimits(const JointLimits &limits, const std::optional<JointSpring> &spring, int slot, bool positions,
               const MakeRow &row, real value) {
    if (positions && spring) return;
    const real lower = value - limits.lower;  // >= 0 within the range
    const real upper = value - limits.upper;  // <= 0 within the range
    if (!positions || lower < 0) {
        JointRow &r = row(slot);
        r.bound = RowBound::Lower;
        r.error = lower;
        springOf(r, spring);
    }
    if (!positions || upper > 0) {
        JointRow &r = row(slot + 1);
        r.bound = RowBound::Upper;
        r.error = upper;
        springOf(r, spring);
    }
}

// A motor's row in `slot`, made by `row` along the joint's free axis: it drives the
// relative speed along it to the motor's, with at most maxForce over the sub-step `h`.
template <class MakeRow>
void addMotor(const JointMotor &motor, int slot, const MakeRow &row, real h) {
    JointRow &r = row(slot);
    r.bound = RowBound::Motor;
    r.target = motor.speed;
    r.maxImpulse = motor.maxForce * h;
}

// A servo's row in `slot`: a spring pulling `value` (angle or offset) to its target, with
// at most maxForce over the sub-step `h`; a hinge measures the error the short way round
// (`period` 2 pi; 0: none).
template <class MakeRow>
void addServo(const JointServo &servo, int slot, const MakeRow &row, real h, real value, real period) {
    JointRow &r = row(slot);
    r.bound = RowBound::Motor;
    r.maxImpulse = servo.maxForce * h;
    real error = value - servo.target;
    if (period > 0) error = std::remainder(error, period);
    r.error = error;
    r.frequency = servo.frequency;
    r.dampingRatio = servo.dampingRatio;
}

// A ball joint's swing row: b's twist axis n_m leans from a's n_c by theta in the
// direction d (unit, perpendicular to n_c), at phi from a's normal. The cone allows
// theta_max(phi) = 1 / E(phi), E = sqrt((cos phi / A)^2 + (sin phi / B)^2); the row's
// value is C = theta - theta_max(phi) (<= 0 within the cone). With w = w_b - w_a and
// s = n_c x d, theta's rate is w.s and phi's is w.(n_c - cot theta d); the row takes the
// rate of F = theta E(phi) over E, exact on the cone (F = 1) and bounded near its axis:
// J = s + (E'/E)(theta n_c - theta cot theta d), E' = dE/dphi. Returns false (no row)
// when the lean has no direction (theta ~ 0, far inside the cone, or ~ pi).
bool swingRow(const JointFrame &f, const JointRecord &j, Vector3 *jacobian, real *error) {
    const JointSwingLimit &cone = *j.settings.swingLimit;
    const Vector3 nc = f.qa * j.axisA;
    const Vector3 normal = f.qa * j.normalA;
    const Vector3 nm = f.axis;
    const Vector3 across = nc.cross(nm);
    const real sine = across.norm();
    if (!(sine > 1e-9)) return false;
    const real theta = std::atan2(sine, nc.dot(nm));
    const Vector3 s = across / sine;
    const Vector3 d = s.cross(nc);
    const real c = d.dot(normal), sn = d.dot(nc.cross(normal));
    const real ia = 1 / cone.normalAngle, ib = 1 / cone.binormalAngle;
    const real e = std::sqrt(c * c * ia * ia + sn * sn * ib * ib);
    const real eDash = c * sn * (ib * ib - ia * ia) / e;
    const real thetaCot = theta * nc.dot(nm) / std::max(sine, real(1e-3));
    *jacobian = s + (eDash / e) * (theta * nc - thetaCot * d);
    *error = theta - 1 / e;
    return true;
}

// The three rows that hold the anchors together (slots 0 to 2).
void pointRows(RowMaker &make) {
    for (int k = 0; k < 3; ++k) make.linear(k, Vector3::Unit(k));
}

// The three rows that hold a's orientation relative to b (slots `slot` to `slot` + 2).
void rotationLockRows(RowMaker &make, const JointFrame &f, const JointRecord &j, int slot) {
    const Vector3 e = rotationError(f, j);
    for (int k = 0; k < 3; ++k) make.angular(slot + k, Vector3::Unit(k), e[k]);
}

// A ball joint: the point, its swing cone (slot 3), its twist limits (4, 5) and its
// friction about the world axes (6 to 8).
void ballRows(RowMaker &make, const JointFrame &f, const JointRecord &j, real h, bool positions) {
    const JointSettings &s = j.settings;
    pointRows(make);
    Vector3 swing;
    real swingError = 0;
    if (s.swingLimit && swingRow(f, j, &swing, &swingError) && (!positions || (swingError > 0 && !s.limitSpring))) {
        JointRow &r = make.angular(3, Vector3::Zero(), swingError);
        r.angA = -swing;
        r.angB = swing;
        r.bound = RowBound::Upper;
        springOf(r, s.limitSpring);
    }
    const Vector3 na = f.qa * j.axisA;
    const real sum = 1 + na.dot(f.axis);
    if (s.twistLimit && sum > 1e-6) {
        // The twist's rate is (w_a - w_b).(n_a + n_b) / (1 + n_a.n_b) (docs/joints.md).
        const Vector3 about = (na + f.axis) / sum;
        const real twist = hingeAngle(f, j);
        const auto row = [&](int slot) -> JointRow & { return make.angular(slot, about, twist); };
        addLimits(*s.twistLimit, s.limitSpring, 4, positions, row, twist);
    }
    if (s.friction > 0 && !positions)
        for (int k = 0; k < 3; ++k) {
            // A rotation row about world axis k (its value is not used).
            const auto about = [&make, k](int slot) -> JointRow & { return make.angular(slot, Vector3::Unit(k), 0); };
            addMotor(JointMotor{0, s.friction}, 6 + k, about, h);
        }
}

// A hinge: the point, the axis (slots 3, 4), its limits (5, 6), its motor or servo (7)
// and its friction (8).
void hingeRows(RowMaker &make, const JointFrame &f, const JointRecord &j, real h, bool positions) {
    const JointSettings &s = j.settings;
    pointRows(make);
    Vector3 t1, t2;
    perpendiculars(f.axis, &t1, &t2);
    const Vector3 axisA = f.qa * j.axisA;
    const Vector3 tilt = f.axis.cross(axisA);
    make.angular(3, t1, tilt.dot(t1));
    make.angular(4, t2, tilt.dot(t2));
    const real angle = hingeAngle(f, j);
    const auto about = [&](int slot) -> JointRow & { return make.angular(slot, f.axis, angle); };
    if (s.limits) addLimits(*s.limits, s.limitSpring, 5, positions, about, angle);
    if (s.motor && !positions) addMotor(*s.motor, 7, about, h);
    if (s.servo && !positions) addServo(*s.servo, 7, about, h, angle, 2 * M_PI);
    if (s.friction > 0 && !positions) addMotor(JointMotor{0, s.friction}, 8, about, h);
}

// A slider: the anchors across the axis (slots 0, 1), the orientation (2 to 4), its
// limits (5, 6) and its motor or servo (7).
void sliderRows(RowMaker &make, const JointFrame &f, const JointRecord &j, real h, bool positions) {
    const JointSettings &s = j.settings;
    Vector3 t1, t2;
    perpendiculars(f.axis, &t1, &t2);
    make.linear(0, t1);
    make.linear(1, t2);
    rotationLockRows(make, f, j, 2);
    const real offset = (f.pa - f.pb).dot(f.axis);
    const auto along = [&](int slot) -> JointRow & { return make.linear(slot, f.axis); };
    if (s.limits) addLimits(*s.limits, s.limitSpring, 5, positions, along, offset);
    if (s.motor && !positions) addMotor(*s.motor, 7, along, h);
    if (s.servo && !positions) addServo(*s.servo, 7, along, h, offset, 0);
}

// A distance joint: one equality row when rigid at a single length, else its lower (slot
// 0) and upper (1) limits; a soft one (a spring) has no rows in the position pass.
void distanceRows(RowMaker &make, const JointFrame &f, const JointRecord &j, bool positions) {
    const Vector3 gap = f.pa - f.pb;
    const real d = gap.norm();
    // Without a direction the anchors coincide: a rope's lower limit of 0 is met.
    const Vector3 n = d > 1e-9 ? Vector3(gap / d) : Vector3::UnitY();
    const bool rigid = j.settings.stiffness == 0;
    if (rigid && j.minDistance == j.maxDistance) {
        if (d > 1e-9) make.linear(0, n).error = d - j.maxDistance;
        return;
    }
    const real lower = d - j.minDistance;
    const real upper = d - j.maxDistance;
    const bool lowerRow = j.minDistance > 0 && d > 1e-9 && (rigid ? !positions || lower < 0 : lower < 0);
    const bool upperRow = d > 1e-9 && (rigid ? !positions || upper > 0 : upper > 0);
    if (lowerRow && !(positions && !rigid)) {
        JointRow &r = make.linear(0, n);
        r.bound = RowBound::Lower;
        r.error = lower;
        r.soft = !rigid;
    }
    if (upperRow && !(positions && !rigid)) {
        JointRow &r = make.linear(1, n);
        r.bound = RowBound::Upper;
        r.error = upper;
        r.soft = !rigid;
    }
}

// A mouse joint: three pull rows (slots 0 to 2), a spring only: none in the position pass.
void mouseRows(RowMaker &make, const JointSettings &s, real h, bool positions) {
    if (positions) return;
    const real maxImpulse = s.pull.value_or(JointPull()).maxForce * h;
    for (int k = 0; k < 3; ++k) {
        JointRow &r = make.linear(k, Vector3::Unit(k));
        r.bound = RowBound::Pull;
        r.soft = true;
        r.maxImpulse = maxImpulse;
    }
}

// The rows of joint `j` by its type, Jacobians and values only.
void typeRows(RowMaker &make, const JointFrame &f, const JointRecord &j, real h, bool positions) {
    switch (j.settings.type) {
        case JointType::Ball: ballRows(make, f, j, h, positions); break;
        case JointType::Fixed:
            pointRows(make);
            rotationLockRows(make, f, j, 3);
            break;
        case JointType::Hinge: hingeRows(make, f, j, h, positions); break;
        case JointType::Slider: sliderRows(make, f, j, h, positions); break;
        case JointType::Distance: distanceRows(make, f, j, positions); break;
        case JointType::Mouse: mouseRows(make, j.settings, h, positions); break;
    }
}

// A joint's solver slots for a and b (0: not moving); false when neither is a simulated
// body, or either is isolated: then the joint has nothing to solve.
bool solvedPair(const BodyStore &bodies, const JointRecord &j, int *a, int *b) {
    const auto solverIndex = [](const BodyRecord &r) { return r.simulated || r.moving ? r.solverIndex : 0; };
    const BodyRecord &ra = bodies[j.settings.a.index];
    const BodyRecord *rb = j.settings.b ? &bodies[j.settings.b->index] : nullptr;
    if (ra.isolated || (rb && rb->isolated)) return false;
    *a = solverIndex(ra);
    *b = rb ? solverIndex(*rb) : 0;
    // Only simulated bodies move: a joint between two others has nothing to solve.
    return (*a >= 1 && ra.simulated) || (rb && *b >= 1 && rb->simulated);
}

// The spring of a joint's soft rows.
struct SoftRows {
    real stiffness;
    real damping;
};

// A joint's softness; a mouse joint's follows from its pull's frequency and a's mass.
SoftRows softRowsOf(const JointSettings &s, const SolverBody &sa) {
    SoftRows soft{s.stiffness, s.damping};
    if (s.type == JointType::Mouse && sa.invMass > 0) {
        const JointPull pull = s.pull.value_or(JointPull());
        const real mass = 1 / sa.invMass;
        const real omega = 2 * M_PI * pull.frequency;
        soft.stiffness = mass * omega * omega;
        soft.damping = 2 * mass * pull.dampingRatio * omega;
    }
    return soft;
}

// Completes row `r` over a sub-step `h`: M^-1 J^T, its effective mass, its softness and bias.
void completeRow(JointRow &r, const SolverBody &sa, const SolverBody &sb, const SoftRows &spring, real h) {
    r.mLinA = sa.invMass * r.linA;
    r.mAngA = sa.invInertia * r.angA;
    r.mLinB = sb.invMass * r.linB;
    r.mAngB = sb.invInertia * r.angB;
    const real k0 = r.linA.dot(r.mLinA) + r.angA.dot(r.mAngA) + r.linB.dot(r.mLinB) + r.angB.dot(r.mAngB);
    if (r.soft) {
        // Catto's soft constraint: the spring and damper over a sub-step, implicitly.
        const real hk = h * spring.stiffness;
        const real denominator = h * (spring.damping + hk);
        r.gamma = denominator > 0 ? 1 / denominator : 0;
        r.bias = r.error * hk * r.gamma;
    }
    r.mass = k0 + r.gamma > 0 ? 1 / (k0 + r.gamma) : 0;
    // A rigid limit may close what is left of its range within the sub-step, no more;
    // once violated, the position pass pushes it back (no bias: no energy).
    if (!r.soft && r.bound == RowBound::Lower) r.bias = std::max(r.error, real(0)) / h;
    if (!r.soft && r.bound == RowBound::Upper) r.bias = std::min(r.error, real(0)) / h;
}

}  // namespace

void JointSet::measure(const BodyStore &bodies, const JointRecord &j, real *error, real *position) const {
    const JointFrame f = frameOf(bodies, j);
    const Vector3 gap = f.pa - f.pb;
    *position = 0;
    switch (j.settings.type) {
        case JointType::Ball:
        case JointType::Fixed:
        case JointType::Mouse: *error = gap.norm(); break;
        case JointType::Hinge:
            *error = gap.norm();
            *position = hingeAngle(f, j);
            break;
        case JointType::Slider:
            *position = gap.dot(f.axis);
            *error = (gap - *position * f.axis).norm();
            break;
        case JointType::Distance: {
            const real d = gap.norm();
            *error = d > j.maxDistance ? d - j.maxDistance : (d < j.minDistance ? j.minDistance - d : 0);
            *position = d;
            break;
        }
    }
}

void JointSet::makeRows(const BodyStore &bodies, bool warmStarting, const std::vector<SolverBody> &solverBodies,
                        real h, bool positions) {
    const bool warmStart = !positions && warmStarting;
    rows_.clear();
    equality_.clear();
    bounded_.clear();
    pulls_.clear();
    for (std::uint32_t index = 0; index < records.size(); ++index) {
        const JointRecord &j = records[index];
        int a = 0, b = 0;
        if (!j.alive || !solvedPair(bodies, j, &a, &b)) continue;
        const JointFrame f = frameOf(bodies, j);
        RowMaker make(rows_, f, a, b, index);
        const std::size_t first = rows_.size();
        typeRows(make, f, j, h, positions);
        const SolverBody &sa = solverBodies[a];
        const SolverBody &sb = solverBodies[b];
        const SoftRows spring = softRowsOf(j.settings, sa);
        for (std::size_t k = first; k < rows_.size(); ++k) {
            JointRow &r = rows_[k];
            completeRow(r, sa, sb, spring, h);
            if (warmStart) r.impulse = j.impulse[r.slot];
            if (positions || r.bound == RowBound::Equality) equality_.push_back(static_cast<int>(k));
            else if (r.bound != RowBound::Pull) bounded_.push_back(static_cast<int>(k));
            else if (r.slot == 0) pulls_.push_back({static_cast<int>(k), Matrix3::Zero()});
        }
    }
}

}  // namespace cyclone::detail
