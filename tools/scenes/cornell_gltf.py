#!/usr/bin/env python3
"""Writes scenes/cornell-box/cornell.gltf: the built-in Cornell box (irradiant-scene's
builtin.rs) as a glTF 2.0 file with its buffer embedded, for the raster host example
(crates/irradiant/examples/raster_host/) and anyone who wants the box in another tool.
Flat normals, one primitive a material, the light's emission through
KHR_materials_emissive_strength, the camera as a node. Run from the repository root."""
import base64
import json
import math
import struct

QUADS = {
    "white": [
        [(-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1)],  # floor
        [(-1, 2, 1), (-1, 2, -1), (1, 2, -1), (1, 2, 1)],  # ceiling
        [(-1, 0, -1), (1, 0, -1), (1, 2, -1), (-1, 2, -1)],  # back
    ],
    "red": [[(-1, 0, 1), (-1, 0, -1), (-1, 2, -1), (-1, 2, 1)]],
    "green": [[(1, 0, -1), (1, 0, 1), (1, 2, 1), (1, 2, -1)]],
    "light": [[(-0.24, 1.98, 0.16), (-0.24, 1.98, -0.22), (0.23, 1.98, -0.22), (0.23, 1.98, 0.16)]],
}
MATERIALS = {
    "white": ((0.725, 0.71, 0.68), None),
    "red": ((0.63, 0.065, 0.05), None),
    "green": ((0.14, 0.45, 0.091), None),
    "light": ((0.78, 0.78, 0.78), (17.0, 12.0, 4.0)),
}


def box(translation, angle_y, scale):
    """The unit cube [-0.5, 0.5]^3 scaled, turned about y and moved: its faces, out."""
    def corner(x, y, z):
        p = [(x - 0.5) * scale[0], (y - 0.5) * scale[1], (z - 0.5) * scale[2]]
        c, s = math.cos(angle_y), math.sin(angle_y)
        p = [c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2]]
        return tuple(p[i] + translation[i] for i in range(3))
    faces = [
        [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)],
        [(1, 0, 0), (0, 0, 0), (0, 1, 0), (1, 1, 0)],
        [(1, 0, 1), (1, 0, 0), (1, 1, 0), (1, 1, 1)],
        [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)],
        [(0, 1, 1), (1, 1, 1), (1, 1, 0), (0, 1, 0)],
        [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)],
    ]
    return [[corner(*v) for v in f] for f in faces]


QUADS["white"] += box((0.33, 0.3, 0.37), -0.29, (0.6, 0.6, 0.6))
QUADS["white"] += box((-0.335, 0.6, -0.29), 0.3, (0.6, 1.2, 0.6))


def normal(q):
    a, b, c = q[0], q[1], q[2]
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    return [x / length for x in n]


blob = bytearray()
buffer_views, accessors, primitives, materials = [], [], [], []


def add(data, target, component, kind, count, bounds=None):
    while len(blob) % 4:
        blob.append(0)
    buffer_views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
    blob.extend(data)
    accessor = {"bufferView": len(buffer_views) - 1, "componentType": component, "count": count, "type": kind}
    if bounds:
        accessor["min"], accessor["max"] = bounds
    accessors.append(accessor)
    return len(accessors) - 1


for name, quads in QUADS.items():
    positions, normals, indices = [], [], []
    for q in quads:
        base = len(positions)
        n = normal(q)
        positions += q
        normals += [n] * 4
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    pos = add(b"".join(struct.pack("<3f", *p) for p in positions), 34962, 5126, "VEC3", len(positions), (lo, hi))
    nrm = add(b"".join(struct.pack("<3f", *p) for p in normals), 34962, 5126, "VEC3", len(normals))
    idx = add(struct.pack(f"<{len(indices)}I", *indices), 34963, 5125, "SCALAR", len(indices))
    albedo, emission = MATERIALS[name]
    material = {
        "name": name,
        "pbrMetallicRoughness": {"baseColorFactor": [*albedo, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
    }
    if emission:
        strength = max(emission)
        material["emissiveFactor"] = [e / strength for e in emission]
        material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    materials.append(material)
    primitives.append({"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": idx, "material": len(materials) - 1})

document = {
    "asset": {"version": "2.0", "generator": "tools/scenes/cornell_gltf.py"},
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [
        {"name": "cornell-box", "mesh": 0},
        # glTF cameras look down -z: from z = 3.5 at the box's middle height.
        {"name": "camera", "camera": 0, "translation": [0.0, 1.0, 3.5]},
    ],
    "cameras": [{"type": "perspective", "perspective": {"yfov": math.radians(40.0), "znear": 0.05}}],
    "meshes": [{"name": "cornell-box", "primitives": primitives}],
    "materials": materials,
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    "bufferViews": buffer_views,
    "accessors": accessors,
}
with open("scenes/cornell-box/cornell.gltf", "w") as f:
    json.dump(document, f, indent=1)
    f.write("\n")
