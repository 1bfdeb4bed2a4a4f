#!/usr/bin/env python3
"""Check MED files written by aster with independent readers.

    python3 tests/med_interop.py SIDECAR.json [--only medcoupling|meshio|mdump]

SIDECAR.json (written by tests/med_interop.rs) lists files and what each must contain:
mesh name, space dimension, coordinates, cells (MED type name and 0-based MED-ordered
connectivity, in aster's cell order), cell groups (aster cell indices), node groups, nodal
and cell fields (steps with numdt, time and entity-major values).

Every available reader is run: medcoupling (preferred: it uses libmed itself), meshio,
and Debian's mdump (libmed-tools).  Exit status: 0 all available readers agree, 1 some
mismatch or read failure, 3 no reader installed.
"""
import json
import os
import shutil
import subprocess
import sys
import warnings

warnings.filterwarnings("ignore")

TOL = 1e-12

# MED type name -> medcoupling name, meshio name, mdump name
TYPES = {
    "PO1": ("NORM_POINT1", "vertex", "MED_POINT1"),
    "SE2": ("NORM_SEG2", "line", "MED_SEG2"),
    "SE3": ("NORM_SEG3", "line3", "MED_SEG3"),
    "TR3": ("NORM_TRI3", "triangle", "MED_TRIA3"),
    "TR6": ("NORM_TRI6", "triangle6", "MED_TRIA6"),
    "QU4": ("NORM_QUAD4", "quad", "MED_QUAD4"),
    "QU8": ("NORM_QUAD8", "quad8", "MED_QUAD8"),
    "TE4": ("NORM_TETRA4", "tetra", "MED_TETRA4"),
    "T10": ("NORM_TETRA10", "tetra10", "MED_TETRA10"),
    "PE6": ("NORM_PENTA6", "wedge", "MED_PENTA6"),
    "P15": ("NORM_PENTA15", "wedge15", "MED_PENTA15"),
    "HE8": ("NORM_HEXA8", "hexahedron", "MED_HEXA8"),
    "H20": ("NORM_HEXA20", "hexahedron20", "MED_HEXA20"),
}


class Checker:
    def __init__(self, reader, path):
        self.reader, self.path, self.errors = reader, path, []

    def eq(self, what, got, want):
        if got != want:
            self.errors.append(f"{what}: got {got!r}, expected {want!r}")

    def close(self, what, got, want):
        got, want = [float(x) for x in got], [float(x) for x in want]
        if len(got) != len(want):
            self.errors.append(f"{what}: {len(got)} values, expected {len(want)}")
            return
        worst = max((abs(a - b) for a, b in zip(got, want)), default=0.0)
        scale = max((abs(b) for b in want), default=0.0)
        if worst > TOL * max(1.0, scale):
            self.errors.append(f"{what}: values differ by up to {worst:g}")

    def true(self, what, cond):
        if not cond:
            self.errors.append(what)


def type_ranks(spec):
    """aster cell index -> (MED type, rank among cells of that type)."""
    seen, out = {}, []
    for t in spec["cell_types"]:
        out.append((t, seen.get(t, 0)))
        seen[t] = seen.get(t, 0) + 1
    return out


def cells_of_type(spec, t):
    return [c for c, ct in zip(spec["cells"], spec["cell_types"]) if ct == t]


# ------------------------------------------------------------------ medcoupling
def check_medcoupling(spec, ck):
    import medcoupling as mc

    path, name = spec["path"], spec["mesh"]
    mm = mc.MEDFileMesh.New(path, name)
    ck.eq("mesh name", mm.getName(), name)
    ck.eq("space dimension", mm.getSpaceDimension(), spec["dim"])
    ck.eq("node count", mm.getNumberOfNodes(), len(spec["coords"]))
    ck.close("coordinates", mm.getCoords().toNumPyArray().ravel(), [x for p in spec["coords"] for x in p])
    mdim = mm.getMeshDimension()
    ck.eq("mesh dimension", mdim, spec["mesh_dim"])
    ranks = type_ranks(spec)
    # per level: cell types, connectivity (MED order) and, for 3D, volumes > 0
    level_cells = {}  # level -> [(type, rank)] in medcoupling's local numbering
    total = 0
    for lev in mm.getNonEmptyLevels():
        m = mm.getMeshAtLevel(lev)
        local, count = [], {}
        for i in range(m.getNumberOfCells()):
            norm = mc.MEDCouplingUMesh.GetReprOfGeometricType(m.getTypeOfCell(i))
            t = next((k for k, v in TYPES.items() if v[0] == norm), norm)
            r = count.get(t, 0)
            count[t] = r + 1
            local.append((t, r))
            ours = cells_of_type(spec, t)
            if r < len(ours):
                ck.eq(f"level {lev} cell {i} ({t}) nodes", list(m.getNodeIdsOfCell(i)), ours[r])
            else:
                ck.errors.append(f"level {lev}: extra {t} cell")
        for t, n in count.items():
            ck.eq(f"number of {t}", n, len(cells_of_type(spec, t)))
        total += m.getNumberOfCells()
        level_cells[lev] = local
        if mdim + lev == 3:
            vols = m.getMeasureField(False).getArray().toNumPyArray()
            ck.true(f"3D cells with non-positive MED volume: {vols.tolist()}", bool((vols > 0).all()))
    ck.eq("cell count", total, len(spec["cells"]))
    # groups, members compared as (type, rank in type)
    names = set(mm.getGroupsNames())
    ck.eq("group names", sorted(names), sorted(set(spec["cell_groups"]) | set(spec["node_groups"])))
    for g, members in spec["cell_groups"].items():
        got = set()
        for lev in mm.getGrpNonEmptyLevels(g) if g in names else []:
            got |= {level_cells[lev][i] for i in mm.getGroupArr(lev, g).getValues()}
        ck.eq(f"cell group {g}", sorted(got), sorted(ranks[c] for c in members))
    for g, members in spec["node_groups"].items():
        got = []
        if g in names and 1 in mm.getGrpNonEmptyLevelsExt(g):
            got = sorted(mm.getGroupArr(1, g).getValues())
        ck.eq(f"node group {g}", got, sorted(members))
    # fields
    present = set(mc.GetAllFieldNames(path)) if spec["nodal_fields"] or spec["cell_fields"] else set()
    ck.eq("field names", sorted(present), sorted(f["name"] for f in spec["nodal_fields"] + spec["cell_fields"]))
    for f in spec["nodal_fields"]:
        fm = mc.MEDFileFieldMultiTS(path, f["name"])
        ck.eq(f"{f['name']} steps", [tuple(fm.getTimeStepAtPos(i).getTime()[:2]) for i in range(len(fm))],
              [(s["numdt"], -1) for s in f["steps"]])
        for s in f["steps"]:
            fld = mc.ReadFieldNode(path, name, 0, f["name"], s["numdt"], -1)
            arr = fld.getArray()
            ck.eq(f"{f['name']} components", list(arr.getInfoOnComponents()), f["components"])
            ck.close(f"{f['name']} time of step {s['numdt']}", [fld.getTime()[0]], [s["time"]])
            ck.close(f"{f['name']} values of step {s['numdt']}", arr.toNumPyArray().ravel(), s["values"])
    for f in spec["cell_fields"]:
        nco = len(f["components"])
        for s in f["steps"]:
            for lev, local in level_cells.items():
                fld = mc.ReadFieldCell(path, name, lev, f["name"], s["numdt"], -1)
                got = fld.getArray().toNumPyArray().reshape(-1, nco)
                index = {tr: c for c, tr in enumerate(ranks)}
                want = [s["values"][index[tr] * nco + k] for tr in local for k in range(nco)]
                ck.close(f"{f['name']} step {s['numdt']} level {lev}", got.ravel(), want)


# ------------------------------------------------------------------ meshio
def check_meshio(spec, ck):
    import meshio
    import meshio._mesh

    # meshio 5.3.5 maps P15 to 'wedge15' but lacks it in its own table (KeyError)
    meshio._mesh.topological_dimension.setdefault("wedge15", 3)
    m = meshio.read(spec["path"], file_format="med")
    dim = spec["dim"]
    ck.close("coordinates", m.points[:, :dim].ravel(), [x for p in spec["coords"] for x in p])
    meshio_to_med = {v[1]: k for k, v in TYPES.items()}
    ranks = type_ranks(spec)
    cell_fam = m.cell_data.get("cell_tags", [None] * len(m.cells))
    got_cell_groups = {}
    for block, fams in zip(m.cells, cell_fam):
        t = meshio_to_med.get(block.type, block.type)
        ck.eq(f"{t} connectivity", block.data.tolist(), cells_of_type(spec, t))
        if fams is None:
            continue
        for r, fam in enumerate(fams):
            for g in m.cell_tags.get(int(fam), []):
                got_cell_groups.setdefault(g, set()).add((t, r))
    ck.eq("cell types", sorted(meshio_to_med.get(b.type, b.type) for b in m.cells), sorted(set(spec["cell_types"])))
    for g, members in spec["cell_groups"].items():
        ck.eq(f"cell group {g}", sorted(got_cell_groups.get(g, set())), sorted(ranks[c] for c in members))
    got_node_groups = {}
    for i, fam in enumerate(m.point_data.get("point_tags", [])):
        for g in m.point_tags.get(int(fam), []):
            got_node_groups.setdefault(g, []).append(i)
    for g, members in spec["node_groups"].items():
        ck.eq(f"node group {g}", got_node_groups.get(g, []), sorted(members))
    for f in spec["nodal_fields"]:
        keys = [k for k in m.point_data if k == f["name"] or k.startswith(f["name"] + "[")]
        ck.eq(f"{f['name']} step count", len(keys), len(f["steps"]))
        for i, s in enumerate(f["steps"]):
            key = f["name"] if len(f["steps"]) == 1 else f"{f['name']}[{i}] - {s['time']:g}"
            if key not in m.point_data:
                ck.errors.append(f"{f['name']}: no point data '{key}' (have {sorted(m.point_data)})")
                continue
            ck.close(f"{key} values", m.point_data[key].ravel(), s["values"])


# ------------------------------------------------------------------ mdump
def check_mdump(spec, ck):
    r = subprocess.run(["mdump", spec["path"], "NODALE", "FULL_INTERLACE", "0"], capture_output=True,
                       text=True, errors="replace", timeout=120)
    txt = r.stdout + r.stderr
    ck.eq("mdump exit status", r.returncode, 0)
    ck.true("mdump printed ERREUR", "ERREUR" not in txt)
    ck.true(f"mdump: mesh name <<{spec['mesh']}>> not listed", f"<<{spec['mesh']}>>" in txt)
    ck.true(f"mdump: node count {len(spec['coords'])} not listed",
            f"Nombre de noeuds : {len(spec['coords'])} " in txt)
    for t in sorted(set(spec["cell_types"])):
        n = spec["cell_types"].count(t)
        ck.true(f"mdump: {n} cells of {TYPES[t][2]} not listed",
                f"Nombre de mailles de type {TYPES[t][2]} : {n} " in txt)
    nsteps = sum(len(f["steps"]) for f in spec["nodal_fields"])
    ck.true(f"mdump: fewer field steps than {nsteps}", txt.count("(* CHAMP |") >= nsteps)


def available():
    out = []
    for mod in ("medcoupling", "meshio"):
        try:
            __import__(mod)
            out.append(mod)
        except ImportError:
            pass
    if shutil.which("mdump"):
        out.append("mdump")
    return out


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    spec_all = json.load(open(argv[0]))
    readers = available()
    if "--only" in argv:
        readers = [r for r in readers if r == argv[argv.index("--only") + 1]]
    if not readers:
        print("skipped: none of medcoupling, meshio, mdump is installed")
        return 3
    fns = {"medcoupling": check_medcoupling, "meshio": check_meshio, "mdump": check_mdump}
    bad = 0
    for spec in spec_all["files"]:
        for reader in readers:
            ck = Checker(reader, spec["path"])
            try:
                fns[reader](spec, ck)
            except Exception as e:  # noqa: BLE001 - report any reader failure as a mismatch
                ck.errors.append(f"{type(e).__name__}: {e}")
            status = "OK  " if not ck.errors else "FAIL"
            print(f"{status} {reader:11s} {os.path.basename(spec['path'])}")
            for err in ck.errors[:20]:
                print(f"       {err}")
            bad += bool(ck.errors)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
