"""Variants of a scene file: parameters ACTOR.FIELD resolved to JSON paths, grids expanded.

A parameter is named ``ACTOR.FIELD``: ACTOR is the ``name`` of an entry of the file's ``actors``
(a ``grid`` entry's copies are all set through the entry's name), or ``settings`` for the scene's
settings. FIELD is a dotted path inside that object (``contact.penalty_coefficient``,
``shape.radius``, ``solver.max_iterations``), where ``x``, ``y``, ``z`` (or 0, 1, 2) index an
array (``position.z``). Shortcuts: a bare contact parameter (``coulomb_friction_coefficient``)
means ``contact.NAME``, and on a soft actor a bare material parameter (``youngs_modulus``) means
``material.NAME``, so the parameter names of ``superdex fit`` work here too.
"""
import copy
import itertools
import json
import numbers

from . import _superdex

# Arrays the loader fills with defaults when absent: a component can be set without them.
_DEFAULT_ARRAYS = {"position": [0.0, 0.0, 0.0], "velocity": [0.0, 0.0, 0.0],
                   "angular_velocity": [0.0, 0.0, 0.0], "gravity": [0.0, 0.0, -9.81]}
_AXES = {"x": 0, "y": 1, "z": 2}


def _fields(cls):
    return {k for k, v in vars(cls).items() if isinstance(v, property)}


def resolve(scene, name):
    """The JSON path (a tuple of keys and indices) that parameter `name` sets in `scene` (a dict).

    Raises ValueError naming the parameter and the rule when the actor or the path is unknown.
    """
    if not isinstance(name, str) or "." not in name:
        raise ValueError(f"parameter {name!r}: must be ACTOR.FIELD (e.g. "
                         "ball.normal_viscous_damping_coefficient or settings.dt)")
    actor, field = name.split(".", 1)
    parts = field.split(".")
    if any(p == "" for p in parts):
        raise ValueError(f"parameter {name!r}: FIELD must not have empty parts")
    actors = scene.get("actors", [])
    names = [a.get("name") for a in actors if isinstance(a, dict)]
    if actor in names:
        index = names.index(actor)
        entry = actors[index]
        head = ("actors", index)
        if len(parts) == 1 and parts[0] in _fields(_superdex.ContactParams):
            parts = ["contact"] + parts
        elif (len(parts) == 1 and entry.get("type") == "soft"
              and parts[0] in _fields(_superdex.SoftMaterial)):
            parts = ["material"] + parts
    elif actor == "settings":
        head, entry = ("settings",), scene.get("settings", {})
    else:
        raise ValueError(f"parameter {name!r}: no actor named {actor!r} in the scene (actors: "
                         f"{', '.join(map(str, names)) or 'none'}; or settings.FIELD)")
    path = list(head)
    node = entry
    for k, part in enumerate(parts):
        holder = parts[k - 1] if k > 0 else actor
        if isinstance(node, list):
            i = _AXES[part] if part in _AXES else int(part) if part.isdigit() else None
            if i is None or i >= len(node):
                raise ValueError(f"parameter {name!r}: {part!r} must index the array "
                                 f"{holder!r} (x, y, z or 0 … {len(node) - 1})")
            path.append(i)
            node = node[i]
        elif not isinstance(node, dict) or part in _AXES or part.isdigit():
            kind = "an array" if part in _AXES or part.isdigit() else "an object"
            raise ValueError(f"parameter {name!r}: {holder!r} is not {kind} in the scene file "
                             "(set the whole field, or write it in the file)")
        else:
            path.append(part)
            node = node.get(part, _DEFAULT_ARRAYS.get(part, {}))
    return tuple(path)


def _json_value(name, value):
    """value as plain JSON data (numpy scalars and arrays become numbers and lists)."""
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return value
    if isinstance(value, numbers.Real):
        return float(value) if not isinstance(value, numbers.Integral) else int(value)
    if isinstance(value, (list, tuple)):
        return [_json_value(name, v) for v in value]
    raise ValueError(f"parameter {name!r}: value {value!r} must be a number, a string, true or "
                     "false, or a list of numbers")


def expand(grid):
    """The variants of `grid` as a list of {name: value}.

    A dict {name: [values]} gives every combination (the last name varies fastest); a list of
    dicts gives those variants as they are.
    """
    if isinstance(grid, dict):
        if not grid:
            raise ValueError("grid: must name at least one parameter")
        names = list(grid)
        for n in names:
            v = grid[n]
            if isinstance(v, (str, bytes)) or not hasattr(v, "__iter__"):
                raise ValueError(f"grid[{n!r}]: must be a list of values, got {v!r}")
        values = [[_json_value(n, v) for v in grid[n]] for n in names]
        for n, v in zip(names, values):
            if not v:
                raise ValueError(f"grid[{n!r}]: must hold at least one value")
        return [dict(zip(names, combo)) for combo in itertools.product(*values)]
    if isinstance(grid, (list, tuple)) and grid and all(isinstance(g, dict) for g in grid):
        return [{n: _json_value(n, v) for n, v in g.items()} for g in grid]
    raise ValueError("grid: must be a dict {ACTOR.FIELD: [values]} or a non-empty list of dicts "
                     "{ACTOR.FIELD: value}")


def apply(scene, paths, variant):
    """A copy of `scene` (a dict) with each parameter of `variant` set at its path."""
    out = copy.deepcopy(scene)
    for name, value in variant.items():
        node = out
        path = paths[name]
        for k, key in enumerate(path[:-1]):
            if isinstance(key, int):
                node = node[key]
                continue
            if key not in node:
                node[key] = copy.deepcopy(_DEFAULT_ARRAYS.get(key, {}))
            node = node[key]
        node[path[-1]] = value
    return out


def parse_values(name, text):
    """The comma-separated values of `--set NAME=v1,v2,...`: JSON numbers, true, false, [lists]
    (commas inside brackets belong to the list) or plain strings (enum names such as BDF2)."""
    values, depth, start = [], 0, 0
    for i, c in enumerate(text + ","):
        depth += (c == "[") - (c == "]")
        if c == "," and depth == 0:
            values.append(text[start:i].strip())
            start = i + 1
    if depth != 0 or any(v == "" for v in values):
        raise ValueError(f"--set {name}: values must be comma-separated and non-empty, "
                         f"got {text!r}")
    out = []
    for v in values:
        try:
            out.append(json.loads(v))
        except ValueError:
            out.append(v)
    return out


def parse_set(option):
    """`ACTOR.FIELD=v1,v2,...` as (name, [values])."""
    name, sep, values = option.partition("=")
    if not sep or not name.strip():
        raise ValueError(f"--set {option!r}: must be ACTOR.FIELD=v1,v2,...")
    return name.strip(), parse_values(name.strip(), values)
