#!/usr/bin/env python3
"""Writes the distorted 2 x 2 patch of tests/verification/cplan_*.comm in
code_aster's .mail format, once per cell type (QUAD4, QUAD8, TRIA3,
TRIA6): the square [0, 2] x [0, 2] whose centre vertex is moved to
(0.9, 1.17) and whose mid-side vertices slide along the sides to
(1.1, 0), (2, 0.8), (0.85, 2), (0, 1.2); the triangles split each
quadrilateral along its diagonal from its first vertex; the mid-edge
nodes of QUAD8/TRIA6 are at the middles of the straight edges. The top
edge is also meshed with SEG2/SEG3 cells (group ARETE_H) for FORCE_CONTOUR.

Groups of cells: PLAQUE (the 2D cells), ARETE_H (the top edge).
Groups of nodes: BAS (y = 0), HAUT (y = 2), GAUCHE (x = 0), DROITE
(x = 2), BORD (the boundary), CENTRE (the moved centre vertex), COIN
(the corner (0, 0)).

Usage: python3 scripts/cplan_meshes.py tests/verification
"""
import sys

V = [(0.0, 0.0), (1.1, 0.0), (2.0, 0.0), (0.0, 1.2), (0.9, 1.17), (2.0, 0.8),
     (0.0, 2.0), (0.85, 2.0), (2.0, 2.0)]
QUADS = [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)]
TOP = [(6, 7), (7, 8)]


def build(kind):
    nodes = list(V)
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            pa, pb = nodes[a], nodes[b]
            nodes.append(((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2))
            mids[key] = len(nodes) - 1
        return mids[key]

    quadratic = kind in ("QUAD8", "TRIA6")
    cells = []
    for q in QUADS:
        polys = [q] if kind.startswith("QUAD") else [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
        for p in polys:
            c = list(p)
            if quadratic:
                c += [mid(p[i], p[(i + 1) % len(p)]) for i in range(len(p))]
            cells.append(c)
    segs = []
    for a, b in TOP:
        segs.append([a, b, mid(a, b)] if quadratic else [a, b])
    return nodes, cells, segs


def write(path, kind):
    nodes, cells, segs = build(kind)
    seg = "SEG3" if kind in ("QUAD8", "TRIA6") else "SEG2"
    out = [" TITRE", f" % distorted 2 x 2 plane patch in {kind} (scripts/cplan_meshes.py)",
           f" CPLAN PATCH {kind}", " FINSF", " COOR_2D"]
    for i, (x, y) in enumerate(nodes):
        out.append(f" N{i + 1} {x!r} {y!r}")
    out.append(" FINSF")
    out.append(f" {kind}")
    for k, c in enumerate(cells):
        out.append(f" M{k + 1} " + " ".join(f"N{n + 1}" for n in c))
    out.append(" FINSF")
    out.append(f" {seg}")
    for k, c in enumerate(segs):
        out.append(f" M{len(cells) + k + 1} " + " ".join(f"N{n + 1}" for n in c))
    out.append(" FINSF")
    out.append(" GROUP_MA")
    out.append(" PLAQUE " + " ".join(f"M{k + 1}" for k in range(len(cells))))
    out.append(" FINSF")
    out.append(" GROUP_MA")
    out.append(" ARETE_H " + " ".join(f"M{len(cells) + k + 1}" for k in range(len(segs))))
    out.append(" FINSF")
    eps = 1e-12
    groups = {
        "BAS": lambda x, y: abs(y) < eps,
        "HAUT": lambda x, y: abs(y - 2) < eps,
        "GAUCHE": lambda x, y: abs(x) < eps,
        "DROITE": lambda x, y: abs(x - 2) < eps,
        "BORD": lambda x, y: min(abs(x), abs(y), abs(x - 2), abs(y - 2)) < eps,
        "CENTRE": lambda x, y: (x, y) == (0.9, 1.17),
        "COIN": lambda x, y: (x, y) == (0.0, 0.0),
    }
    for name, keep in groups.items():
        members = [f"N{i + 1}" for i, (x, y) in enumerate(nodes) if keep(x, y)]
        out.append(" GROUP_NO")
        out.append(f" {name} " + " ".join(members))
        out.append(" FINSF")
    out.append(" FIN")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    d = sys.argv[1] if len(sys.argv) > 1 else "."
    for kind in ("QUAD4", "QUAD8", "TRIA3", "TRIA6"):
        write(f"{d}/cplan_{kind.lower()}.mail", kind)
