#!/usr/bin/env python3
"""Mitsuba 3 (variant ``cuda_ad_rgb``, which traces through OptiX) timed on the very rays that
``irradiant bench --dump-rays DIR`` traced, so that the two ray throughputs compare like with
like (issue 42, "the peer, side by side"; run by ``tools/device/peer.sh``).

For each ``<scene>.triangles.f32`` in DIR: one Mitsuba mesh of those world-space triangles (9
little-endian floats a triangle), no materials; then for each ray set (``primary``,
``diffuse``: 6 floats a ray, origin and direction):

* closest hit: ``scene.ray_intersect_preliminary`` (distance, primitive and barycentrics, what
  Irradiant's ``raycast/trace`` returns), and for ``diffuse`` also any hit: ``scene.ray_test``;
* each timed as ``bench`` times a pass: untimed runs for at least ``--warmup-ms`` first, then
  the median of ``--iterations`` runs, the kernel's own GPU time from Dr.Jit's kernel history
  (wall clock around the launch beside it);
* the hits checked against Irradiant's (``<scene>.<set>.t.f32``): the share of rays whose
  hit or miss agrees and whose distance agrees within 1e-3 relative, so that a figure is only
  trusted where both traced the same thing.
"""

import argparse
import glob
import json
import os
import statistics
import time

import numpy as np
import drjit as dr
import mitsuba as mi


def floats(path, width):
    return np.fromfile(path, dtype="<f4").reshape(-1, width)


def column(array, i):
    return mi.Float(np.ascontiguousarray(array[:, i]))


def build_scene(name, corners):
    faces = len(corners) // 3
    mesh = mi.Mesh(name, len(corners), faces, has_vertex_normals=False, has_vertex_texcoords=False)
    params = mi.traverse(mesh)
    params["vertex_positions"] = mi.Float(np.ascontiguousarray(corners.ravel()))
    params["faces"] = mi.UInt32(np.arange(len(corners), dtype=np.uint32))
    params.update()
    return mi.load_dict({"type": "scene", "mesh": mesh})


def timed(run, warmup_ms, iterations):
    """(median kernel ms, median wall ms) of `run` after the warm-up."""
    start, runs = time.perf_counter(), 0
    while runs < 3 or (time.perf_counter() - start) * 1e3 < warmup_ms:
        run()
        dr.sync_thread()
        runs += 1
    kernel, wall = [], []
    for _ in range(iterations):
        dr.kernel_history()  # empties it
        t = time.perf_counter()
        run()
        dr.sync_thread()
        wall.append((time.perf_counter() - t) * 1e3)
        history = dr.kernel_history()
        ms = sum(k.get("execution_time", 0.0) for k in history)
        if ms > 0:
            kernel.append(ms)
    return (statistics.median(kernel) if kernel else None, statistics.median(wall))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("dir", help="the folder irradiant bench --dump-rays wrote")
    parser.add_argument("--iterations", type=int, default=30)
    parser.add_argument("--warmup-ms", type=float, default=500.0)
    parser.add_argument("--json", help="also write every figure here")
    parser.add_argument("--variant", default="cuda_ad_rgb", help="llvm_ad_rgb checks the script on a CPU")
    args = parser.parse_args()
    mi.set_variant(args.variant)
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    records = []
    print(f"{'scene':<24} {'rays':<22} {'ms (kernel)':>12} {'ms (wall)':>10} {'Mrays/s':>9} {'agree':>7}")
    for path in sorted(glob.glob(os.path.join(args.dir, "*.triangles.f32"))):
        name = os.path.basename(path)[: -len(".triangles.f32")]
        start = time.perf_counter()
        scene = build_scene(name, floats(path, 3))
        dr.eval()
        dr.sync_thread()
        build_ms = (time.perf_counter() - start) * 1e3
        for ray_set in ("primary", "diffuse"):
            rays = floats(os.path.join(args.dir, f"{name}.{ray_set}.rays.f32"), 6)
            expected = floats(os.path.join(args.dir, f"{name}.{ray_set}.t.f32"), 1).ravel()
            ray = mi.Ray3f(
                mi.Point3f(column(rays, 0), column(rays, 1), column(rays, 2)),
                mi.Vector3f(column(rays, 3), column(rays, 4), column(rays, 5)),
            )
            dr.eval(ray)
            kinds = [("closest hit", False)] + ([("any hit", True)] if ray_set == "diffuse" else [])
            for kind, any_hit in kinds:
                if any_hit:
                    def run():
                        hit = scene.ray_test(ray)
                        dr.eval(hit)
                        return hit
                else:
                    def run():
                        pi = scene.ray_intersect_preliminary(ray)
                        dr.eval(pi.t, pi.prim_index, pi.prim_uv)
                        return pi
                kernel_ms, wall_ms = timed(run, args.warmup_ms, args.iterations)
                result = run()
                dr.sync_thread()
                if any_hit:
                    ours = expected >= 0.0
                    agree = float(np.mean(np.asarray(result) == ours))
                else:
                    t = np.asarray(result.t)
                    theirs_hit = np.isfinite(t)
                    ours_hit = expected >= 0.0
                    close = np.abs(np.where(theirs_hit, t, 0) - np.where(ours_hit, expected, 0)) <= 1e-3 * np.maximum(1.0, np.abs(expected))
                    agree = float(np.mean((theirs_hit == ours_hit) & (~ours_hit | close)))
                ms = kernel_ms if kernel_ms is not None else wall_ms
                mrays = len(rays) / (ms * 1e-3) / 1e6
                label = f"{ray_set}, {kind}"
                kernel_text = f"{kernel_ms:.3f}" if kernel_ms is not None else "-"
                print(f"{name:<24} {label:<22} {kernel_text:>12} {wall_ms:>10.3f} {mrays:>9.0f} {agree:>7.4f}")
                records.append({
                    "scene": name, "rays": label, "count": len(rays), "kernel_ms": kernel_ms,
                    "wall_ms": wall_ms, "mrays_per_s": mrays, "agreement": agree,
                    "build_ms": build_ms,
                })
    if not records:
        raise SystemExit(f"{args.dir}: no *.triangles.f32; run irradiant bench --dump-rays {args.dir} first")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"renderer": f"Mitsuba {mi.__version__} {args.variant}, Dr.Jit {dr.__version__}",
                       "records": records}, f, indent=1)


if __name__ == "__main__":
    main()
