"""The Python API's consistency: unique names, shapes checked when made, contact parameters
changed in place, one name for the initial velocity, notices for coefficients that combine to 0."""
import pytest
import superdex as sd


def box(name, **contact):
    d = sd.RigidActorDesc(name, sd.RigidShape.box([0.2, 0.2, 0.2]))
    d.mass = 1.0
    d.position = [0, 0, 0.1]
    for k, v in contact.items():
        setattr(d.contact, k, v)
    return d


def test_a_second_actor_of_the_same_name_is_refused():
    scene = sd.Scene()
    scene.add_rigid_actor(box("box"))
    with pytest.raises(ValueError, match=r'^name: duplicate actor name "box"'):
        scene.add_rigid_actor(box("box"))
    assert len(scene.actors) == 1


def test_shapes_are_checked_when_made():
    with pytest.raises(ValueError, match=r"^shape\.radius: must be > 0, got -1"):
        sd.RigidShape.sphere(-1)
    with pytest.raises(ValueError, match=r"surface_resolution"):
        sd.RigidShape.sphere(0.1, surface_resolution=9)
    with pytest.raises(ValueError, match=r"half_extents: must be > 0"):
        sd.RigidShape.box([0.2, 0, 0.2])
    with pytest.raises(ValueError, match=r"^scale: must be > 0"):
        sd.RigidShape.mesh("unused.obj", scale=-1)
    assert sd.RigidShape.sphere(0.1).kind == "sphere"


def test_contact_parameters_change_in_place_and_validate():
    scene = sd.Scene()
    ground = scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
    b = scene.add_rigid_actor(box("box"))
    b.contact_params.coulomb_friction_coefficient = 0.0
    assert b.contact_params.coulomb_friction_coefficient == 0.0
    assert ground.contact_params.coulomb_friction_coefficient == 0.5
    with pytest.raises(ValueError, match="penalty_coefficient: must be > 0"):
        b.contact_params.penalty_coefficient = -3
    assert b.contact_params.penalty_coefficient == 1e9  # unchanged
    kept = b.contact_params.copy()  # a ContactParams, no longer tied to the actor
    assert isinstance(kept, sd.ContactParams)
    b.contact_params.coulomb_friction_coefficient = 0.25
    assert kept.coulomb_friction_coefficient == 0.0
    ground.contact_params = b.contact_params  # another actor's values
    assert ground.contact_params.coulomb_friction_coefficient == 0.25
    b.contact_params = sd.ContactParams()
    assert b.contact_params.coulomb_friction_coefficient == 0.5


def test_a_coefficient_set_on_one_actor_only_gives_a_notice():
    scene = sd.Scene()
    scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
    scene.add_rigid_actor(box("box", normal_viscous_damping_coefficient=2.0))
    notes = [n for n in scene.notices() if "normal_viscous_damping_coefficient" in n]
    assert len(notes) == 1 and "set on 'box' but 0 on 'ground'" in notes[0]
    # A 0 against the default (0.5) is the usual frictionless pair: no notice.
    scene.actor("ground").contact_params.coulomb_friction_coefficient = 0.0
    assert not any("coulomb_friction_coefficient" in n for n in scene.notices())
    scene.actor("box").contact_params.coulomb_friction_coefficient = 0.8
    assert any("coulomb_friction_coefficient: set on 'box' but 0 on 'ground'" in n
               for n in scene.notices())


def test_rigid_and_soft_descriptions_share_the_velocity_name():
    soft = sd.SoftActorDesc("jelly", sd.make_tet_box([0.1] * 3, [1] * 3))
    soft.velocity = [1, 0, 0]
    assert list(soft.velocity) == [1, 0, 0]
    assert not hasattr(soft, "linear_velocity")
    assert hasattr(sd.RigidActorDesc("b", sd.RigidShape.sphere(0.1)), "velocity")
