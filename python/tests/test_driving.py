"""Driving rigid bodies from Python: applied forces and torques, kinematic actors."""
import math

import numpy as np
import pytest
import superdex as sd


def settings(gravity=(0, 0, 0)):
    s = sd.SceneSettings()
    s.gravity = list(gravity)
    return s


def sphere(name="ball", mass=2.0, r=0.1):
    d = sd.RigidActorDesc(name, sd.RigidShape.sphere(r))
    d.mass = mass
    return d


def test_applied_force_ramp_and_torque_give_the_closed_form_motion():
    scene = sd.Scene(settings())
    d = sphere()
    d.applied_force = [(0.0, [0, 0, 0]), (1.0, [4, 0, 0])]  # a = 2t on 2 kg
    d.applied_torque = [(0.0, [0, 0, 0.3])]                 # constant; I = 0.008 kg m^2
    assert len(d.applied_force) == 2 and d.applied_force[1][0] == 1.0
    a = scene.add_rigid_actor(d)
    scene.run(1.0, 1e-3)
    assert a.velocity[0] == pytest.approx(1.0, rel=1e-5)
    assert a.position[0] == pytest.approx(1.0 / 3.0, rel=1e-5)
    # BDF2 turns with an O((omega h)^2) relative error (test_applied_loads.cpp: it shrinks 4x when
    # h halves); DIRK22 keeps dL/dt = tau exactly.
    omega = 0.3 / 0.008
    assert a.angular_velocity[2] == pytest.approx(omega, rel=2 * (omega * 1e-3) ** 2)
    s = settings()
    s.integrator = sd.IntegrationMethod.DIRK22
    exact = sd.Scene(s)
    b = exact.add_rigid_actor(d)
    exact.run(1.0, 1e-3)
    assert b.angular_velocity[2] == pytest.approx(omega, rel=1e-9)


def test_applied_loads_are_refused_on_a_static_actor_and_checked():
    scene = sd.Scene()
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.applied_force = [(0.0, [1, 0, 0])]
    with pytest.raises(ValueError, match="applied_force: only a dynamic actor"):
        scene.add_rigid_actor(g)
    d = sphere()
    d.applied_torque = [(1.0, [0, 0, 1]), (0.5, [0, 0, 1])]
    with pytest.raises(ValueError, match="applied_torque: keyframe times must increase"):
        scene.add_rigid_actor(d)


def test_kinematic_plate_pushes_a_box_with_mu_m_g():
    scene = sd.Scene(settings((0, 0, -9.81)))
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.penalty_coefficient = 1e7
    g.contact.normal_viscous_damping_coefficient = 5.0
    scene.add_rigid_actor(g)
    # A slab (a tall cube pushed at mid-height rocks without settling: test_applied_loads.cpp).
    c = sd.RigidActorDesc("slab", sd.RigidShape.box([0.2, 0.2, 0.05], surface_resolution=2))
    c.mass = 1.0
    c.position = [0, 0, 0.025]
    c.contact.penalty_coefficient = 1e7
    c.contact.normal_viscous_damping_coefficient = 5.0
    cube = scene.add_rigid_actor(c)
    p = sd.RigidActorDesc("plate", sd.RigidShape.box([0.02, 0.3, 0.04], surface_resolution=4),
                          kinematic=True)
    assert not p.dynamic and p.kinematic
    p.position = [-0.112, 0, 0.025]
    p.velocity = [0.1, 0, 0]
    p.contact.penalty_coefficient = 1e7
    p.contact.coulomb_friction_coefficient = 0.0
    p.contact.normal_viscous_damping_coefficient = 5.0
    plate = scene.add_rigid_actor(p)
    assert plate.kinematic and not plate.dynamic
    scene.run(1.0, 1e-3)
    assert cube.velocity[0] == pytest.approx(0.1, rel=1e-3)
    assert plate.position[0] == pytest.approx(-0.012, abs=1e-12)
    pairs = {(q["a"], q["b"]): q for q in scene.contact_pairs()}
    push = pairs[(cube.index, plate.index)]["force"][0]  # on the cube
    assert push == pytest.approx(0.5 * 9.81, rel=0.01)
    with pytest.raises(ValueError, match="kinematic actor"):
        plate.position = [0, 0, 1]


def test_kinematic_path_keyframes_round_trip_and_are_followed():
    scene = sd.Scene(settings())
    p = sd.RigidActorDesc("paddle", sd.RigidShape.box([0.6, 0.04, 0.2]), kinematic=True)
    quarter = [0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4)]
    p.path = [(0.0, [0, 0, 1]), (1.0, [1, 0, 1], quarter)]
    t, x, q = p.path[1]
    assert t == 1.0 and list(x) == [1, 0, 1] and np.allclose(q, quarter)
    assert np.allclose(p.path[0][2], [0, 0, 0, 1])  # the actor's orientation
    paddle = scene.add_rigid_actor(p)
    scene.run(0.5, 1e-2)
    assert np.allclose(paddle.position, [0.5, 0, 1], atol=1e-12)
    assert np.allclose(paddle.velocity, [1, 0, 0], atol=1e-12)
    assert np.allclose(paddle.angular_velocity, [0, 0, math.pi / 2], atol=1e-12)
    d = sd.RigidActorDesc("x", sd.RigidShape.sphere(0.1))
    d.path = [(0.0, [0, 0, 0])]
    with pytest.raises(ValueError, match="path: only a kinematic actor follows a path"):
        scene.add_rigid_actor(d)
