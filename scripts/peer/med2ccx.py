#!/usr/bin/env python3
"""Write the CalculiX (ccx) input deck of SDNV103 modelling B from one of our
axisymmetric Taylor-bar MED meshes (`aster mesh taylor --kind axis`).

The MED file is read with h5py alone (layout: /work/shared/fixtures/med/
MED_LAYOUT.md, our reader src/medio/read.rs), so this needs no MED library.
The deck reproduces comm/sdnv103b.comm as closely as CalculiX allows; every
place where it cannot is listed in docs/peer-calculix.md.

Usage: med2ccx.py MESH.mmed OUT.inp [--contact node|face|gap] [--penalty K]
                  [--gap-stiffness KG] [--stick-slope L] [--alpha A]
                  [--auto [--min-divisor D]] [--touch] [--controls LINE]
                  [--elements wedge|cax] [--wedge-angle DEG] [--steps N0,N1,N2]
"""
import argparse
import sys

import h5py
import numpy as np

# --- the study (comm/sdnv103b.comm) -----------------------------------------
E, NU, RHO = 117.0e3, 0.35, 8.93e-9
SY, ET = 400.0, 100.0  # ECRO_LINE: yield stress, tangent slope of sigma(eps)
MU = 0.25  # Coulomb
V0 = -227000.0  # axial initial velocity of the bar, mm/s
# DEFI_LIST_REEL of the comm file: from -1e-5, (end, number of steps) per interval
T0 = -1.0e-5
INTERVALS = [(-1.0e-7, 1), (1.0e-6, 4), (8.0e-5, 158)]
# --touch: the same 163 increments, but the first contact increment starts at
# the instant of first touch (INST 0) instead of -1e-7, where the face is still
# 0.0227 mm above the block (docs/peer-calculix.md says why this matters to ccx)
INTERVALS_TOUCH = [(0.0, 1), (1.0e-6, 4), (8.0e-5, 158)]


def die(msg):
    print(f"med2ccx: {msg}", file=sys.stderr)
    sys.exit(1)


def names80(ds):
    """Group names of a family: rows of 80 int8, blank/NUL padded."""
    out = []
    # ds[()] (not np.asarray) is what h5py can read for an H5T_ARRAY type
    for row in np.asarray(ds[()]).reshape(-1, 80):
        raw = bytes(np.asarray(row, dtype=np.int8).astype(np.uint8))
        out.append(raw.split(b"\0")[0].decode("ascii").strip())
    return out


def read_med(path):
    """Nodes (n x 2), cells {MED type: (nc x npc) 1-based}, families and the
    node/cell groups as {name: sorted ids}; cells are numbered per type."""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        die(f"{path}: not an HDF5/MED file ({e})")
    with f:
        if "ENS_MAA" not in f or len(f["ENS_MAA"]) != 1:
            die(f"{path}: expected exactly one mesh under ENS_MAA")
        mesh = list(f["ENS_MAA"].keys())[0]
        mg = f["ENS_MAA"][mesh]
        if int(mg.attrs["ESP"]) != 2:
            die(f"{path}: mesh {mesh} is not 2D (ESP={mg.attrs['ESP']})")
        step = mg[list(mg.keys())[0]]
        coo = np.asarray(step["NOE/COO"], dtype=float)
        n = int(step["NOE/COO"].attrs["NBR"])
        xy = coo.reshape(2, n).T  # component-major
        nfam = np.asarray(step["NOE/FAM"], dtype=np.int64)
        cells, cfam = {}, {}
        for typ, g in step["MAI"].items():
            nc = int(g["NOD"].attrs["NBR"])
            nod = np.asarray(g["NOD"], dtype=np.int64)
            cells[typ] = nod.reshape(-1, nc).T  # node-rank-major
            cfam[typ] = np.asarray(g["FAM"], dtype=np.int64)
        fams = {}
        for kind in ("NOEUD", "ELEME"):
            base = f"FAS/{mesh}/{kind}"
            if base not in f:
                continue
            for fg in f[base].values():
                num = int(fg.attrs["NUM"])
                fams[num] = names80(fg["GRO/NOM"]) if "GRO" in fg else []
    ngroups = {}
    for i, fa in enumerate(nfam):
        for gname in fams.get(int(fa), []):
            ngroups.setdefault(gname, []).append(i + 1)
    cgroups = {}  # name -> list of (type, index 0-based)
    for typ, fa in cfam.items():
        for i, v in enumerate(fa):
            for gname in fams.get(int(v), []):
                cgroups.setdefault(gname, []).append((typ, i))
    return xy, cells, ngroups, cgroups


def hardening_table():
    """*PLASTIC points (true stress, equivalent plastic strain). ECRO_LINE gives
    sigma = SY + H p with H = E ET / (E - ET); two points make ccx's piecewise
    linear table exactly that line up to p = 10 (the bar reaches p ~ 3)."""
    h = E * ET / (E - ET)
    return [(SY, 0.0), (SY + h * 10.0, 10.0)]


def time_steps(counts, intervals):
    """Three ccx steps (initial increment = step length / count, DIRECT) with
    ccx time 0 at our INST -1e-5."""
    out, t = [], T0
    for (end, _), nb in zip(intervals, counts):
        out.append(((end - t) / nb, end - t, nb))
        t = end
    return out


def wedge(w, nset, a, xy, quads, elset, ngroups, bar_nodes, rig_nodes, surface):
    """The axisymmetric model written as a thin C3D20R wedge, the expansion
    ccx itself would make of CAX8R, but with every node ours so that the
    initial velocity reaches all of them.

    x = r cos(phi), y = axis, z = r sin(phi), phi in [-a/2, a/2]. 2D node i
    gives node i (back face, phi = -a/2), i + N (front, +a/2) and, for QUAD8
    corners, i + 2N (phi = 0, the C3D20 mid-thickness nodes). Linear
    equations make the wedge axisymmetric: every node of a 2D node moves by
    the same radial and axial displacement (U_r, U_y) and never turns
    (u_phi = 0). The phi = 0 node carries (U_r, U_y) as (u_x, u_y); where a
    2D node has no phi = 0 node (QUAD8 mid-edge nodes) the front node does.
    Returns the *BOUNDARY lines, the *INITIAL CONDITIONS lines and the node
    sets to print for B1 and A2."""
    n = len(xy)
    half = np.radians(a.wedge_angle) / 2.0
    c, s = np.cos(half), np.sin(half)
    corners = sorted({int(v) for q in quads for v in q[:4]})
    w("*NODE, NSET=NALL")
    for i, (r, y) in enumerate(xy):
        w(f"{i + 1}, {r * c:.15g}, {y:.15g}, {-r * s:.15g}")
    for i, (r, y) in enumerate(xy):
        w(f"{i + 1 + n}, {r * c:.15g}, {y:.15g}, {r * s:.15g}")
    for i in corners:
        r, y = xy[i - 1]
        w(f"{i + 2 * n}, {r:.15g}, {y:.15g}, 0")
    for g in ("VOL", "VOL_RIG"):
        # C3D20R: 2x2x2 reduced integration, the 2x2 of AXIS_SI times 2
        # points across the wedge. Nodes 1-4 back corners, 5-8 front
        # corners, 9-12 back mid-edges, 13-16 front mid-edges, 17-20 the
        # corners at phi = 0; 1-2-3-4 counter-clockwise in (r, y) turns
        # towards +phi, so the Jacobian is positive.
        w(f"*ELEMENT, TYPE=C3D20R, ELSET={g}")
        for k in elset[g]:
            q = [int(v) for v in quads[k]]
            conn = q[:4] + [v + n for v in q[:4]] + q[4:] + [v + n for v in q[4:]] \
                + [v + 2 * n for v in q[:4]]
            w(f"{k + 1}, " + ", ".join(str(v) for v in conn[:15]) + ",")
            w(", ".join(str(v) for v in conn[15:]))
    on_axis = {i + 1 for i, (r, _) in enumerate(xy) if abs(r) < 1e-12}
    corner_set = set(corners)
    bar = set(bar_nodes)
    everything = lambda i: [i, i + n] + ([i + 2 * n] if i in corner_set else [])
    nset("NBAR", sorted(v for i in bar for v in everything(i)))
    nset("NRIG", sorted(v for i in rig_nodes for v in everything(int(i))))
    # printed: the phi = 0 node of B1 and A2 (both QUAD8 corners)
    for g in ("B1", "A2"):
        ids = [int(v) for v in ngroups[g]]
        if any(i not in corner_set for i in ids):
            die(f"node group {g} is not on QUAD8 corners")
        nset(f"{g}W", [i + 2 * n for i in ids])
    # faces: 2D edge k (1-2, 2-3, 3-4, 4-1) becomes C3D20 face S(k+2)
    for name in ("SZZ", "RIGID"):
        w(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        for e, k in surface(name):
            w(f"{e}, S{k + 2}")

    fixed = []
    eqs = []
    rig = {int(i) for i in rig_nodes}
    for i in range(1, n + 1):
        if i in rig:
            continue  # fixed below
        b, f, m = i, i + n, i + 2 * n
        if i in on_axis:
            # the AXE condition DX = 0: no radial motion, nodes coincide
            for v in everything(i):
                fixed += [f"{v}, 1, 1", f"{v}, 3, 3"]
            ref = m if i in corner_set else f
            for v in everything(i):
                if v != ref:
                    eqs.append([(v, 2, 1.0), (ref, 2, -1.0)])
            continue
        if i in corner_set:
            fixed.append(f"{m}, 3, 3")  # u_phi = 0 at phi = 0
            for v, sign in ((b, -1.0), (f, 1.0)):
                eqs.append([(v, 1, 1.0), (m, 1, -c)])
                eqs.append([(v, 3, 1.0), (m, 1, -sign * s)])
                eqs.append([(v, 2, 1.0), (m, 2, -1.0)])
        else:
            # front node independent in x, y; its u_phi = 0 fixes z
            eqs.append([(f, 3, 1.0), (f, 1, -s / c)])
            eqs.append([(b, 1, 1.0), (f, 1, -1.0)])
            eqs.append([(b, 3, 1.0), (f, 1, s / c)])
            eqs.append([(b, 2, 1.0), (f, 2, -1.0)])
    w("*EQUATION")
    for terms in eqs:
        w(str(len(terms)))
        w(", ".join(f"{v}, {d}, {co:.15g}" for v, d, co in terms))
    fixed.insert(0, "NRIG, 1, 3")
    velocity = [f"NBAR, 2, {V0:.6g}"]
    # the node whose (u_x, u_y) is the (U_r, U_y) of 2D node i (see above)
    carrier = lambda i: i + 2 * n if i in corner_set else i + n
    return fixed, velocity, {"B1": "B1W", "A2": "A2W"}, carrier


def gap_elements(w, xy, face_nodes, block_nodes, carrier, stiffness):
    """Unilateral supports instead of contact: one GAPUNI element per node of
    the impact face, from a (fixed) block node to the node carrying that face
    node's axial displacement. ccx counts these as ordinary elements, not as
    contact elements, so the energy/impact rule of its implicit dynamics
    (checkimpacts, docs/peer-calculix.md) never applies; they are
    frictionless. Gap condition of ccx: d + n.(u2 - u1) >= 0 with n = +y, so
    the clearance d is the height of the face node above the block's top."""
    top = {round(float(xy[i - 1][1]), 12) for i in block_nodes}
    if len(top) != 1:
        die("--contact gap needs a flat block top (RIGID at one height)")
    y0 = top.pop()
    clear = {}
    for i in face_nodes:
        d = float(xy[i - 1][1]) - y0
        if d < 0:
            die(f"impact-face node {i} is below the block top")
        clear.setdefault(round(d, 12), []).append(i)
    anchor = min(block_nodes)
    num = 1 + 10 ** (len(str(len(xy) * 3)) + 1)  # above every C3D20R number
    for k, (d, nodes) in enumerate(sorted(clear.items())):
        w(f"*ELEMENT, TYPE=GAPUNI, ELSET=GAP{k + 1}")
        for i in nodes:
            w(f"{num}, {anchor}, {carrier(i)}")
            num += 1
        w(f"*GAP, ELSET=GAP{k + 1}")
        # clearance, direction (0, 1, 0), unused, spring stiffness (N/mm)
        w(f"{d:.15g}, 0., 1., 0., 0., {stiffness:.6g}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--elements", choices=("wedge", "cax"), default="wedge",
                    help="our own C3D20R wedge (default) or ccx's CAX8R")
    ap.add_argument("--wedge-angle", type=float, default=2.0,
                    help="opening of the wedge, degrees")
    ap.add_argument("--contact", choices=("node", "face", "gap"), default="node",
                    help="node-to-surface (default) or surface-to-surface penalty "
                         "contact with friction, or frictionless GAPUNI supports")
    ap.add_argument("--gap-stiffness", type=float, default=1.0e8,
                    help="spring stiffness of each GAPUNI element, N/mm")
    ap.add_argument("--penalty", type=float, default=1.0e8,
                    help="pressure-overclosure slope K, MPa/mm")
    ap.add_argument("--stick-slope", type=float, default=1.0e5,
                    help="friction stick slope lambda, MPa/mm")
    ap.add_argument("--alpha", type=float, default=-1.0 / 3.0,
                    help="HHT alpha of *DYNAMIC (ccx accepts [-1/3, 0])")
    ap.add_argument("--auto", action="store_true",
                    help="let ccx cut increments (default: *DYNAMIC, DIRECT, our 163 increments)")
    ap.add_argument("--min-divisor", type=float, default=16.0,
                    help="smallest increment ccx may take = our increment / this")
    ap.add_argument("--steps", default=",".join(str(n) for _, n in INTERVALS),
                    help="increments per interval (default 1,4,158 as the comm file)")
    ap.add_argument("--touch", action="store_true",
                    help="start the contact interval at the first touch (INST 0) "
                         "instead of -1e-7")
    ap.add_argument("--controls", metavar="LINE",
                    help="data line of *CONTROLS, PARAMETERS=TIME INCREMENTATION "
                         "(I0,IR,IP,IC,IL,IG,IS,IA), e.g. 20,30,9,50,10,4,,5")
    a = ap.parse_args()
    if a.contact == "gap" and a.elements != "wedge":
        die("--contact gap needs --elements wedge")
    counts = [int(s) for s in a.steps.split(",")]
    if len(counts) != len(INTERVALS) or min(counts) < 1:
        die(f"--steps needs {len(INTERVALS)} positive counts")

    xy, cells, ngroups, cgroups = read_med(a.mesh)
    if "QU8" not in cells or "SE3" not in cells:
        die(f"{a.mesh}: expected QUAD8 cells and SEG3 skin cells")
    for g in ("VOL", "VOL_RIG", "SZZ", "RIGID", "AXE"):
        if g not in cgroups:
            die(f"{a.mesh}: cell group {g} missing")
    for g in ("A1", "B1", "A2", "B2"):
        if g not in ngroups:
            die(f"{a.mesh}: node group {g} missing")
    quads = cells["QU8"]
    segs = cells["SE3"]

    # ccx wants counter-clockwise CAX8 in (r, z): check, never silently flip.
    for k, q in enumerate(quads):
        p = xy[q[:4] - 1]
        area2 = sum(p[i, 0] * p[(i + 1) % 4, 1] - p[(i + 1) % 4, 0] * p[i, 1] for i in range(4))
        if area2 <= 0:
            die(f"QUAD8 #{k + 1} turns clockwise")

    elset = {g: [i for t, i in cgroups[g] if t == "QU8"] for g in ("VOL", "VOL_RIG")}
    # element face of an edge: CAX8 faces S1..S4 = edges 1-2, 2-3, 3-4, 4-1
    edge_of = {}
    for k, q in enumerate(quads):
        for s in range(4):
            edge_of[frozenset((q[s], q[(s + 1) % 4]))] = (k + 1, s + 1)

    def surface(g):
        out = []
        for t, i in cgroups[g]:
            if t != "SE3":
                continue
            key = frozenset((segs[i][0], segs[i][1]))
            if key not in edge_of:
                die(f"SEG3 of {g} is not an edge of a QUAD8")
            out.append(edge_of[key])
        return out

    def nodes_of(g, typ):
        ids = set()
        for t, i in cgroups[g]:
            if t == typ:
                ids.update(int(v) for v in cells[typ][i])
        return sorted(ids)

    bar_nodes = nodes_of("VOL", "QU8")
    rig_nodes = nodes_of("VOL_RIG", "QU8")
    axe_nodes = nodes_of("AXE", "SE3")

    L = []
    w = L.append
    w("*HEADING")
    w(f"SDNV103 B Taylor bar, from {a.mesh} by scripts/peer/med2ccx.py ({a.elements})")

    def nset(name, ids):
        w(f"*NSET, NSET={name}")
        for j in range(0, len(ids), 12):
            w(", ".join(str(v) for v in ids[j:j + 12]))

    if a.elements == "cax":
        # ccx's own axisymmetric elements. ccx 2.20 expands them into a C3D20R
        # wedge but does not carry *INITIAL CONDITIONS TYPE=VELOCITY over to
        # the expanded nodes: the bar never moves (docs/peer-calculix.md).
        w("*NODE, NSET=NALL")
        for i, (x, y) in enumerate(xy):
            w(f"{i + 1}, {x:.15g}, {y:.15g}")
        for g in ("VOL", "VOL_RIG"):
            # CAX8R: 2x2 reduced integration, as AXIS_SI
            w(f"*ELEMENT, TYPE=CAX8R, ELSET={g}")
            for k in elset[g]:
                w(f"{k + 1}, " + ", ".join(str(int(v)) for v in quads[k]))
        for g in ("A1", "B1", "A2", "B2"):
            nset(g, ngroups[g])
        nset("NBAR", bar_nodes)
        nset("NRIG", rig_nodes)
        nset("AXE", axe_nodes)
        for name, g in (("SZZ", "SZZ"), ("RIGID", "RIGID")):
            w(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
            for e, s in surface(g):
                w(f"{e}, S{s}")
        fixed = ["NRIG, 1, 2", "AXE, 1, 1"]
        velocity = [f"NBAR, 2, {V0:.6g}"]
        printed = {"B1": "B1", "A2": "A2"}
    else:
        fixed, velocity, printed, carrier = wedge(w, nset, a, xy, quads, elset, ngroups,
                                                  bar_nodes, rig_nodes, surface)

    w("*MATERIAL, NAME=CUIVRE")
    w("*ELASTIC")
    w(f"{E:.6g}, {NU}")
    w("*DENSITY")
    w(f"{RHO:.6g}")
    w("*PLASTIC")
    for s, p in hardening_table():
        w(f"{s:.10g}, {p:.10g}")
    # the block: same material as in the comm file (AFFE_MATERIAU TOUT), but all
    # its nodes are fixed, so its law never matters
    w("*SOLID SECTION, ELSET=VOL, MATERIAL=CUIVRE")
    w("*SOLID SECTION, ELSET=VOL_RIG, MATERIAL=CUIVRE")

    if a.contact == "gap":
        face = sorted({int(v) for t, i in cgroups["SZZ"] if t == "SE3" for v in segs[i]})
        block = sorted({int(v) for t, i in cgroups["RIGID"] if t == "SE3" for v in segs[i]})
        gap_elements(w, xy, face, block, carrier, a.gap_stiffness)
        typ = "GAPUNI (frictionless)"
    else:
        w("*SURFACE INTERACTION, NAME=SI")
        w("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR")
        if a.contact == "node":
            # K, sigma_inf (tension at large clearance, node-to-face only)
            w(f"{a.penalty:.6g}, 1.e-3")
        else:
            # K, sigma_inf (unused), c0 (clearance where the spring starts)
            w(f"{a.penalty:.6g}, 1.e-3, 1.e-6")
        w("*FRICTION")
        w(f"{MU}, {a.stick_slope:.6g}")
        typ = "NODE TO SURFACE" if a.contact == "node" else "SURFACE TO SURFACE"
        w(f"*CONTACT PAIR, INTERACTION=SI, TYPE={typ}")
        w("SZZ, RIGID")

    w("*BOUNDARY")
    for line in fixed:
        w(line)
    w("*INITIAL CONDITIONS, TYPE=VELOCITY")
    for line in velocity:
        w(line)

    intervals = INTERVALS_TOUCH if a.touch else INTERVALS
    for k, (dt, length, nb) in enumerate(time_steps(counts, intervals)):
        w(f"** interval {k + 1}: {nb} increments of {dt:.6g} s")
        w(f"*STEP, NLGEOM, INC={1000 * nb}")
        if not a.auto:
            w(f"*DYNAMIC, DIRECT, ALPHA={a.alpha:.10g}")
            w(f"{dt:.10g}, {length:.10g}")
        else:
            # our increment as the first and the largest one: ccx may only cut
            w(f"*DYNAMIC, ALPHA={a.alpha:.10g}")
            w(f"{dt:.10g}, {length:.10g}, {dt / a.min_divisor:.10g}, {dt:.10g}")
        if a.controls:
            # more Newton iterations before ccx calls an increment divergent
            # (default I0 = 4: a gap closing in the first increments makes
            # the residual rise twice before it falls)
            w("*CONTROLS, PARAMETERS=TIME INCREMENTATION")
            w(a.controls)
        for g in ("B1", "A2"):
            w(f"*NODE PRINT, NSET={printed[g]}")
            w("U, V")
        w("*END STEP")
    with open(a.out, "w") as fo:
        fo.write("\n".join(L) + "\n")
    print(f"med2ccx: {a.out}: {len(xy)} nodes, {len(quads)} QUAD8, "
          f"{sum(counts)} increments, {a.elements}, contact {typ}", file=sys.stderr)


if __name__ == "__main__":
    main()
