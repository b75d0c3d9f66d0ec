"""A scene's state through the Python API: get_state / set_state, pickling, clone, setters."""
import copy
import math
import pickle

import numpy as np
import pytest
import superdex as sd


def tumbling_scene(integrator=sd.IntegrationMethod.BDF2):
    """Two boxes, one tumbling onto the other on a plane, with friction and damping."""
    s = sd.SceneSettings()
    s.integrator = integrator
    scene = sd.Scene(s)
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.normal_viscous_damping_coefficient = 1.0
    scene.add_rigid_actor(g)
    a = sd.RigidActorDesc("a", sd.RigidShape.box([0.2, 0.2, 0.2], surface_resolution=2))
    a.mass = 1.0
    a.position = [0, 0, 0.1 + 1e-4]
    scene.add_rigid_actor(a)
    b = sd.RigidActorDesc("b", sd.RigidShape.box([0.1, 0.2, 0.05], surface_resolution=2))
    b.mass = 0.5
    b.position = [0.02, 0, 0.3]
    b.velocity = [0.3, 0, 0]
    b.angular_velocity = [1, 2, 0]
    scene.add_rigid_actor(b)
    return scene


def soft_scene():
    scene = sd.Scene()
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.penalty_coefficient = 1e6
    scene.add_rigid_actor(g)
    d = sd.SoftActorDesc("cube", sd.make_tet_box([0.05] * 3, [2] * 3),
                         sd.SoftMaterial(youngs_modulus=1e5, density=1000))
    d.position = [0, 0, 0.06]
    scene.add_soft_actor(d)
    return scene


def states(scene):
    """Every actor's exact state (positions, orientations, velocities; soft: nodes)."""
    out = []
    for a in scene.actors:
        out.append(a.position.copy())
        out.append(a.velocity.copy())
        if a.is_soft:
            out += [a.node_positions, a.node_velocities]
        else:
            out += [a.rotation.copy(), a.angular_velocity.copy()]
    return out


def run(scene, steps, dt=5e-3):
    trace = []
    for _ in range(steps):
        scene.step(dt)
        trace.append(states(scene))
    return trace


def same(a, b):
    return all(np.array_equal(x, y) for sa, sb in zip(a, b) for x, y in zip(sa, sb))


@pytest.mark.parametrize("integrator", [sd.IntegrationMethod.BDF2, sd.IntegrationMethod.BDF3,
                                        sd.IntegrationMethod.DIRK22])
def test_state_round_trip_through_pickle_continues_bit_for_bit(integrator):
    scene = tumbling_scene(integrator)
    run(scene, 20)  # in contact, with a filled multistep history
    state = scene.get_state()
    assert state.time == pytest.approx(0.1, abs=1e-12)
    if integrator != sd.IntegrationMethod.DIRK22:
        assert state.history_states > 0
    expected = run(scene, 30)
    # The state restored from a pickle, into the scene itself and into a scene built again.
    back = pickle.loads(pickle.dumps(state))
    scene.set_state(back)
    assert scene.time == state.time
    assert same(run(scene, 30), expected)
    fresh = tumbling_scene(integrator)
    fresh.set_state(pickle.loads(pickle.dumps(state)))
    assert same(run(fresh, 30), expected)


def test_soft_state_round_trip_continues_bit_for_bit():
    scene = soft_scene()
    run(scene, 10, 1e-3)
    state = pickle.loads(pickle.dumps(scene.get_state()))
    expected = run(scene, 10, 1e-3)
    scene.set_state(state)
    assert same(run(scene, 10, 1e-3), expected)


def test_clone_and_copies_are_independent_and_step_alike():
    scene = tumbling_scene()
    run(scene, 10)
    twin = scene.clone()
    for other in (twin, copy.copy(scene), copy.deepcopy(scene)):
        assert other is not scene and other.time == scene.time
    a = run(scene, 20)
    assert twin.time == pytest.approx(0.05)  # the clone did not move with the scene
    assert same(run(twin, 20), a)


def test_scene_pickle_error_says_what_to_do_instead():
    with pytest.raises(TypeError, match=r"get_state\(\).*clone\(\)"):
        pickle.dumps(tumbling_scene())


def test_set_state_refuses_a_state_of_another_scene_naming_the_field():
    with pytest.raises(ValueError, match=r"^state: rigid: 3 rigid actors, the scene has 2"):
        s = sd.Scene()
        s.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
        s.add_rigid_actor(sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1)))
        s.set_state(tumbling_scene().get_state())
    with pytest.raises(ValueError, match=r"^state: format"):
        pickle.loads(pickle.dumps(tumbling_scene().get_state()).replace(b"superdex-state",
                                                                          b"superdex-stale"))


def test_rigid_setters_change_the_state_and_restart_the_history():
    s = sd.SceneSettings()
    s.gravity = [0, 0, 0]
    scene = sd.Scene(s)
    ball = scene.add_rigid_actor(sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1)))
    scene.step(0.01)
    ball.position = [1, 2, 3]
    ball.velocity = [0.5, 0, 0]
    ball.angular_velocity = [0, 0, 2]
    q = [0, 0, math.sin(0.3), math.cos(0.3)]
    ball.orientation = [2 * c for c in q]  # normalized on assignment
    assert np.allclose(ball.orientation, q, atol=1e-15)
    assert np.allclose(ball.angular_velocity, [0, 0, 2], atol=1e-14)  # kept by the rotation
    assert scene.get_state().history_states == 0
    scene.step(0.1)  # free flight: exact for the implicit integrators' linear motion
    assert np.allclose(ball.position, [1.05, 2, 3], atol=1e-12)
    assert np.allclose(ball.velocity, [0.5, 0, 0], atol=1e-12)
    with pytest.raises(ValueError, match="velocity: must be finite"):
        ball.velocity = [math.nan, 0, 0]
    with pytest.raises(ValueError, match="orientation: must be a finite non-zero quaternion"):
        ball.orientation = [0, 0, 0, 0]
    wall = scene.add_rigid_actor(sd.RigidActorDesc("wall", sd.RigidShape.plane(), dynamic=False))
    with pytest.raises(ValueError, match="position: 'wall' is a static actor"):
        wall.position = [0, 0, 1]


def test_soft_setters_move_the_centre_of_mass_and_the_nodes():
    scene = soft_scene()
    cube = scene.actors[1]
    x0 = cube.node_positions
    cube.position = cube.position + [0.1, 0, 0.2]
    assert np.allclose(cube.node_positions, x0 + [0.1, 0, 0.2], atol=1e-14)
    cube.velocity = [0, 0, -1]
    assert np.allclose(cube.node_velocities, [[0, 0, -1]] * cube.num_nodes, atol=1e-14)
    cube.node_positions = x0
    assert np.array_equal(cube.node_positions, x0)
    with pytest.raises(ValueError, match=r"node_velocities: needs \d+ rows \(one per node\), got 2"):
        cube.node_velocities = [[0, 0, 0], [0, 0, 0]]
