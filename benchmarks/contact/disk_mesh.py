#!/usr/bin/env python3
"""Write a quadrilateral mesh of a disk (gmsh 2.2 ASCII) for a body with
'shape = mesh' and 'mesh points = Gauss points'.

A ball filled on the grid's lattice has a flat bottom row, up to
sqrt(2 s R) either side of its lowest point (s the points' spacing), and a
flat wider than mu R keeps a disk from turning under friction
(benchmarks/contact/README.md). Points at the Gauss points of a mesh whose
outer cells follow the circle make the disk round.

  disk_mesh.py --center 0.15,0.14 --radius 0.1 --cells 16 -o disk.msh

--cells: cells along each side of the square core (even); the four blocks
around it have as many along the circle and about 0.4 of that across, so
the cells at the circle are about 1.6 R / cells long.
"""
import argparse, math


def disk_cells(radius, n):
    """Vertices and quadrilaterals (counter-clockwise) of a square core of
    half-side radius / 2 and four blocks between its sides and the circle."""
    a, m = 0.5 * radius, max(1, round(0.4 * n))
    index, vertices, quads = {}, [], []

    def vertex(x, y):
        key = (round(x, 12), round(y, 12))
        if key not in index:
            index[key] = len(vertices)
            vertices.append((x, y))
        return index[key]

    core = [[vertex(-a + 2 * a * i / n, -a + 2 * a * j / n)
             for j in range(n + 1)] for i in range(n + 1)]
    for i in range(n):
        for j in range(n):
            quads.append((core[i][j], core[i + 1][j], core[i + 1][j + 1],
                          core[i][j + 1]))
    for quarter in range(4):
        c, s = math.cos(quarter * math.pi / 2), math.sin(quarter * math.pi / 2)
        block = []
        for i in range(n + 1):
            # The top side (y = a) from left to right, and the arc from 135
            # to 45 degrees at uniform angles above it.
            side = (-a + 2 * a * i / n, a)
            phi = 0.75 * math.pi - 0.5 * math.pi * i / n
            arc = (radius * math.cos(phi), radius * math.sin(phi))
            column = []
            for j in range(m + 1):
                t = j / m
                x = (1 - t) * side[0] + t * arc[0]
                y = (1 - t) * side[1] + t * arc[1]
                column.append(vertex(c * x - s * y, s * x + c * y))
            block.append(column)
        for i in range(n):
            for j in range(m):
                quads.append((block[i][j], block[i + 1][j],
                              block[i + 1][j + 1], block[i][j + 1]))
    return vertices, quads


def main():
    parser = argparse.ArgumentParser(
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--center", default="0,0")
    parser.add_argument("--radius", type=float, default=1)
    parser.add_argument("--cells", type=int, default=16)
    parser.add_argument("-o", "--output", required=True)
    a = parser.parse_args()
    if a.cells < 2 or a.cells % 2:
        parser.error("--cells must be even and at least 2")
    cx, cy = (float(v) for v in a.center.split(","))
    vertices, quads = disk_cells(a.radius, a.cells)
    with open(a.output, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" %
                len(vertices))
        for k, (x, y) in enumerate(vertices):
            f.write("%d %.15g %.15g 0\n" % (k + 1, cx + x, cy + y))
        f.write("$EndNodes\n$Elements\n%d\n" % len(quads))
        for k, q in enumerate(quads):
            f.write("%d 3 2 0 1 %d %d %d %d\n" % ((k + 1,) + tuple(v + 1 for v in q)))
        f.write("$EndElements\n")


if __name__ == "__main__":
    main()
