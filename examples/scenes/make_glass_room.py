#!/usr/bin/env python3
"""Writes glass_room.json and its two variants, the thesis's test scene in dstrans's scene format.

About 60K triangles, a third of them transparent: coloured glass panes, bottles and spheres in front of
and behind opaque objects, 64 shadow-casting spot lights in a grid under the ceiling, two point lights
and a directional light. glass_room_17.json and glass_room_0.json keep every object and so the
triangle count, turning glass opaque until 17% and 0% of the triangles are transparent (Tables 4.6/4.7).
glass_room_sun.json (without the room's walls and ceiling) and glass_room_lamp.json light it by one
shadowed directional or point light alone. glass_room_smoke.json adds smoke behind one pane and in front of
another.
Run it from anywhere; it writes next to itself.
"""
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

# Triangle counts of the shapes, as include/dstrans/scene.hpp builds them.
def triangles(obj):
    s, seg = obj["shape"], obj.get("segments", 32)
    if s in ("box", "room"):
        return 12
    if s == "pane":
        return 2
    if s == "sphere":
        stacks = max(seg // 2, 2)
        return 2 * seg * stacks
    if s == "cylinder":
        return 2 * seg * 5
    if s == "bottle":
        return 2 * seg * 8
    raise ValueError(s)


def scene(opaque_glass):
    """The room; glass objects whose index is in `opaque_glass` get an opaque material instead."""
    rng = random.Random(2015)
    materials = {
        "wall": {"diffuse": [0.72, 0.7, 0.66], "spec_intensity": 0.05, "spec_power": 4},
        "floor": {"diffuse": [0.8, 0.78, 0.74], "spec_intensity": 0.2, "spec_power": 16},
        "wood": {"diffuse": [0.55, 0.36, 0.2], "spec_intensity": 0.15, "spec_power": 12},
        "red": {"diffuse": [0.78, 0.12, 0.1], "spec_intensity": 0.6, "spec_power": 48},
        "white": {"diffuse": [0.9, 0.9, 0.88], "spec_intensity": 0.4, "spec_power": 32},
        "teal": {"diffuse": [0.1, 0.55, 0.5], "spec_intensity": 0.5, "spec_power": 40},
        "opaque_glass": {"diffuse": [0.35, 0.45, 0.5], "spec_intensity": 0.8, "spec_power": 96},
    }
    glass_colours = [[0.15, 0.45, 1.0], [0.2, 0.9, 0.3], [1.0, 0.3, 0.2], [1.0, 0.85, 0.2], [0.8, 0.3, 1.0]]
    for i, c in enumerate(glass_colours):
        materials["glass%d" % i] = {"diffuse": c, "alpha": 0.45, "spec_intensity": 0.9, "spec_power": 128,
                                    "refractive": True}
    objects = [
        {"shape": "room", "size": [12, 4, 12], "material": "wall"},
        {"shape": "box", "size": [12, 0.02, 12], "position": [0, 0.01, 0], "material": "floor"},
        {"shape": "box", "size": [4.5, 0.08, 1.6], "position": [0, 0.8, -1.2], "material": "wood"},
        {"shape": "box", "size": [4.5, 0.08, 1.6], "position": [0, 0.8, 1.4], "material": "wood"},
    ]
    for x in (-2.1, 2.1):
        for z in (-1.9, -0.5, 0.7, 2.1):
            objects.append({"shape": "box", "size": [0.08, 0.8, 0.08], "position": [x, 0.4, z], "material": "wood"})
    # Opaque things on and around the tables.
    opaque = ["red", "white", "teal"]
    for i in range(16):
        x, z = -2.0 + (i % 8) * 0.57, -1.5 + (i // 8) * 2.6
        objects.append({"shape": "sphere", "radius": 0.16, "segments": 40, "position": [x, 0.99, z],
                        "material": opaque[i % 3]})
    for i in range(10):
        x, z = -1.8 + i * 0.4, -0.75 + (i % 2) * 2.6
        objects.append({"shape": "cylinder", "radius": 0.09, "height": 0.35, "segments": 48, "position": [x, 0.84, z],
                        "material": opaque[(i + 1) % 3]})
    for i in range(8):
        objects.append({"shape": "bottle", "radius": 0.1, "height": 0.45, "segments": 48,
                        "position": [-1.6 + i * 0.45, 0.84, -1.0 + (i % 2) * 0.3], "material": opaque[i % 3]})
    for i in range(6):
        objects.append({"shape": "box", "size": [0.5, 0.5, 0.5], "position": [-3.5 + i * 1.4, 0.25, -3.8],
                        "rotation_y": rng.uniform(-40, 40), "material": opaque[i % 3]})
    # Glass: bottles and spheres on the tables, panes in front of and behind them.
    glass = []
    for i in range(12):
        glass.append({"shape": "bottle", "radius": 0.11, "height": 0.55, "segments": 48,
                      "position": [-1.9 + i * 0.34, 0.84, 1.2 + (i % 3) * 0.2]})
    for i in range(8):
        glass.append({"shape": "sphere", "radius": 0.2, "segments": 40, "position": [-1.8 + i * 0.5, 1.05, -0.45]})
    for i, (x, z, r) in enumerate([(-2.4, 2.4, 35), (2.5, 2.4, -35), (0.0, -2.3, 5), (-2.6, 0.2, 80), (2.7, 0.0, -75),
                                   (0.2, 0.3, 0)]):
        glass.append({"shape": "pane", "size": [1.6, 1.4], "position": [x, 1.2, z], "rotation_y": r})
    # Glass shelves over the tables: coloured shadows on the table tops and the floor.
    for x in (-1.2, 1.2):
        glass.append({"shape": "pane", "size": [1.6, 1.0], "position": [x, 1.9, 0.1], "rotation_x": -90})
    for i, obj in enumerate(glass):
        obj["material"] = "opaque_glass" if i in opaque_glass else "glass%d" % (i % len(glass_colours))
        objects.append(obj)
    lights = []
    # Two bright spots low at the sides shine through the front panes and the shelves.
    lights.append({"type": "spot", "position": [-4.5, 3.2, 4.2], "direction": [0.75, -0.55, -0.75], "colour": [1, 1, 1],
                   "intensity": 1.3, "range": 11, "inner_angle": 22, "outer_angle": 30, "shadows": True})
    lights.append({"type": "spot", "position": [0.3, 3.9, 0.1], "direction": [0, -1, 0], "colour": [1, 1, 1],
                   "intensity": 1.1, "range": 6, "inner_angle": 35, "outer_angle": 45, "shadows": True})
    for i in range(62):
        x, z = -4.2 + (i % 8) * 1.2, -4.2 + (i // 8) * 1.2
        lights.append({"type": "spot", "position": [x, 3.8, z], "direction": [-x * 0.08, -1, -z * 0.08],
                       "colour": [1.0, 0.94, 0.86], "intensity": 0.08, "range": 6.5, "inner_angle": 28,
                       "outer_angle": 38, "shadows": True})
    lights.append({"type": "point", "position": [-3.5, 2.6, 2.8], "colour": [0.5, 0.6, 1.0], "intensity": 0.6, "range": 5})
    lights.append({"type": "point", "position": [3.2, 1.4, -2.5], "colour": [1.0, 0.6, 0.4], "intensity": 0.5, "range": 4})
    lights.append({"type": "directional", "direction": [0.3, -1, -0.4], "colour": [1, 1, 1], "intensity": 0.12})
    return {"camera": {"position": [0.4, 2.1, 4.6], "target": [0.0, 0.9, 0.0], "fov_y": 58, "near": 0.1, "far": 30},
            "ambient": [0.09, 0.09, 0.1], "materials": materials, "objects": objects, "lights": lights}, glass


def share(s):
    total = sum(triangles(o) for o in s["objects"])
    clear = sum(triangles(o) for o in s["objects"] if s["materials"][o["material"]].get("alpha", 1.0) < 1.0)
    return total, clear / total


def main():
    full, glass = scene(set())
    total, full_share = share(full)
    # Turn the first n glass objects of each shape opaque, for the counts that come closest to 17%.
    by_shape = {}
    for i, obj in enumerate(glass):
        by_shape.setdefault(obj["shape"], []).append(i)
    shapes = sorted(by_shape)
    best = None
    def pick(k, chosen):
        nonlocal best
        if k == len(shapes):
            d = abs(share(scene(chosen)[0])[1] - 0.17)
            if best is None or d < best[0]:
                best = (d, set(chosen))
            return
        for n in range(len(by_shape[shapes[k]]) + 1):
            pick(k + 1, chosen | set(by_shape[shapes[k]][:n]))
    pick(0, set())
    opaque = best[1]
    # The room under one shadowed light of the kinds the thesis left as future work: the sun (an
    # orthographic map) and a lamp hanging between the shelves (a cube map).
    # The sun's room has no walls or ceiling (they would shade everything): its floor and tables alone.
    sun = dict(full, objects=[o for o in full["objects"] if o["shape"] != "room"],
               lights=[{"type": "directional", "direction": [0.3, -1, -0.4], "colour": [1, 0.97, 0.9],
                        "intensity": 0.9, "shadows": True}])
    lamp = dict(full, lights=[{"type": "point", "position": [0.05, 2.55, 0.15], "colour": [1, 0.95, 0.85],
                               "intensity": 1.6, "range": 9, "shadows": True}])
    # Smoke beside glass: a column rising behind the front left pane, seen through it, and one rising from
    # the front table in front of the centre pane.
    smoke = dict(full, materials=dict(full["materials"], smoke={"diffuse": [0.85, 0.85, 0.82], "alpha": 0.3}),
                 particles=[{"material": "smoke", "base": [-2.75, 0.0, 1.55], "radius": 0.35, "height": 2.2,
                             "size": 0.3, "count": 300, "seed": 4},
                            {"material": "smoke", "base": [0.6, 0.84, 0.85], "radius": 0.25, "height": 1.3,
                             "size": 0.25, "count": 200, "seed": 5}])
    variants = [("glass_room.json", full), ("glass_room_17.json", scene(opaque)[0]),
                ("glass_room_0.json", scene(set(range(len(glass))))[0]),
                ("glass_room_sun.json", sun), ("glass_room_lamp.json", lamp), ("glass_room_smoke.json", smoke)]
    for name, s in variants:
        with open(os.path.join(HERE, name), "w") as f:
            json.dump(s, f, indent=1)
            f.write("\n")
        t, p = share(s)
        print("%s: %d triangles, %.1f%% transparent, %d lights" % (name, t, 100 * p, len(s["lights"])))


if __name__ == "__main__":
    main()
