#!/usr/bin/env python3
"""Writes glass_shelf.gltf: a glass scene as glTF 2.0, one text file with its buffer and floor texture inside.

A shelf against a wall on a chequered floor, with glass as glTF describes it: standing panes (thin, tinted
by their base colour, KHR_materials_transmission), bottles and spheres that are solid glass
(KHR_materials_volume: thickness and a Beer's-law attenuation colour, KHR_materials_ior), a frosted pane
(rough), an opaque bottle and cube among them; lit by a shadowed spot light, a lamp (point light) and a
low sun (KHR_lights_punctual), seen by its own camera. About 12K triangles. The floor's chequer is a
base-colour texture with its sampler and texture coordinates.
Run it from anywhere; it writes next to itself.
"""
import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


class Writer:
    """One buffer, its views and accessors, and the meshes, materials and nodes that use them."""

    def __init__(self):
        self.buffer = bytearray()
        self.gltf = {"asset": {"version": "2.0", "generator": "dstrans examples/scenes/make_glass_shelf.py"},
                     "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                     "accessors": [], "bufferViews": []}

    def view(self, data, target=None):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        v = {"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.buffer += data
        self.gltf["bufferViews"].append(v)
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, values, kind, width):
        flat = [x for v in values for x in (v if width > 1 else [v])]
        if kind == "index":
            data, component, target = struct.pack("<%dI" % len(flat), *flat), 5125, 34963
        else:
            data, component, target = struct.pack("<%df" % len(flat), *flat), 5126, 34962
        a = {"bufferView": self.view(data, target), "componentType": component, "count": len(values),
             "type": {1: "SCALAR", 2: "VEC2", 3: "VEC3"}[width]}
        if kind == "position":  # the specification requires POSITION's bounds
            a["min"] = [min(v[i] for v in values) for i in range(3)]
            a["max"] = [max(v[i] for v in values) for i in range(3)]
        self.gltf["accessors"].append(a)
        return len(self.gltf["accessors"]) - 1

    def material(self, name, colour, roughness=0.5, metallic=0.0, transmission=0.0, ior=None, volume=None,
                 texture=None, double_sided=False):
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour, "metallicFactor": metallic,
                                                     "roughnessFactor": roughness}}
        if texture is not None:
            m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": texture}
        if double_sided:
            m["doubleSided"] = True
        ext = {}
        if transmission:
            ext["KHR_materials_transmission"] = {"transmissionFactor": transmission}
        if ior is not None:
            ext["KHR_materials_ior"] = {"ior": ior}
        if volume is not None:
            thickness, distance, attenuation = volume
            ext["KHR_materials_volume"] = {"thicknessFactor": thickness, "attenuationDistance": distance,
                                           "attenuationColor": attenuation}
        if ext:
            m["extensions"] = ext
        self.gltf["materials"].append(m)
        return len(self.gltf["materials"]) - 1

    def mesh(self, name, shape, material):
        positions, normals, uvs, indices = shape
        attributes = {"POSITION": self.accessor(positions, "position", 3), "NORMAL": self.accessor(normals, "normal", 3)}
        if uvs:
            attributes["TEXCOORD_0"] = self.accessor(uvs, "uv", 2)
        self.gltf["meshes"].append({"name": name, "primitives": [
            {"attributes": attributes, "indices": self.accessor(indices, "index", 1), "material": material}]})
        return len(self.gltf["meshes"]) - 1

    def node(self, node):
        self.gltf["nodes"].append(node)
        self.gltf["scenes"][0]["nodes"].append(len(self.gltf["nodes"]) - 1)

    def place(self, name, mesh, at, turn_y=0.0, turn_x=0.0):
        """A node holding `mesh` at `at`, turned `turn_y` degrees about y, then `turn_x` about x."""
        qy = (0.0, math.sin(math.radians(turn_y) / 2), 0.0, math.cos(math.radians(turn_y) / 2))
        qx = (math.sin(math.radians(turn_x) / 2), 0.0, 0.0, math.cos(math.radians(turn_x) / 2))
        self.node({"name": name, "mesh": mesh, "translation": list(at), "rotation": list(quat_mul(qy, qx))})

    def write(self, path):
        self.gltf["buffers"] = [{"byteLength": len(self.buffer),
                                 "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.buffer)).decode()}]
        with open(path, "w") as f:
            json.dump(self.gltf, f, separators=(",", ":"))
            f.write("\n")


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def box(sx, sy, sz, tile=None):
    """A box of size (sx, sy, sz) standing on y = 0, centred in x and z; texture coordinates repeat every
    `tile` units on its faces where given."""
    positions, normals, uvs, indices = [], [], [], []
    hx, hz = sx / 2, sz / 2
    faces = [((0, 1, 0), (-hx, sy, hz), (sx, 0, 0), (0, 0, -sz)), ((0, -1, 0), (-hx, 0, -hz), (sx, 0, 0), (0, 0, sz)),
             ((0, 0, 1), (-hx, 0, hz), (sx, 0, 0), (0, sy, 0)), ((0, 0, -1), (hx, 0, -hz), (-sx, 0, 0), (0, sy, 0)),
             ((1, 0, 0), (hx, 0, hz), (0, 0, -sz), (0, sy, 0)), ((-1, 0, 0), (-hx, 0, -hz), (0, 0, sz), (0, sy, 0))]
    for n, o, u, v in faces:
        base = len(positions)
        for s, t in ((0, 0), (1, 0), (1, 1), (0, 1)):
            positions.append(tuple(o[i] + s * u[i] + t * v[i] for i in range(3)))
            normals.append(n)
            if tile:
                uvs.append((s * math.sqrt(sum(x * x for x in u)) / tile, t * math.sqrt(sum(x * x for x in v)) / tile))
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, normals, uvs, indices


def pane(w, h):
    """A quad of w x h in the plane z = 0 facing +z, standing on y = 0."""
    return ([(-w / 2, 0, 0), (w / 2, 0, 0), (w / 2, h, 0), (-w / 2, h, 0)], [(0, 0, 1)] * 4, [],
            [0, 1, 2, 0, 2, 3])


def lathe(profile, slices):
    """A surface of revolution about y of `profile` [(radius, height)...], going up, normals outward."""
    positions, normals, indices = [], [], []
    for i, (r, y) in enumerate(profile):
        pr, py = profile[max(i - 1, 0)]
        nr, ny = profile[min(i + 1, len(profile) - 1)]
        tr, ty = nr - pr, ny - py
        length = math.hypot(tr, ty) or 1.0
        n2 = (ty / length, -tr / length)
        for k in range(slices + 1):
            a = 2 * math.pi * k / slices
            positions.append((r * math.cos(a), y, r * math.sin(a)))
            normals.append((n2[0] * math.cos(a), n2[1], n2[0] * math.sin(a)))
    ring = slices + 1
    for i in range(len(profile) - 1):
        for k in range(slices):
            a, b = i * ring + k, (i + 1) * ring + k
            indices += [a, b, a + 1, a + 1, b, b + 1]
    return positions, normals, [], indices


def bottle(r, h, slices=48):
    return lathe([(0, 0), (r * 0.9, 0), (r, 0.05 * h), (r, 0.55 * h), (r * 0.8, 0.68 * h), (r * 0.35, 0.78 * h),
                  (r * 0.3, 0.95 * h), (r * 0.38, h), (0, h)], slices)


def sphere(r, slices=48):
    stacks = slices // 2
    profile = [(r * math.sin(math.pi * i / stacks), r - r * math.cos(math.pi * i / stacks)) for i in range(stacks + 1)]
    positions, _, uvs, indices = lathe(profile, slices)
    normals = [tuple(c / r for c in (p[0], p[1] - r, p[2])) for p in positions]
    return positions, normals, uvs, indices


def checker_png(size=64, squares=8):
    """An RGB PNG of a grey chequer, written with zlib alone."""
    rows = b""
    for y in range(size):
        rows += b"\0" + b"".join(bytes((200, 196, 188) if ((x * squares // size) + (y * squares // size)) % 2 else (90, 88, 84))
                                 for x in range(size))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def main():
    w = Writer()
    w.gltf["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                "KHR_materials_volume"]
    # The floor's chequer: an image in the buffer, its sampler repeating.
    image = w.view(checker_png())
    w.gltf["images"] = [{"bufferView": image, "mimeType": "image/png"}]
    w.gltf["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]
    w.gltf["textures"] = [{"sampler": 0, "source": 0}]

    floor = w.material("floor", [0.62, 0.6, 0.56, 1.0], roughness=0.9, texture=0)
    wall = w.material("wall", [0.75, 0.72, 0.68, 1.0], roughness=0.95)
    wood = w.material("wood", [0.45, 0.3, 0.18, 1.0], roughness=0.6)
    clay = w.material("clay", [0.75, 0.35, 0.2, 1.0], roughness=0.8)
    steel = w.material("steel", [0.7, 0.72, 0.75, 1.0], roughness=0.3, metallic=1.0)
    # Thin panes: transmission, tinted by their base colour.
    rose = w.material("rose pane", [1.0, 0.35, 0.45, 1.0], roughness=0.05, transmission=0.6, ior=1.5, double_sided=True)
    cyan = w.material("cyan pane", [0.3, 0.85, 1.0, 1.0], roughness=0.05, transmission=0.7, ior=1.5, double_sided=True)
    frosted = w.material("frosted pane", [0.9, 0.95, 1.0, 1.0], roughness=0.6, transmission=0.5, ior=1.5, double_sided=True)
    # Solid glass: volume attenuation over its thickness.
    green = w.material("bottle green", [1.0, 1.0, 1.0, 1.0], roughness=0.05, transmission=0.8, ior=1.5,
                       volume=(0.3, 0.2, [0.35, 0.8, 0.4]))
    amber = w.material("amber", [1.0, 1.0, 1.0, 1.0], roughness=0.05, transmission=0.75, ior=1.5,
                       volume=(0.3, 0.25, [0.95, 0.6, 0.2]))
    blue = w.material("cobalt", [1.0, 1.0, 1.0, 1.0], roughness=0.05, transmission=0.8, ior=1.5,
                      volume=(0.4, 0.3, [0.3, 0.45, 0.95]))
    clear = w.material("clear", [1.0, 1.0, 1.0, 1.0], roughness=0.02, transmission=0.9, ior=1.5)

    w.place("floor", w.mesh("floor", box(8, 0.2, 8, tile=1.0), floor), (0, -0.2, 0))
    w.place("wall", w.mesh("wall", box(8, 3.2, 0.2), wall), (0, 0, -2.1))
    top = w.mesh("shelf top", box(3.6, 0.06, 1.0), wood)
    leg = w.mesh("shelf leg", box(0.08, 0.9, 0.08), wood)
    w.place("shelf top", top, (0, 0.9, -1.2))
    for x in (-1.7, 1.7):
        for z in (-1.6, -0.8):
            w.place("shelf leg", leg, (x, 0, z))
    tall = w.mesh("tall bottle", bottle(0.14, 0.6), green)
    short = w.mesh("short bottle", bottle(0.12, 0.42), amber)
    wide = w.mesh("wide bottle", bottle(0.18, 0.5), blue)
    vase = w.mesh("vase", bottle(0.13, 0.5), clay)
    for name, mesh, x in (("green bottle", tall, -1.3), ("amber bottle", short, -0.75), ("clay vase", vase, -0.2),
                          ("cobalt bottle", wide, 0.4), ("green bottle 2", tall, 1.0), ("amber bottle 2", short, 1.45)):
        w.place(name, mesh, (x, 0.96, -1.25))
    w.place("glass ball", w.mesh("glass ball", sphere(0.22), clear), (-0.9, 0, 0.3))
    w.place("cobalt ball", w.mesh("cobalt ball", sphere(0.16), blue), (1.2, 0, 0.6))
    w.place("steel cube", w.mesh("steel cube", box(0.35, 0.35, 0.35), steel), (0.35, 0, 0.9), turn_y=30)
    w.place("rose pane", w.mesh("rose pane", pane(1.1, 1.4), rose), (-1.6, 0, 0.9), turn_y=25)
    w.place("cyan pane", w.mesh("cyan pane", pane(1.0, 1.2), cyan), (0.1, 0, 1.6), turn_y=-10)
    w.place("frosted pane", w.mesh("frosted pane", pane(0.9, 1.3), frosted), (1.9, 0, 0.1), turn_y=-55)

    # Lights: glTF intensities are candela (point, spot) and lux (directional); dstrans maps them
    # (tools/scene_gltf.hpp). Each node looks down its -z.
    w.gltf["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "spot", "type": "spot", "color": [1.0, 0.95, 0.85], "intensity": 18.0, "range": 10.0,
         "spot": {"innerConeAngle": 0.45, "outerConeAngle": 0.7}},
        {"name": "lamp", "type": "point", "color": [1.0, 0.85, 0.6], "intensity": 2.5, "range": 6.0},
        {"name": "sun", "type": "directional", "color": [0.8, 0.85, 1.0], "intensity": 0.25}]}}
    down_forward = quat_mul((0.0, math.sin(math.radians(20) / 2), 0.0, math.cos(math.radians(20) / 2)),
                            (math.sin(math.radians(-60) / 2), 0.0, 0.0, math.cos(math.radians(-60) / 2)))
    w.node({"name": "spot", "translation": [-1.0, 3.2, 2.6], "rotation": list(down_forward),
            "extensions": {"KHR_lights_punctual": {"light": 0}}})
    w.node({"name": "lamp", "translation": [0.8, 2.2, 0.2], "extensions": {"KHR_lights_punctual": {"light": 1}}})
    sun = quat_mul((0.0, math.sin(math.radians(-35) / 2), 0.0, math.cos(math.radians(-35) / 2)),
                   (math.sin(math.radians(-40) / 2), 0.0, 0.0, math.cos(math.radians(-40) / 2)))
    w.node({"name": "sun", "rotation": list(sun), "extensions": {"KHR_lights_punctual": {"light": 2}}})
    # The camera: in front, a little above, looking down at the shelf.
    w.gltf["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.85, "znear": 0.1, "zfar": 40.0}}]
    look = quat_mul((0.0, math.sin(math.radians(8) / 2), 0.0, math.cos(math.radians(8) / 2)),
                    (math.sin(math.radians(-16) / 2), 0.0, 0.0, math.cos(math.radians(-16) / 2)))
    w.node({"name": "camera", "camera": 0, "translation": [0.6, 2.0, 4.6], "rotation": list(look)})
    w.write(os.path.join(HERE, "glass_shelf.gltf"))


if __name__ == "__main__":
    main()
