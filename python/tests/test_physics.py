"""Physics through the Python API: incline acceleration, restitution trend, resting tractions."""
import math

import numpy as np
import pytest
import superdex as sd


def rotation(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def cube(name, mu=0.5, cn=0.0, k=1e9):
    d = sd.RigidActorDesc(name, sd.RigidShape.box([0.2, 0.2, 0.2], surface_resolution=2))
    d.mass = 1.0
    d.contact.penalty_coefficient = k
    d.contact.coulomb_friction_coefficient = mu
    d.contact.normal_viscous_damping_coefficient = cn
    return d


def test_incline_sliding_acceleration_within_one_percent():
    th = math.pi / 6
    n = np.array([math.sin(th), 0, math.cos(th)])
    down = np.array([math.cos(th), 0, -math.sin(th)])
    scene = sd.Scene()
    g = sd.RigidActorDesc("incline", sd.RigidShape.plane(n), dynamic=False)
    g.contact.normal_viscous_damping_coefficient = 1.0
    scene.add_rigid_actor(g)
    c = cube("cube", mu=0.5, cn=1.0)
    c.orientation = [0, math.sin(th / 2), 0, math.cos(th / 2)]
    c.position = n * (0.1 + 1e-5)
    scene.add_rigid_actor(c)
    traj = scene.run(1.0, 1e-3)
    # Distance travelled by the bottom-face centre (insensitive to the cube's rocking).
    bottom = np.array([traj["p"][i, 1] + rotation(traj["q"][i, 1]) @ [0, 0, -0.1]
                       for i in range(len(traj["t"]))])
    s = (bottom - bottom[0]) @ down
    window = traj["t"] >= 0.3
    a = 2 * np.polyfit(traj["t"][window], s[window], 2)[0]
    expected = 9.81 * (math.sin(th) - 0.5 * math.cos(th))
    assert a == pytest.approx(expected, rel=0.01)


def launch(cn, v=1.0):
    s = sd.SceneSettings()
    s.gravity = [0, 0, 0]
    scene = sd.Scene(s)
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.penalty_coefficient = 1e6
    g.contact.normal_viscous_damping_coefficient = cn
    scene.add_rigid_actor(g)
    c = cube("cube", cn=cn, k=1e6)
    c.position = [0, 0, 0.1 + 0.001 + 1e-4]
    c.velocity = [0, 0, -v]
    box = scene.add_rigid_actor(c)
    touched = False
    while scene.time < 1.0:
        r = scene.step(1e-4)
        if r.active_samples > 0:
            touched = True
        elif touched:
            return box.velocity[2] / v
    raise AssertionError("no rebound")


def test_restitution_follows_the_rational_formula_and_falls_with_damping():
    previous = 1.0
    for cnv in (0.25, 1.0, 2.5):
        e = launch(cnv)
        assert e == pytest.approx(sd.hunt_crossley_restitution_from_damping(cnv, 1.0), rel=0.03)
        assert e < previous
        previous = e


def test_contact_tractions_of_a_resting_cube_sum_to_its_weight():
    s = sd.SceneSettings()
    s.integrator = sd.IntegrationMethod.BackwardEuler
    scene = sd.Scene(s)
    scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
    c = cube("cube")
    c.position = [0, 0, 0.101]
    scene.add_rigid_actor(c)
    scene.run(2.0, 5e-3, every=400)
    samples = scene.contact_samples()
    force = (samples["weight"][:, None] * samples["traction"]).sum(axis=0)
    assert force[2] == pytest.approx(9.81, rel=1e-6)
    assert np.all(samples["colliding"] == 1) and np.all(samples["collider"] == 0)
    pairs = scene.contact_pairs()
    assert [(p["a"], p["b"]) for p in pairs] == [(0, 1)]
    assert pairs[0]["force"][2] == pytest.approx(-9.81, rel=1e-6)  # on the ground
    assert pairs[0]["area"] == pytest.approx(0.04, rel=1e-9)


def test_friction_on_a_resting_cube_on_an_incline_holds_it():
    th = math.pi / 6
    n = np.array([math.sin(th), 0, math.cos(th)])
    down = np.array([math.cos(th), 0, -math.sin(th)])
    scene = sd.Scene()
    g = sd.RigidActorDesc("incline", sd.RigidShape.plane(n), dynamic=False)
    g.contact.coulomb_friction_coefficient = 0.7
    g.contact.normal_viscous_damping_coefficient = 5.0
    scene.add_rigid_actor(g)
    c = cube("cube", mu=0.7, cn=5.0, k=1e7)
    c.orientation = [0, math.sin(th / 2), 0, math.cos(th / 2)]
    c.position = n * (0.1 + 1e-5)
    scene.add_rigid_actor(c)
    scene.run(6.0, 1e-3, every=6000)  # the creep's transient decays (see test_contact_report.cpp)
    samples = scene.contact_samples()
    friction = (samples["weight"][:, None] * samples["friction"]).sum(axis=0)  # on the cube
    assert friction @ down == pytest.approx(-9.81 * math.sin(th), rel=1e-4)
    pair = scene.contact_pairs()[0]
    assert -pair["friction_force"] @ down == pytest.approx(-9.81 * math.sin(th), rel=1e-4)
    assert -pair["force"] == pytest.approx([0, 0, 9.81], abs=1e-4 * 9.81)


def test_an_exact_sphere_rests_with_one_cap_record_carrying_its_weight():
    s = sd.SceneSettings()
    s.integrator = sd.IntegrationMethod.BackwardEuler
    scene = sd.Scene(s)
    scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
    ball = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1))
    assert ball.surface_integral == sd.SurfaceIntegral.Quadrature
    ball.surface_integral = sd.SurfaceIntegral.ExactSphere
    ball.mass = 1.0
    ball.position = [0, 0, 0.1]
    scene.add_rigid_actor(ball)
    scene.run(1.0, 5e-3, every=200)
    samples = scene.contact_samples()
    assert len(samples["weight"]) == 1  # the active cap, whole
    force = (samples["weight"][:, None] * samples["traction"]).sum(axis=0)
    assert force[2] == pytest.approx(9.81, rel=1e-6)


def test_exact_sphere_integral_needs_a_sphere():
    scene = sd.Scene()
    box = cube("box")
    box.surface_integral = sd.SurfaceIntegral.ExactSphere
    with pytest.raises(ValueError, match="surface_integral: ExactSphere needs a sphere shape"):
        scene.add_rigid_actor(box)
