#!/usr/bin/env python3
"""Writes a quadruped of other proportions from a Unitree-form URDF: the legs
(thigh, calf, foot) scaled by one length factor, the trunk and hips by another,
every mass by a third; inertias follow (mass factor x length factor squared),
joint efforts and velocity limits by their own factors. Visual meshes are left
out (they would be drawn at the source's size). Test data for pronk's
"robots as data" checks (tests/robots/README.md), not a shipped robot.

  python3 tools/scale_robot.py SOURCE.urdf OUT.urdf --name NAME --leg 1.5 --body 1.25 \
      --mass 3 --effort 4.5 --velocity 0.816
"""
import argparse
import sys
import xml.etree.ElementTree as ET


def scaled(text, factor):
    return " ".join(f"{float(v) * factor:.6g}" for v in text.split())


def link_factor(name, leg, body):
    """The length factor of a link by its Unitree name."""
    if any(part in name for part in ("_thigh", "_calf", "_foot")):
        return leg
    return body


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("source")
    p.add_argument("out")
    p.add_argument("--name", required=True)
    p.add_argument("--leg", type=float, required=True, help="length factor of thighs, calves and feet")
    p.add_argument("--body", type=float, required=True, help="length factor of the trunk and the hips")
    p.add_argument("--mass", type=float, required=True, help="factor of every mass")
    p.add_argument("--effort", type=float, required=True, help="factor of every joint's effort limit")
    p.add_argument("--velocity", type=float, required=True, help="factor of every joint's velocity limit")
    p.add_argument("--note", default="", help="a sentence for the header comment")
    a = p.parse_args(argv)

    tree = ET.parse(a.source)
    robot = tree.getroot()
    robot.set("name", a.name)
    for material in robot.findall("material"):
        robot.remove(material)
    factors = {}
    for link in robot.findall("link"):
        f = link_factor(link.get("name"), a.leg, a.body)
        factors[link.get("name")] = f
        for visual in link.findall("visual"):
            link.remove(visual)
        for collision in link.findall("collision"):
            origin = collision.find("origin")
            if origin is not None:
                origin.set("xyz", scaled(origin.get("xyz", "0 0 0"), f))
            geometry = collision.find("geometry")
            for shape in geometry:
                for attr in ("size", "radius", "length"):
                    if shape.get(attr) is not None:
                        shape.set(attr, scaled(shape.get(attr), f))
        inertial = link.find("inertial")
        if inertial is not None:
            origin = inertial.find("origin")
            if origin is not None:
                origin.set("xyz", scaled(origin.get("xyz", "0 0 0"), f))
            mass = inertial.find("mass")
            mass.set("value", scaled(mass.get("value"), a.mass))
            inertia = inertial.find("inertia")
            for attr in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
                inertia.set(attr, scaled(inertia.get(attr), a.mass * f * f))
    for joint in robot.findall("joint"):
        parent = joint.find("parent").get("link")
        origin = joint.find("origin")
        if origin is not None:
            origin.set("xyz", scaled(origin.get("xyz", "0 0 0"), factors.get(parent, a.body)))
        limit = joint.find("limit")
        if limit is not None:
            if limit.get("effort") is not None:
                limit.set("effort", scaled(limit.get("effort"), a.effort))
            if limit.get("velocity") is not None:
                limit.set("velocity", scaled(limit.get("velocity"), a.velocity))

    header = (f" {a.name}: {a.source} with legs x{a.leg}, trunk and hips x{a.body}, masses x{a.mass}, "
              f"efforts x{a.effort}, velocity limits x{a.velocity}; no visual meshes. {a.note}"
              f" Written by tools/scale_robot.py; do not edit. ")
    ET.indent(tree, space="  ")
    with open(a.out, "w") as out:
        out.write('<?xml version="1.0"?>\n')
        out.write(f"<!--{header}-->\n")
        out.write(ET.tostring(robot, encoding="unicode"))
        out.write("\n")


if __name__ == "__main__":
    main(sys.argv[1:])
