#!/usr/bin/env python3
"""Writes examples/scenes/ragdolls.json (eight ragdolls dropped in a pile onto stairs)
and examples/scenes/servo.json (servo motors on hinges and sliders).

The ragdolls are those addRagdoll makes (world/src/ragdoll/ragdoll.cpp): the same parts,
joints and limits, at the reference 1.83 m and 69 kg. RagdollScene.MatchesAddRagdoll
(tests/runner) checks that the scene's first ragdoll is addRagdoll's body for body and
joint for joint, so a change to one without the other fails.

    python3 scripts/ragdoll_scenes.py
"""
import json
import math
import os

# name, radius, length, mass, centre (standing frame: pelvis centre at the origin, up +y,
# facing +x, left towards -z), upright (capsule along y, else along z)
PARTS = [
    ("pelvis", 0.10, 0.20, 12, (0, 0, 0), False),
    ("torso", 0.14, 0.20, 20, (0, 0.35, 0), True),
    ("head", 0.10, 0.06, 5, (0, 0.75, 0), True),
    ("left_upper_arm", 0.05, 0.19, 2.5, (0, 0.355, -0.26), True),
    ("left_lower_arm", 0.045, 0.20, 1.5, (0, 0.045, -0.26), True),
    ("right_upper_arm", 0.05, 0.19, 2.5, (0, 0.355, 0.26), True),
    ("right_lower_arm", 0.045, 0.20, 1.5, (0, 0.045, 0.26), True),
    ("left_thigh", 0.07, 0.30, 8, (0, -0.27, -0.1), True),
    ("left_shin", 0.06, 0.32, 4, (0, -0.73, -0.1), True),
    ("right_thigh", 0.07, 0.30, 8, (0, -0.27, 0.1), True),
    ("right_shin", 0.06, 0.32, 4, (0, -0.73, 0.1), True),
]
# name, parent, child, anchor, hinge, axis, forward, sideways, range
JOINTS = [
    ("waist", "pelvis", "torso", (0, 0.10, 0), False, (0, 1, 0), 0.6, 0.35, (-0.5, 0.5)),
    ("neck", "torso", "head", (0, 0.605, 0), False, (0, 1, 0), 0.7, 0.5, (-1.0, 1.0)),
    ("left_shoulder", "torso", "left_upper_arm", (0, 0.5, -0.26), False, (0, -1, 0), 1.5, 0.8, (-0.8, 0.8)),
    ("right_shoulder", "torso", "right_upper_arm", (0, 0.5, 0.26), False, (0, -1, 0), 1.5, 0.8, (-0.8, 0.8)),
    ("left_elbow", "left_upper_arm", "left_lower_arm", (0, 0.2, -0.26), True, (0, 0, 1), 0, 0, (0, 2.4)),
    ("right_elbow", "right_upper_arm", "right_lower_arm", (0, 0.2, 0.26), True, (0, 0, 1), 0, 0, (0, 2.4)),
    ("left_hip", "pelvis", "left_thigh", (0, -0.05, -0.1), False, (0, -1, 0), 1.4, 0.6, (-0.6, 0.6)),
    ("right_hip", "pelvis", "right_thigh", (0, -0.05, 0.1), False, (0, -1, 0), 1.4, 0.6, (-0.6, 0.6)),
    ("left_knee", "left_thigh", "left_shin", (0, -0.5, -0.1), True, (0, 0, 1), 0, 0, (-2.4, 0)),
    ("right_knee", "right_thigh", "right_shin", (0, -0.5, 0.1), True, (0, 0, 1), 0, 0, (-2.4, 0)),
]


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def axis_angle(axis, angle):
    s = math.sin(angle / 2)
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


def rotate(q, v):
    p = qmul(qmul(q, (0, *v)), (q[0], -q[1], -q[2], -q[3]))
    return p[1:]


def rounded(v):
    return [round(x, 9) + 0.0 for x in v]


def ragdoll(prefix, position, q, velocity):
    """The bodies and joints addRagdoll makes at the reference size."""
    upright = qmul(q, axis_angle((1, 0, 0), math.pi / 2))
    bodies, joints = [], []
    for name, radius, length, mass, centre, up in PARTS:
        p = [a + b for a, b in zip(position, rotate(q, centre))]
        bodies.append({"name": prefix + name, "shape": {"type": "capsule", "radius": radius, "length": length},
                       "mass": mass, "position": rounded(p), "orientation": rounded(upright if up else q),
                       "velocity": list(velocity)})
    for name, parent, child, anchor, hinge, axis, forward, sideways, limits in JOINTS:
        j = {"name": prefix + name, "anchor": rounded([a + b for a, b in zip(position, rotate(q, anchor))]),
             "axis": rounded(rotate(q, axis))}
        if hinge:
            j.update({"type": "hinge", "a": prefix + child, "b": prefix + parent, "limits": list(limits)})
        else:
            j.update({"type": "ball", "a": prefix + parent, "b": prefix + child, "swing_limit": [forward, sideways],
                      "normal": rounded(rotate(q, (1, 0, 0))), "twist_limit": list(limits)})
        joints.append({"name": j.pop("name"), "type": j.pop("type"), **j})
    return bodies, joints


def stairs():
    bodies = [{"name": "floor", "static": True, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}},
              {"name": "landing", "static": True, "shape": {"type": "box", "half_extents": [1.0, 1.0, 1.5]},
               "position": [-0.5, 1.0, 0]}]
    for k in range(1, 8):
        h = 1.0 - 0.125 * k
        bodies.append({"name": f"stair{k}", "static": True,
                       "shape": {"type": "box", "half_extents": [0.2, h, 1.5]}, "position": [0.3 + 0.4 * k, h, 0]})
    return bodies


def ragdolls_scene():
    bodies, joints = stairs(), []
    face_down = axis_angle((0, 0, 1), -math.pi / 2)
    for k in range(8):
        q = qmul(axis_angle((0, 1, 0), k * math.pi / 4), face_down)
        b, j = ragdoll(f"r{k}_", (-0.3, 2.5 + 0.6 * k, 0), q, (1.0, 0, 0))
        bodies += b
        joints += j
    return {"name": "ragdolls", "settings": {"steps": 900}, "bodies": bodies, "joints": joints}


def servo_scene():
    door = {"name": "door", "shape": {"type": "box", "half_extents": [0.5, 1.0, 0.05]}, "mass": 10,
            "position": [0.5, 1.2, 0]}
    cabin = {"name": "cabin", "shape": {"type": "box", "half_extents": [0.5, 0.1, 0.5]}, "mass": 50,
             "position": [3, 0.5, 0]}
    arm = {"name": "arm", "shape": {"type": "box", "half_extents": [0.5, 0.05, 0.05]}, "mass": 2,
           "position": [-2.5, 1.5, 0]}
    floor = {"name": "floor", "static": True, "shape": {"type": "plane", "normal": [0, 1, 0], "offset": 0}}
    joints = [
        {"name": "door_hinge", "type": "hinge", "a": "door", "b": None, "anchor": [0, 1.2, 0], "axis": [0, 1, 0],
         "motor": {"target": 1.2, "frequency": 1.0, "damping_ratio": 1.0, "max_force": 200}},
        {"name": "lift", "type": "slider", "a": "cabin", "b": None, "anchor": [3, 0.5, 0], "axis": [0, 1, 0],
         "limits": [0, 3], "motor": {"target": 2.0, "frequency": 0.5, "damping_ratio": 1.0, "max_force": 2000}},
        {"name": "shoulder", "type": "hinge", "a": "arm", "b": None, "anchor": [-3, 1.5, 0], "axis": [0, 0, 1],
         "motor": {"target": 0.8, "frequency": 2.0, "damping_ratio": 0.3, "max_force": 100}},
    ]
    return {"name": "servo", "settings": {"steps": 600}, "bodies": [floor, door, cabin, arm], "joints": joints}


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "scenes")
    for name, scene in (("ragdolls.json", ragdolls_scene()), ("servo.json", servo_scene())):
        with open(os.path.join(root, name), "w") as f:
            json.dump(scene, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
