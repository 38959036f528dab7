#!/usr/bin/env python3
"""Writes an OBJ of a dense cluster of tiny triangles on a floor (the property of the built-in
`dense-cluster`: 330 000 triangles of about 0.3 mm in a 4 cm cube), for binaries that predate
the built-in. Usage: dense_cluster_obj.py OUT.obj"""
import random
import sys

random.seed(1)
lines = ["v -3 0 -3", "v 3 0 -3", "v 3 0 3", "v -3 0 3", "f 1 3 2", "f 1 4 3"]
count = 4
for _ in range(330_000):
    p = [random.uniform(-0.02, 0.02), 0.77 + random.uniform(-0.02, 0.02), random.uniform(-0.02, 0.02)]
    for _ in range(3):
        lines.append("v %.6f %.6f %.6f" % tuple(c + random.uniform(-0.00015, 0.00015) for c in p))
    lines.append("f %d %d %d" % (count + 1, count + 2, count + 3))
    count += 3
with open(sys.argv[1], "w") as f:
    f.write("\n".join(lines) + "\n")
