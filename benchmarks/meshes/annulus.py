#!/usr/bin/env python3
"""Write a quarter annulus a <= r <= b, 0 <= theta <= pi/2 as a gmsh 2.2
ASCII mesh: n_r x n_theta quadrilaterals (or each split in two triangles).
Cells in the inner half of the rings get physical tag (material id) 1, the
outer half 2; the inner arc's edges get boundary tag 10, the outer 11.

The cells' straight edges make the meshed area the polygon's, not the
annulus's: sum over rings and sectors of the quadrilateral areas, printed
on stdout so that tests can assert it.

    annulus.py --inner 1 --outer 2 --rings 4 --sectors 6 out.msh
"""
import argparse
import math


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--inner", type=float, default=1.0)
    p.add_argument("--outer", type=float, default=2.0)
    p.add_argument("--rings", type=int, default=4)
    p.add_argument("--sectors", type=int, default=6)
    p.add_argument("--triangles", action="store_true")
    p.add_argument("output")
    a = p.parse_args()

    nodes = []
    for i in range(a.rings + 1):
        r = a.inner + (a.outer - a.inner) * i / a.rings
        for j in range(a.sectors + 1):
            t = 0.5 * math.pi * j / a.sectors
            nodes.append((r * math.cos(t), r * math.sin(t)))

    def node(i, j):
        return i * (a.sectors + 1) + j + 1  # gmsh numbers from 1

    cells, lines = [], []
    areas = {1: 0.0, 2: 0.0}
    for i in range(a.rings):
        tag = 1 if 2 * i < a.rings else 2
        for j in range(a.sectors):
            q = [node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]
            xs = [nodes[k - 1] for k in q]
            areas[tag] += 0.5 * sum(xs[k][0] * xs[(k + 1) % 4][1] -
                                    xs[(k + 1) % 4][0] * xs[k][1]
                                    for k in range(4))
            if a.triangles:
                cells += [(2, tag, [q[0], q[1], q[2]]),
                          (2, tag, [q[0], q[2], q[3]])]
            else:
                cells.append((3, tag, q))
    for j in range(a.sectors):
        lines.append((1, 10, [node(0, j + 1), node(0, j)]))
        lines.append((1, 11, [node(a.rings, j), node(a.rings, j + 1)]))

    with open(a.output, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n")
        f.write(f"{len(nodes)}\n")
        for k, (x, y) in enumerate(nodes):
            f.write(f"{k + 1} {x:.17g} {y:.17g} 0\n")
        f.write("$EndNodes\n$Elements\n")
        elements = lines + cells
        f.write(f"{len(elements)}\n")
        for k, (kind, tag, vs) in enumerate(elements):
            f.write(f"{k + 1} {kind} 2 {tag} {tag} " +
                    " ".join(map(str, vs)) + "\n")
        f.write("$EndElements\n")
    print(f"area id 1: {areas[1]:.17g}")
    print(f"area id 2: {areas[2]:.17g}")


if __name__ == "__main__":
    main()
