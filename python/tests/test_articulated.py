"""Articulated actors through the Python API: descriptions, URDF, joint state, errors, physics."""
import math
import os

import numpy as np
import pytest
import superdex as sd

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "scenes", "data")
G = 9.81


def pendulum_desc(angle, length=1.0, radius=0.05):
    """A 1 kg sphere of `radius` hanging `length` below a revolute pivot about y, at `angle`."""
    link = sd.ArticulatedLinkDesc("bob", sd.JointType.Revolute, mass=1.0,
                                  center_of_mass=[0, 0, -length],
                                  inertia=0.4 * radius**2 * np.eye(3), axis=[0, 1, 0])
    link.origin_position = [0, 0, 1]
    d = sd.ArticulatedActorDesc("pendulum", [link])
    d.joint_positions = [angle]
    return d


def elliptic_k(k):
    a, b = 1.0, math.sqrt(1 - k * k)
    for _ in range(40):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2 * a)


def test_a_pendulum_returns_after_one_period():
    # The compound pendulum's period 4 sqrt(L_eq/g) K(sin(theta0/2)), L_eq = L + k^2/L.
    theta0, L, r = 0.8, 1.0, 0.05
    period = 4 * math.sqrt((L + 0.4 * r * r / L) / G) * elliptic_k(math.sin(theta0 / 2))
    scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.SymplecticDIRK22))
    arm = scene.add_articulated_actor(pendulum_desc(theta0))
    assert arm.is_articulated and not arm.is_soft and arm.dynamic
    dt = 1e-3
    steps = round(period / dt)
    for _ in range(steps):
        scene.step(dt)
    # After a whole period, to within half a step dt/2 (and the method's 1e-5 of the period), the
    # bob is back at rest at theta0: |theta_dot| <= (g/L) sin(theta0) (dt/2 + 2e-5 s) = 3.7e-3
    # rad/s, |theta - theta0| of second order in that time (1e-6 rad).
    assert abs(arm.joint_velocities[0]) < 4e-3
    assert abs(arm.joint_positions[0] - theta0) < 1e-5


def test_joint_state_links_and_rigid_only_properties():
    scene = sd.Scene()
    arm = scene.add_articulated_actor(pendulum_desc(0.0))
    assert arm.link_names == ["bob"]
    assert arm.link_positions.shape == (1, 3) and np.allclose(arm.link_positions[0], [0, 0, 1])
    assert arm.mass == 1.0
    arm.joint_positions = [math.pi / 2]  # the bob swung up about +y: its centre at x = -1
    assert np.allclose(arm.position, [-1, 0, 1], atol=1e-12)
    arm.joint_velocities = [2.0]
    assert arm.joint_velocities[0] == pytest.approx(2.0)
    with pytest.raises(TypeError, match=r"^rotation: 'pendulum' is an articulated actor"):
        arm.rotation
    with pytest.raises(TypeError, match=r"^position: 'pendulum' is an articulated actor"):
        arm.position = [0, 0, 0]
    with pytest.raises(ValueError, match=r"^joint_positions: must have 1 finite entries"):
        arm.joint_positions = [0.0, 1.0]
    assert "articulated" in repr(arm)


def test_a_urdf_arm_with_a_drive_runs_and_reports_its_forces():
    p = sd.JointParams()
    p.drive_stiffness = 200
    p.drive_damping = 20
    p.drive_target_position = [(0.0, 0.0), (1.0, -0.6)]
    desc = sd.read_urdf(os.path.join(DATA, "robots", "three_link_arm.urdf"), position=[0, 0, 1.5],
                        joint_params={"shoulder": p}, joint_positions={"elbow": 0.2})
    assert [l.name for l in desc.links] == ["base", "upper", "fore", "hand"]
    assert desc.links[2].joint_params.lower_limit == -2.5
    assert desc.joint_positions[1] == 0.2  # shoulder, elbow, wrist (the base is fixed)
    scene = sd.Scene()
    arm = scene.add_articulated_actor(desc)
    out = scene.run(0.2, 2e-3)
    assert np.isnan(out["q"]).all()  # no single orientation: NaN, as for soft actors
    assert out["p"].shape[1:] == (1, 3)
    forces = arm.drive_forces
    assert forces.shape == (3,) and forces[0] != 0 and forces[1] == 0 and forces[2] == 0


def test_bad_articulated_input_names_the_link_or_file():
    d = pendulum_desc(0.0)
    d.links[0].mass = -1.0
    with pytest.raises(ValueError, match=r"link 0 \('bob'\): mass must be finite and >= 0"):
        sd.Scene().add_articulated_actor(d)
    with pytest.raises(ValueError, match=r"cannot open the URDF file"):
        sd.read_urdf("/nonexistent/robot.urdf")
    with pytest.raises(ValueError, match=r'^base: must be "fixed" or "free"'):
        sd.read_urdf(os.path.join(DATA, "robots", "three_link_arm.urdf"), base="floating")
    p = sd.JointParams()
    with pytest.raises(ValueError, match=r"damping: must be >= 0"):
        p.damping = -1


def test_a_scene_file_with_an_articulated_actor_loads_and_runs():
    f = sd.load_scene(os.path.join(DATA, "swinging_arm.json"))
    arm = f.scene.actors[0]
    assert arm.name == "arm" and arm.is_articulated
    q0 = arm.joint_positions.copy()
    f.scene.run(0.1, f.dt)
    assert not np.allclose(arm.joint_positions, q0)


def test_a_link_shape_rests_on_the_ground_with_its_links_weight():
    # A box link on a vertical slider, dropped onto a plane: the ground carries its weight
    # through the shape, an actor nested under the articulation that moves with the link
    # (Backward Euler damps the landing's bounce out within the 3 s).
    scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler))
    ground = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    scene.add_rigid_actor(ground)
    link = sd.ArticulatedLinkDesc("block", sd.JointType.Prismatic, mass=1.0,
                                  inertia=np.eye(3) / 600.0, axis=[0, 0, 1])
    shape = sd.LinkShapeDesc(sd.RigidShape.box([0.1, 0.1, 0.1], surface_resolution=4))
    shape.contact.penalty_coefficient = 1e6
    link.shapes = [shape]
    desc = sd.ArticulatedActorDesc("slider", [link])
    desc.joint_positions = [0.06]
    slider = scene.add_articulated_actor(desc)
    body = scene.actor("slider/block")
    assert body.is_attached and not slider.is_attached
    assert body.mass == 0.0
    for _ in range(300):
        scene.step(0.01)
    pairs = scene.contact_pairs()
    assert len(pairs) == 1
    assert abs(abs(pairs[0]["normal_force"][2]) - G) < 1e-6 * G
    # The shape follows the link: its centre is the link's.
    assert np.allclose(body.position, slider.link_positions[0], atol=1e-12)
    with pytest.raises(TypeError):
        body.position = [0, 0, 1]


def test_read_urdf_gives_the_links_collision_shapes():
    desc = sd.read_urdf(os.path.join(DATA, "robots", "two_finger_gripper.urdf"))
    kinds = [[s.shape.kind for s in l.shapes] for l in desc.links]
    assert kinds == [[], ["mesh"], ["box"], ["box"]]
    assert np.allclose(desc.links[2].shapes[0].position, [0, 0, -0.03])
    assert all(not l.shapes for l in sd.read_urdf(
        os.path.join(DATA, "robots", "two_finger_gripper.urdf"), collisions=False).links)


def carriage_with_skin(scene, z_star=0.3):
    """A 0.2 kg vertical carriage driven to z_star (k_p 2000 N/m, critically damped) with a soft
    cube hanging from it, the cube's top layer bound to the carriage."""
    p = sd.JointParams()
    p.drive_stiffness = 2000.0
    p.drive_damping = 2 * math.sqrt(2000.0 * 0.3)
    p.drive_target_position = [(0.0, z_star)]
    link = sd.ArticulatedLinkDesc("carriage", sd.JointType.Prismatic, mass=0.2,
                                  inertia=1e-4 * np.eye(3), axis=[0, 0, 1])
    link.joint_params = p
    d = sd.ArticulatedActorDesc("rig", [link])
    d.joint_positions = [z_star]
    rig = scene.add_articulated_actor(d)
    cube = sd.SoftActorDesc("skin", sd.make_tet_box([0.03] * 3, [3] * 3),
                            sd.SoftMaterial(youngs_modulus=2e4, density=500, stiffness_damping=0.01))
    cube.position = [0, 0, z_star - 0.03]
    cube.skin = [sd.SkinBinding("carriage", region=([-1, -1, -1e-3], [1, 1, 1e-3]))]
    return rig, scene.add_soft_actor(cube, parent=rig)


def test_a_soft_skin_hangs_from_its_driven_carriage():
    # At rest the drive carries the carriage's and the skin's weight: k_p (z* - z) = (m_c + m_s) g.
    scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler))
    rig, skin = carriage_with_skin(scene)
    assert skin.is_soft and not skin.is_attached and skin.carrier.name == "rig"
    assert rig.carrier is None
    top = skin.node_positions[:, 2] > 0.3 - 1e-9
    assert top.sum() == 16
    rig.joint_positions = [0.4]  # the bound nodes follow the joint
    assert np.allclose(skin.node_positions[top, 2], 0.4, atol=1e-12)
    rig.joint_positions = [0.3]
    scene.run(3.0, 1e-2)  # raises RuntimeError on a stage that does not converge
    weight = (0.2 + skin.mass) * G
    assert 2000.0 * (0.3 - rig.joint_positions[0]) == pytest.approx(weight, rel=1e-6)
    assert rig.drive_forces[0] == pytest.approx(weight, rel=1e-6)


def test_bad_skin_bindings_name_the_field():
    scene = sd.Scene()
    rig, _ = carriage_with_skin(scene)
    cube = sd.SoftActorDesc("pad", sd.make_tet_box([0.03] * 3, [2] * 3))
    cube.position = [0, 0, 0.27]
    b = sd.SkinBinding("wheel", nodes=[0, 1])
    assert b.region is None and b.shape_distance < 0 and "wheel" in repr(b)
    cube.skin = [b]
    with pytest.raises(ValueError, match=r'^skin\[0\]\.link: no link named "wheel" in \'rig\''):
        scene.add_soft_actor(cube, parent=rig)
    with pytest.raises(ValueError, match=r"^skin: a soft-skinned actor needs its skeleton"):
        scene.add_soft_actor(cube)
    cube.skin = [sd.SkinBinding("carriage", region=([0, 0, 1], [1, 1, 0]))]
    with pytest.raises(ValueError, match=r"^skin\[0\]\.region: min must be finite and < max"):
        scene.add_soft_actor(cube, parent=rig)
