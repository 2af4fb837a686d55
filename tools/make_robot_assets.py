#!/usr/bin/env python3
"""Write pronk's own robot descriptions (URDF + simple OBJ meshes + README).

    python3 tools/make_robot_assets.py            # (re)write assets/robots/{go1,aliengo}/
    python3 tools/make_robot_assets.py --check    # exit 1 if the committed files are stale
    python3 tools/make_robot_assets.py --compare-vendor ../shared/thirdparty/unitree
                                                  # compare inertials, joints and collision
                                                  # shapes with the vendor URDFs (writes nothing)

Every number comes from the project's reference notes on the Unitree Go1 and Aliengo
(robots.md, sections 1-3: the unitree_ros figures "reconfirmed" on 2022-11-16). The meshes are
built here from a handful of convex primitives; no vendor geometry is used.

Standard library only. The output is deterministic: fixed number formatting, no timestamps,
'\n' line endings, so running the script twice gives byte-identical files.
"""

import argparse
import math
import os
import sys
import xml.dom.minidom
from decimal import Decimal

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMAND = "python3 tools/make_robot_assets.py"
HALF_PI = repr(math.pi / 2)  # "1.5707963267948966", the usual URDF spelling

LEGS = ("FR", "FL", "RR", "RL")  # Unitree order; SDK index 0..3
MIRROR = {"FR": -1, "FL": 1, "RR": -1, "RL": 1}  # +1 left, -1 right
FRONT_HIND = {"FR": 1, "FL": 1, "RR": -1, "RL": -1}  # +1 front, -1 rear
STANCE = (0.0, 0.75, -1.5)  # (hip, thigh, calf); the paper's q0 in the Unitree sign convention


# --------------------------------------------------------------------------------------------
# Robot data (robots.md). Inertial rows are the per-leg tables exactly as the vendor's generated
# URDF has them (mirroring already applied); the script checks them against the mirroring rules.
# Columns: link, mass, com x y z, ixx ixy ixz iyy iyz izz (about the COM, link axes).
# --------------------------------------------------------------------------------------------

GO1_INERTIALS = """
trunk          5.204     0.0223    0.002     -0.0005   0.0168128557   -0.0002296769  -0.0002945293  0.063009565    -4.18731e-05   0.0716547275
FR_hip         0.591     -0.005657 0.008752  -0.000102 0.000334008405 1.0826066e-05  1.290732e-06   0.000619101213 -1.643194e-06  0.00040057614
FR_hip_rotor   0.089     0         0         0         0.000111842    0              0              5.9647e-05     0              5.9647e-05
FR_thigh       0.92      -0.003342 0.018054  -0.033451 0.004431760472 -5.7496807e-05 -0.000218457134 0.004485671726 -0.000572001265 0.000740309489
FR_thigh_rotor 0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
FR_calf        0.135862  0.006197  0.001408  -0.116695 0.001088793059 -2.55679e-07   7.117814e-06   0.001100428748 2.077264e-06   2.4787446e-05
FR_calf_rotor  0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
FR_foot        0.06      0         0         0         9.6e-06        0              0              9.6e-06        0              9.6e-06
FL_hip         0.591     -0.005657 -0.008752 -0.000102 0.000334008405 -1.0826066e-05 1.290732e-06   0.000619101213 1.643194e-06   0.00040057614
FL_hip_rotor   0.089     0         0         0         0.000111842    0              0              5.9647e-05     0              5.9647e-05
FL_thigh       0.92      -0.003342 -0.018054 -0.033451 0.004431760472 5.7496807e-05  -0.000218457134 0.004485671726 0.000572001265 0.000740309489
FL_thigh_rotor 0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
FL_calf        0.135862  0.006197  0.001408  -0.116695 0.001088793059 -2.55679e-07   7.117814e-06   0.001100428748 2.077264e-06   2.4787446e-05
FL_calf_rotor  0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
FL_foot        0.06      0         0         0         9.6e-06        0              0              9.6e-06        0              9.6e-06
RR_hip         0.591     0.005657  0.008752  -0.000102 0.000334008405 -1.0826066e-05 -1.290732e-06  0.000619101213 -1.643194e-06  0.00040057614
RR_hip_rotor   0.089     0         0         0         0.000111842    0              0              5.9647e-05     0              5.9647e-05
RR_thigh       0.92      -0.003342 0.018054  -0.033451 0.004431760472 -5.7496807e-05 -0.000218457134 0.004485671726 -0.000572001265 0.000740309489
RR_thigh_rotor 0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
RR_calf        0.135862  0.006197  0.001408  -0.116695 0.001088793059 -2.55679e-07   7.117814e-06   0.001100428748 2.077264e-06   2.4787446e-05
RR_calf_rotor  0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
RR_foot        0.06      0         0         0         9.6e-06        0              0              9.6e-06        0              9.6e-06
RL_hip         0.591     0.005657  -0.008752 -0.000102 0.000334008405 1.0826066e-05  -1.290732e-06  0.000619101213 1.643194e-06   0.00040057614
RL_hip_rotor   0.089     0         0         0         0.000111842    0              0              5.9647e-05     0              5.9647e-05
RL_thigh       0.92      -0.003342 -0.018054 -0.033451 0.004431760472 5.7496807e-05  -0.000218457134 0.004485671726 0.000572001265 0.000740309489
RL_thigh_rotor 0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
RL_calf        0.135862  0.006197  0.001408  -0.116695 0.001088793059 -2.55679e-07   7.117814e-06   0.001100428748 2.077264e-06   2.4787446e-05
RL_calf_rotor  0.089     0         0         0         5.9647e-05     0              0              0.000111842    0              5.9647e-05
RL_foot        0.06      0         0         0         9.6e-06        0              0              9.6e-06        0              9.6e-06
"""

ALIENGO_INERTIALS = """
trunk          11.644    0.008811  0.003839  0.000273  0.051944892    0.001703617    0.000235941    0.24693924     0.000119783    0.270948307
FR_hip         1.993     -0.022191 -0.015144 -1.5e-05  0.002446735    0.00059805     1.945e-06      0.003925876    -1.284e-06     0.004148145
FR_hip_rotor   0.146     0         0         0         0.000138702    0              0              8.3352e-05     0              8.3352e-05
FR_thigh       0.639     -0.005607 0.003877  -0.048199 0.004173855    -1.0284e-05    -0.000318874   0.004343802    -0.000109233   0.000340136
FR_thigh_rotor 0.146     0         0         0         8.3352e-05     0              0              0.000138702    0              8.3352e-05
FR_calf        0.207     0.002781  6.3e-05   -0.142518 0.002129279    3.9e-08        5.757e-06      0.002141463    -5.16e-07      3.7583e-05
FR_calf_rotor  0.132     0         0         0         0.000145463    0              0              0.000133031    0              0.000145463
FR_foot        0.06      0         0         0         1.6854e-05     0              0              1.6854e-05     0              1.6854e-05
FL_hip         1.993     -0.022191 0.015144  -1.5e-05  0.002446735    -0.00059805    1.945e-06      0.003925876    1.284e-06      0.004148145
FL_hip_rotor   0.146     0         0         0         0.000138702    0              0              8.3352e-05     0              8.3352e-05
FL_thigh       0.639     -0.005607 -0.003877 -0.048199 0.004173855    1.0284e-05     -0.000318874   0.004343802    0.000109233    0.000340136
FL_thigh_rotor 0.146     0         0         0         8.3352e-05     0              0              0.000138702    0              8.3352e-05
FL_calf        0.207     0.002781  6.3e-05   -0.142518 0.002129279    3.9e-08        5.757e-06      0.002141463    -5.16e-07      3.7583e-05
FL_calf_rotor  0.132     0         0         0         0.000145463    0              0              0.000133031    0              0.000145463
FL_foot        0.06      0         0         0         1.6854e-05     0              0              1.6854e-05     0              1.6854e-05
RR_hip         1.993     0.022191  -0.015144 -1.5e-05  0.002446735    -0.00059805    -1.945e-06     0.003925876    -1.284e-06     0.004148145
RR_hip_rotor   0.146     0         0         0         0.000138702    0              0              8.3352e-05     0              8.3352e-05
RR_thigh       0.639     -0.005607 0.003877  -0.048199 0.004173855    -1.0284e-05    -0.000318874   0.004343802    -0.000109233   0.000340136
RR_thigh_rotor 0.146     0         0         0         8.3352e-05     0              0              0.000138702    0              8.3352e-05
RR_calf        0.207     0.002781  6.3e-05   -0.142518 0.002129279    3.9e-08        5.757e-06      0.002141463    -5.16e-07      3.7583e-05
RR_calf_rotor  0.132     0         0         0         0.000145463    0              0              0.000133031    0              0.000145463
RR_foot        0.06      0         0         0         1.6854e-05     0              0              1.6854e-05     0              1.6854e-05
RL_hip         1.993     0.022191  0.015144  -1.5e-05  0.002446735    0.00059805     -1.945e-06     0.003925876    1.284e-06      0.004148145
RL_hip_rotor   0.146     0         0         0         0.000138702    0              0              8.3352e-05     0              8.3352e-05
RL_thigh       0.639     -0.005607 -0.003877 -0.048199 0.004173855    1.0284e-05     -0.000318874   0.004343802    0.000109233    0.000340136
RL_thigh_rotor 0.146     0         0         0         8.3352e-05     0              0              0.000138702    0              8.3352e-05
RL_calf        0.207     0.002781  6.3e-05   -0.142518 0.002129279    3.9e-08        5.757e-06      0.002141463    -5.16e-07      3.7583e-05
RL_calf_rotor  0.132     0         0         0         0.000145463    0              0              0.000133031    0              0.000145463
RL_foot        0.06      0         0         0         1.6854e-05     0              0              1.6854e-05     0              1.6854e-05
"""

# Kinematics, limits, collision primitives (robots.md 2.1/2.5/2.6 and 3.1/3.5/3.6) and the
# parameters of the project's own visual meshes. Lengths in m, angles in rad. Offsets marked
# "left" are for the reference leg FL and are multiplied by the mirror sign on the right legs.
ROBOTS = {
    "go1": {
        "title": "Unitree Go1",
        "section": "2",
        "inertials": GO1_INERTIALS,
        "vendor_urdf": "go1_description/urdf/go1.urdf",
        "vendor_total": "13.100528",  # robots.md 2.4, URDF as shipped
        "dropped": [("imu_link", "0.001"),
                    ("5 camera + 3 ultrasound frames (1e-5 kg each; optical and laserscan "
                     "frames are massless)", "0.00008")],
        "leg_offset_x": "0.1881",
        "leg_offset_y": "0.04675",
        "thigh_offset": "0.08",
        "thigh_length": "0.213",
        "calf_length": "0.213",
        "hip_rotor_offset": ("0.11215", "0.04675"),
        "thigh_rotor_offset_y": "-0.00015",  # left
        "calf_rotor_offset_y": "-0.03235",  # left
        "limits": {  # lower, upper, effort, velocity (left legs; right hip mirrored by rule)
            "hip": ("-0.863", "0.863", "23.7", "30.1"),
            "thigh": ("-0.686", "4.501", "23.7", "30.1"),
            "calf": ("-2.818", "-0.888", "35.55", "20.06"),
        },
        "trunk_box": ("0.3762", "0.0935", "0.114"),
        "hip_cylinder": ("0.046", "0.04", "0.08"),  # radius, length, y centre (left)
        "thigh_box": ("0.213", "0.0245", "0.034"),  # size in the geometry frame (rpy 0 pi/2 0)
        "calf_box": ("0.213", "0.016", "0.016"),
        "foot_radius": "0.02",
        "foot_visual_radius": "0.01",
        "mesh": {
            "trunk": {"size": (0.38, 0.10, 0.114), "chamfer": 0.01},
            # Housing of the thigh motor on the hip link: y from -0.0345 to 0.0175 (left hip frame).
            "hip": {"radius": 0.046, "y": (-0.0345, 0.0175), "chamfer": 0.004},
            # Thigh bar (hull of two circles in x-z) plus, inboard, the knee-motor housing that
            # turns with the thigh, so left and right thighs differ (thigh.obj / thigh_mirror.obj).
            "thigh": {"r_top": 0.026, "r_bottom": 0.016, "half_width": 0.01225, "chamfer": 0.003,
                      "drum": {"radius": 0.046, "y": (-0.0615, -0.0135), "chamfer": 0.004}},
            "calf": {"r_top": 0.020, "r_bottom": 0.008, "half_width": 0.008, "chamfer": 0.002},
        },
    },
    "aliengo": {
        "title": "Unitree Aliengo",
        "section": "3",
        "inertials": ALIENGO_INERTIALS,
        "vendor_urdf": "aliengo_description/urdf/aliengo.urdf",
        "vendor_total": "24.937",  # robots.md 3.4, URDF as shipped
        "dropped": [("imu_link", "0.001")],
        "leg_offset_x": "0.2407",
        "leg_offset_y": "0.051",
        "thigh_offset": "0.0868",
        "thigh_length": "0.25",
        "calf_length": "0.25",
        "hip_rotor_offset": ("0.139985", "0.051"),
        "thigh_rotor_offset_y": "0.0298",  # left
        "calf_rotor_offset_y": "-0.0997",  # left
        # The vendor defines these in degrees (const.xacro); robots.md 3.5 rounds them to 4
        # decimals. Written here as the vendor's URDF spells deg * pi / 180.
        "limits": {
            "hip": ("-1.2217304763960306", "1.2217304763960306", "35.278", "20"),  # +-70 deg
            # continuous in the vendor URDF; its const.xacro bounds, -120 deg .. 240 deg
            "thigh": ("-2.0943951023931953", "4.1887902047863905", "35.278", "20"),
            "calf": ("-2.775073510670984", "-0.6457718232379019", "44.4", "15.89"),  # -159..-37 deg
        },
        "limits_note": "hip +-70 deg, thigh -120 .. 240 deg, calf -159 .. -37 deg",
        "trunk_box": ("0.647", "0.15", "0.112"),
        "hip_cylinder": ("0.046", "0.0418", "0.083"),  # y centre is hip_offset, not thigh_offset
        "thigh_box": ("0.25", "0.0374", "0.043"),
        "calf_box": ("0.25", "0.0208", "0.016"),
        "foot_radius": "0.0265",
        "foot_visual_radius": "0.0165",
        "mesh": {
            "trunk": {"size": (0.65, 0.15, 0.112), "chamfer": 0.015},
            # Both leg motors sit on the hip link: y from -0.0515 to 0.0621 (left hip frame).
            "hip": {"radius": 0.046, "y": (-0.0515, 0.0621), "chamfer": 0.005},
            "thigh": {"r_top": 0.042, "r_bottom": 0.018, "half_width": 0.0187, "chamfer": 0.004},
            "calf": {"r_top": 0.024, "r_bottom": 0.011, "half_width": 0.0104, "chamfer": 0.0025},
        },
    },
}

MATERIALS = (  # name, rgba
    ("pronk_trunk", "0.22 0.23 0.25 1"),
    ("pronk_motor", "0.42 0.43 0.45 1"),
    ("pronk_leg", "0.72 0.73 0.75 1"),
    ("pronk_foot", "0.05 0.05 0.05 1"),
)

CIRCLE_SEGMENTS = 40  # facets on a full circle of a mesh


# --------------------------------------------------------------------------------------------
# Small helpers
# --------------------------------------------------------------------------------------------

def num(value):
    """Exact decimal text of a Decimal/str (no exponent, no trailing zeros, no '-0')."""
    d = Decimal(value).normalize()
    s = format(d, "f")
    return "0" if s in ("-0", "0") else s


def neg(value):
    return num(-Decimal(value))


def scaled(value, sign):
    return num(Decimal(value) * sign)


def parse_inertials(text):
    rows = {}
    for line in text.strip().splitlines():
        f = line.split()
        assert len(f) == 11, line
        rows[f[0]] = {"mass": f[1], "com": tuple(f[2:5]), "inertia": tuple(f[5:11])}
    return rows


def check_mirroring(rows):
    """The per-leg rows must follow robots.md 1's mirroring rules applied to the FL row."""
    problems = []
    fl = {k: rows["FL_" + k] for k in ("hip", "thigh", "calf", "foot", "hip_rotor",
                                       "thigh_rotor", "calf_rotor")}
    for leg in LEGS:
        m, fh = MIRROR[leg], FRONT_HIND[leg]
        for part, ref in fl.items():
            mass, (x, y, z) = ref["mass"], ref["com"]
            ixx, ixy, ixz, iyy, iyz, izz = ref["inertia"]
            if part == "hip":
                com = (scaled(x, fh), scaled(y, m), num(z))
                inertia = (ixx, scaled(ixy, m * fh), scaled(ixz, fh), iyy, scaled(iyz, m), izz)
            elif part == "thigh":
                com = (num(x), scaled(y, m), num(z))
                inertia = (ixx, scaled(ixy, m), ixz, iyy, scaled(iyz, m), izz)
            else:
                com = (num(x), num(y), num(z))
                inertia = ref["inertia"]
            want = (num(mass),) + com + tuple(num(v) for v in inertia)
            row = rows[leg + "_" + part]
            got = (num(row["mass"]),) + tuple(num(v) for v in row["com"] + row["inertia"])
            if want != got:
                problems.append("%s_%s: table %s, mirroring rule gives %s" % (leg, part, got, want))
    return problems


# 4x4 homogeneous transforms as nested lists (row major)

def mat_mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def translation(x, y, z):
    return [[1.0, 0.0, 0.0, x], [0.0, 1.0, 0.0, y], [0.0, 0.0, 1.0, z], [0.0, 0.0, 0.0, 1.0]]


def rotation(axis, angle):
    """Rodrigues' formula for a unit axis."""
    x, y, z = axis
    c, s, t = math.cos(angle), math.sin(angle), 1.0 - math.cos(angle)
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
            [0.0, 0.0, 0.0, 1.0]]


def apply(t, p):
    return tuple(t[i][0] * p[0] + t[i][1] * p[1] + t[i][2] * p[2] + t[i][3] for i in range(3))


def vsub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def vadd(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def vscale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


# --------------------------------------------------------------------------------------------
# Meshes. A mesh is a list of closed convex parts; a part is a list of triangles, each
# ((p0, n0), (p1, n1), (p2, n2)) with per-corner unit normals, wound counter-clockwise seen from
# outside.
# --------------------------------------------------------------------------------------------

def orient(tri):
    """Wind a triangle so that its geometric normal agrees with its corner normals."""
    (p0, n0), (p1, n1), (p2, n2) = tri
    g = cross(vsub(p1, p0), vsub(p2, p0))
    if dot(g, vadd(vadd(n0, n1), n2)) < 0:
        return (tri[0], tri[2], tri[1])
    return tri


def loft(rings, normals, cap_normals):
    """Triangles joining consecutive rings (equal point counts) plus fan caps on the end rings.

    rings[k][j] is a point; normals[k][j] = (normal at ring k side, normal at ring k+1 side)
    for the band between ring k and k+1 at column j; cap_normals = (first cap, last cap).
    """
    tris = []
    n = len(rings[0])
    for k in range(len(rings) - 1):
        a, b = rings[k], rings[k + 1]
        for j in range(n):
            j1 = (j + 1) % n
            na0, nb0 = normals[k][j]
            na1, nb1 = normals[k][j1]
            tris.append(orient(((a[j], na0), (a[j1], na1), (b[j1], nb1))))
            tris.append(orient(((a[j], na0), (b[j1], nb1), (b[j], nb0))))
    for ring, cn in ((rings[0], cap_normals[0]), (rings[-1], cap_normals[1])):
        for j in range(1, n - 1):
            tris.append(orient(((ring[0], cn), (ring[j], cn), (ring[j + 1], cn))))
    return tris


def rounded_profile(circles):
    """Outline of the convex hull of one or two circles in the x-z plane.

    circles: [(cx, cz, r)], the first on top when there are two. Returns a list of
    (centre, unit outward normal, radius) so that each point is centre + r * normal and an
    inset outline is centre + (r - d) * normal (the same hull, shrunk by d).
    """
    out = []
    if len(circles) == 1:
        cx, cz, r = circles[0]
        for j in range(CIRCLE_SEGMENTS):
            th = 2.0 * math.pi * j / CIRCLE_SEGMENTS
            out.append(((cx, cz), (math.cos(th), math.sin(th)), r))
        return out
    (x1, z1, r1), (x2, z2, r2) = circles
    assert x1 == x2 and z1 > z2 and r1 >= r2
    alpha = math.asin((r1 - r2) / (z1 - z2))  # tilt of the straight sides
    spans = ((x1, z1, r1, -alpha, math.pi + alpha), (x2, z2, r2, math.pi + alpha, 2 * math.pi - alpha))
    for cx, cz, r, t0, t1 in spans:
        steps = max(2, int(round(CIRCLE_SEGMENTS * (t1 - t0) / (2 * math.pi))))
        for j in range(steps + 1):
            th = t0 + (t1 - t0) * j / steps
            out.append(((cx, cz), (math.cos(th), math.sin(th)), r))
    return out


def extrude_y(profile, y0, y1, chamfer):
    """A profile (x-z plane) extruded along y from y0 to y1, with 45-degree chamfered rims."""
    c = chamfer
    s = math.sqrt(0.5)
    layers = ((y0, c), (y0 + c, 0.0), (y1 - c, 0.0), (y1, c))  # (y, inset)
    rings = []
    for y, inset in layers:
        rings.append([(cx + (r - inset) * nx, y, cz + (r - inset) * nz)
                      for (cx, cz), (nx, nz), r in profile])
    side = [((nx, 0.0, nz), (nx, 0.0, nz)) for _, (nx, nz), _ in profile]
    low = [((nx * s, -s, nz * s),) * 2 for _, (nx, nz), _ in profile]
    high = [((nx * s, s, nz * s),) * 2 for _, (nx, nz), _ in profile]
    return loft(rings, [low, side, high], ((0.0, -1.0, 0.0), (0.0, 1.0, 0.0)))


def chamfered_box(size, chamfer):
    """A box centred at the origin with all edges bevelled at 45 degrees (flat shaded)."""
    a, b, h = size[0] / 2, size[1] / 2, size[2] / 2
    c = chamfer
    k_full = c  # corner cut of the full-size octagon, along each axis

    def octagon(ha, hb, k, z):
        return [(ha, -hb + k, z), (ha, hb - k, z), (ha - k, hb, z), (-ha + k, hb, z),
                (-ha, hb - k, z), (-ha, -hb + k, z), (-ha + k, -hb, z), (ha - k, -hb, z)]

    # The inset octagon's diagonal cut keeps every bevel face 45 degrees wide by c.
    k_in = k_full - c * (2.0 - math.sqrt(2.0))
    rings = [octagon(a - c, b - c, k_in, -h), octagon(a, b, k_full, -h + c),
             octagon(a, b, k_full, h - c), octagon(a - c, b - c, k_in, h)]
    tris = []
    for k in range(3):
        lo, hi = rings[k], rings[k + 1]
        for j in range(8):
            j1 = (j + 1) % 8
            quad = (lo[j], lo[j1], hi[j1], hi[j])
            nrm = normalize(cross(vsub(quad[1], quad[0]), vsub(quad[3], quad[0])))
            if dot(nrm, vadd(quad[0], quad[2])) < 0:  # box is centred: outward = away from 0
                nrm = vscale(nrm, -1.0)
            tris.append(orient(((quad[0], nrm), (quad[1], nrm), (quad[2], nrm))))
            tris.append(orient(((quad[0], nrm), (quad[2], nrm), (quad[3], nrm))))
    for ring, nrm in ((rings[0], (0.0, 0.0, -1.0)), (rings[3], (0.0, 0.0, 1.0))):
        for j in range(1, 7):
            tris.append(orient(((ring[0], nrm), (ring[j], nrm), (ring[j + 1], nrm))))
    return tris


def mirror_y(parts):
    """Mirror image in y: negate y of points and normals, reverse the winding."""
    def m(pn):
        (x, y, z), (nx, ny, nz) = pn
        return ((x, -y, z), (nx, -ny, nz))
    return [[(m(t[0]), m(t[2]), m(t[1])) for t in part] for part in parts]


def key(p):
    return tuple("%.6f" % (0.0 if abs(v) < 5e-7 else v) for v in p)


def check_part(part, name):
    """Closed, consistently wound, outward (positive volume), normals agree with faces."""
    edges = {}
    volume = 0.0
    for tri in part:
        ks = [key(p) for p, _ in tri]
        if len(set(ks)) < 3:
            raise SystemExit("mesh %s: degenerate triangle" % name)
        for i in range(3):
            e = (ks[i], ks[(i + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
        p0, p1, p2 = (p for p, _ in tri)
        volume += dot(p0, cross(p1, p2)) / 6.0
        g = cross(vsub(p1, p0), vsub(p2, p0))
        for _, n in tri:
            if dot(g, n) <= 0:
                raise SystemExit("mesh %s: a vertex normal points against its face" % name)
    for (a, b), count in edges.items():
        if count != 1 or edges.get((b, a)) != 1:
            raise SystemExit("mesh %s: not a closed, consistently wound surface" % name)
    if volume <= 0:
        raise SystemExit("mesh %s: inward-facing surface" % name)
    return volume


def obj_text(parts, title):
    """Wavefront OBJ: shared positions and normals, triangles 'f v//vn'."""
    positions, normals, faces = {}, {}, []
    for part in parts:
        for tri in part:
            face = []
            for p, n in tri:
                pk, nk = key(p), key(n)
                if pk not in positions:
                    positions[pk] = len(positions) + 1
                if nk not in normals:
                    normals[nk] = len(normals) + 1
                face.append("%d//%d" % (positions[pk], normals[nk]))
            faces.append("f " + " ".join(face))
    lines = ["# %s" % title,
             "# Generated by %s; do not edit. Units: metres, link frame." % COMMAND,
             "# %d vertices, %d normals, %d triangles" % (len(positions), len(normals), len(faces)),
             "o %s" % title.split()[-1]]
    lines += ["v %s %s %s" % k for k in positions]
    lines += ["vn %s %s %s" % k for k in normals]
    lines += faces
    return "\n".join(lines) + "\n", len(faces)


def bounds(parts):
    pts = [p for part in parts for tri in part for p, _ in tri]
    lo = tuple(min(p[i] for p in pts) for i in range(3))
    hi = tuple(max(p[i] for p in pts) for i in range(3))
    return lo, hi


def build_meshes(spec):
    """Returns {file name: (parts, description)} for one robot."""
    ms = spec["mesh"]
    L1 = float(spec["thigh_length"])
    L2 = float(spec["calf_length"])
    meshes = {}
    t = ms["trunk"]
    meshes["trunk.obj"] = ([chamfered_box(t["size"], t["chamfer"])],
                           "trunk: box %.3f x %.3f x %.3f m with %.3f m bevelled edges"
                           % (t["size"] + (t["chamfer"],)))
    h = ms["hip"]
    hl = h["y"][1] - h["y"][0]
    meshes["hip.obj"] = ([extrude_y(rounded_profile([(0.0, 0.0, h["radius"])]), -hl / 2, hl / 2,
                                    h["chamfer"])],
                         "hip: motor housing, cylinder r %.3f m, length %.4f m along y, centred "
                         "(placed by the visual origin)" % (h["radius"], hl))
    th = ms["thigh"]
    bar = extrude_y(rounded_profile([(0.0, 0.0, th["r_top"]), (0.0, -L1, th["r_bottom"])]),
                    -th["half_width"], th["half_width"], th["chamfer"])
    desc = ("thigh: tapered rounded bar, r %.3f m at the hip pitch axis to r %.3f m at the knee "
            "(%.3f m below), %.4f m thick" % (th["r_top"], th["r_bottom"], L1, 2 * th["half_width"]))
    parts = [bar]
    if "drum" in th:
        d = th["drum"]
        parts.append(extrude_y(rounded_profile([(0.0, 0.0, d["radius"])]), d["y"][0], d["y"][1],
                               d["chamfer"]))
        desc += ("; knee-motor housing r %.3f m from y %.4f to %.4f (inboard)"
                 % (d["radius"], d["y"][0], d["y"][1]))
        meshes["thigh.obj"] = (parts, desc + ", left legs")
        meshes["thigh_mirror.obj"] = (mirror_y(parts), desc.replace("inboard", "mirrored in y")
                                      + ", right legs")
    else:
        meshes["thigh.obj"] = (parts, desc + ", all legs")
    c = ms["calf"]
    meshes["calf.obj"] = ([extrude_y(rounded_profile([(0.0, 0.0, c["r_top"]), (0.0, -L2, c["r_bottom"])]),
                                     -c["half_width"], c["half_width"], c["chamfer"])],
                          "calf: tapered rounded bar, r %.3f m at the knee to r %.3f m at the foot "
                          "(%.3f m below), %.4f m thick" % (c["r_top"], c["r_bottom"], L2,
                                                             2 * c["half_width"]))
    return meshes


# --------------------------------------------------------------------------------------------
# Robot model: links and joints as data (used for the URDF text and for the kinematics)
# --------------------------------------------------------------------------------------------

def build_model(name, spec):
    rows = parse_inertials(spec["inertials"])
    problems = check_mirroring(rows)
    if problems:
        raise SystemExit("%s inertial table breaks the mirroring rules:\n  %s"
                         % (name, "\n  ".join(problems)))
    links, joints = [], []
    zero3 = ("0", "0", "0")

    def link(lname, visuals=(), collisions=()):
        links.append({"name": lname, "inertial": rows[lname], "visuals": list(visuals),
                      "collisions": list(collisions)})

    def joint(jname, jtype, parent, child, xyz, axis=None, limit=None):
        joints.append({"name": jname, "type": jtype, "parent": parent, "child": child,
                       "xyz": tuple(num(v) for v in xyz), "axis": axis, "limit": limit})

    tb = spec["trunk_box"]
    link("trunk",
         visuals=[{"xyz": zero3, "rpy": "0 0 0", "mesh": "meshes/trunk.obj", "material": "pronk_trunk"}],
         collisions=[{"xyz": zero3, "rpy": "0 0 0", "geometry": '<box size="%s %s %s"/>' % tb}])
    hip_mesh = spec["mesh"]["hip"]
    hip_centre = Decimal(repr(round((hip_mesh["y"][0] + hip_mesh["y"][1]) / 2, 6)))
    asymmetric_thigh = "drum" in spec["mesh"]["thigh"]
    r_c, l_c, y_c = spec["hip_cylinder"]
    for leg in LEGS:
        m, fh = MIRROR[leg], FRONT_HIND[leg]
        lo, hi, eff, vel = spec["limits"]["hip"]
        hip_limit = (lo, hi) if m > 0 else (neg(hi), neg(lo))
        joint(leg + "_hip_joint", "revolute", "trunk", leg + "_hip",
              (Decimal(spec["leg_offset_x"]) * fh, Decimal(spec["leg_offset_y"]) * m, 0),
              axis="1 0 0", limit=hip_limit + (eff, vel))
        link(leg + "_hip",
             visuals=[{"xyz": ("0", scaled(hip_centre, m), "0"), "rpy": "0 0 0",
                       "mesh": "meshes/hip.obj", "material": "pronk_motor"}],
             collisions=[{"xyz": ("0", scaled(y_c, m), "0"), "rpy": HALF_PI + " 0 0",
                          "geometry": '<cylinder radius="%s" length="%s"/>' % (r_c, l_c)}])
        hrx, hry = spec["hip_rotor_offset"]
        joint(leg + "_hip_rotor_joint", "fixed", "trunk", leg + "_hip_rotor",
              (Decimal(hrx) * fh, Decimal(hry) * m, 0))
        link(leg + "_hip_rotor")
        lo, hi, eff, vel = spec["limits"]["thigh"]
        joint(leg + "_thigh_joint", "revolute", leg + "_hip", leg + "_thigh",
              (0, Decimal(spec["thigh_offset"]) * m, 0), axis="0 1 0", limit=(lo, hi, eff, vel))
        thigh_mesh = "meshes/thigh_mirror.obj" if (asymmetric_thigh and m < 0) else "meshes/thigh.obj"
        L1 = spec["thigh_length"]
        link(leg + "_thigh",
             visuals=[{"xyz": zero3, "rpy": "0 0 0", "mesh": thigh_mesh, "material": "pronk_leg"}],
             collisions=[{"xyz": ("0", "0", num(-Decimal(L1) / 2)), "rpy": "0 " + HALF_PI + " 0",
                          "geometry": '<box size="%s %s %s"/>' % spec["thigh_box"]}])
        joint(leg + "_thigh_rotor_joint", "fixed", leg + "_hip", leg + "_thigh_rotor",
              (0, Decimal(spec["thigh_rotor_offset_y"]) * m, 0))
        link(leg + "_thigh_rotor")
        lo, hi, eff, vel = spec["limits"]["calf"]
        joint(leg + "_calf_joint", "revolute", leg + "_thigh", leg + "_calf",
              (0, 0, -Decimal(L1)), axis="0 1 0", limit=(lo, hi, eff, vel))
        L2 = spec["calf_length"]
        link(leg + "_calf",
             visuals=[{"xyz": zero3, "rpy": "0 0 0", "mesh": "meshes/calf.obj", "material": "pronk_leg"}],
             collisions=[{"xyz": ("0", "0", num(-Decimal(L2) / 2)), "rpy": "0 " + HALF_PI + " 0",
                          "geometry": '<box size="%s %s %s"/>' % spec["calf_box"]}])
        joint(leg + "_calf_rotor_joint", "fixed", leg + "_thigh", leg + "_calf_rotor",
              (0, Decimal(spec["calf_rotor_offset_y"]) * m, 0))
        link(leg + "_calf_rotor")
        joint(leg + "_foot_fixed", "fixed", leg + "_calf", leg + "_foot", (0, 0, -Decimal(L2)))
        link(leg + "_foot",
             visuals=[{"xyz": zero3, "rpy": "0 0 0", "material": "pronk_foot",
                       "geometry": '<sphere radius="%s"/>' % spec["foot_visual_radius"]}],
             collisions=[{"xyz": zero3, "rpy": "0 0 0",
                          "geometry": '<sphere radius="%s"/>' % spec["foot_radius"]}])
    assert sorted(l["name"] for l in links) == sorted(rows), "every table row is used once"
    return {"name": name, "links": links, "joints": joints}


def urdf_text(model, spec):
    out = ['<?xml version="1.0"?>',
           "<!-- %s for pronk. Generated by %s; do not edit. -->" % (spec["title"], COMMAND),
           "<!-- Written from the project's reference notes (robots.md section %s; unitree_ros "
           "figures reconfirmed 2022-11-16). See README.md beside this file. -->" % spec["section"],
           '<robot name="%s">' % model["name"]]
    for mname, rgba in MATERIALS:
        out += ['  <material name="%s">' % mname, '    <color rgba="%s"/>' % rgba, "  </material>"]
    by_child = {j["child"]: j for j in model["joints"]}
    for link in model["links"]:
        j = by_child.get(link["name"])
        if j is not None:
            out.append('  <joint name="%s" type="%s">' % (j["name"], j["type"]))
            out.append('    <origin xyz="%s %s %s" rpy="0 0 0"/>' % j["xyz"])
            out.append('    <parent link="%s"/>' % j["parent"])
            out.append('    <child link="%s"/>' % j["child"])
            if j["axis"]:
                out.append('    <axis xyz="%s"/>' % j["axis"])
                out.append('    <dynamics damping="0" friction="0"/>')
                out.append('    <limit lower="%s" upper="%s" effort="%s" velocity="%s"/>' % j["limit"])
            out.append("  </joint>")
        out.append('  <link name="%s">' % link["name"])
        for v in link["visuals"]:
            geometry = v.get("geometry") or '<mesh filename="%s"/>' % v["mesh"]
            out += ["    <visual>",
                    '      <origin xyz="%s %s %s" rpy="%s"/>' % (v["xyz"] + (v["rpy"],)),
                    "      <geometry>", "        " + geometry, "      </geometry>",
                    '      <material name="%s"/>' % v["material"],
                    "    </visual>"]
        for c in link["collisions"]:
            out += ["    <collision>",
                    '      <origin xyz="%s %s %s" rpy="%s"/>' % (c["xyz"] + (c["rpy"],)),
                    "      <geometry>", "        " + c["geometry"], "      </geometry>",
                    "    </collision>"]
        ine = link["inertial"]
        out += ["    <inertial>",
                '      <origin xyz="%s %s %s" rpy="0 0 0"/>' % tuple(num(v) for v in ine["com"]),
                '      <mass value="%s"/>' % num(ine["mass"]),
                '      <inertia ixx="%s" ixy="%s" ixz="%s" iyy="%s" iyz="%s" izz="%s"/>'
                % tuple(num(v) for v in ine["inertia"]),
                "    </inertial>",
                "  </link>"]
    out.append("</robot>")
    return "\n".join(out) + "\n"


# --------------------------------------------------------------------------------------------
# Kinematics and derived figures
# --------------------------------------------------------------------------------------------

def link_poses(model, q):
    """World (= trunk) pose of every link for joint angles q {joint name: angle}."""
    poses = {"trunk": translation(0.0, 0.0, 0.0)}
    children = {}
    for j in model["joints"]:
        children.setdefault(j["parent"], []).append(j)
    stack = ["trunk"]
    while stack:
        parent = stack.pop()
        for j in children.get(parent, []):
            t = mat_mul(poses[parent], translation(*(float(v) for v in j["xyz"])))
            if j["axis"]:
                axis = tuple(float(v) for v in j["axis"].split())
                t = mat_mul(t, rotation(axis, q.get(j["name"], 0.0)))
            poses[j["child"]] = t
            stack.append(j["child"])
    return poses


def centre_of_mass(model, q):
    poses = link_poses(model, q)
    total, acc = 0.0, (0.0, 0.0, 0.0)
    for link in model["links"]:
        m = float(link["inertial"]["mass"])
        p = apply(poses[link["name"]], tuple(float(v) for v in link["inertial"]["com"]))
        acc = vadd(acc, vscale(p, m))
        total += m
    return vscale(acc, 1.0 / total)


def stance_q(hip, thigh, calf):
    q = {}
    for leg in LEGS:
        q[leg + "_hip_joint"], q[leg + "_thigh_joint"], q[leg + "_calf_joint"] = hip, thigh, calf
    return q


def derived(model, spec):
    d = {}
    d["total_mass"] = sum(Decimal(l["inertial"]["mass"]) for l in model["links"])
    by_kind = {}
    for l in model["links"]:
        kind = l["name"].split("_", 1)[1] if "_" in l["name"] else l["name"]
        by_kind[kind] = by_kind.get(kind, Decimal(0)) + Decimal(l["inertial"]["mass"])
    d["mass_by_kind"] = by_kind
    dropped = sum(Decimal(m) for _, m in spec["dropped"])
    d["vendor_minus_dropped"] = Decimal(spec["vendor_total"]) - dropped
    if d["total_mass"] != d["vendor_minus_dropped"]:
        raise SystemExit("%s: total mass %s differs from the vendor total minus dropped links %s"
                         % (model["name"], d["total_mass"], d["vendor_minus_dropped"]))
    q0 = stance_q(0.0, 0.0, 0.0)
    qs = stance_q(*STANCE)
    d["com_q0"] = centre_of_mass(model, q0)
    d["com_stance"] = centre_of_mass(model, qs)
    poses0, poses = link_poses(model, q0), link_poses(model, qs)
    r = float(spec["foot_radius"])
    feet = {}
    for leg in LEGS:
        hip = apply(poses[leg + "_hip"], (0.0, 0.0, 0.0))
        pitch = apply(poses[leg + "_thigh"], (0.0, 0.0, 0.0))
        foot = apply(poses[leg + "_foot"], (0.0, 0.0, 0.0))
        foot0 = apply(poses0[leg + "_foot"], (0.0, 0.0, 0.0))
        feet[leg] = {"hip": hip, "foot": foot, "foot_q0": foot0,
                     "dx": foot[0] - hip[0], "dz": hip[2] - foot[2],
                     "pitch_to_foot": math.sqrt(dot(vsub(foot, pitch), vsub(foot, pitch))),
                     "hip_to_foot": math.sqrt(dot(vsub(foot, hip), vsub(foot, hip)))}
        # With equal thigh and calf lengths and calf = -2 * thigh the foot must lie exactly
        # below the hip (robots.md 5); any offset means a kinematic error.
        if spec["thigh_length"] == spec["calf_length"] and abs(feet[leg]["dx"]) > 1e-12:
            raise SystemExit("%s %s: stance foot is %.3g m off the hip in x"
                             % (model["name"], leg, feet[leg]["dx"]))
    d["feet"] = feet
    dz = feet["FL"]["dz"]
    d["hip_to_foot_dz"] = dz
    d["analytic_dz"] = float(spec["thigh_length"]) * math.cos(STANCE[1]) + \
        float(spec["calf_length"]) * math.cos(STANCE[1] + STANCE[2])
    assert abs(dz - d["analytic_dz"]) < 1e-12
    d["trunk_height"] = dz + r
    d["trunk_height_q0"] = feet["FL"]["hip"][2] - feet["FL"]["foot_q0"][2] + r
    d["com_height_stance"] = d["trunk_height"] + d["com_stance"][2]
    return d


# --------------------------------------------------------------------------------------------
# README
# --------------------------------------------------------------------------------------------

def f3(v):
    return "(%s)" % ", ".join("%+.5f" % (0.0 if abs(x) < 5e-6 else x) for x in v)


def readme_text(name, spec, model, figures, mesh_info):
    s = spec["section"]
    lim = spec["limits"]
    lines = []
    w = lines.append
    w("# %s: pronk's robot description" % spec["title"])
    w("")
    w("`%s.urdf` is the project's own URDF of the %s, written from the figures in the "
      "project's reference notes on Unitree robots (robots.md, sections 1 and %s). `meshes/` "
      "holds its visual meshes: simple shapes built by the project, not the vendor's meshes." %
      (name, spec["title"], s))
    w("")
    w("**Generated files, do not edit by hand.** Everything in this folder, this README "
      "included, is written by")
    w("")
    w("    %s" % COMMAND)
    w("")
    w("run from the repository root. Change the numbers in `tools/make_robot_assets.py` and run it "
      "again; `%s --check` fails when the committed files are stale, and `%s --compare-vendor "
      "<dir with go1_description/ and aliengo_description/>` compares the inertials, joints and "
      "collision shapes with the vendor's URDF." % (COMMAND, COMMAND))
    w("")
    w("## Sources")
    w("")
    w("- robots.md section 1 (frames, leg order, chain, mirroring rules, sign convention), "
      "%s.1 (kinematic constants), %s.2 (joint origins), %s.3 (per-leg mass, COM and inertia), "
      "%s.4 (total mass), %s.5 (joint limits), %s.6 (collision geometry), %s.8 (mesh sizes)."
      % ((s,) * 7))
    w("- Those tables were read from `unitreerobotics/unitree_ros` at commit d6f13aad "
      "(`robots/%s_description/xacro/const.xacro`, `xacro/leg.xacro`, `xacro/robot.xacro`, "
      "`urdf/%s.urdf`), with the inertial parameters \"reconfirmed\" on 2022-11-16 (commit %s). "
      "Older parameter sets still found downstream are not used." %
      (name, name, "ca57a18" if name == "go1" else "fc15975"))
    w("")
    w("## Choices")
    w("")
    w("- **Root link `trunk`.** There is no massless dummy `base` link and no `floating_base` "
      "joint; the simulator adds the free joint to the root itself. The trunk frame is at the "
      "trunk's geometric centre, x forward, y left, z up.")
    w("- **Names and sign convention as Unitree's.** Legs FR, FL, RR, RL; joints "
      "`<L>_hip_joint` (axis +x), `<L>_thigh_joint` (axis +y), `<L>_calf_joint` (axis +y), "
      "`<L>_foot_fixed` to `<L>_foot`. Every joint origin has rpy = 0, so at q = 0 the legs hang "
      "straight down. A positive thigh angle swings the foot back; calf angles are always "
      "negative (the knee points back). The paper's q0 = [0, -0.75, 1.5] is (0, +0.75, -1.5) here.")
    w("- **Rotors included as fixed links.** `<L>_hip_rotor` (child of the trunk), "
      "`<L>_thigh_rotor` (child of the hip) and `<L>_calf_rotor` (child of the thigh) carry the "
      "vendor's rotor masses, inertias and offsets. The loader lumps links on fixed joints into "
      "the moving body they hang from, so the rotors end up as rigid mass of trunk, hip and "
      "thigh, as in the vendor model. Their spin and the reflected inertia of the gearbox are not "
      "modelled (the vendor's own note says the rotor links only show where the rotors are). They "
      "have no collision shapes (removed upstream) and no visuals (they sit inside the housings).")
    w("- **No IMU or sensor links**: they carry no physics that matters; their mass is left out "
      "(see the mass table below).")
    if name == "aliengo":
        w("- **Thigh joints are `revolute`, not `continuous`.** The vendor URDF declares the Aliengo "
          "thigh joints continuous; this file gives them the bounds from the vendor's "
          "const.xacro, %.4f .. %.4f rad (-120 deg .. 240 deg), so that every joint has position "
          "limits." % tuple(float(v) for v in lim["thigh"][:2]))
        w("- **Two lateral offsets, kept as the vendor has them.** The thigh joint sits %s m "
          "outboard of the hip joint (`thigh_offset`), but the hip collision cylinder is centred "
          "at %s m (`hip_offset`). Older Aliengo files use 0.083 for both and put the hip at "
          "x = 0.2399 instead of %s." % (spec["thigh_offset"], spec["hip_cylinder"][2],
                                          spec["leg_offset_x"]))
    w("- **Joint limits** are the current vendor figures (robots.md %s.5): hip %s .. %s rad, "
      "thigh %s .. %s rad, calf %s .. %s rad; effort %s / %s / %s N m; velocity %s / %s / %s "
      "rad/s (hip / thigh / calf). `<dynamics damping=\"0\" friction=\"0\"/>` on every joint." %
      (s, lim["hip"][0], lim["hip"][1], lim["thigh"][0], lim["thigh"][1], lim["calf"][0],
       lim["calf"][1], lim["hip"][2], lim["thigh"][2], lim["calf"][2], lim["hip"][3],
       lim["thigh"][3], lim["calf"][3]))
    if "limits_note" in spec:
        w("  The position limits are the vendor's round degrees (%s) converted exactly, as its "
          "URDF writes them; robots.md rounds them to 4 decimals." % spec["limits_note"])
    if name == "go1":
        w("  The thigh's upper limit, 4.501 rad, is far beyond the SDK's 2.966 rad; the controller, "
          "not the URDF, should keep the leg in its useful range.")
    w("- **Feet.** Collision sphere r = %s m on the foot link (the vendor's figure%s); visual "
      "sphere r = %s m, as in the vendor file. The vendor hides the smaller visual sphere inside "
      "its calf mesh, which includes the rubber foot; here the calf bar ends at the foot centre, so "
      "a render shows the foot ball %s m smaller than the contact sphere: in stance the drawn "
      "foot stops %s m above the ground. Set `foot_visual_radius` to the collision radius in the "
      "script to draw the contact sphere instead." %
      (spec["foot_radius"], "; MuJoCo Menagerie uses 0.023" if name == "go1" else "",
       spec["foot_visual_radius"],
       num(Decimal(spec["foot_radius"]) - Decimal(spec["foot_visual_radius"])),
       num(Decimal(spec["foot_radius"]) - Decimal(spec["foot_visual_radius"]))))
    w("- **Inertials** are the vendor's per-leg figures verbatim (mirroring of COM and products "
      "of inertia already applied); the script checks every row against the mirroring rules of "
      "robots.md section 1 before writing.")
    if name == "aliengo":
        w("  The vendor's calf rotor has its smallest moment about its spin axis y (%s, against %s "
          "about x and z); it is kept as published." % ("0.000133031", "0.000145463"))
    w("- **Collision shapes** are the vendor's primitives: trunk box %s x %s x %s m; hip cylinder "
      "r %s m, length %s m, axis y, centred %s m outboard of the hip joint; thigh box %s (x) x %s "
      "(y) x %s (z) m and calf box %s x %s x %s m, each centred half-way down its link "
      "(written as `size=\"L w h\"` with rpy 0 pi/2 0); foot sphere r %s m." %
      (spec["trunk_box"] + spec["hip_cylinder"] +
       (spec["thigh_box"][2], spec["thigh_box"][1], spec["thigh_box"][0],
        spec["calf_box"][2], spec["calf_box"][1], spec["calf_box"][0], spec["foot_radius"])))
    w("- **Visuals** are the project's own Wavefront OBJ meshes (triangles, vertex normals, metres, "
      "link frame), referenced with URIs relative to this folder (`meshes/...`), plus sphere "
      "primitives for the feet. URDF materials colour them: dark grey trunk, mid grey motor "
      "housings, light grey thighs and calves, black feet. The trunk mesh is close to the "
      "collision box so that what is drawn is what collides; the vendor's trunk mesh is wider"
      "%s." % (" (MuJoCo Menagerie's envelope is about 0.196 m)" if name == "go1"
               else " (0.209 m)"))
    w("")
    w("## Meshes")
    w("")
    w("| file | triangles | bounds min (x, y, z) [m] | bounds max [m] | what it is |")
    w("|---|---|---|---|---|")
    for fname, (tris, lo, hi, desc) in mesh_info.items():
        w("| `meshes/%s` | %d | %s | %s | %s |" % (fname, tris, f3(lo), f3(hi), desc))
    hip = spec["mesh"]["hip"]
    w("")
    w("The hip mesh is centred on its own origin; each hip's `<visual><origin>` moves it to "
      "y = %+.4f m (left) / %+.4f m (right) in the hip frame, so one file serves all four legs. "
      % ((hip["y"][0] + hip["y"][1]) / 2, -(hip["y"][0] + hip["y"][1]) / 2) +
      ("The thigh mesh carries the knee-motor housing on its inboard side, so the right legs use "
       "`thigh_mirror.obj`, the left mesh mirrored in y." if "drum" in spec["mesh"]["thigh"]
       else "The thigh and calf meshes are symmetric in y and serve all legs."))
    w("")
    w("## Mass")
    w("")
    w("| links | mass [kg] |")
    w("|---|---|")
    labels = (("trunk", "trunk"), ("hip", "4 hips"), ("thigh", "4 thighs"), ("calf", "4 calves"),
              ("foot", "4 feet"), ("hip_rotor", "4 hip rotors"), ("thigh_rotor", "4 thigh rotors"),
              ("calf_rotor", "4 calf rotors"))
    for kind, label in labels:
        w("| %s | %s |" % (label, num(figures["mass_by_kind"][kind])))
    w("| **total, this file** | **%s** |" % num(figures["total_mass"]))
    w("| vendor URDF as shipped (robots.md %s.4) | %s |" % (s, spec["vendor_total"]))
    for what, m in spec["dropped"]:
        w("| left out: %s | %s |" % (what, m))
    w("")
    w("The total equals the vendor's total minus the links left out, exactly (the script "
      "checks it).")
    w("")
    w("## Derived figures (computed by the script's forward kinematics)")
    w("")
    w("Trunk frame, hips at z = 0. Stance q = (hip, thigh, calf) = (%g, %g, %g) rad on all legs; "
      "trunk height = vertical hip-to-foot-centre distance + foot radius, on flat ground." % STANCE)
    w("")
    fl = figures["feet"]["FL"]
    w("| figure | value |")
    w("|---|---|")
    w("| total mass | %s kg |" % num(figures["total_mass"]))
    w("| whole-body COM at q = 0 | %s m |" % f3(figures["com_q0"]))
    w("| whole-body COM at the stance | %s m |" % f3(figures["com_stance"]))
    w("| hip-to-foot vertical distance at the stance | %.5f m (= %s cos 0.75 + %s cos(-0.75)) |"
      % (figures["hip_to_foot_dz"], spec["thigh_length"], spec["calf_length"]))
    w("| foot x relative to its hip joint at the stance | %.5f m (exactly below the hip) |"
      % abs(fl["dx"]))
    w("| hip pitch axis to foot centre at the stance | %.5f m |" % fl["pitch_to_foot"])
    w("| hip (abduction) joint to foot centre at the stance | %.5f m (includes the %s m lateral "
      "offset) |" % (fl["hip_to_foot"], spec["thigh_offset"]))
    w("| **standing trunk height at the stance** | **%.5f m** (%.5f + %s) |"
      % (figures["trunk_height"], figures["hip_to_foot_dz"], spec["foot_radius"]))
    w("| COM height above ground at the stance | %.5f m |" % figures["com_height_stance"])
    w("| trunk height with straight legs (q = 0) | %.5f m |" % figures["trunk_height_q0"])
    w("")
    w("Feet at the stance, in the trunk frame [m]:")
    w("")
    w("| leg | hip joint | foot centre |")
    w("|---|---|---|")
    for leg in LEGS:
        w("| %s | %s | %s |" % (leg, f3(figures["feet"][leg]["hip"]), f3(figures["feet"][leg]["foot"])))
    w("")
    w("## Differences from the vendor URDF")
    w("")
    w("- No `base` link, `floating_base` joint, `imu_link`%s." %
      (", camera or ultrasound frames" if name == "go1" else ""))
    w("- No rotor collision cylinders (the vendor's generated URDF still has them; its xacro "
      "dropped them in 2023).")
    if name == "aliengo":
        w("- Thigh joints revolute with limits instead of continuous.")
    w("- Own visual meshes (OBJ) instead of the vendor's COLLADA meshes; no Gazebo, transmission "
      "or sensor plugin elements.")
    w("- Everything else (link and joint names, joint origins and axes, limits, inertials, "
      "collision primitives) has the vendor's values.")
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------------
# Assemble, write, check, compare
# --------------------------------------------------------------------------------------------

def generate():
    """Returns ({relative path: text}, {robot: figures})."""
    files, all_figures = {}, {}
    for name, spec in ROBOTS.items():
        model = build_model(name, spec)
        figures = derived(model, spec)
        meshes = build_meshes(spec)
        referenced = sorted({v["mesh"] for l in model["links"] for v in l["visuals"] if "mesh" in v})
        if referenced != sorted("meshes/" + f for f in meshes):
            raise SystemExit("%s: meshes referenced %s but built %s" % (name, referenced, sorted(meshes)))
        mesh_info = {}
        for fname, (parts, desc) in meshes.items():
            for i, part in enumerate(parts):
                check_part(part, "%s/%s part %d" % (name, fname, i))
            text, ntri = obj_text(parts, "pronk %s %s" % (name, fname[:-4]))
            if ntri >= 2000:
                raise SystemExit("%s/%s: %d triangles, the budget is < 2000" % (name, fname, ntri))
            lo, hi = bounds(parts)
            mesh_info[fname] = (ntri, lo, hi, desc)
            files["assets/robots/%s/meshes/%s" % (name, fname)] = text
        files["assets/robots/%s/%s.urdf" % (name, name)] = urdf_text(model, spec)
        files["assets/robots/%s/README.md" % name] = readme_text(name, spec, model, figures, mesh_info)
        all_figures[name] = figures
    return files, all_figures


def print_figures(all_figures):
    for name, d in all_figures.items():
        print("%s: total mass %s kg (vendor total minus left-out links: %s kg)"
              % (name, num(d["total_mass"]), num(d["vendor_minus_dropped"])))
        print("  COM q=0      %s m" % f3(d["com_q0"]))
        print("  COM stance   %s m" % f3(d["com_stance"]))
        fl = d["feet"]["FL"]
        print("  stance %s: hip-to-foot dz %.5f m, foot dx %+.1e m, pitch-axis-to-foot %.5f m, "
              "trunk height %.5f m" % (STANCE, d["hip_to_foot_dz"], fl["dx"], fl["pitch_to_foot"],
                                       d["trunk_height"]))


def top_level(doc, tag):
    return [e for e in doc.documentElement.childNodes
            if e.nodeType == e.ELEMENT_NODE and e.tagName == tag]


def urdf_summary(text):
    doc = xml.dom.minidom.parseString(text)
    links, joints = {}, {}
    for l in top_level(doc, "link"):
        ine = l.getElementsByTagName("inertial")
        if not ine:
            links[l.getAttribute("name")] = None
            continue
        ine = ine[0]
        origin = ine.getElementsByTagName("origin")
        xyz = origin[0].getAttribute("xyz") if origin else "0 0 0"
        mass = float(ine.getElementsByTagName("mass")[0].getAttribute("value"))
        it = ine.getElementsByTagName("inertia")[0]
        inertia = [float(it.getAttribute(k)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")]
        links[l.getAttribute("name")] = [mass] + [float(v) for v in xyz.split()] + inertia
    for j in top_level(doc, "joint"):
        origin = j.getElementsByTagName("origin")
        axis = j.getElementsByTagName("axis")
        limit = j.getElementsByTagName("limit")
        vals = [float(v) for v in (origin[0].getAttribute("xyz").split() if origin else [0, 0, 0])]
        vals += [float(v) for v in (origin[0].getAttribute("rpy").split()
                                    if origin and origin[0].getAttribute("rpy") else [0, 0, 0])]
        vals += [float(v) for v in (axis[0].getAttribute("xyz").split() if axis else [])]
        lim = {}
        if limit:
            for k in ("lower", "upper", "effort", "velocity"):
                if limit[0].getAttribute(k):
                    lim[k] = float(limit[0].getAttribute(k))
        joints[j.getAttribute("name")] = (j.getAttribute("type"),
                                          j.getElementsByTagName("parent")[0].getAttribute("link"),
                                          j.getElementsByTagName("child")[0].getAttribute("link"),
                                          vals, lim)
    return links, joints


def collision_summary(text):
    """{link: [(origin xyz + rpy, geometry tag, sorted attribute values)]}, rotors left out."""
    doc = xml.dom.minidom.parseString(text)
    out = {}
    for l in top_level(doc, "link"):
        if "rotor" in l.getAttribute("name"):
            continue  # the vendor's generated URDF still has rotor cylinders; we have none
        for c in l.getElementsByTagName("collision"):
            origin = c.getElementsByTagName("origin")
            vals = [float(v) for v in (origin[0].getAttribute("xyz").split() if origin else [0, 0, 0])]
            vals += [float(v) for v in (origin[0].getAttribute("rpy").split()
                                        if origin and origin[0].getAttribute("rpy") else [0, 0, 0])]
            geometry = [e for e in c.getElementsByTagName("geometry")[0].childNodes
                        if e.nodeType == e.ELEMENT_NODE][0]
            attrs = tuple((k, tuple(float(x) for x in v.split()))
                          for k, v in sorted(geometry.attributes.items()))
            out.setdefault(l.getAttribute("name"), []).append((tuple(vals), geometry.tagName, attrs))
    return out


def close(a, b):
    return len(a) == len(b) and all(abs(x - y) <= 1e-12 + 1e-12 * abs(y) for x, y in zip(a, b))


def compare_vendor(files, vendor_dir):
    """Inertials and joints of our URDFs against the vendor's; returns the number of surprises."""
    surprises = 0
    for name, spec in ROBOTS.items():
        path = os.path.join(vendor_dir, spec["vendor_urdf"])
        with open(path, encoding="utf-8") as fh:
            vlinks, vjoints = urdf_summary(fh.read())
        olinks, ojoints = urdf_summary(files["assets/robots/%s/%s.urdf" % (name, name)])
        print("%s: vendor %s" % (name, path))
        only_vendor = sorted(set(vlinks) - set(olinks))
        only_ours = sorted(set(olinks) - set(vlinks))
        vmass = sum(v[0] for v in vlinks.values() if v)
        vmass_shared = sum(vlinks[k][0] for k in olinks if k in vlinks and vlinks[k])
        omass = sum(v[0] for v in olinks.values())
        print("  links only in the vendor file: %s" % ", ".join(
            "%s (%s)" % (k, "%g kg" % vlinks[k][0] if vlinks[k] else "no inertial") for k in only_vendor))
        print("  links only in ours: %s" % (", ".join(only_ours) or "none"))
        print("  mass: vendor %.6f kg, vendor over our links %.6f kg, ours %.6f kg"
              % (vmass, vmass_shared, omass))
        surprises += len(only_ours)
        bad = [k for k in olinks if k in vlinks and not close(olinks[k], vlinks[k] or [])]
        for k in bad:
            print("  INERTIAL DIFFERS %s: ours %s vendor %s" % (k, olinks[k], vlinks[k]))
        surprises += len(bad)
        print("  inertials identical on %d of %d links" % (len(olinks) - len(bad), len(olinks)))
        missing = sorted(set(ojoints) - set(vjoints))
        surprises += len(missing)
        if missing:
            print("  joints only in ours: %s" % ", ".join(missing))
        same = 0
        for k, (otype, op, oc, ovals, olim) in ojoints.items():
            if k not in vjoints:
                continue
            vtype, vp, vc, vvals, vlim = vjoints[k]
            notes = []
            if otype != vtype:
                notes.append("type %s vs vendor %s" % (otype, vtype))
            if (op, oc) != (vp, vc) or not close(ovals, vvals):
                notes.append("origin/axis/links differ: ours %s %s %s vendor %s %s %s"
                             % (op, oc, ovals, vp, vc, vvals))
            for lk in ("lower", "upper", "effort", "velocity"):
                if lk in vlim and (lk not in olim or abs(olim[lk] - vlim[lk]) > 1e-12):
                    notes.append("%s %s vs vendor %s" % (lk, olim.get(lk), vlim[lk]))
                elif lk in olim and lk not in vlim:
                    notes.append("%s %s (vendor: none)" % (lk, olim[lk]))
            if notes:
                expected = (name == "aliengo" and k.endswith("_thigh_joint"))
                print("  %s %s: %s" % ("expected" if expected else "DIFFERS", k, "; ".join(notes)))
                surprises += 0 if expected else 1
            else:
                same += 1
        print("  joints identical (type, links, origin, axis, limits): %d of %d"
              % (same, len(ojoints)))
        with open(path, encoding="utf-8") as fh:
            vcol = collision_summary(fh.read())
        ocol = collision_summary(files["assets/robots/%s/%s.urdf" % (name, name)])
        bad = [k for k in ocol if ocol[k] != vcol.get(k)]
        for k in bad:
            print("  COLLISION DIFFERS %s: ours %s vendor %s" % (k, ocol[k], vcol.get(k)))
        surprises += len(bad)
        print("  collision shapes identical on %d of %d links (rotors not compared)"
              % (len(ocol) - len(bad), len(ocol)))
    return surprises


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 if a committed file differs from the output")
    parser.add_argument("--compare-vendor", metavar="DIR",
                        help="write nothing; compare with DIR/{go1,aliengo}_description/urdf/*.urdf")
    args = parser.parse_args()
    files, figures = generate()
    if args.compare_vendor:
        surprises = compare_vendor(files, args.compare_vendor)
        print("unexpected differences: %d" % surprises)
        return 1 if surprises else 0
    if args.check:
        stale = []
        for rel, text in sorted(files.items()):
            path = os.path.join(ROOT, rel)
            try:
                with open(path, encoding="utf-8", newline="") as fh:
                    if fh.read() != text:
                        stale.append(rel)
            except FileNotFoundError:
                stale.append(rel)
        for rel in stale:
            print("stale: %s" % rel)
        if stale:
            print("run: %s" % COMMAND)
        return 1 if stale else 0
    for rel, text in sorted(files.items()):
        path = os.path.join(ROOT, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        print("wrote %s" % rel)
    print_figures(figures)
    return 0


if __name__ == "__main__":
    sys.exit(main())
