#!/usr/bin/env python3
"""Writes the pile variants the README's solver measurements use, from scenes/data/pile.json.

    /usr/bin/python3 bench/make_pile_variants.py [--out out/bench_scenes]

pile75.json         the shipped pile's container with 5 x 5 x 3 = 75 spheres, 2 s (default mode)
pile4x75.json       four such piles in separate containers, 2 m apart (independent parts)
*_explicit.json     the same in explicit-normals mode

Run each with ./build/bench/superdex_bench_steps FILE [--one-step-length].
"""
import argparse
import copy
import json
import os

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def pile75(base):
    scene = copy.deepcopy(base)
    scene["description"] = "75 spheres of radius 0.05 m falling into a 1.3 m box container, 2 s."
    scene["settings"]["duration"] = 2.0
    scene.pop("output", None)
    scene.pop("expect", None)
    for actor in scene["actors"]:
        if "grid" in actor:
            actor["grid"]["count"] = [5, 5, 3]
    return scene


def four(scene):
    out = copy.deepcopy(scene)
    out["description"] = "Four 75-sphere piles in separate containers 2 m apart, 2 s."
    out["actors"] = []
    for i, (ox, oy) in enumerate([(0, 0), (2, 0), (0, 2), (2, 2)]):
        for actor in scene["actors"]:
            a = copy.deepcopy(actor)
            a["name"] = f"{actor['name']}{i}"
            a["position"] = [actor["position"][0] + ox, actor["position"][1] + oy,
                             actor["position"][2]]
            if "grid" in a:
                a["grid"]["seed"] = actor["grid"].get("seed", 0) + i
            out["actors"].append(a)
    return out


def explicit(scene):
    out = copy.deepcopy(scene)
    out["settings"]["experimental_eval_params"] = {"explicit_normals": True}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(SOURCE, "out", "bench_scenes"))
    args = ap.parse_args()
    with open(os.path.join(SOURCE, "scenes", "data", "pile.json")) as f:
        base = json.load(f)
    os.makedirs(args.out, exist_ok=True)
    one = pile75(base)
    scenes = {"pile75": one, "pile4x75": four(one)}
    for name, scene in list(scenes.items()):
        scenes[name + "_explicit"] = explicit(scene)
    for name, scene in scenes.items():
        path = os.path.join(args.out, name + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
        print(path)


if __name__ == "__main__":
    main()
