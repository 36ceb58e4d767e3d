#!/usr/bin/env python3
"""What the Python module costs over the C++ call: a 1M-point NumPy array in, the model back.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--points 1000000] [--repetitions 5]

The cloud is bench_skeleton's synthetic tree (a 10 m trunk, 8 limbs, 4 twigs each; noisy cylinder
surfaces, Y up), drawn with NumPy. Each repetition times, from Python, Cloud.from_numpy (one
copy of the array) + reconstruct + the model's cylinder columns, mesh and metrics as Python
objects, and takes from the same call the library's own wall time measured in C++ around the
work (Model.summary["library_ms"]: up axis, automatic skeleton sketch, cylinder model, metrics
with the cloud, what `reconstruct --auto` computes). Prints each repetition and the medians.

--cli build/treesketch also compares the module's C++ call with the CLI's on the same cloud (written
to a temporary PLY): skeleton + fit + sweep times of Model.summary against those of `treesketch
reconstruct --auto --report` (its "timings"; their metrics time also holds the report's fit against
the cloud, so it is left out), run alternately: whether the library built for the module
(position-independent code) is slower than the command's.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

import treesketch


def bench_tree(rng):
    cyls = [((0, 0, 0), (0, 10, 0), 0.3)]
    for i in range(8):
        h, phi = 3.0 + 0.8 * i, 2.4 * i
        base = np.array([0, h, 0.0])
        d = np.array([np.cos(phi), 0.8, np.sin(phi)])
        d /= np.linalg.norm(d)
        length = 4.0 - 0.3 * i
        cyls.append((base, base + length * d, 0.15 - 0.01 * i))
        for k in range(4):
            tb = base + (0.35 + 0.15 * k) * length * d
            td = d + [rng.uniform() - 0.5, 0.6, rng.uniform() - 0.5]
            cyls.append((tb, tb + 1.2 * td / np.linalg.norm(td), 0.05))
    return [(np.asarray(a, float), np.asarray(b, float), r) for a, b, r in cyls]


def bench_cloud(n, seed=7):
    rng = np.random.default_rng(seed)
    cyls = bench_tree(rng)
    area = sum(2 * np.pi * r * np.linalg.norm(b - a) for a, b, r in cyls)
    parts = []
    for a, b, r in cyls:
        length = np.linalg.norm(b - a)
        axis = (b - a) / length
        u = np.cross(axis, [1.0, 0, 0] if abs(axis[0]) < 0.9 else [0, 1.0, 0])
        u /= np.linalg.norm(u)
        v = np.cross(axis, u)
        m = int(n * 2 * np.pi * r * length / area)
        t = rng.uniform(0, length, m)[:, None]
        ang = rng.uniform(0, 2 * np.pi, m)[:, None]
        rad = r + rng.normal(0, 0.005, m)[:, None]
        parts.append(a + t * axis + rad * (np.cos(ang) * u + np.sin(ang) * v))
    return np.vstack(parts)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--repetitions", type=int, default=5)
    ap.add_argument("--cli", help="the treesketch command: compare the C++ call with the CLI's")
    args = ap.parse_args()
    xyz = bench_cloud(args.points)
    print(f"cloud: {len(xyz)} points")
    treesketch.reconstruct(treesketch.Cloud.from_numpy(xyz), up="y")  # warm up (TBB's threads, page faults)
    rows = []
    for i in range(args.repetitions):
        t0 = time.perf_counter()
        cloud = treesketch.Cloud.from_numpy(xyz)
        t1 = time.perf_counter()
        model = treesketch.reconstruct(cloud, up="y")
        cylinders = model.cylinders
        vertices, faces = model.mesh()
        metrics = model.metrics()
        t2 = time.perf_counter()
        python_ms = (t2 - t0) * 1000
        library_ms = model.summary["library_ms"]
        rows.append((python_ms, library_ms, (t1 - t0) * 1000))
        print(f"  {i}: Python {python_ms:8.1f} ms   C++ call {library_ms:8.1f} ms   ratio {python_ms / library_ms:.4f}"
              f"   (from_numpy {(t1 - t0) * 1000:.1f} ms; {len(cylinders['id'])} cylinders, {len(faces)} triangles,"
              f" {len(metrics)} metrics)")
    ratios = [p / c for p, c, _ in rows]
    print(f"median: Python {statistics.median(r[0] for r in rows):.1f} ms, C++ call "
          f"{statistics.median(r[1] for r in rows):.1f} ms, from_numpy {statistics.median(r[2] for r in rows):.1f} ms;"
          f" ratio median {statistics.median(ratios):.4f} (min {min(ratios):.4f}, max {max(ratios):.4f})")
    if args.cli:
        compare_with_cli(args.cli, xyz, args.repetitions)


def compare_with_cli(cli, xyz, repetitions):
    keys = ("skeleton", "fit", "sweep")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "cloud.ply")
        treesketch.Cloud.from_numpy(xyz, up="y").write(path)
        cloud = treesketch.read_cloud(path)
        ratios = []
        for i in range(repetitions):
            s = treesketch.reconstruct(cloud).summary
            module_ms = sum(s[k + "_ms"] for k in keys)
            subprocess.run([cli, "reconstruct", path, "--auto", "-o", os.path.join(tmp, "m.obj"), "--report",
                            os.path.join(tmp, "r.json")], check=True, capture_output=True)
            with open(os.path.join(tmp, "r.json")) as f:
                t = json.load(f)["timings"]
            cli_ms = sum(t[k + "Ms"] for k in keys)
            ratios.append(module_ms / cli_ms)
            print(f"  {i}: module's C++ {module_ms:8.1f} ms   CLI {cli_ms:8.1f} ms   ratio {ratios[-1]:.3f}")
        print(f"module's C++ call / CLI's: median {statistics.median(ratios):.3f}")


if __name__ == "__main__":
    main()
