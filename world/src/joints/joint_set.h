// The World's joints: their records, and the rows the solver solves them with.
//
// Design note (measurements and what was tried: docs/joints.md). A joint is a set of
// scalar rows J v = target between its two bodies' velocities (joint_rows.cpp makes them
// at the poses of each sub-step). The rows that hold a joint together (the anchors'
// gap, the rotation locks, a rod's length) are equalities; limits, motors, ropes and soft
// distances are bounded. The equality rows of every joint are solved together, exactly,
// by a sparse LDL^T factorisation of J M^-1 J^T (Eigen's SimplicialLDLT): the joint graph
// is then one block of the velocity passes' block Gauss-Seidel, so a 100 kg body on a
// chain of 1 kg links is held as firmly as a light one, which sequential impulses cannot
// do in a few passes. The bounded rows are sequential impulses with clamped accumulated
// impulses, in the same passes. Everything is warm-started with the last sub-step's
// impulses. Drift is removed after each sub-step's integration by a Newton projection of
// the positions onto the equality rows (and the violated limits), with the same
// factorisation at the new poses: it moves positions only, so it adds no kinetic energy.
// A mouse joint's three rows are a soft spring bounded as a whole (the length of their
// impulse): they are solved together, as one 3x3 block, between the bounded rows and the
// direct block.
#pragma once

#include <Eigen/SparseCholesky>

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "cyclone/world/debug_draw.h"
#include "cyclone/world/events.h"
#include "cyclone/world/joints.h"
#include "cyclone/world/stats.h"
#include "solver/contact_solver.h"
#include "world/body_store.h"
#include "world/body_transitions.h"

namespace cyclone::detail {

struct StepContext;

/// Most rows a joint has: a slider's 2 across + 3 rotation locks + lower, upper, motor
/// (a ball joint: 3 + swing + twist lower, upper + 3 friction; a hinge's friction: 8).
inline constexpr int kMaxJointRows = 9;

/// Most Newton iterations of the position projection per sub-step (joint_set.cpp).
inline constexpr int kMaxProjections = 4;
/// The projection stops once every row's error is below this, m or rad.
inline constexpr real kProjectionTolerance = 1e-9;
/// Times a Newton step of the projection that leaves the sum of the squared row errors
/// larger than before is taken back and halved before the projection gives up for the
/// sub-step (near a singular pose a full step can be many times too long).
inline constexpr int kProjectionHalvings = 20;

struct JointRecord {
    JointSettings settings;      ///< As given, the axis normalised.
    std::uint32_t generation = 0;
    bool alive = false;
    Vector3 localA = Vector3::Zero();  ///< Anchor on a, a's body space, m.
    Vector3 localB = Vector3::Zero();  ///< Anchor on b, b's body space (world space without b), m.
    Vector3 axisA = Vector3::UnitY();  ///< Axis in a's body space.
    Vector3 axisB = Vector3::UnitY();  ///< Axis in b's body space (world space without b).
    Vector3 normalA = Vector3::UnitX();  ///< Ball joints' swing cone: its normal in a's body space.
    Quaternion reference = Quaternion::Identity();  ///< conj(q_b) q_a at creation.
    real minDistance = 0;  ///< Distance joints, m.
    real maxDistance = 0;
    real impulse[kMaxJointRows] = {};  ///< Each row slot's impulse in the last sub-step, N s (warm start).
    Vector3 linearImpulse = Vector3::Zero();   ///< On a, summed over this step's sub-steps, N s.
    Vector3 angularImpulse = Vector3::Zero();  ///< Of the angular rows on a, this step, N m s.
    Vector3 force = Vector3::Zero();   ///< Mean over the last step, N.
    Vector3 torque = Vector3::Zero();  ///< Mean over the last step, N m.
};

/// How a row's accumulated impulse is bounded.
enum class RowBound : std::uint8_t {
    Equality,  ///< Free: solved with the others exactly (the direct block).
    Lower,     ///< >= 0: keeps the value above a lower limit.
    Upper,     ///< <= 0: keeps the value below an upper limit.
    Motor,     ///< |impulse| <= maxImpulse: drives the rate to `target`.
    Pull,      ///< One of a mouse joint's three soft rows, whose impulse's length is <= maxImpulse.
};

/// One scalar constraint row of a joint during a sub-step.
struct JointRow {
    int a = 0, b = 0;  ///< Solver bodies (0: immovable).
    std::uint32_t joint = 0;
    int slot = 0;          ///< Index in JointRecord::impulse.
    RowBound bound = RowBound::Equality;
    bool angular = false;  ///< A rotation row (counted in the joint's torque).
    bool soft = false;     ///< A spring (distance stiffness): never in the position pass.
    Vector3 linA = Vector3::Zero(), angA = Vector3::Zero();  ///< J for a's v and w.
    Vector3 linB = Vector3::Zero(), angB = Vector3::Zero();  ///< J for b's v and w.
    Vector3 mLinA = Vector3::Zero(), mAngA = Vector3::Zero();  ///< M^-1 J^T for a.
    Vector3 mLinB = Vector3::Zero(), mAngB = Vector3::Zero();
    real error = 0;        ///< C: the constraint's position error (value - limit), m or rad.
    real target = 0;       ///< Motor rows: the rate the motor drives to.
    real maxImpulse = 0;   ///< Motor and pull rows: largest |impulse| per sub-step, N s.
    real mass = 0;         ///< 1 / (J M^-1 J^T + gamma), kg.
    real gamma = 0;        ///< Soft rows: the softness (Catto's), 1/kg.
    real bias = 0;         ///< Soft rows: the spring's velocity bias, m/s.
    /// Servos and soft limits: the spring's natural frequency (Hz) and damping ratio; its
    /// softness is set once the row's held mass is known (constrainBoundedMasses).
    real frequency = 0, dampingRatio = 0;
    real massScale = 1;     ///< Servos and soft limits: the held mass's share the impulse sees.
    real impulseScale = 0;  ///< Servos and soft limits: the accumulated impulse's share it gives back.
    real impulse = 0;      ///< Accumulated this sub-step (warm start included), N s.
};

class JointSet {
public:
    friend struct StateFields;  ///< Saves and restores the state (snapshot/world_state_io.cpp).
    std::vector<JointRecord> records;
    std::vector<std::uint32_t> free;  ///< Slots of removed joints, reused first.
    int count = 0;                    ///< Live joints.

    bool empty() const { return count == 0; }
    bool contains(JointId id) const {
        return id.index < records.size() && records[id.index].alive && records[id.index].generation == id.generation;
    }

    /// Adds a validated joint at the bodies' current poses; returns its handle.
    JointId add(const BodyStore &bodies, const JointSettings &settings);
    /// Removes the joint in slot `index` (its bodies are not woken here).
    void remove(std::uint32_t index);
    /// Whether a joint without collideConnected joins bodies i and j.
    bool excludesContact(std::uint32_t i, std::uint32_t j) const {
        return !excluded_.empty() && excluded_.count(pairKey(i, j)) != 0;
    }
    /// The joint's error and position at the bodies' current poses.
    void measure(const BodyStore &bodies, const JointRecord &joint, real *error, real *position) const;

    /// Start of a step: a joint whose one end is simulated wakes the other (`transitions`;
    /// from the next step on, as springs do); counts the joints the step solves
    /// (context.activeJoints).
    void beginStep(StepContext &context, const BodyStore &bodies, BodyTransitions transitions);
    /// The sub-step's rows at the bodies' current poses (warm started unless the settings'
    /// debug.warmStarting is off), and the direct block's factorisation; nothing when
    /// context.activeJoints is 0. Counts the rows in stats.jointRows.
    void prepare(const StepContext &context, const BodyStore &bodies, const std::vector<SolverBody> &solverBodies,
                 StepStats &stats);
    /// Applies the rows' warm-start impulses.
    void warmStart(std::vector<SolverBody> &solverBodies) const;
    /// One velocity pass: the equality rows at once (when there are bounded rows or
    /// pulls), the bounded rows one by one, each followed by the equality rows' answer to
    /// it, the pulls, then the equality rows at once.
    void solveVelocities(std::vector<SolverBody> &solverBodies);
    /// Keeps the sub-step's impulses for warm starting and for the step's force.
    void storeImpulses();
    /// After integration: projects the positions onto the joints (no projection when
    /// WorldSettings::positionIterations is 0).
    void correctPositions(const StepContext &context, BodyStore &bodies, const std::vector<SolverBody> &solverBodies);
    /// End of a step: each joint's mean force and torque; the joints whose force or
    /// torque exceeds their threshold are removed, their bodies woken (`transitions`),
    /// and reported in `events`.
    void finishStep(const StepContext &context, const BodyStore &bodies, BodyTransitions transitions,
                    WorldEvents &events);
    /// Removes the joints of body `id`, waking their other bodies (`transitions`).
    void removeJointsOf(const BodyStore &bodies, BodyTransitions transitions, BodyId id);
    /// Draws every joint's anchors, axis and limits (joint_drawing.cpp).
    void draw(const BodyStore &bodies, DebugDraw &draw, const DebugDrawOptions &options) const;
    /// Whether a sub-step has rows to solve.
    bool solving() const { return !rows_.empty(); }

private:
    static std::uint64_t pairKey(std::uint32_t i, std::uint32_t j) {
        if (i > j) std::swap(i, j);
        return std::uint64_t(i) << 32 | j;
    }
    /// Makes the rows of every joint at the current poses (joint_rows.cpp); `positions`
    /// leaves out motors and soft rows, and keeps only violated limits.
    void makeRows(const BodyStore &bodies, bool warmStarting, const std::vector<SolverBody> &solverBodies, real h,
                  bool positions);
    /// Factorises J M^-1 J^T of the equality rows (equality_).
    void factorise(const std::vector<SolverBody> &solverBodies);
    /// Gives each bounded row and pull block its effective mass with the equality rows
    /// held, and the servos and soft limits their softness for the sub-step `h`.
    void constrainBoundedMasses(const std::vector<SolverBody> &solverBodies, real h);
    /// Bounded row `b` (in bounded_'s order): its held mass and heldResponse_, when `held`.
    void holdMass(const std::vector<SolverBody> &solverBodies, std::size_t b, bool held);
    /// A servo's or soft limit's softness for the sub-step h, from its held mass.
    static void soften(JointRow &r, real h);
    /// The equality rows at once (factorised_ must hold).
    void solveEquality(std::vector<SolverBody> &solverBodies);
    /// Per bounded row (in bounded_'s order), when it has its held mass: K^-1 of its
    /// coupling to the equality rows, n entries each (what they give back per N s of it).
    std::vector<real> heldResponse_;
    std::vector<char> responds_;
    /// K^-1 k_e,row into delta_ (k_e,row: the row's couplings to the equality rows, into
    /// rhs_); false when the row shares no body with them.
    bool solveCoupling(const std::vector<SolverBody> &solverBodies, const JointRow &row);
    /// One velocity pass over the pull blocks.
    void solvePulls(std::vector<SolverBody> &solverBodies);

    /// A mouse joint's three rows during a sub-step, solved as one block.
    struct PullBlock {
        int row = 0;                     ///< The first of its three consecutive rows.
        Matrix3 mass = Matrix3::Zero();  ///< (K + gamma)^-1 of the three, the equality rows held, kg.
    };

    std::unordered_map<std::uint64_t, int> excluded_;  ///< Joined pairs that do not collide: joints per pair.
    std::vector<JointRow> rows_;
    std::vector<int> equality_;            ///< Rows of the direct block, in row order.
    std::vector<int> bounded_;             ///< The other rows but the pulls', in row order.
    std::vector<PullBlock> pulls_;         ///< Mouse joints' rows, in row order.
    std::vector<Vector3> moves_;           ///< Scratch of correctPositions: each solver body's move and turn.
    /// Scratch of correctPositions: each simulated body's pose before a Newton step, to
    /// take the step back.
    std::vector<Vector3> savedPositions_;
    std::vector<Quaternion> savedOrientations_;
    /// The errors of the equality rows (rows_ as made last): the largest, m or rad, and
    /// the sum of their squares.
    struct EqualityErrors {
        real largest = 0;
        real squares = 0;
    };
    EqualityErrors equalityErrors() const;
    /// Moves and turns each simulated body by `scale` times its entry in moves_.
    void applyMoves(BodyStore &bodies, real scale) const;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<real>> ldlt_;
    bool factorised_ = false;
    Eigen::VectorXd rhs_, delta_;
    std::vector<Eigen::Triplet<real>> triplets_;
    std::vector<std::vector<int>> rowsOfBody_;  ///< Scratch of factorise: equality entries per solver body.
    std::vector<std::uint32_t> broken_;         ///< Scratch of finishStep.
    real stepTime_ = 0;                         ///< Sum of this step's sub-steps, s.
};

}  // namespace cyclone::detail
