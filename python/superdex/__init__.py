"""superdex: a simulator for contact-rich scenes on a compliant contact model.

Units are SI throughout (m, kg, s, N, Pa). Build a Scene, add actors, step or run it; states and
trajectories come back as numpy arrays. Bad values raise ValueError with the field and the rule;
a stage that does not converge raises RuntimeError.

sweep() and fit_batch() run many variants of a scene file, or fits to many observed trajectories,
on dask.distributed workers (docs/sweeps.md).
"""
from . import _superdex
from ._superdex import *  # noqa: F401,F403  (the compiled API)
from ._superdex import __version__  # noqa: F401  (the CMake project version)
from ._sweep import fit_batch, sweep  # noqa: F401

# The compiled classes present themselves by their public name, superdex.NAME.
for _type in vars(_superdex).values():
    if isinstance(_type, type) and _type.__module__ == _superdex.__name__:
        _type.__module__ = __name__
del _type
