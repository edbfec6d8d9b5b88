/// \file
/// Debug drawing: the game implements DebugDraw with its renderer's lines, and
/// World::debugDraw() draws the bodies' shapes, their broadphase boxes and the contacts
/// through it, coloured by state (awake, asleep, static, isolated) and sensors apart.
#pragma once

#include "cyclone/core.h"

namespace cyclone {

/// A colour: red, green, blue and opacity, each in [0, 1].
struct DebugColor {
    float r = 1;  ///< Red, [0, 1].
    float g = 1;  ///< Green, [0, 1].
    float b = 1;  ///< Blue, [0, 1].
    float a = 1;  ///< Opacity, [0, 1].
};

/// What World::debugDraw() draws, and in which colours. World::debugDraw() validates it.
struct DebugDrawOptions {
    /// Wireframes of the bodies' shapes.
    bool shapes = true;
    /// Whether static bodies' shapes are drawn (a large static mesh can be many lines).
    bool staticBodies = true;
    /// The boxes of the broadphase trees (each body's box, enlarged by a 2 cm margin).
    bool boundingBoxes = false;
    /// Contact points of the touching pairs, with their normals.
    bool contacts = true;
    /// Length of a drawn contact normal, m, finite, > 0.
    real normalLength = 0.2;
    /// Half size of the square drawn for a plane, around the point of the plane nearest
    /// the world origin, m, finite, > 0.
    real planeHalfSize = 10;
    /// Line segments of a full circle of a sphere, capsule or cylinder, in [4, 256].
    int circleSegments = 24;
    /// Joints: a small cross at each body's anchor (and the line between them when they
    /// part: a distance joint, a mouse joint's target), the axis of hinges, sliders and
    /// limited ball joints, and the limits: a hinge's or a ball joint's twist range as an
    /// arc with a line at the current angle, a slider's as ticks along the axis, a ball
    /// joint's swing cone as its rim and four spokes.
    bool joints = true;
    /// Size of a drawn joint (half the axis's length, the arcs' and the cone's radius), m,
    /// finite, > 0.
    real jointSize = 0.15;

    /// Dynamic bodies that are awake.
    DebugColor awake{0.3f, 0.9f, 0.3f, 1};
    /// Dynamic bodies that are asleep.
    DebugColor asleep{0.35f, 0.45f, 0.9f, 1};
    /// Static bodies.
    DebugColor staticBody{0.65f, 0.65f, 0.65f, 1};
    /// Bodies isolated because their state became non-finite (or beyond 1e12 m).
    DebugColor isolated{1, 0.1f, 0.1f, 1};
    /// Sensors (BodySettings::sensor), whatever their motion: translucent by default.
    DebugColor sensor{0.2f, 0.85f, 0.85f, 0.5f};
    /// Broadphase boxes.
    DebugColor boundingBox{0.9f, 0.6f, 0.2f, 1};
    /// Contact points.
    DebugColor contactPoint{1, 1, 0.2f, 1};
    /// Contact normals.
    DebugColor contactNormal{1, 0.3f, 0.3f, 1};
    /// Joints' anchors (and the line between them).
    DebugColor jointAnchor{1, 0.55f, 0.1f, 1};
    /// Joints' axes and the current angle of a limited one.
    DebugColor jointAxis{0.85f, 0.3f, 0.95f, 1};
    /// Joints' limits.
    DebugColor jointLimit{0.95f, 0.95f, 0.6f, 1};
};

/// The drawing interface a game implements. Only line() is required; the others have
/// default implementations made of lines, which a renderer may replace with its own
/// primitives. All positions are world space, in m.
class DebugDraw {
public:
    virtual ~DebugDraw() = default;

    /// A line segment from `from` to `to`.
    virtual void line(const Vector3 &from, const Vector3 &to, const DebugColor &color) = 0;

    /// A box with half sizes `halfExtents` (m, each >= 0) placed at `pose`. Default: its
    /// 12 edges.
    virtual void box(const Matrix4 &pose, const Vector3 &halfExtents, const DebugColor &color);

    /// A circle of radius `radius` (m, >= 0) around `centre` in the plane through it
    /// perpendicular to the unit vector `normal`, as `segments` (>= 3) lines. Default:
    /// those lines.
    virtual void circle(const Vector3 &centre, const Vector3 &normal, real radius, int segments,
                        const DebugColor &color);

    /// A contact point with its unit normal (pointing from the first body to the second)
    /// and its depth (m, > 0 overlapping). Default: a small cross at `point` (a tenth of
    /// `normalLength` across) in `pointColor`, and a line of length `normalLength` (m)
    /// along `normal` in `normalColor`.
    virtual void contact(const Vector3 &point, const Vector3 &normal, real depth, real normalLength,
                         const DebugColor &pointColor, const DebugColor &normalColor);
};

}  // namespace cyclone
