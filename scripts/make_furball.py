#!/usr/bin/env python3
"""Writes scenes/showcase/furball.txt: a strand file (x y z radius per line,
a blank line between strands) of fur on a unit sphere, for
scenes/showcase/curves.json. Deterministic (fixed seed); run it again to
regenerate the file."""
import math
import random
import sys

random.seed(7)
strands = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
out = []
for i in range(strands):
    # Fibonacci-sphere roots: evenly spread, jittered a little.
    z = 1.0 - 2.0 * (i + 0.5) / strands
    phi = i * math.pi * (3.0 - math.sqrt(5.0)) + random.uniform(-0.05, 0.05)
    s = math.sqrt(max(0.0, 1.0 - z * z))
    root = (s * math.cos(phi), s * math.sin(phi), z)
    length = random.uniform(0.35, 0.55)
    # Combed down a little and curled: five B-spline control points.
    bend = (random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), -0.5)
    for k in range(5):
        t = k / 4.0
        p = [root[j] * (0.98 + length * t) + bend[j] * length * t * t for j in range(3)]
        r = 0.012 * (1.0 - 0.8 * t)
        out.append(f"{p[0]:.4f} {p[1]:.4f} {p[2]:.4f} {r:.4f}")
    out.append("")
with open("scenes/showcase/furball.txt", "w") as f:
    f.write("# fur on a unit sphere, from scripts/make_furball.py\n" + "\n".join(out))
