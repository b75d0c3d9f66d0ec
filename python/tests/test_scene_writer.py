"""A scene built in Python: written as a scene file, run, fitted."""
import math
import os

import numpy as np
import pytest
import superdex as sd


def built(mass=1.0):
    s = sd.SceneSettings()
    s.integrator = sd.IntegrationMethod.BDF2
    scene = sd.Scene(s)
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.normal_viscous_damping_coefficient = 2.0
    scene.add_rigid_actor(g)
    b = sd.RigidActorDesc("box", sd.RigidShape.box([0.2, 0.2, 0.1], surface_resolution=2))
    b.mass = mass
    b.position = [0, 0, 0.0505]
    b.orientation = [0, 0, math.sin(0.2), math.cos(0.2)]
    b.applied_force = [(0.0, [8.0, 0, 0])]
    b.contact.normal_viscous_damping_coefficient = 2.0
    scene.add_rigid_actor(b)
    ball = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.05))
    ball.mass = 0.3
    ball.position = [0.5, 0.3, 0.3]
    ball.velocity = [-0.5, 0, 0]
    ball.angular_velocity = [0, 4, 0]
    scene.add_rigid_actor(ball)
    p = sd.RigidActorDesc("paddle", sd.RigidShape.box([0.02, 0.4, 0.1]), kinematic=True)
    p.path = [(0.0, [-0.3, 0, 0.05]), (0.2, [-0.2, 0, 0.05])]
    scene.add_rigid_actor(p)
    m = sd.make_tet_box([0.05, 0.05, 0.05], [2, 2, 2])
    soft = sd.SoftActorDesc("jelly", m)
    soft.position = [0, -0.5, 0.0505]
    soft.material.youngs_modulus = 1e5
    scene.add_soft_actor(soft)
    scene.enable_layer_contact_symmetric("default", "default", True)
    return scene


def test_a_python_scene_written_and_loaded_runs_the_same_trajectory_bit_for_bit(tmp_path):
    scene = built()
    path = str(tmp_path / "built.json")
    scene.write_scene_file(path, dt=2e-3, duration=0.1, description="from Python")
    assert os.path.exists(tmp_path / "built.jelly.msh")
    loaded = sd.load_scene(path)
    assert loaded.dt == 2e-3 and loaded.duration == 0.1
    a = scene.run(0.1, 2e-3)
    b = loaded.scene.run(loaded.duration, loaded.dt)
    for key in ("t", "p", "q", "v", "w", "energy"):
        assert np.array_equal(a[key], b[key], equal_nan=True), key
    # The written file runs as a scene file does, and states the version that wrote it.
    summary = sd.run_scene(sd.load_scene(path), out="", vtk="")
    assert summary.stopped + summary.diverged == 0
    import json
    with open(path) as f:
        assert json.load(f)["superdex_version"] == sd.__version__


def test_writing_a_scene_that_has_stepped_is_refused(tmp_path):
    scene = built()
    scene.step(1e-3)
    with pytest.raises(ValueError, match="it has stepped"):
        scene.write_scene_file(str(tmp_path / "x.json"), dt=1e-3, duration=1.0)


def test_run_scene_and_fit_take_a_python_scene(tmp_path):
    scene = built()
    summary = sd.run_scene(scene, dt=2e-3, duration=0.05)
    assert summary.stopped + summary.diverged == 0
    assert scene.time == 0.0  # a copy ran
    with pytest.raises(ValueError, match="dt: a Scene built in Python has no time step"):
        sd.run_scene(scene, duration=0.05)
    # The box's mass from its pushed path: observed at m = 1.3, fitted from the scene's 1.0.
    truth = built(mass=1.3)
    times, com = [], []
    for n in range(1, 51):
        truth.step(2e-3)
        if n % 10 == 0:
            times.append(truth.time)
            com.append(truth.actor("box").position)
    r = sd.fit(scene, ["box.mass"], times=np.array(times), positions={"box": np.array(com)},
               dt=2e-3)
    assert r.converged, r.message
    assert r.fitted[0] == pytest.approx(1.3, rel=1e-6)
    assert scene.actor("box").mass == 1.0  # left unchanged
    r.apply(scene)
    assert scene.actor("box").mass == r.fitted[0]
    path = str(tmp_path / "fitted.json")
    scene.write_scene_file(path, dt=2e-3, duration=0.1)
    assert sd.load_scene(path).scene.actor("box").mass == r.fitted[0]
    g = sd.trajectory_gradient(built(), ["box.mass"], times=np.array(times),
                               positions={"box": np.array(com)}, dt=2e-3)
    assert g.gradient[0] < 0  # heavier moves less far: closer to the observed path
