// Every class of scene error: refused before any step with exit status 2, one line on
// stderr "FILE: PATH: message" naming the place, and no output file written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "runner_test_support.h"
#include "scene_loader.h"

namespace {

using namespace runner_test;
using cyclone::scene::loadScene;
using cyclone::scene::SceneError;

struct ErrorCase {
    const char *name;
    const char *scene;
    const char *path;
    const char *message;  // a part of the message
};

#define BOX R"("shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]})"
#define BODY(fields) R"({"bodies": [{"name": "b", )" fields "}]}"
#define TWO_BODIES(extra) \
    R"({"bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}, {"name": "g", "static": true, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}}])" extra "}"

const ErrorCase kErrors[] = {
    {"NotJsonTruncated", R"({"bodies": [)", "bodies[0]", "invalid JSON"},
    {"NotJsonTrailingText", R"({"bodies": []} extra)", "(top level)", "invalid JSON"},
    {"NotJsonInsideABody", R"({"bodies": [{"name": "b", "mass": 1,, }]})", "bodies[0]", "invalid JSON"},
    {"EmptyFile", "", "(top level)", "invalid JSON"},
    {"TopLevelNotObject", "[1, 2]", "(top level)", "must be an object"},
    {"MissingBodies", "{}", "bodies", "required field missing"},
    {"BodiesNotArray", R"({"bodies": {}})", "bodies", "must be an array"},
    {"BodyNotObject", R"({"bodies": [3]})", "bodies[0]", "must be an object"},
    {"MissingName", R"({"bodies": [{)" BOX "}]}", "bodies[0].name", "required field missing"},
    {"EmptyName", BODY(R"("name": "", )" BOX), "bodies[0].name", "must not be empty"},
    {"NameNotString", R"({"name": 7, "bodies": []})", "name", "must be a string"},
    {"MissingShape", BODY(R"("mass": 1)"), "bodies[0].shape", "required field missing"},
    {"DuplicateName", R"({"bodies": [{"name": "x", )" BOX R"(}, {"name": "x", )" BOX "}]}", "bodies[1].name",
     "duplicate name \"x\""},
    {"NegativeMass", BODY(BOX R"(, "mass": -1)"), "bodies[0].mass", "must be finite and > 0, got -1"},
    {"ZeroMass", BODY(BOX R"(, "mass": 0)"), "bodies[0].mass", "must be finite and > 0, got 0"},
    {"MassWrongType", BODY(BOX R"(, "mass": "heavy")"), "bodies[0].mass", "must be a number, got string \"heavy\""},
    {"MassNull", BODY(BOX R"(, "mass": null)"), "bodies[0].mass", "must be a number, got null"},
    {"NonFiniteNumber", BODY(BOX R"(, "position": [0, 1e999, 0])"), "bodies[0].position[1]", "finite"},
    {"NegativeInfinity", BODY(BOX R"(, "velocity": [-1e999, 0, 0])"), "bodies[0].velocity[0]", "finite"},
    {"VectorWrongLength", BODY(BOX R"(, "velocity": [1, 2])"), "bodies[0].velocity", "array of 3 numbers"},
    {"StaticNotBool", BODY(BOX R"(, "static": 1)"), "bodies[0].static", "true or false"},
    {"LayerOutOfRange", BODY(BOX R"(, "layer": 32)"), "bodies[0].layer", "must be an integer in [0, 31], got 32"},
    {"CollidesWithOutOfRange", BODY(BOX R"(, "collides_with": [0, -1])"), "bodies[0].collides_with[1]",
     "must be an integer in [0, 31]"},
    {"UnknownMotion", BODY(BOX R"(, "motion": "floating")"), "bodies[0].motion",
     "must be \"dynamic\", \"static\" or \"kinematic\", got \"floating\""},
    {"MotionDisagreesWithStatic", BODY(BOX R"(, "static": true, "motion": "kinematic")"), "bodies[0].motion",
     "disagrees with \"static\": true"},
    {"PlaneOnKinematicBody", BODY(R"("motion": "kinematic", "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0})"),
     "bodies[0].shape.type", "static bodies only"},
    {"CompoundWithoutChildren", BODY(R"("shape": {"type": "compound", "children": []})"), "bodies[0].shape.children",
     "needs at least 1 child"},
    {"CompoundChildrenMissing", BODY(R"("shape": {"type": "compound"})"), "bodies[0].shape.children",
     "required field missing"},
    {"CompoundMeshChild",
     BODY(R"("shape": {"type": "compound", "children": [{"shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]}}]})"),
     "bodies[0].shape.children[0].shape.type", "a compound's child must be convex"},
    {"CompoundPlaneChild",
     BODY(R"("shape": {"type": "compound", "children": [)" R"({"shape": {"type": "sphere", "radius": 1}}, {"shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}}]})"),
     "bodies[0].shape.children[1].shape.type", "a compound's child must be convex"},
    {"CompoundChildBadSize",
     BODY(R"("shape": {"type": "compound", "children": [{"shape": {"type": "box", "half_extents": [1, -1, 1]}}]})"),
     "bodies[0].shape.children[0].shape.half_extents[1]", "> 0"},
    {"CompoundChildBadPosition",
     BODY(R"("shape": {"type": "compound", "children": [{"shape": {"type": "sphere", "radius": 1}, "position": [0, 1e999, 0]}]})"),
     "bodies[0].shape.children[0].position[1]", "finite"},
    {"CompoundChildBadOrientation",
     BODY(R"("shape": {"type": "compound", "children": [{"shape": {"type": "sphere", "radius": 1}, "orientation": [1, 0, 0]}]})"),
     "bodies[0].shape.children[0].orientation", "array of 4 numbers"},
    {"ImpulseOnKinematicBody",
     R"({"bodies": [{"name": "k", "motion": "kinematic", )" BOX R"(}], "events": [{"step": 1, "apply_impulse": "k", "impulse": [1, 0, 0]}]})",
     "events[0].apply_impulse", "is kinematic"},
    {"UnknownShape", BODY(R"("shape": {"type": "torus"})"), "bodies[0].shape.type", "unknown shape type \"torus\""},
    {"ShapeWithoutType", BODY(R"("shape": {"radius": 1})"), "bodies[0].shape.type", "required field missing"},
    {"PlaneOnDynamicBody", BODY(R"("shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0})"),
     "bodies[0].shape.type", "static bodies only"},
    {"MeshOnDynamicBody",
     BODY(R"("shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 2]]})"),
     "bodies[0].shape.type", "static bodies only"},
    {"BadHalfExtent", BODY(R"("shape": {"type": "box", "half_extents": [1, 1, 0]})"),
     "bodies[0].shape.half_extents[2]", "must be finite and > 0 (at most 1e12 m), got 0"},
    {"AbsurdPosition", BODY(BOX R"(, "position": [0, 1e300, 0])"), "bodies[0].position[1]", "within ±1e12 m"},
    {"MissingRadius", BODY(R"("shape": {"type": "sphere"})"), "bodies[0].shape.radius", "required field missing"},
    {"NegativeCapsuleLength", BODY(R"("shape": {"type": "capsule", "radius": 1, "length": -2})"),
     "bodies[0].shape.length", "must be finite and >= 0"},
    {"ZeroCylinderLength", BODY(R"("shape": {"type": "cylinder", "radius": 1, "length": 0})"),
     "bodies[0].shape.length", "must be finite and > 0"},
    {"CoplanarConvex",
     BODY(R"("shape": {"type": "convex", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 2, 0]]})"),
     "bodies[0].shape.vertices", "not all on one plane"},
    {"TooFewConvexPoints", BODY(R"("shape": {"type": "convex", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]})"),
     "bodies[0].shape.vertices", "at least 4 points"},
    {"MeshIndexOutOfRange",
     BODY(R"("static": true, "shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 3]]})"),
     "bodies[0].shape.triangles[0][2]", "[0, 2]"},
    {"InertiaNotPositiveDefinite", BODY(BOX R"(, "inertia": [[1, 0, 0], [0, -1, 0], [0, 0, 1]])"), "bodies[0].inertia",
     "positive definite"},
    {"InertiaNotSymmetric", BODY(BOX R"(, "inertia": [[1, 0.5, 0], [0, 1, 0], [0, 0, 1]])"), "bodies[0].inertia",
     "symmetric"},
    {"InertiaRowWrong", BODY(BOX R"(, "inertia": [[1, 0, 0], [0, 1], [0, 0, 1]])"), "bodies[0].inertia[1]",
     "row of 3 numbers"},
    {"OrientationWrongLength", BODY(BOX R"(, "orientation": [1, 0, 0])"), "bodies[0].orientation", "4 numbers"},
    {"DampingOutOfRange", BODY(BOX R"(, "linear_damping": 1.5)"), "bodies[0].linear_damping", "in [0, 1]"},
    {"RestitutionOutOfRange", BODY(BOX R"(, "restitution": -0.1)"), "bodies[0].restitution", "in [0, 1]"},
    {"NegativeFriction", BODY(BOX R"(, "friction": -1)"), "bodies[0].friction", ">= 0"},
    {"NegativeRollingFriction", BODY(BOX R"(, "rolling_friction": -0.5)"), "bodies[0].rolling_friction", ">= 0"},
    {"NegativeSpinningFriction", BODY(BOX R"(, "spinning_friction": -2)"), "bodies[0].spinning_friction", ">= 0"},
    {"SettingsNotObject", R"({"settings": [], "bodies": []})", "settings", "must be an object"},
    {"ZeroDt", R"({"settings": {"dt": 0}, "bodies": []})", "settings.dt", "must be finite and > 0, got 0"},
    {"HugeDt", R"({"settings": {"dt": 1e400}, "bodies": []})", "settings.dt", "finite"},
    // A 10 s step let a resting stack slide apart (kMaxStep = 1 s, world/settings.h).
    {"LongDt", R"({"settings": {"dt": 10}, "bodies": []})", "settings.dt", "must be at most 1 s"},
    {"ExtremeSteps", R"({"settings": {"steps": 1000000000000}, "bodies": []})", "settings.steps", "[0, 100000000]"},
    {"StepsBeyondInt64", R"({"settings": {"steps": 99999999999999999999999}, "bodies": []})", "settings.steps",
     "[0, 100000000]"},
    {"NegativeSteps", R"({"settings": {"steps": -1}, "bodies": []})", "settings.steps", "[0, 100000000]"},
    {"FractionalSteps", R"({"settings": {"steps": 1.5}, "bodies": []})", "settings.steps", "must be an integer"},
    {"ZeroVelocityIterations", R"({"settings": {"velocity_iterations": 0}, "bodies": []})",
     "settings.velocity_iterations", "[1, 1000]"},
    {"ExtremeSubsteps", R"({"settings": {"substeps": 4294967296}, "bodies": []})", "settings.substeps", "[1, 1000]"},
    {"UnknownIntegrator", R"({"settings": {"integrator": "rk4"}, "bodies": []})", "settings.integrator",
     "unknown integrator \"rk4\""},
    {"SleepNotBool", R"({"settings": {"sleep": "yes"}, "bodies": []})", "settings.sleep", "true or false"},
    {"NonPositiveSleepEpsilon", R"({"settings": {"sleep_epsilon": 0}, "bodies": []})", "settings.sleep_epsilon", "> 0"},
    {"SpringsNotArray", TWO_BODIES(R"(, "springs": {})"), "springs", "must be an array"},
    {"SpringUnknownBody", TWO_BODIES(R"(, "springs": [{"a": "nobody"}])"), "springs[0].a", "no body named \"nobody\""},
    {"SpringMissingA", TWO_BODIES(R"(, "springs": [{"b": "a"}])"), "springs[0].a", "required field missing"},
    {"SpringToItself", TWO_BODIES(R"(, "springs": [{"a": "a", "b": "a"}])"), "springs[0].b", "different body"},
    {"SpringZeroStiffness", TWO_BODIES(R"(, "springs": [{"a": "a", "stiffness": 0}])"), "springs[0].stiffness", "> 0"},
    {"SpringNegativeRestLength", TWO_BODIES(R"(, "springs": [{"a": "a", "rest_length": -1}])"),
     "springs[0].rest_length", ">= 0"},
    {"EventsNotArray", TWO_BODIES(R"(, "events": 5)"), "events", "must be an array"},
    {"EventWithoutStep", TWO_BODIES(R"(, "events": [{"remove": "a"}])"), "events[0].step", "required field missing"},
    {"EventNegativeStep", TWO_BODIES(R"(, "events": [{"step": -3, "remove": "a"}])"), "events[0].step",
     "[0, 100000000]"},
    {"EventWithoutAction", TWO_BODIES(R"(, "events": [{"step": 1}])"), "events[0]", "needs one of"},
    {"EventWithTwoActions",
     TWO_BODIES(R"(, "events": [{"step": 1, "set_velocity": "a", "velocity": [0, 0, 0], "set_rotation": "a", "rotation": [0, 0, 0]}])"),
     "events[0].set_rotation", "does one thing"},
    {"EventUnknownBody", TWO_BODIES(R"(, "events": [{"step": 1, "set_velocity": "ghost", "velocity": [1, 0, 0]}])"),
     "events[0].set_velocity", "no body named \"ghost\""},
    {"EventMissingValue", TWO_BODIES(R"(, "events": [{"step": 1, "set_velocity": "a"}])"), "events[0].velocity",
     "required field missing"},
    {"EventMissingAwake", TWO_BODIES(R"(, "events": [{"step": 1, "set_awake": "a"}])"), "events[0].awake",
     "required field missing"},
    {"EventOnStaticBody", TWO_BODIES(R"(, "events": [{"step": 1, "apply_impulse": "g", "impulse": [0, 1, 0]}])"),
     "events[0].apply_impulse", "is static"},
    {"EventAfterRemoval",
     TWO_BODIES(R"(, "events": [{"step": 1, "remove": "a"}, {"step": 2, "set_velocity": "a", "velocity": [1, 0, 0]}])"),
     "events[1].set_velocity", "was removed by events[0] at step 1"},
    {"RemovedTwice", TWO_BODIES(R"(, "events": [{"step": 4, "remove": "a"}, {"step": 4, "remove": "a"}])"),
     "events[1].remove", "was removed by events[0]"},
    {"MeshSensorOnDynamicBody",
     BODY(R"("sensor": true, "shape": {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0, 1]], "triangles": [[0, 1, 2]]})"),
     "bodies[0].shape.type", "static bodies only"},
    {"SensorNotABool", BODY(BOX R"(, "sensor": 1)"), "bodies[0].sensor", "true or false"},
    // Fields of the contract this engine does not build yet are refused, never run as something else.
    // Joints: the place is the joint's index and field.
    {"JointAxisZero",
     TWO_BODIES(R"(, "joints": [{"name": "j0", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0]},
                                {"name": "j1", "type": "fixed", "a": "a", "b": "g", "anchor": [0, 3, 0]},
                                {"name": "j2", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, 0, 0]}])"),
     "joints[2].axis", "must not be zero"},
    {"JointMissingName", TWO_BODIES(R"(, "joints": [{"type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0]}])"),
     "joints[0].name", "required field missing"},
    {"JointMissingB", TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "anchor": [0, 3, 0]}])"),
     "joints[0].b", "required field missing"},
    {"JointUnknownType", TWO_BODIES(R"(, "joints": [{"name": "j", "type": "rope", "a": "a", "b": null, "anchor": [0, 3, 0]}])"),
     "joints[0].type", "unknown joint type \"rope\""},
    {"JointUnknownBody", TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "nobody", "b": null, "anchor": [0, 3, 0]}])"),
     "joints[0].a", "no body named \"nobody\""},
    {"JointSameBodies", TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": "a", "anchor": [0, 3, 0]}])"),
     "joints[0].b", "must name a different body"},
    {"JointHingeWithoutAxis", TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0]}])"),
     "joints[0].axis", "required field missing"},
    {"JointLimitsReversed",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "slider", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "limits": [1, -1]}])"),
     "joints[0].limits", "lo must be <= hi"},
    {"JointHingeLimitsBeyondPi",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "limits": [-4, 1]}])"),
     "joints[0].limits", "within [-pi, pi]"},
    {"JointLimitsOnABall",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "limits": [-1, 1]}])"),
     "joints[0].limits", "only hinge and slider joints"},
    {"JointMotorNegativeForce",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"speed": 1, "max_force": -1}}])"),
     "joints[0].motor.max_force", ">= 0"},
    {"JointSwingLimitOnAHinge",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "swing_limit": [0.5, 0.5]}])"),
     "joints[0].swing_limit", "only ball joints"},
    {"JointSwingLimitWithoutAxis",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "swing_limit": [0.5, 0.5]}])"),
     "joints[0].axis", "required field missing"},
    {"JointSwingLimitZero",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0, 0.5], "normal": [1, 0, 0]}])"),
     "joints[0].swing_limit[0]", "(0, pi]"},
    {"JointSwingLimitBeyondPi",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0.5, 3.5], "normal": [1, 0, 0]}])"),
     "joints[0].swing_limit[1]", "(0, pi]"},
    {"JointSwingLimitNotAPair",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0.5]}])"),
     "joints[0].swing_limit", "two numbers"},
    {"JointEllipticSwingWithoutNormal",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0.5, 0.3]}])"),
     "joints[0].swing_limit", "needs a \"normal\""},
    {"JointSwingNormalAlongTheAxis",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0.5, 0.3], "normal": [1, 1, 0]}])"),
     "joints[0].normal", "perpendicular"},
    {"JointSwingNormalZero",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "swing_limit": [0.5, 0.3], "normal": [0, 0, 0]}])"),
     "joints[0].normal", "must not be zero"},
    {"JointNormalWithoutSwing",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "twist_limit": [-1, 1], "normal": [1, 0, 0]}])"),
     "joints[0].normal", "swing_limit"},
    {"JointTwistLimitReversed",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "twist_limit": [1, -1]}])"),
     "joints[0].twist_limit", "-pi <= lo <= hi <= pi"},
    {"JointTwistLimitBeyondPi",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [0, -1, 0], "twist_limit": [-4, 1]}])"),
     "joints[0].twist_limit", "-pi <= lo <= hi <= pi"},
    {"JointTwistLimitOnASlider",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "slider", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "twist_limit": [-1, 1]}])"),
     "joints[0].twist_limit", "only ball joints"},
    {"JointServoWithSpeed",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"speed": 1, "target": 0.5, "frequency": 2, "damping_ratio": 1, "max_force": 5}}])"),
     "joints[0].motor.speed", "not both"},
    {"JointServoFrequencyZero",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"target": 0.5, "frequency": 0, "damping_ratio": 1, "max_force": 5}}])"),
     "joints[0].motor.frequency", "> 0"},
    {"JointServoWithoutDampingRatio",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "slider", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"target": 0.5, "frequency": 2, "max_force": 5}}])"),
     "joints[0].motor.damping_ratio", "required field missing"},
    {"JointServoNegativeDampingRatio",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "slider", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"target": 0.5, "frequency": 2, "damping_ratio": -1, "max_force": 5}}])"),
     "joints[0].motor.damping_ratio", ">= 0"},
    {"JointHingeServoBeyondPi",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"target": 4, "frequency": 2, "damping_ratio": 1, "max_force": 5}}])"),
     "joints[0].motor.target", "within [-pi, pi]"},
    {"JointSpeedMotorWithFrequency",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "hinge", "a": "a", "b": null, "anchor": [0, 3, 0], "axis": [1, 0, 0], "motor": {"speed": 1, "frequency": 2, "max_force": 5}}])"),
     "joints[0].motor.frequency", "only a servo"},
    {"JointDistanceMinAboveMax",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "distance", "a": "a", "b": null, "anchor": [0, 3, 0], "min_distance": 2, "max_distance": 1}])"),
     "joints[0].max_distance", "min_distance must be <= max_distance"},
    {"JointBreakForceZero",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0], "break_force": 0}])"),
     "joints[0].break_force", "> 0"},
    {"JointDuplicateName",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0]},
                                {"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 2, 0]}])"),
     "joints[1].name", "duplicate joint name \"j\""},
    {"RemoveJointUnknown", TWO_BODIES(R"(, "events": [{"step": 1, "remove_joint": "j"}])"), "events[0].remove_joint",
     "no joint named \"j\""},
    {"JointRemovedTwice",
     TWO_BODIES(R"(, "joints": [{"name": "j", "type": "ball", "a": "a", "b": null, "anchor": [0, 3, 0]}],
                  "events": [{"step": 1, "remove_joint": "j"}, {"step": 2, "remove_joint": "j"}])"),
     "events[1].remove_joint", "was removed by events[0]"},
};

// The place the runner prints: the body's or joint's name after its index, as in
// `bodies[0] ("b").mass`, when the (valid JSON) file gives it one.
std::string placeWithName(const std::string &path, const std::string &text) {
    const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
    for (const std::string array : {"bodies", "joints"}) {
        if (path.rfind(array + "[", 0) != 0 || !document.is_object() || !document.contains(array)) continue;
        const std::size_t close = path.find(']');
        const std::size_t index = std::stoul(path.substr(array.size() + 1, close - array.size() - 1));
        const nlohmann::json &element = document[array][index];
        if (!element.is_object() || !element.contains("name") || !element["name"].is_string()) return path;
        const std::string name = element["name"];
        if (name.empty()) return path;
        return path.substr(0, close + 1) + " (\"" + name + "\")" + path.substr(close + 1);
    }
    return path;
}

class SceneErrorClass : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(SceneErrorClass, LoaderNamesThePlace) {
    const ErrorCase &c = GetParam();
    try {
        loadScene(c.scene, "x");
        FAIL() << "accepted: " << c.scene;
    } catch (const SceneError &error) {
        EXPECT_EQ(error.path(), c.path) << error.what();
        EXPECT_NE(error.message().find(c.message), std::string::npos) << error.what();
    }
}

TEST_P(SceneErrorClass, RunnerExitsTwoWithOneLineAndWritesNothing) {
    const ErrorCase &c = GetParam();
    TempDir dir;
    const std::string scene = dir.file("bad.json");
    writeText(scene, c.scene);
    const Process p = runWorld({"run", scene, "--summary", dir.file("out.json"), "--trace", dir.file("out.csv")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    const std::string prefix = scene + ": " + placeWithName(c.path, c.scene) + ": ";
    EXPECT_EQ(p.err.compare(0, prefix.size(), prefix), 0) << p.err;
    EXPECT_NE(p.err.find(c.message), std::string::npos) << p.err;
    EXPECT_TRUE(p.out.empty()) << p.out;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.json"});
}

INSTANTIATE_TEST_SUITE_P(Scene, SceneErrorClass, ::testing::ValuesIn(kErrors),
                         [](const ::testing::TestParamInfo<ErrorCase> &info) { return std::string(info.param.name); });

TEST(SceneErrors, TheContractsExampleMessage) {
    TempDir dir;
    const std::string scene = dir.file("tower.json");
    writeText(scene, R"({"bodies": [)"
                     R"({"name": "b0", "shape": {"type": "sphere", "radius": 1}},)"
                     R"({"name": "b1", "shape": {"type": "sphere", "radius": 1}},)"
                     R"({"name": "b2", "shape": {"type": "sphere", "radius": 1}},)"
                     R"({"name": "b3", "shape": {"type": "sphere", "radius": 1}, "mass": -1}]})");
    const Process p = runWorld({"run", scene}, dir);
    EXPECT_EQ(p.status, 2);
    // The place names the body (bodies[3] is "b3") as well as its index.
    EXPECT_EQ(p.err, scene + ": bodies[3] (\"b3\").mass: must be finite and > 0, got -1\n");
}

TEST(SceneErrors, MissingFileAndDirectory) {
    TempDir dir;
    Process p = runWorld({"run", dir.file("absent.json"), "--summary", dir.file("out.json")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1);
    EXPECT_NE(p.err.find("absent.json: cannot read"), std::string::npos) << p.err;
    p = runWorld({"run", dir.file("")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_NE(p.err.find("is a directory"), std::string::npos) << p.err;
    EXPECT_TRUE(dir.files().empty());
}

TEST(SceneErrors, UnwritableOutputIsRefusedBeforeStepping) {
    TempDir dir;
    const Process p =
        runWorld({"run", scenePath("tower"), "--summary", dir.file("no/such/folder/out.json"), "--trace", dir.file("t.csv")}, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1);
    EXPECT_NE(p.err.find("cannot write"), std::string::npos) << p.err;
    EXPECT_TRUE(p.out.empty());
    EXPECT_TRUE(dir.files().empty());
}

struct UsageCase {
    const char *name;
    std::vector<std::string> args;
    const char *message;
};

class BadCommandLine : public ::testing::TestWithParam<UsageCase> {};

TEST_P(BadCommandLine, ExitsTwoWithOneLine) {
    TempDir dir;
    std::vector<std::string> args = GetParam().args;
    for (auto &arg : args) {
        if (arg == "SCENE") arg = scenePath("tower");
    }
    const Process p = runWorld(args, dir);
    EXPECT_EQ(p.status, 2);
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_NE(p.err.find(GetParam().message), std::string::npos) << p.err;
    EXPECT_TRUE(p.out.empty());
    EXPECT_TRUE(dir.files().empty());
}

const UsageCase kUsage[] = {
    {"NoArguments", {}, "missing command"},
    {"UnknownCommand", {"simulate", "SCENE"}, "unknown command 'simulate'"},
    {"UnknownOption", {"run", "SCENE", "--fast"}, "unknown option '--fast'"},
    {"NoScene", {"run", "--steps", "10"}, "needs a scene file"},
    {"TwoScenes", {"run", "SCENE", "SCENE"}, "one scene file only"},
    {"MissingValue", {"run", "SCENE", "--steps"}, "--steps needs a value"},
    {"NegativeSteps", {"run", "SCENE", "--steps", "-1"}, "--steps needs a whole number"},
    {"AbsurdSteps", {"run", "SCENE", "--steps", "1000000000"}, "0..100000000"},
    {"EveryZero", {"run", "SCENE", "--every", "0"}, "--every needs a whole number in 1.."},
    {"ZeroDt", {"run", "SCENE", "--dt", "0"}, "--dt needs a finite number"},
    {"NanDt", {"run", "SCENE", "--dt=nan"}, "--dt needs a finite number"},
    {"InfiniteDt", {"run", "SCENE", "--dt", "inf"}, "--dt needs a finite number"},
    {"LongDt", {"run", "SCENE", "--dt", "1.5"}, "--dt needs a finite number of seconds in [1e-06, 1]"},
    {"GivenTwice", {"run", "SCENE", "--steps", "1", "--steps", "2"}, "given twice"},
    {"SameOutputTwice", {"run", "SCENE", "--summary", "x", "--trace", "x"}, "same file"},
};

INSTANTIATE_TEST_SUITE_P(Cli, BadCommandLine, ::testing::ValuesIn(kUsage),
                         [](const ::testing::TestParamInfo<UsageCase> &info) { return std::string(info.param.name); });

}  // namespace
