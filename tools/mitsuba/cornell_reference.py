#!/usr/bin/env python3
"""Mitsuba 3 ground-truth render of the Cornell box, for testing Irradiant's path tracer.

What it renders
---------------
The Cornell box OBJ (default: CornellBox-Original.obj from the Williams/McGuire set,
with its MTL), rendered by Mitsuba 3 (variant ``scalar_rgb``) into a linear float32
RGB OpenEXR (channels R, G, B; no alpha; no tonemapping).

Conventions (they must match Irradiant's renderer exactly)
----------------------------------------------------------
* Geometry: the OBJ is parsed here, not by Mitsuba's loader (which makes one shape
  per file). ``v`` and ``f`` lines are read (positive and negative/relative indices;
  ``v/vt/vn`` forms use only the position index), ``usemtl`` switches the current
  material, and one Mitsuba mesh is built per material. Every polygon is triangulated
  as a fan from its first vertex: (0,1,2), (0,2,3), ... No vertex normals: flat
  shading (``face_normals=True``). Geometric normal = cross(p1-p0, p2-p0).
* Materials: every material is a two-sided Lambertian,
  ``{'type': 'twosided', 'bsdf': {'type': 'diffuse', 'reflectance': rgb Kd}}``
  with Kd from the MTL. A material with non-zero Ke (``light``, Ke = 17 12 4) also
  gets a one-sided ``area`` emitter with radiance rgb Ke, emitting on the side of the
  geometric normal (Mitsuba's convention). No other light; black background.
* Camera: pinhole ``perspective``, origin (0, 1, 3.5), target (0, 1, 0),
  up (0, 1, 0), fov 40 degrees with fov_axis 'y', near_clip 0.01, far_clip 1e4;
  square image size x size.
* Film: ``hdrfilm``, pixel_format 'rgb', component_format 'float32', rfilter ``box``
  (each pixel is the average over its own square; samples uniformly jittered in the
  pixel by the ``independent`` sampler).
* Integrator: ``path``, max_depth = -1 (unbounded), rr_depth 5 (Mitsuba default,
  Russian roulette is unbiased), hide_emitters = False.
* Image orientation: pixel (0, 0) is the top-left (Mitsuba's convention, also the
  EXR's). The script checks that the red wall is in the left half of the image.
* The EXR is written with Mitsuba's own bitmap writer (mi.Bitmap(...).write()).

Install
-------
    pip install mitsuba==3.9.1      # pulls drjit==1.5.0; numpy is not needed

Command that produced tests/golden/cornell-box/mitsuba-original-64.exr
(run from the repository root, /work/main):
    python3 tools/mitsuba/cornell_reference.py \
        --obj ../shared/scenes/cornell-box/CornellBox-Original.obj \
        --size 64 --spp 32768 --out tests/golden/cornell-box/mitsuba-original-64.exr

Options: --seed (sampler seed, default 0), --preview PATH (also write a clamped,
sRGB-encoded 8-bit PNG preview), --variant (default scalar_rgb).
"""

import argparse
import os
import sys
import time

import mitsuba as mi

CAMERA_ORIGIN = (0.0, 1.0, 3.5)
CAMERA_TARGET = (0.0, 1.0, 0.0)
CAMERA_UP = (0.0, 1.0, 0.0)
CAMERA_FOV_Y_DEG = 40.0
NEAR_CLIP = 0.01
FAR_CLIP = 1.0e4
MAX_DEPTH = -1
RR_DEPTH = 5


def parse_mtl(path):
    """Return {name: {'Kd': (r,g,b), 'Ke': (r,g,b)}} from an MTL file."""
    mats = {}
    cur = None
    with open(path, "r") as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            key = parts[0]
            if key == "newmtl":
                cur = " ".join(parts[1:])
                mats[cur] = {"Kd": (0.0, 0.0, 0.0), "Ke": (0.0, 0.0, 0.0)}
            elif cur is not None and key in ("Kd", "Ke"):
                vals = [float(x) for x in parts[1:4]]
                if len(vals) == 1:
                    vals = vals * 3
                mats[cur][key] = tuple(vals)
    return mats


def parse_obj(path):
    """Parse an OBJ file.

    Returns (positions, groups, mtllibs) where positions is a list of (x,y,z) and
    groups is an ordered dict-like list of (material_name, [triangles]) with
    triangles as (i0, i1, i2) 0-based indices into positions. Polygons are fan
    triangulated from their first vertex.
    """
    positions = []
    tris_by_mat = {}
    order = []
    mtllibs = []
    cur_mat = None
    with open(path, "r") as f:
        for lineno, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            parts = line.split()
            key = parts[0]
            if key == "v":
                positions.append(tuple(float(x) for x in parts[1:4]))
            elif key == "f":
                idx = []
                for tok in parts[1:]:
                    i = int(tok.split("/")[0])
                    if i < 0:
                        i = len(positions) + i  # relative: -1 is the last vertex so far
                    else:
                        i = i - 1
                    if not (0 <= i < len(positions)):
                        raise ValueError(f"{path}:{lineno}: vertex index {tok} out of range")
                    idx.append(i)
                if cur_mat not in tris_by_mat:
                    tris_by_mat[cur_mat] = []
                    order.append(cur_mat)
                for k in range(1, len(idx) - 1):
                    tris_by_mat[cur_mat].append((idx[0], idx[k], idx[k + 1]))
            elif key == "usemtl":
                cur_mat = " ".join(parts[1:])
            elif key == "mtllib":
                mtllibs.append(" ".join(parts[1:]))
    return positions, [(m, tris_by_mat[m]) for m in order], mtllibs


def build_mesh(name, positions, tris, kd, ke):
    # Compact the vertex set used by this material.
    remap = {}
    verts = []
    faces = []
    for t in tris:
        for i in t:
            if i not in remap:
                remap[i] = len(verts)
                verts.append(positions[i])
            faces.append(remap[i])
    props = mi.Properties()
    props["bsdf"] = mi.load_dict({
        "type": "twosided",
        "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(kd)}},
    })
    if any(c != 0.0 for c in ke):
        props["emitter"] = mi.load_dict({
            "type": "area",
            "radiance": {"type": "rgb", "value": list(ke)},
        })
    props["face_normals"] = True
    mesh = mi.Mesh(name, len(verts), len(tris), props=props,
                   has_vertex_normals=False, has_vertex_texcoords=False)
    params = mi.traverse(mesh)
    params["vertex_positions"] = [c for v in verts for c in v]
    params["faces"] = faces
    params.update()
    return mesh


def build_scene(obj_path, size, spp, seed):
    positions, groups, mtllibs = parse_obj(obj_path)
    mats = {}
    for lib in mtllibs:
        mats.update(parse_mtl(os.path.join(os.path.dirname(obj_path), lib)))
    scene = {
        "type": "scene",
        "integrator": {
            "type": "path",
            "max_depth": MAX_DEPTH,
            "rr_depth": RR_DEPTH,
            "hide_emitters": False,
        },
        "sensor": {
            "type": "perspective",
            "fov": CAMERA_FOV_Y_DEG,
            "fov_axis": "y",
            "near_clip": NEAR_CLIP,
            "far_clip": FAR_CLIP,
            "to_world": mi.ScalarTransform4f().look_at(
                origin=list(CAMERA_ORIGIN), target=list(CAMERA_TARGET), up=list(CAMERA_UP)),
            "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
            "film": {
                "type": "hdrfilm",
                "width": size,
                "height": size,
                "pixel_format": "rgb",
                "component_format": "float32",
                "rfilter": {"type": "box"},
            },
        },
    }
    n_emitters = 0
    for mat, tris in groups:
        m = mats.get(mat)
        if m is None:
            raise ValueError(f"material {mat!r} not found in MTL")
        if any(c != 0.0 for c in m["Ke"]):
            n_emitters += 1
        print(f"  mesh {mat!r}: {len(tris)} triangles, Kd={m['Kd']}, Ke={m['Ke']}")
        scene["mesh_" + str(mat)] = build_mesh(str(mat), positions, tris, m["Kd"], m["Ke"])
    if n_emitters == 0:
        raise ValueError("no emissive material found")
    return mi.load_dict(scene)


def pixel_rows(img, size):
    """Return the image as a list of rows of (r,g,b) tuples (row 0 = top)."""
    flat = list(img.array)
    return [[tuple(flat[(y * size + x) * 3:(y * size + x) * 3 + 3]) for x in range(size)]
            for y in range(size)]


def region_mean(rows, x0, x1, y0, y1):
    s = [0.0, 0.0, 0.0]
    n = 0
    for y in range(y0, y1):
        for x in range(x0, x1):
            for c in range(3):
                s[c] += rows[y][x][c]
            n += 1
    return tuple(v / n for v in s)


def fmt(t):
    return "(" + ", ".join(f"{v:.6f}" for v in t) + ")"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--obj", required=True)
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=16384)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    ap.add_argument("--preview", default=None, help="optional PNG preview path")
    ap.add_argument("--variant", default="scalar_rgb")
    args = ap.parse_args()

    mi.set_variant(args.variant)
    print(f"mitsuba {mi.__version__}, variant {mi.variant()}")
    scene = build_scene(args.obj, args.size, args.spp, args.seed)

    t0 = time.time()
    img = mi.render(scene, spp=args.spp, seed=args.seed)
    dt = time.time() - t0
    print(f"rendered {args.size}x{args.size} at {args.spp} spp in {dt:.1f} s")

    bmp = mi.Bitmap(img, mi.Bitmap.PixelFormat.RGB)
    if bmp.component_format() != mi.Struct.Type.Float32:
        bmp = bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)) or ".", exist_ok=True)
    bmp.write(args.out)
    print(f"wrote {args.out}")

    # Read it back and check format/orientation.
    back = mi.Bitmap(args.out)
    print(f"readback: {back.pixel_format()}, {back.component_format()}, "
          f"{back.width()}x{back.height()}, srgb_gamma={back.srgb_gamma()}, "
          f"channels={[back.struct_()[i].name for i in range(back.channel_count())]}")
    rows = pixel_rows(mi.TensorXf(back), args.size)
    n = args.size
    h = n // 2
    strip = max(1, n // 8)
    left = region_mean(rows, 0, strip, 0, n)
    right = region_mean(rows, n - strip, n, 0, n)
    ok = left[0] > right[0]
    print(f"orientation check: mean red of left {strip} columns = {left[0]:.6f}, "
          f"right {strip} columns = {right[0]:.6f} -> {'OK (red wall on the left)' if ok else 'FAIL'}")
    print(f"mean RGB:          {fmt(region_mean(rows, 0, n, 0, n))}")
    print(f"mean top-left:     {fmt(region_mean(rows, 0, h, 0, h))}")
    print(f"mean top-right:    {fmt(region_mean(rows, h, n, 0, h))}")
    print(f"mean bottom-left:  {fmt(region_mean(rows, 0, h, h, n))}")
    print(f"mean bottom-right: {fmt(region_mean(rows, h, n, h, n))}")

    if args.preview:
        png = bmp.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, srgb_gamma=True)
        png.write(args.preview)
        print(f"wrote preview {args.preview}")
    if not ok:
        sys.exit(1)


if __name__ == "__main__":
    main()
