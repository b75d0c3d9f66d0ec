"""The Python API: names, defaults and enums against the spec's tables, and its errors."""
import math
import os
import re

import pytest
import superdex as sd

SOURCE = os.environ.get("SUPERDEX_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_version_is_the_cmake_project_version():
    with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
        version = re.search(r"project\(superdex VERSION (\S+)", f.read()).group(1)
    assert sd.__version__ == version


def test_contact_params_defaults_match_the_spec_table():
    c = sd.ContactParams()
    assert c.penalty_coefficient == 1e9
    assert c.penalty_smoothing_half_distance == 0.005
    assert c.penalty_threshold_default == 0.001
    assert c.penalty_threshold_extra_padding == 0.0
    assert c.friction_with_collider_normal is True
    assert c.max_alignment_normals == 0.0
    assert c.viscous_friction_coefficient == 0.0
    assert c.coulomb_friction_coefficient == 0.5
    assert c.friction_falloff_vel == 0.01
    assert c.normal_viscous_damping_coefficient == 0.0
    assert c.distance_error_bound == 0.0
    assert c.colliding_penalty_length_scale == 1.0


def test_other_parameter_defaults():
    e = sd.ExperimentalEvalParams()
    assert (e.explicit_normals, e.implicit_normal_force_for_dissipation, e.fade_friction) == (
        False, False, True)
    p = sd.PointCloudColliderParams()
    assert (p.radius, p.self_contact_exclusion_ratio, p.spatial_hash_load_factor) == (
        0.01, 1.5, 0.0625)
    assert p.self_contact is False and p.collider_triangle_element_type is None
    g = sd.GridSdfParams()
    assert g.min_grid_resolution >= 2 and g.resolution_delta > 0


def test_enums_carry_the_spec_names():
    # The spec's values, and Capsule: superdex's analytic capsule field (docs/parameters.md).
    assert set(sd.ColliderType.__members__) == {
        "Auto", "None", "Sphere", "Box", "Plane", "Mesh", "Sdf", "PointCloud", "Capsule"}
    assert set(sd.ActorBoundaryElementType.__members__) == {
        "P1Q1", "P1Q3", "P1Q6", "ExperimentalP1Q7", "ExperimentalP1Q12", "ExperimentalP1Q16"}
    assert set(sd.IntegrationMethod.__members__) == {
        "BackwardEuler", "BDF2", "BDF3", "DIRK22", "DIRK23", "DIRK33", "SymplecticDIRK12",
        "SymplecticDIRK22"}
    assert set(sd.IncludeNestedActors.__members__) == {"No", "Yes"}
    assert sd.SceneSettings().integrator == sd.IntegrationMethod.BDF2


def test_help_shows_units_and_defaults():
    doc = sd.ContactParams.penalty_coefficient.__doc__
    assert "[Pa/m]" in doc and "Default 1e9" in doc
    assert "[s/m]" in sd.ContactParams.normal_viscous_damping_coefficient.__doc__


def test_run_summary_figures_and_their_units():
    f = sd.load_scene(os.path.join(SOURCE, "scenes", "data", "drop.json"))
    s = sd.run_scene(f, dt=0.005, duration=0.05, out="", vtk="")
    assert s.steps == 10 and s.converged == 10 and s.stopped == s.diverged == 0
    assert s.stages >= s.steps and s.krylov_fallbacks == 0
    assert s.simulated_seconds == pytest.approx(0.05) and s.wall_seconds >= 0
    assert s.trajectory_path == "" and s.vtk_frames == 0 and math.isinf(s.min_det_f)
    assert list(s.expectation_failures) == []
    assert "[m]" in sd.RunSummary.max_penetration.__doc__
    assert "[s]" in sd.RunSummary.wall_seconds.__doc__
    assert "[J]" in sd.RunSummary.initial_energy.__doc__


def test_bad_values_raise_value_error_naming_the_field_and_rule():
    c = sd.ContactParams()
    with pytest.raises(ValueError, match=r"^penalty_coefficient: must be > 0, got -3$"):
        c.penalty_coefficient = -3
    assert c.penalty_coefficient == 1e9  # rolled back
    with pytest.raises(ValueError, match="max_alignment_normals"):
        c.max_alignment_normals = 1.5
    s = sd.SceneSettings()
    s.experimental_eval_params.explicit_normals = True
    with pytest.raises(ValueError, match=r"the combination \(true, true\) is unsupported"):
        s.experimental_eval_params.implicit_normal_force_for_dissipation = True
    assert s.experimental_eval_params.implicit_normal_force_for_dissipation is False
    with pytest.raises(ValueError, match="stage_solver"):
        sd.SceneSettings().stage_solver = "lbfgs"
    w = sd.SceneSettings()
    assert w.warm_start is True
    w.warm_start = False
    assert w.warm_start is False
    assert w.closed_form_free_stages is True
    w.closed_form_free_stages = False
    assert w.closed_form_free_stages is False
    with pytest.raises(ValueError, match="no actor named"):
        sd.Scene().actor("nobody")


def test_solver_failure_raises_runtime_error():
    s = sd.SceneSettings()
    s.solver.max_iterations = 1
    s.solver.absolute_tolerance = 0.0
    s.solver.relative_tolerance = 0.0
    s.solver.step_tolerance = 0.0
    s.closed_form_free_stages = False  # a free ball's stage would need no Newton iteration
    scene = sd.Scene(s)
    d = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1))
    d.mass = 1.0
    d.angular_velocity = [0.0, 3.0, 1.0]
    scene.add_rigid_actor(d)
    with pytest.raises(RuntimeError, match="Stopped"):
        scene.step(0.01)
    report = scene.step(0.01, check=False)
    assert report.status == "Stopped"
    assert report.free_stages == 0


def test_free_flight_is_solved_in_closed_form():
    scene = sd.Scene(sd.SceneSettings())
    d = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1))
    d.mass = 1.0
    d.angular_velocity = [0.0, 3.0, 1.0]
    scene.add_rigid_actor(d)
    report = scene.step(0.01)
    assert report.status == "Converged"
    assert report.newton_iterations == 0
    assert report.free_stages == report.stages == 1


def test_hunt_crossley_helpers_are_inverse():
    for v in (0.5, 2.0):
        for e in (0.2, 0.6, 0.95):
            cn = sd.hunt_crossley_damping_from_restitution(e, v)
            assert sd.hunt_crossley_restitution_from_damping(cn, v) == pytest.approx(e, rel=1e-12)
    assert math.isnan(sd.hunt_crossley_damping_from_restitution(0.0, 1.0))


def test_load_and_run_a_shipped_scene_with_progress():
    f = sd.load_scene(os.path.join(SOURCE, "scenes", "data", "slide_to_rest.json"))
    assert f.actor_names == ["ground", "box"]
    seen = []
    traj = f.scene.run(0.05, f.dt, every=10, progress=lambda frac, r: seen.append(frac))
    assert seen[-1] == pytest.approx(1.0)
    assert traj["p"].shape == (len(traj["t"]), 2, 3)
    assert traj["t"][0] == 0.0 and traj["t"][-1] == pytest.approx(0.05)
    with pytest.raises(ValueError, match="cannot open"):
        sd.load_scene("/nonexistent/scene.json")


def test_filtering_methods():
    scene = sd.Scene()
    ground = scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), False))
    arm = scene.add_rigid_actor(sd.RigidActorDesc("arm", sd.RigidShape.box([0.2, 0.2, 0.2])))
    hand = scene.add_rigid_actor(sd.RigidActorDesc("hand", sd.RigidShape.box([0.1, 0.1, 0.1])),
                                 parent=arm)
    scene.enable_actor_contact_symmetric(arm, arm, False, sd.IncludeNestedActors.Yes)
    assert not scene.contact_allowed(arm, hand) and not scene.contact_allowed(hand, arm)
    assert scene.contact_allowed(hand, ground)
    hand.set_contact_layer("ghost")
    assert hand.contact_layer == "ghost"
    scene.enable_layer_contact_asymmetric("ghost", "default", False)
    assert not scene.contact_allowed(hand, ground) and scene.contact_allowed(ground, hand)


def test_mesh_and_sdf_colliders_from_python(tmp_path):
    obj = tmp_path / "tet.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    scene = sd.Scene()
    d = sd.RigidActorDesc("rock", sd.RigidShape.mesh(str(obj), scale=0.2), dynamic=False)
    d.grid_sdf.min_grid_resolution = 8
    rock = scene.add_rigid_actor(d)
    assert rock.dynamic is False
    open_obj = tmp_path / "open.obj"
    open_obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n")
    bad = sd.RigidActorDesc("bad", sd.RigidShape.mesh(str(open_obj)), dynamic=False)
    bad.collider_type = sd.ColliderType.Mesh
    with pytest.raises(ValueError, match="not closed"):
        scene.add_rigid_actor(bad)


def test_part_line_search_setting_changes_the_path_not_the_solution():
    def run(parts):
        s = sd.SceneSettings()
        s.solver.part_line_search = parts
        scene = sd.Scene(s)
        scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), False))
        for name, x, z in (("a", 0.0, 0.12), ("b", 2.0, 0.6)):
            d = sd.RigidActorDesc(name, sd.RigidShape.box([0.2, 0.2, 0.2]))
            d.position = [x, 0.0, z]
            d.velocity = [0.5, 0.0, 0.0]
            scene.add_rigid_actor(d)
        traj = scene.run(0.6, 0.01)
        return traj["p"][-1], s.solver.part_line_search

    (p_on, on), (p_off, off) = run(True), run(False)
    assert on and not off
    # Two boxes that never touch (one set down, one dropped onto the plane, where it bounces):
    # the solutions agree to the solver's tolerance whichever line search found them.
    assert abs(p_on - p_off).max() < 1e-7
    assert p_on[1, 2] == pytest.approx(0.1, abs=1e-3)


def test_run_refuses_step_counts_beyond_the_limit():
    # duration / dt used to wrap the int step count (4294967.296 s at 1 ms ran one step).
    scene = sd.Scene()
    scene.add_rigid_actor(sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.1)))
    for duration in (4294967.296, 1e308):
        with pytest.raises(ValueError, match=r"^duration / dt: .* steps \(limit 1e\+08\)"):
            scene.run(duration, 1e-3)
    assert scene.run(0.01, 1e-3)["t"].shape == (11,)


def test_scene_settings_properties_are_the_docs_table_rows():
    # docs/parameters.md is generated from kSceneSettingsFields (a C++ test keeps it current).
    with open(os.path.join(SOURCE, "docs", "parameters.md"), encoding="utf-8") as f:
        docs = f.read()
    section = docs.split("## SceneSettings", 1)[1].split("\n## ", 1)[0]
    names = re.findall(r"^\| `(\w+)` \|", section, re.M)
    assert names == ["gravity", "integrator", "solver", "stage_solver",
                     "experimental_eval_params", "warm_start", "closed_form_free_stages"]
    s = sd.SceneSettings()
    for name in names:
        assert isinstance(getattr(type(s), name), property)
        assert name + "=" in repr(s)
    assert list(s.gravity) == [0.0, 0.0, -9.81]
    with pytest.raises(ValueError, match=r"^gravity: must be finite, got \[0, nan, 0\]$"):
        s.gravity = [0.0, float("nan"), 0.0]
    assert list(s.gravity) == [0.0, 0.0, -9.81]  # rolled back
    s.stage_solver = "Ceres"  # a capitalized name, as scene files accept it
    assert s.stage_solver == "ceres"
    s.solver.max_iterations = 3  # the nested struct itself, not a copy
    assert s.solver.max_iterations == 3
    t = sd.SceneSettings(integrator=sd.IntegrationMethod.DIRK22, warm_start=False)
    assert t.integrator == sd.IntegrationMethod.DIRK22 and t.warm_start is False


def test_a_capsule_shape_collides_with_its_analytic_field():
    shape = sd.RigidShape.capsule(0.05, 0.2, surface_resolution=8)
    assert shape.kind == "capsule"
    with pytest.raises(ValueError, match=r"^shape.radius: must be > 0, got -0.05$"):
        sd.RigidShape.capsule(-0.05, 0.2)
    with pytest.raises(ValueError, match="half_length: must be > 0"):
        sd.RigidShape.capsule(0.05, 0.0)
    # Standing on an end cap it rests as a sphere of its radius and weight does on its own:
    # the same hemisphere in contact (its centre 0.1 m below the capsule's).
    heights = []
    for name, s, lift in (("capsule", shape, 0.1), ("sphere", sd.RigidShape.sphere(0.05), 0.0)):
        scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler))
        scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
        d = sd.RigidActorDesc(name, s)
        d.position = [0, 0, 0.0505 + lift]  # just clear of the ground
        d.mass = 1.0
        actor = scene.add_rigid_actor(d)
        for _ in range(200):
            scene.step(0.01)
        heights.append(actor.position[2] - lift)
    assert heights[1] < 0.05
    assert abs(heights[0] - heights[1]) < 1e-5
