#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora and the scene-file dictionary into OUT (fuzz/run.sh).

Seeds: the shipped scene files (their slow parts made small: quick()) and observed trajectory
(scenes/data), the shipped tet meshes
(scenes/data/meshes: Gmsh 2.2, TetGen), that Gmsh mesh rewritten as Gmsh 4.1, and a unit cube in
every surface format (OBJ, OFF, STL ASCII and binary, PLY ASCII and binary, both byte orders).
The dictionary: every key and keyword the scene-file reader knows, taken from its sources (the
string literals of its field lists and enum names).
"""
import glob
import json
import os
import re
import shutil
import struct
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "scenes", "data")

V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
F = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
     (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def quick(node):
    """The scene with its slow parts made small (meshes 3x coarser, grids of at most 2 per axis,
    soft boxes of at most 3 cells per axis, a soft cylinder as a box of its size: CGAL's feature
    protection takes a minute per cylinder under the fuzzing instrumentation): loading takes
    under a second instead of up to a minute, which would leave the fuzzer a few hundred runs."""
    if isinstance(node, dict):
        out = {k: quick(v) for k, v in node.items()}
        if out.get("type") == "cylinder" and "radius" in out and "length" in out:
            d = 2 * out["radius"]
            return {"type": "box", "size": [d, d, out["length"]], "cells": [2, 2, 3]}
        if isinstance(out.get("edge_length"), (int, float)):
            out["edge_length"] *= 3
        for key in ("count", "cells"):
            if isinstance(out.get(key), list):
                out[key] = [min(c, 2 if key == "count" else 3) if isinstance(c, int) else c
                            for c in out[key]]
        return out
    if isinstance(node, list):
        return [quick(v) for v in node]
    return node


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def surface_seeds(out):
    obj = "".join(f"v {x} {y} {z}\n" for x, y, z in V)
    write(f"{out}/fuzz_mesh_obj/cube.obj", "# cube\n" + obj + "".join(
        f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F))
    write(f"{out}/fuzz_mesh_obj/quads.obj", obj + "vn 0 0 1\nvt 0 0\n"
          "f 1/1/1 4/1/1 3/1/1 2/1/1\nf -4 -3 -2 -1\ng side\nf 1//1 2//1 6//1 5//1\n")
    off = f"OFF\n{len(V)} {len(F)} 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in V)
    write(f"{out}/fuzz_mesh_off/cube.off", off + "".join(f"3 {a} {b} {c}\n" for a, b, c in F))
    write(f"{out}/fuzz_mesh_off/quads.off", "COFF\n# comment\n4 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n"
          "1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n4 0 1 2 3 255 0 0\n")
    stl = "solid cube\n"
    for a, b, c in F:
        stl += " facet normal 0 0 0\n  outer loop\n"
        stl += "".join(f"   vertex {V[i][0]} {V[i][1]} {V[i][2]}\n" for i in (a, b, c))
        stl += "  endloop\n endfacet\n"
    write(f"{out}/fuzz_mesh_stl/cube_ascii.stl", stl + "endsolid cube\n")
    binary = b"binary cube".ljust(80, b" ") + struct.pack("<I", len(F))
    for a, b, c in F:
        binary += struct.pack("<3f", 0, 0, 0)
        for i in (a, b, c):
            binary += struct.pack("<3f", *V[i])
        binary += b"\0\0"
    write(f"{out}/fuzz_mesh_stl/cube_binary.stl", binary)
    head = ("ply\nformat {fmt} 1.0\ncomment cube\nelement vertex 8\nproperty float x\n"
            "property float y\nproperty float z\nproperty uchar red\nelement face 12\n"
            "property list uchar int vertex_indices\nelement edge 0\nproperty int vertex1\n"
            "end_header\n")
    write(f"{out}/fuzz_mesh_ply/cube_ascii.ply", head.format(fmt="ascii") +
          "".join(f"{x} {y} {z} 7\n" for x, y, z in V) + "".join(f"3 {a} {b} {c}\n" for a, b, c in F))
    for order, name in (("<", "binary_little_endian"), (">", "binary_big_endian")):
        body = b"".join(struct.pack(order + "3fB", *v, 7) for v in V)
        body += b"".join(struct.pack(order + "B3i", 3, *f) for f in F)
        write(f"{out}/fuzz_mesh_ply/cube_{name}.ply", head.format(fmt=name).encode() + body)


def gmsh41(msh22):
    """The shipped Gmsh 2.2 mesh as a Gmsh 4.1 file (one node block, one tet block)."""
    lines = msh22.split("\n")
    nodes = lines[lines.index("$Nodes") + 2:lines.index("$EndNodes")]
    elems = lines[lines.index("$Elements") + 2:lines.index("$EndElements")]
    tets = [e.split() for e in elems if e.split()[1] == "4"]
    tags = [n.split()[0] for n in nodes]
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$Entities", "0 0 0 1",
           "1 0 0 0 1 1 1 0 0", "$EndEntities", "$Nodes", f"1 {len(nodes)} 1 {tags[-1]}",
           f"3 1 0 {len(nodes)}"] + tags + [" ".join(n.split()[1:]) for n in nodes]
    out += ["$EndNodes", "$Elements", f"1 {len(tets)} 1 {len(tets)}", f"3 1 4 {len(tets)}"]
    out += [f"{i + 1} " + " ".join(t[-4:]) for i, t in enumerate(tets)]
    return "\n".join(out + ["$EndElements", ""])


def tet_seeds(out):
    meshes = os.path.join(DATA, "meshes")
    for msh in glob.glob(f"{meshes}/*.msh"):
        text = open(msh).read()
        shutil.copy(msh, f"{out}/fuzz_mesh_gmsh/")
        write(f"{out}/fuzz_mesh_gmsh/{os.path.basename(msh)[:-4]}_41.msh", gmsh41(text))
    write(f"{out}/fuzz_mesh_gmsh/small_41.msh",
          "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n"
          "1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n")
    for node in glob.glob(f"{meshes}/*.node"):
        ele = node[:-5] + ".ele"
        write(f"{out}/fuzz_mesh_tetgen/{os.path.basename(node)[:-5]}",
              open(node, "rb").read() + b"\0" + open(ele, "rb").read())
    write(f"{out}/fuzz_mesh_tetgen/small", "# one tet\n4 3 1 1\n1 0 0 0 5 1\n2 1 0 0 5 1\n"
          "3 0 1 0 5 1\n4 0 0 1 5 1\n\0" "1 10 1\n1 1 2 3 4 5 6 7 8 9 10 2\n")


def scene_dictionary(path):
    sources = ["scenes/scene_file.cpp", "scenes/soft_mesh_spec.cpp", "scenes/json_fields.h",
               "core/model/contact_params.h", "core/model/soft_body.h", "core/model/enums.cpp",
               "optim/field_table.h", "core/dynamics/scene_settings.h"]
    words = set()
    for s in sources:
        p = os.path.join(ROOT, s)
        if os.path.exists(p):
            words |= set(re.findall(r'"([A-Za-z][A-Za-z0-9_./-]{0,40})"', open(p).read()))
    with open(path, "w") as f:
        f.write("# The scene format's keys and keywords (fuzz/make_seeds.py, from the reader's sources)\n")
        for w in sorted(words):
            f.write(f'"\\"{w}\\""\n')
        for t in ["{", "}", "[", "]", ":", ",", "true", "false", "null", "1e308", "-1", "0.5"]:
            f.write(f'"{t}"\n')
    return len(words)


def main():
    out = sys.argv[1]
    for target in ["fuzz_scene_file", "fuzz_mesh_obj", "fuzz_mesh_off", "fuzz_mesh_stl",
                   "fuzz_mesh_ply", "fuzz_mesh_gmsh", "fuzz_mesh_tetgen", "fuzz_trajectory"]:
        os.makedirs(f"{out}/{target}", exist_ok=True)
    for scene in glob.glob(f"{DATA}/*.json"):
        write(f"{out}/fuzz_scene_file/{os.path.basename(scene)}",
              json.dumps(quick(json.load(open(scene))), indent=1) + "\n")
    for traj in glob.glob(f"{DATA}/*.jsonl"):
        shutil.copy(traj, f"{out}/fuzz_trajectory/")
    surface_seeds(out)
    tet_seeds(out)
    n = scene_dictionary(f"{out}/scene.dict")
    print(f"seeds in {out}; scene.dict: {n} keys")


if __name__ == "__main__":
    main()
