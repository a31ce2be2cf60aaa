#!/usr/bin/env python3
"""Converged continuum references for the trainer's tool loads (issue 37), made with CalculiX.

Two load cases, both on the trainer's own surfaces (the geometry is kept exactly: the surface is
only split, never moved, so every trainer vertex is a node of the reference):

  liver-hook      data/anatomy/liver.vtk; the hook's tip: the liver vertex of the gallbladder bed
                  nearest the bed's centroid and its one-ring (the footprint is the union of the
                  triangles around it) pushed 5 mm into the surface (along the vertex normal, all
                  three components prescribed, as the capacitance solver does); the bare area
                  (vesica_label 1) fixed. E = 170 kPa, nu = 0.4 (gallbladder paper Table 1).
  gallbladder-grasp
                  data/anatomy/gallbladder_1000_surface.vtk; the grasper's jaw: a 10 x 5 mm
                  footprint (long side along the gallbladder's axis) on the side facing away from
                  the liver, pulled 5 mm out along its normal; the bed (surface within 6 mm of a
                  liver vertex) fixed. E = 2.3 kPa, nu = 0.45. The footprint is the exact
                  rectangle at every level: the surface is cut along its four sides first.
  gallbladder-press
                  the same jaw pressed 5 mm in along its normal, frictionless: the normal
                  component prescribed, the tangential ones free (closed jaws pushing the wall).

Each case is meshed with quadratic tets (gmsh, C3D10) graded toward the contact: the surface is
split 1:4 (red-green, conforming) in shrinking rings around the contact, the volume grows from it.
It is solved by ccx (linear statics) at rising refinement until the total contact force moves by
under 1 %; the last level is written to tests/bem/data or tests/fem/data:

  force_N fx fy fz            total reaction on the footprint (N), what the tool feels
  contact i j k ...           the trainer vertices in the footprint
  u i ux uy uz                displacement (m) of every trainer vertex
  centre_m, jaw_long_axis     (grasp only) the jaw's centre and its long side

Usage (slow: minutes to an hour; one thread, niced):
  python3 tools/convergence/reference.py [--case liver-hook|gallbladder-grasp|gallbladder-press|all] [--keep DIR]
With --keep DIR, a level whose ccx results are already in DIR is read back, not solved again, so
an interrupted run resumes where it stopped (a level meshed but not solved keeps its mesh); with
--mesh-from DIR2 as well, the press takes the grasp's finished meshes from DIR2 (or vice versa).
"""

import argparse
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
LABEL_FIXED = 1
LABEL_BED = 2
INDENT_M = 0.005
BED_DISTANCE_M = 0.006
JAW_LENGTH_M = 0.010
JAW_WIDTH_M = 0.005
JAW_SNAP_M = 0.0001
# ccx's equation solver: "SPOOLES" (direct; level 2 of the gallbladder, 132k dofs, took 36 min on
# one thread) or "ITERATIVE CHOLESKY" (PCG with an incomplete Cholesky preconditioner: 21 s there,
# |F| within 0.006 % and the force vector within 0.19 % of SPOOLES's). Set by --solver.
SOLVER = "SPOOLES"


# ---------------------------------------------------------------------------------------------
# Reading the trainer's legacy VTK polydata (ASCII, 5.1 OFFSETS/CONNECTIVITY or the older form).
def read_vtk_surface(path):
    toks = pathlib.Path(path).read_text().split()
    i = toks.index("POINTS")
    n = int(toks[i + 1])
    pts = [tuple(float(t) for t in toks[i + 3 + 3 * k:i + 6 + 3 * k]) for k in range(n)]
    p = toks.index("POLYGONS")
    if "CONNECTIVITY" in toks:
        j = toks.index("CONNECTIVITY")
        m = int(toks[p + 2])
        conn = [int(t) for t in toks[j + 2:j + 2 + m]]
        tris = [tuple(conn[3 * k:3 * k + 3]) for k in range(m // 3)]
    else:
        count = int(toks[p + 1])
        tris = [tuple(int(t) for t in toks[p + 4 + 4 * k:p + 7 + 4 * k]) for k in range(count)]
    labels = [0] * n
    if "vesica_label" in toks:
        k = toks.index("vesica_label")
        labels = [int(t) for t in toks[k + 4:k + 4 + n]]
    return pts, tris, labels


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def vertex_normal(pts, tris, v):
    n = (0.0, 0.0, 0.0)
    for t in tris:
        if v in t:
            c = cross(sub(pts[t[1]], pts[t[0]]), sub(pts[t[2]], pts[t[0]]))  # 2 x area x normal
            n = (n[0] + c[0], n[1] + c[1], n[2] + c[2])
    return unit(n)


# ---------------------------------------------------------------------------------------------
# Graded conforming refinement: triangles for which near(corners) holds are split 1:4 (red); a
# neighbour left with one split edge is halved (green), with two or three it is split red too.
# Each triangle carries a set of flags that its children inherit. (physics/bem/
# graded_surface_refinement.cpp is the same pass, with near = a corner within a radius.)
def refine(pts, tris, flags, near):
    red = [near([pts[v] for v in t]) for t in tris]
    while True:
        split = set()
        for t, r in zip(tris, red):
            if r:
                for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                    split.add((min(a, b), max(a, b)))
        changed = False
        for k, t in enumerate(tris):
            if red[k]:
                continue
            cut = sum((min(a, b), max(a, b)) in split for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
            if cut >= 2:
                red[k] = changed = True
        if not changed:
            break
    pts = list(pts)
    mid = {}
    for a, b in sorted(split):
        mid[(a, b)] = len(pts)
        pts.append(tuple(0.5 * (pts[a][c] + pts[b][c]) for c in range(3)))

    def m(a, b):
        return mid.get((min(a, b), max(a, b)))

    out_t, out_f = [], []
    for t, f, r in zip(tris, flags, red):
        a, b, c = t
        if r:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            children = [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        else:
            children = [t]
            for (p, q, o) in ((a, b, c), (b, c, a), (c, a, b)):
                x = m(p, q)
                if x is not None:
                    children = [(p, x, o), (x, q, o)]
        out_t += children
        out_f += [f] * len(children)
    return pts, out_t, out_f


# Cutting a surface along a plane's trace, conformingly: every edge whose ends lie strictly on
# opposite sides of f = 0 (f linear in position) and both in the patch is split at f = 0 (a point
# on the edge, so the geometry is kept), and each triangle is split along its cut edges. Corners
# within `snap` of the line count as on it (no sliver next to them; the trace then bends through
# that corner by at most `snap`).
def cut_along(pts, tris, flags, f, in_patch, snap):
    value = [f(p) for p in pts]
    side = [0 if abs(v) <= snap else (1 if v > 0 else -1) for v in value]
    patch = [in_patch(p) for p in pts]
    pts = list(pts)
    mid = {}

    def cut(a, b):
        e = (min(a, b), max(a, b))
        if not (patch[a] and patch[b] and side[a] * side[b] < 0):
            return None
        if e not in mid:
            s = value[e[0]] / (value[e[0]] - value[e[1]])
            mid[e] = len(pts)
            pts.append(tuple(pts[e[0]][k] + s * (pts[e[1]][k] - pts[e[0]][k]) for k in range(3)))
        return mid[e]

    out_t, out_f = [], []
    for t, fl in zip(tris, flags):
        a, b, c = t
        x = [cut(a, b), cut(b, c), cut(c, a)]
        n_cut = sum(v is not None for v in x)
        if n_cut == 0:
            children = [t]
        elif n_cut == 1:  # through the opposite corner (on the line, or the patch's border)
            k = next(i for i in range(3) if x[i] is not None)
            p, q, o = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
            children = [(p, x[k], o), (x[k], q, o)]
        else:  # two cut edges: the corner between them alone on its side
            k = next(i for i in range(3) if x[i] is None)  # the uncut edge t[k] - t[k+1]
            p, q, o = t[k], t[(k + 1) % 3], t[(k + 2) % 3]
            xq, xo = x[(k + 1) % 3], x[(k + 2) % 3]  # on q-o and o-p
            children = [(xo, xq, o), (p, q, xq), (p, xq, xo)]
        out_t += children
        out_f += [fl] * len(children)
    return pts, out_t, out_f


def segment_distance(p, a, b):
    ab, ap = sub(b, a), sub(p, a)
    s = max(0.0, min(1.0, dot(ap, ab) / dot(ab, ab)))
    return math.dist(p, tuple(a[k] + s * ab[k] for k in range(3)))


# ---------------------------------------------------------------------------------------------
# gmsh: quadratic tets from the refined surface (kept as is), sizes growing away from the contact.
def mesh_volume(work, pts, tris, centre, size_near, size_far, reach, hxt=False):
    """hxt: gmsh's HXT tetrahedraliser instead of the default Delaunay, which gives up ("a deleted
    triangle is a neighbor of a non deleted triangle") on the gallbladder's level 3, whose surface
    has the thin triangles that the cuts along the jaw's sides leave."""
    stl = work / "surface.stl"
    with open(stl, "w") as f:
        f.write("solid s\n")
        for t in tris:
            n = unit(cross(sub(pts[t[1]], pts[t[0]]), sub(pts[t[2]], pts[t[0]])))
            f.write(f"facet normal {n[0]:.9e} {n[1]:.9e} {n[2]:.9e}\nouter loop\n")
            for v in t:
                f.write(f"vertex {pts[v][0]:.12e} {pts[v][1]:.12e} {pts[v][2]:.12e}\n")
            f.write("endloop\nendfacet\n")
        f.write("endsolid s\n")
    geo = work / "volume.geo"
    algorithm = "\nMesh.Algorithm3D = 10;" if hxt else ""
    geo.write_text(f"""Merge "surface.stl";
Surface Loop(1) = {{1}};
Volume(1) = {{1}};
Physical Volume(1) = {{1}};
Point(100000) = {{{centre[0]:.12e}, {centre[1]:.12e}, {centre[2]:.12e}}};
Field[1] = Distance; Field[1].PointsList = {{100000}};
Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = {size_near:.6e}; Field[2].SizeMax = {size_far:.6e};
Field[2].DistMin = {size_near:.6e}; Field[2].DistMax = {reach:.6e};
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderLinear = 1;
Mesh.Optimize = 1;{algorithm}
Mesh.MshFileVersion = 2.2;
General.NumThreads = 1;
""")
    run(["gmsh", "-3", "-nt", "1", "-format", "msh22", "-o", "volume.msh", "volume.geo"], work)
    return read_msh(work / "volume.msh")


def read_msh(path):
    nodes, tets = {}, []
    lines = path.read_text().split("\n")
    i = lines.index("$Nodes")
    for line in lines[i + 2:i + 2 + int(lines[i + 1])]:
        w = line.split()
        nodes[int(w[0])] = (float(w[1]), float(w[2]), float(w[3]))
    i = lines.index("$Elements")
    for line in lines[i + 2:i + 2 + int(lines[i + 1])]:
        w = [int(x) for x in line.split()]
        if w[1] == 11:  # 10-node tet; gmsh's last two edge nodes are ccx's swapped
            c = w[3 + w[2]:]
            tets.append(c[:8] + [c[9], c[8]])
    return nodes, tets


def run(cmd, cwd):
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    r = subprocess.run(["nice", "-n", "10"] + cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed in {cwd}:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r.stdout


def key(p):
    return (round(p[0] * 1e7), round(p[1] * 1e7), round(p[2] * 1e7))


class NodeIndex:
    """gmsh node ids by position (0.1 um cells, neighbours searched: no rounding-edge misses)."""

    def __init__(self, nodes):
        self.cells = {}
        for i, p in nodes.items():
            self.cells.setdefault(key(p), []).append((i, p))

    def __getitem__(self, p):
        k = key(p)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i, q in self.cells.get((k[0] + dx, k[1] + dy, k[2] + dz), []):
                        if math.dist(p, q) < 1e-7:
                            return i
        raise KeyError(f"no mesh node at {p}: gmsh changed the surface mesh")


def region_nodes(pts, tris, flags, flag, index):
    """gmsh nodes (corners and edge midpoints) on the triangles carrying `flag`."""
    out = set()
    for t, f in zip(tris, flags):
        if flag in f:
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                out.add(index[pts[a]])
                out.add(index[tuple(0.5 * (pts[a][c] + pts[b][c]) for c in range(3))])
    return out


def solve_ccx(work, nodes, tets, fixed, contact, displacement, youngs_Pa, poisson, trainer_nodes, normal_only=None):
    """normal_only: a unit vector; then the contact nodes move only along it (a frictionless press:
    a local system whose x is the normal, x prescribed, y and z free)."""
    with open(work / "job.inp", "w") as f:
        f.write("*NODE\n")
        for i, p in nodes.items():
            f.write(f"{i},{p[0]:.12e},{p[1]:.12e},{p[2]:.12e}\n")
        f.write("*ELEMENT, TYPE=C3D10, ELSET=EALL\n")
        for k, t in enumerate(tets, 1):
            f.write(f"{k}," + ",".join(map(str, t)) + "\n")

        def nset(name, ids):
            f.write(f"*NSET, NSET={name}\n")
            ids = sorted(ids)
            for s in range(0, len(ids), 12):
                f.write(",".join(map(str, ids[s:s + 12])) + ",\n")

        nset("NFIXED", fixed)
        nset("NCONTACT", contact)
        nset("NTRAINER", trainer_nodes)
        f.write(f"*MATERIAL, NAME=TISSUE\n*ELASTIC\n{youngs_Pa},{poisson}\n")
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=TISSUE\n")
        if normal_only is not None:
            n = normal_only
            t = unit(cross(n, (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)))
            f.write(f"*TRANSFORM, NSET=NCONTACT, TYPE=R\n{n[0]:.12e},{n[1]:.12e},{n[2]:.12e},{t[0]:.12e},{t[1]:.12e},{t[2]:.12e}\n")
        f.write("*STEP\n*STATIC" + ("" if SOLVER == "SPOOLES" else f", SOLVER={SOLVER}") + "\n*BOUNDARY\nNFIXED,1,3,0.\n")
        if normal_only is not None:
            f.write(f"NCONTACT,1,1,{dot(displacement, normal_only):.12e}\n")
        else:
            for c in range(3):
                f.write(f"NCONTACT,{c + 1},{c + 1},{displacement[c]:.12e}\n")
        f.write("*NODE PRINT, NSET=NCONTACT, TOTALS=ONLY, GLOBAL=YES\nRF\n"
                "*NODE PRINT, NSET=NTRAINER, GLOBAL=YES\nU\n*END STEP\n")
    run(["ccx", "-i", "job"], work)
    results = read_ccx_results(work)
    if results is None:
        sys.exit(f"could not read the force and displacements from {work / 'job.dat'}")
    return results


def read_ccx_results(work):
    """(total force on NCONTACT, {node: displacement} of NTRAINER) from job.dat, or None."""
    if not (work / "job.dat").exists():
        return None
    lines = (work / "job.dat").read_text().split("\n")
    force, u = None, {}
    for i, line in enumerate(lines):
        if line.strip().startswith("total force") and "NCONTACT" in line:
            force = tuple(float(x) for x in lines[i + 2].split())
        if line.strip().startswith("displacements") and "NTRAINER" in line:
            for row in lines[i + 2:]:
                w = row.split()
                if len(w) != 4:
                    break
                u[int(w[0])] = tuple(float(x) for x in w[1:])
    if force is None or not u:
        return None
    return force, u


# ---------------------------------------------------------------------------------------------
def liver_case():
    pts, tris, labels = read_vtk_surface(ROOT / "data/anatomy/liver.vtk")
    bed = [v for v in range(len(pts)) if labels[v] & LABEL_BED]
    centroid = tuple(sum(pts[v][c] for v in bed) / len(bed) for c in range(3))
    ring_ok = lambda v: all(not (labels[w] & LABEL_FIXED) for t in tris if v in t for w in t)
    tip = min((v for v in bed if ring_ok(v)), key=lambda v: math.dist(pts[v], centroid))
    normal = vertex_normal(pts, tris, tip)
    flags = []
    for t in tris:
        f = set()
        if tip in t:
            f.add("contact")
        if all(labels[v] & LABEL_FIXED for v in t):
            f.add("fixed")
        flags.append(f)
    fixed_vertices = [v for v in range(len(pts)) if labels[v] & LABEL_FIXED]
    contact_vertices = sorted({v for t in tris if tip in t for v in t})
    edge = max(math.dist(pts[tip], pts[v]) for v in contact_vertices)
    rim = [tuple(v for v in t if v != tip) for t in tris if tip in t]
    rim = [(pts[a], pts[b]) for a, b in rim]
    return dict(name="liver-hook", source="data/anatomy/liver.vtk", pts=pts, tris=tris, flags=flags,
                fixed_vertices=fixed_vertices, contact_vertices=contact_vertices, centre=pts[tip],
                displacement=tuple(-INDENT_M * c for c in normal), youngs_Pa=170e3, poisson=0.4,
                footprint_m=edge, edge_distance=lambda q: min(segment_distance(q, a, b) for a, b in rim),
                out=ROOT / "tests/bem/data/liver_hook_reference.txt",
                note=f"hook tip at liver vertex {tip} and its one-ring, {INDENT_M * 1e3:g} mm into the surface")


def gallbladder_case(press=False):
    pts, tris, _ = read_vtk_surface(ROOT / "data/anatomy/gallbladder_1000_surface.vtk")
    n_trainer = len(pts)
    lpts, _, _ = read_vtk_surface(ROOT / "data/anatomy/liver.vtk")
    near_liver = [min(math.dist(p, q) for q in lpts) < BED_DISTANCE_M for p in pts]
    # Axis: the principal direction of the surface points (power iteration on the covariance).
    centroid = tuple(sum(p[c] for p in pts) / len(pts) for c in range(3))
    cov = [[sum((p[a] - centroid[a]) * (p[b] - centroid[b]) for p in pts) for b in range(3)] for a in range(3)]
    axis = (1.0, 0.3, 0.2)
    for _ in range(200):
        axis = unit(tuple(dot(cov[a], axis) for a in range(3)))
    liver_centroid = tuple(sum(p[c] for p in lpts if True) / len(lpts) for c in range(3))
    bed_points = [p for p, n in zip(pts, near_liver) if n]
    bed_centroid = tuple(sum(p[c] for p in bed_points) / len(bed_points) for c in range(3))
    away = unit(sub(centroid, bed_centroid))
    # The jaw's centre: the surface vertex farthest from the bed across the axis (mid-body).
    grasp = max(range(len(pts)), key=lambda v: dot(sub(pts[v], centroid), away) - abs(dot(sub(pts[v], centroid), axis)))
    normal = vertex_normal(pts, tris, grasp)
    along = unit(sub(axis, tuple(dot(axis, normal) * c for c in normal)))
    across = cross(normal, along)
    del liver_centroid

    def edge_distance(p):
        d = sub(p, pts[grasp])
        x, y = abs(dot(d, along)) - 0.5 * JAW_LENGTH_M, abs(dot(d, across)) - 0.5 * JAW_WIDTH_M
        return math.hypot(max(x, 0.0), max(y, 0.0)) if x > 0 or y > 0 else -max(x, y)

    def in_jaw(p):
        d = sub(p, pts[grasp])
        return abs(dot(d, along)) <= 0.5 * JAW_LENGTH_M and abs(dot(d, across)) <= 0.5 * JAW_WIDTH_M and dot(d, normal) > -0.004

    # The jaw's footprint is the exact rectangle, the same at every level: the surface is cut along
    # its four sides once (level 0), the triangles inside carry "contact" and their children inherit
    # it, so refinement only resolves the footprint, never redraws it.
    centre = pts[grasp]
    patch = lambda p: (abs(dot(sub(p, centre), along)) < 0.5 * JAW_LENGTH_M + 0.010 and
                       abs(dot(sub(p, centre), across)) < 0.5 * JAW_WIDTH_M + 0.010 and dot(sub(p, centre), normal) > -0.010)
    flags = [set() for _ in tris]
    for axis, half in ((along, JAW_LENGTH_M), (along, -JAW_LENGTH_M), (across, JAW_WIDTH_M), (across, -JAW_WIDTH_M)):
        line = lambda p, axis=axis, half=half: dot(sub(p, centre), axis) - 0.5 * half
        pts, tris, flags = cut_along(pts, tris, flags, line, patch, JAW_SNAP_M)
    near_liver += [min(math.dist(p, q) for q in lpts) < BED_DISTANCE_M for p in pts[n_trainer:]]
    flags = [{"fixed"} if all(near_liver[v] for v in t) else set() for t in tris]
    for t, f in zip(tris, flags):
        if in_jaw(tuple(sum(pts[v][c] for v in t) / 3 for c in range(3))):
            f.add("contact")
    fixed_vertices = [v for v in range(n_trainer) if near_liver[v]]
    contact_vertices = [v for v in range(n_trainer) if in_jaw(pts[v])]
    sign = -1.0 if press else 1.0
    name = "gallbladder-press" if press else "gallbladder-grasp"
    load = ("pressed 5 mm in along its normal, frictionless (the normal component prescribed, the tangential free)"
            if press else f"pulled {INDENT_M * 1e3:g} mm along its normal (all components prescribed)")
    return dict(name=name, source="data/anatomy/gallbladder_1000_surface.vtk", pts=pts, tris=tris, n_trainer=n_trainer,
                flags=flags, fixed_vertices=fixed_vertices, contact_vertices=contact_vertices, centre=centre,
                displacement=tuple(sign * INDENT_M * c for c in normal), normal_only=normal if press else None,
                youngs_Pa=2.3e3, poisson=0.45, exact_footprint=True, edge_distance=edge_distance,
                footprint_m=JAW_WIDTH_M, extra={"centre_m": centre, "jaw_long_axis": along},
                out=ROOT / f"tests/fem/data/gallbladder_{'press' if press else 'grasp'}_reference.txt",
                note=(f"jaw {JAW_LENGTH_M * 1e3:g} x {JAW_WIDTH_M * 1e3:g} mm centred at vertex {grasp}, long side "
                      f"({along[0]:.6f} {along[1]:.6f} {along[2]:.6f}), {load}; the surface cut along the jaw's "
                      f"sides (corners within {JAW_SNAP_M * 1e3:g} mm of a side count as on it); "
                      f"bed: surface within {BED_DISTANCE_M * 1e3:g} mm of a liver vertex"))


def solve_level(case, level, work):
    """Level L: L passes of 1:4 splitting, each of the triangles within a band around the
    footprint's edge (where the traction is singular) that halves each pass (2, 1, 1/2 ...
    footprints, plus half the triangle's own size so that a large triangle across the edge is
    caught); tets grade from the finest surface size at the contact to 12 mm."""
    pts, tris, flags = case["pts"], case["tris"], case["flags"]
    n_trainer = case.get("n_trainer", len(pts))
    band = 2.0 * case["footprint_m"]
    for _ in range(level):
        def near(corners, band=band):
            size = max(math.dist(corners[a], corners[b]) for a, b in ((0, 1), (1, 2), (2, 0)))
            samples = corners + [tuple(sum(c[k] for c in corners) / 3 for k in range(3))]
            return min(case["edge_distance"](q) for q in samples) < band + 0.5 * size
        pts, tris, flags = refine(pts, tris, flags, near)
        band *= 0.5
    kept = read_ccx_results(work) if (work / "volume.msh").exists() else None
    if kept is not None:  # a finished level of an earlier run with the same --keep: resume from it
        nodes, tets = read_msh(work / "volume.msh")
        trainer_nodes = [NodeIndex(nodes)[pts[v]] for v in range(n_trainer)]
        return kept[0], [kept[1][i] for i in trainer_nodes], len(nodes), len(tets)
    # The volume's size at the contact: the footprint's mean edge (not its shortest: the cuts along
    # the jaw's sides leave a few short edges that would make the whole volume needlessly fine).
    contact_edges = [math.dist(pts[t[k]], pts[t[(k + 1) % 3]]) for t, f in zip(tris, flags) if "contact" in f
                     for k in range(3)]
    size_near = (sum(contact_edges) / len(contact_edges) if case.get("exact_footprint")
                 else min(math.dist(pts[t[0]], pts[t[1]]) for t, f in zip(tris, flags) if "contact" in f))
    if (work / "volume.msh").exists():  # meshed already (--mesh-from, or a run stopped in ccx)
        nodes, tets = read_msh(work / "volume.msh")
    else:
        nodes, tets = mesh_volume(work, pts, tris, case["centre"], size_near, 0.012, 0.06,
                                  hxt=case.get("exact_footprint", False))
    index = NodeIndex(nodes)
    fixed = region_nodes(pts, tris, flags, "fixed", index) | {index[pts[v]] for v in case["fixed_vertices"]}
    contact = region_nodes(pts, tris, flags, "contact", index)
    if "exact_footprint" not in case:
        contact |= {index[pts[v]] for v in case["contact_vertices"]}
    trainer_nodes = [index[pts[v]] for v in range(n_trainer)]
    force, u = solve_ccx(work, nodes, tets, fixed, contact, case["displacement"], case["youngs_Pa"],
                         case["poisson"], trainer_nodes, case.get("normal_only"))
    return force, [u[i] for i in trainer_nodes], len(nodes), len(tets)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", default="all", choices=["all", "liver-hook", "gallbladder-grasp", "gallbladder-press"])
    parser.add_argument("--keep", help="keep the meshes and ccx files under this folder")
    parser.add_argument("--max-level", type=int, default=6)
    parser.add_argument("--mesh-from", help="with --keep: take each level's volume.msh from this --keep folder of the "
                        "other gallbladder case (the grasp and the press share their meshes)")
    parser.add_argument("--start-level", type=int, default=0, help="first level to solve (to resume a long run)")
    parser.add_argument("--write-unconverged", action="store_true",
                        help="write the last level even when the force still moved by 1 %% or more (marked in the file)")
    parser.add_argument("--solver", default="spooles", choices=["spooles", "iterative"],
                        help="ccx's equation solver: spooles (direct) or iterative (PCG, incomplete Cholesky; "
                        "minutes instead of hours from about 100k nodes)")
    args = parser.parse_args()
    global SOLVER
    SOLVER = "SPOOLES" if args.solver == "spooles" else "ITERATIVE CHOLESKY"
    for tool in ("gmsh", "ccx"):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found: apt-get install calculix-ccx gmsh (tools/convergence/deps.txt)")
    cases = {"liver-hook": liver_case, "gallbladder-grasp": gallbladder_case,
             "gallbladder-press": lambda: gallbladder_case(press=True)}
    cases = list(cases.values()) if args.case == "all" else [cases[args.case]]
    for make in cases:
        case = make()
        history, previous = [], None
        for level in range(args.start_level, args.max_level + 1):
            work = pathlib.Path(args.keep) / f"{case['name']}-{level}" if args.keep else pathlib.Path(tempfile.mkdtemp())
            work.mkdir(parents=True, exist_ok=True)
            if args.mesh_from and args.keep and not (work / "volume.msh").exists():
                other = "gallbladder-press" if case["name"] == "gallbladder-grasp" else "gallbladder-grasp"
                source = pathlib.Path(args.mesh_from) / f"{other}-{level}" / "volume.msh"
                if source.exists() and (source.parent / "job.dat").exists():  # a finished level's mesh
                    shutil.copy(source, work / "volume.msh")
            force, u, n_nodes, n_tets = solve_level(case, level, work)
            magnitude = math.sqrt(dot(force, force))
            change = abs(magnitude - previous) / magnitude if previous else float("nan")
            history.append((level, n_nodes, n_tets, magnitude, change))
            print(f"{case['name']} level {level}: {n_nodes} nodes, {n_tets} C3D10, |F| = {magnitude:.6g} N, "
                  f"change {100 * change:.2f} %", flush=True)
            if not args.keep:
                shutil.rmtree(work)
            if previous and change < 0.01:
                break
            previous = magnitude
        else:
            if not args.write_unconverged:
                sys.exit(f"{case['name']}: not converged to 1 % by level {args.max_level}")
            print(f"{case['name']}: NOT converged to 1 % by level {args.max_level}; writing the last level, marked")
        case["out"].parent.mkdir(parents=True, exist_ok=True)
        with open(case["out"], "w") as f:
            f.write(f"# CalculiX reference for issue 37 ({case['name']}): {case['note']}.\n")
            f.write(f"# Made by: python3 tools/convergence/reference.py --case {case['name']} --solver {args.solver}\n")
            f.write(f"# Surface: {case['source']} (its vertex order); CalculiX {ccx_version()} C3D10, "
                    f"E = {case['youngs_Pa']:g} Pa, nu = {case['poisson']:g}, linear statics, solver {SOLVER}.\n")
            if history[-1][4] >= 0.01 or history[-1][4] != history[-1][4]:
                f.write(f"# NOT CONVERGED: the last level moved the force by {100 * history[-1][4]:.2f} % (>= 1 %).\n")
            f.write("# Refinement (level, nodes, tets, |F| N, change):\n")
            for level, n, t, mag, ch in history:
                f.write(f"#   {level} {n} {t} {mag:.6g} {ch:.4f}\n")
            f.write(f"prescribed_m {' '.join(f'{c:.9e}' for c in case['displacement'])}\n")
            for name, value in case.get("extra", {}).items():
                f.write(f"{name} {' '.join(f'{c:.9e}' for c in value)}\n")
            f.write(f"force_N {' '.join(f'{c:.9e}' for c in force)}\n")
            f.write("contact " + " ".join(map(str, case["contact_vertices"])) + "\n")
            for v, d in enumerate(u):
                f.write(f"u {v} {d[0]:.9e} {d[1]:.9e} {d[2]:.9e}\n")
        print(f"wrote {case['out'].relative_to(ROOT)}")


def ccx_version():
    r = subprocess.run(["ccx", "-v"], capture_output=True, text=True)
    words = (r.stdout + r.stderr).split()
    return words[words.index("Version") + 1] if "Version" in words else "?"


if __name__ == "__main__":
    main()
