"""Soft (tet FEM) actors through the Python API: meshes, descriptions, errors and physics."""
import math

import numpy as np
import pytest
import superdex as sd

G = 9.81


def soft_cube(name, half=0.1, cells=4, position=(0, 0, 0), **material):
    d = sd.SoftActorDesc(name, sd.make_tet_box([half] * 3, [cells] * 3), sd.SoftMaterial(**material))
    d.mesh_source = "tet box"
    d.position = list(position)
    return d


def ground(k=1e6):
    g = sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False)
    g.contact.penalty_coefficient = k
    return g


def test_tet_mesh_generators_and_arrays(tmp_path):
    box = sd.make_tet_box([0.1, 0.2, 0.3], [2, 1, 3])
    assert (box.num_vertices, box.num_tets) == (3 * 2 * 4, 6 * 2 * 1 * 3)
    assert box.vertices.shape == (24, 3) and box.vertices.dtype == np.float64
    assert box.tets.shape == (36, 4) and np.issubdtype(box.tets.dtype, np.integer)
    assert np.allclose(box.vertices.max(axis=0), [0.1, 0.2, 0.3])
    faces = sd.boundary_faces(box)
    assert faces.shape == (2 * (2 * 1 + 1 * 3 + 2 * 3) * 2, 3)
    # Outward (counter-clockwise seen from outside): the enclosed volume is positive.
    x = box.vertices
    volume = np.einsum("ij,ij->i", x[faces[:, 0]], np.cross(x[faces[:, 1]], x[faces[:, 2]])).sum() / 6
    assert volume == pytest.approx(0.2 * 0.4 * 0.6, rel=1e-12)

    # A mesh from arrays, and a Gmsh round trip.
    tet = sd.TetMesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], [[0, 1, 2, 3]])
    assert (tet.num_vertices, tet.num_tets) == (4, 1)
    path = str(tmp_path / "box.msh")
    sd.write_gmsh22(box, path)
    back = sd.read_tet_mesh(path)
    assert np.array_equal(back.tets, box.tets) and np.allclose(back.vertices, box.vertices)
    with pytest.raises(ValueError, match=r"^/nonexistent/mesh\.msh: cannot open"):
        sd.read_tet_mesh("/nonexistent/mesh.msh")
    with pytest.raises(ValueError, match=r"tets: must be an \(n, 4\) array"):
        sd.TetMesh([[0, 0, 0]], [[0, 1, 2]])
    with pytest.raises(ValueError, match="tets: must hold integers"):
        tet.tets = [[0.0, 1.0, 2.0, 3.0]]
    with pytest.raises(ValueError, match="cells"):
        sd.make_tet_box([0.1, 0.1, 0.1], [0, 1, 1])

    # Sphere, and remeshing its boundary surface.
    ball = sd.make_tet_sphere(0.1, 0.05)
    assert ball.num_tets > 100
    assert np.linalg.norm(ball.vertices, axis=1).max() <= 0.1 + 1e-9
    bf = sd.boundary_faces(ball)
    used = np.unique(bf)
    index = np.full(ball.num_vertices, -1)
    index[used] = np.arange(len(used))
    again = sd.tet_mesh_from_surface(ball.vertices[used], index[bf], 0.05)
    assert again.num_tets > 100
    with pytest.raises(ValueError, match="MeshTetsFromSurface: .*not closed"):
        sd.tet_mesh_from_surface(ball.vertices[used], index[bf][:-1], 0.05)
    with pytest.raises(ValueError, match="edge_length"):
        sd.make_tet_sphere(0.1, 0.0)


def test_descriptions_carry_the_snake_case_names_and_defaults():
    m = sd.SoftMaterial()
    assert (m.youngs_modulus, m.poisson_ratio, m.density, m.stiffness_damping) == (
        1e5, 0.3, 1000.0, 0.0)
    d = sd.SoftActorDesc("jelly")
    assert d.mesh is None and d.mesh_source == ""
    assert d.collider_type == getattr(sd.ColliderType, "None")  # `.None` is a syntax error
    assert d.boundary_element_type == sd.ActorBoundaryElementType.P1Q3
    assert d.contact_layer == "default" and d.constraints == []
    assert list(d.orientation) == [0, 0, 0, 1] and list(d.velocity) == [0, 0, 0]
    assert d.contact.penalty_coefficient == 1e9 and d.grid_sdf.min_grid_resolution >= 2
    d.orientation = [0, 0, 2, 0]
    assert list(d.orientation) == [0, 0, 1, 0]
    d.material.youngs_modulus = 2e5  # nested assignment reaches the description
    assert d.material.youngs_modulus == 2e5
    mesh = sd.make_tet_box([0.1] * 3, [1] * 3)
    d.mesh = mesh
    assert d.mesh is mesh
    c = sd.NodeConstraint([0, 1], [(0.0, [0, 0, 0]), (1.0, [0, 0, 0.2])])
    assert c.nodes == [0, 1] and c.path[1][0] == 1.0
    assert np.allclose(c.displacement(0.25), [0, 0, 0.05])
    assert np.allclose(sd.NodeConstraint([3]).displacement(5.0), [0, 0, 0])


def test_bad_input_raises_value_error_naming_the_field():
    m = sd.SoftMaterial()
    with pytest.raises(ValueError, match=r"^poisson_ratio: must be in \(-1, 0\.5\), got 0\.5$"):
        m.poisson_ratio = 0.5
    assert m.poisson_ratio == 0.3  # rolled back
    with pytest.raises(ValueError, match="^poisson_ratio:"):
        sd.SoftMaterial(poisson_ratio=0.5)
    with pytest.raises(ValueError, match="^youngs_modulus:"):
        m.youngs_modulus = -1
    with pytest.raises(ValueError, match="^stiffness_damping:"):
        m.stiffness_damping = -0.1

    scene = sd.Scene()
    with pytest.raises(ValueError, match="^mesh: a tet mesh is required"):
        scene.add_soft_actor(sd.SoftActorDesc("empty"))
    d = soft_cube("cube", cells=1)
    d.constraints = [sd.NodeConstraint([1000])]
    with pytest.raises(ValueError, match=r"^constraints\[0\]\.nodes: node 1000 does not exist"):
        scene.add_soft_actor(d)
    d = soft_cube("cube", cells=1)
    d.collider_type = sd.ColliderType.Sphere
    with pytest.raises(ValueError, match="^collider_type: Sphere is not available for soft actors"):
        scene.add_soft_actor(d)
    d = soft_cube("cube", cells=1)
    d.constraints = [sd.NodeConstraint([0], [(1.0, [0, 0, 0]), (0.5, [0, 0, 0])])]
    with pytest.raises(ValueError, match="keyframe times must increase"):
        scene.add_soft_actor(d)
    d = soft_cube("cube", cells=1)
    tets = d.mesh.tets
    tets[0, [0, 1]] = tets[0, [1, 0]]
    d.mesh = sd.TetMesh(d.mesh.vertices, tets)
    with pytest.raises(ValueError, match="^mesh: tet box: tet 0 is inverted"):
        scene.add_soft_actor(d)
    assert scene.actors == []


def test_mixing_rigid_and_soft_actors_gives_the_right_names_and_masses():
    s = sd.SceneSettings()
    s.gravity = [0, 0, 0]
    scene = sd.Scene(s)
    jelly = scene.add_soft_actor(soft_cube("jelly", half=0.05, cells=2, position=(0, 0, 1),
                                           density=500))
    ball_desc = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.05))
    ball_desc.mass = 2.0
    ball_desc.position = [1, 0, 1]
    ball = scene.add_rigid_actor(ball_desc)
    floor = scene.add_rigid_actor(sd.RigidActorDesc("floor", sd.RigidShape.plane(), False))
    blob = scene.add_soft_actor(soft_cube("blob", half=0.1, cells=1, position=(-1, 0, 1)),
                                parent=ball)
    assert [a.name for a in scene.actors] == ["jelly", "ball", "floor", "blob"]
    assert [a.index for a in scene.actors] == [0, 1, 2, 3]
    assert [a.is_soft for a in scene.actors] == [True, False, False, True]
    assert [a.dynamic for a in scene.actors] == [True, True, False, True]
    assert jelly.mass == pytest.approx(500 * 0.1 ** 3, rel=1e-12)
    assert ball.mass == 2.0
    assert blob.mass == pytest.approx(1000 * 0.2 ** 3, rel=1e-12)
    for name, mass in (("jelly", 0.5), ("ball", 2.0), ("blob", 8.0)):
        assert scene.actor(name).name == name
        assert scene.actor(name).mass == pytest.approx(mass, rel=1e-12)
    assert scene.actor("floor").index == 2
    assert "'blob' soft" in repr(blob)
    assert np.allclose(blob.position, [-1, 0, 1]) and np.allclose(blob.velocity, 0)
    assert np.allclose(ball.position, [1, 0, 1]) and ball.orientation.shape == (4,)
    assert blob.node_masses.sum() == pytest.approx(blob.mass, rel=1e-12)
    assert blob.num_nodes == 8 and blob.faces.shape == (12, 3)
    assert blob.face_areas.sum() == pytest.approx(6 * 0.2 ** 2, rel=1e-12)
    assert np.array_equal(blob.node_positions, blob.rest_positions)
    assert blob.min_det_f == pytest.approx(1.0, rel=1e-12)
    blob.set_contact_layer("ghost")
    assert blob.contact_layer == "ghost"
    with pytest.raises(TypeError, match="^rotation: 'jelly' is a soft actor"):
        jelly.rotation
    with pytest.raises(TypeError, match="orientation"):
        jelly.orientation
    with pytest.raises(TypeError, match="angular_velocity"):
        jelly.angular_velocity
    with pytest.raises(TypeError, match="^node_positions: 'ball' is a rigid actor"):
        ball.node_positions
    with pytest.raises(TypeError, match="face_tractions"):
        ball.face_tractions()
    # Trajectories: soft actors by their centre of mass, with NaN orientation.
    traj = scene.run(0.02, 0.01)
    assert traj["p"].shape == (3, 4, 3)
    assert np.allclose(traj["p"][-1, 3], [-1, 0, 1]) and np.allclose(traj["p"][-1, 1], [1, 0, 1])
    assert np.isnan(traj["q"][-1, 0]).all() and not np.isnan(traj["q"][-1, 1]).any()
    assert set(scene.energies()) == {"kinetic", "gravity", "contact", "elastic", "total"}


def test_soft_cube_resting_on_a_plane_carries_its_weight():
    s = sd.SceneSettings()
    s.integrator = sd.IntegrationMethod.BackwardEuler
    scene = sd.Scene(s)
    scene.add_rigid_actor(ground(1e6))
    d = soft_cube("cube", position=(0, 0, 0.1005), stiffness_damping=0.02)
    d.contact.penalty_coefficient = 1e6
    cube = scene.add_soft_actor(d)
    min_det_f = math.inf
    for _ in range(200):
        report = scene.step(0.01)
        min_det_f = min(min_det_f, report.min_det_f)
    assert 0.9 < min_det_f < 1.0
    assert cube.min_det_f == pytest.approx(report.min_det_f, rel=1e-12)
    assert np.linalg.norm(cube.velocity) < 1e-4
    tractions = cube.face_tractions()
    assert tractions.shape == (len(cube.faces), 3)
    force = (tractions * cube.face_areas[:, None]).sum(axis=0)
    weight = cube.mass * G
    assert force[2] == pytest.approx(weight, rel=0.01)
    assert np.linalg.norm(force[:2]) < 1e-6 * weight
    # Only the bottom faces (normal -z) carry load, pressing up on the cube.
    loaded = np.abs(tractions[:, 2]) > 0
    x = cube.node_positions
    assert np.all(x[cube.faces[loaded]][:, :, 2] < 0.01)
    assert np.all(tractions[loaded, 2] > 0)
    # The same resultant as the contact samples (normal traction, the step's friction and damping).
    samples = scene.contact_samples()
    total = samples["traction"] + samples["friction"] + samples["damping"]
    assert (samples["weight"][:, None] * total).sum(axis=0) == pytest.approx(
        force, rel=1e-9, abs=1e-9)
    # Each sample names its boundary face: the per-face sums are the face tractions.
    assert np.all(samples["face"] >= 0)
    per_face = np.zeros_like(tractions)
    np.add.at(per_face, samples["face"], samples["weight"][:, None] * total)
    assert per_face / cube.face_areas[:, None] == pytest.approx(tractions, rel=1e-12, abs=1e-9)
    e = scene.energies()
    assert e["elastic"] > 0
    assert e["total"] == pytest.approx(e["kinetic"] + e["gravity"] + e["contact"] + e["elastic"])


def test_pinned_nodes_stay_put_and_driven_nodes_follow_their_path():
    scene = sd.Scene()
    d = soft_cube("hanging", cells=2, position=(0, 0, 0.5))
    z = d.mesh.vertices[:, 2]
    top = [int(i) for i in np.flatnonzero(z > 0.099)]
    bottom = [int(i) for i in np.flatnonzero(z < -0.099)]
    d.constraints = [sd.NodeConstraint(top),
                     sd.NodeConstraint(bottom, [(0.0, [0, 0, 0]), (0.1, [0, 0, -0.02])])]
    block = scene.add_soft_actor(d)
    for _ in range(20):
        scene.step(0.01)
    x, rest = block.node_positions, block.rest_positions
    assert np.array_equal(x[top], rest[top])
    assert np.allclose(x[bottom] - rest[bottom], [0, 0, -0.02], atol=1e-14)
    assert np.all(block.node_velocities[top] == 0)
    free = np.setdiff1d(np.arange(block.num_nodes), top + bottom)
    assert np.all(x[free, 2] < rest[free, 2])  # stretched downward between the two sets
    assert block.min_det_f > 0.5


def test_rigid_sphere_bounces_on_a_soft_sdf_collider_and_stops_above_the_plane():
    s = sd.SceneSettings()
    s.integrator = sd.IntegrationMethod.BackwardEuler
    scene = sd.Scene(s)
    scene.add_rigid_actor(sd.RigidActorDesc("ground", sd.RigidShape.plane(), dynamic=False))
    d = sd.SoftActorDesc("pad", sd.make_tet_box([0.1, 0.1, 0.05], [3, 3, 2]),
                         sd.SoftMaterial(youngs_modulus=1e5, stiffness_damping=0.01))
    d.position = [0, 0, 0.0505]
    d.contact.penalty_coefficient = 1e7
    d.collider_type = sd.ColliderType.Sdf
    d.grid_sdf.min_grid_resolution = 16
    pad = scene.add_soft_actor(d)
    assert any("soft collider grid SDF" in n for n in scene.notices())
    b = sd.RigidActorDesc("ball", sd.RigidShape.sphere(0.04))
    b.mass = 0.5
    b.position = [0, 0, 0.2]
    b.contact.penalty_coefficient = 1e7
    ball = scene.add_rigid_actor(b)
    rebound, lowest, on_pad = 0.0, math.inf, 0
    for _ in range(100):
        report = scene.step(0.005)
        lowest = min(lowest, ball.position[2])
        rebound = max(rebound, ball.velocity[2])
        samples = scene.contact_samples()
        on_pad += np.count_nonzero((samples["colliding"] == ball.index) &
                                   (samples["collider"] == pad.index))
    assert on_pad > 0  # the ball met the pad's SDF collider
    assert rebound > 0.1  # it bounced (it hit at about 1 m/s)
    assert np.linalg.norm(ball.velocity) < 0.02  # and came to rest
    # On top of the pad (top face at 0.1 m), well above the plane.
    assert lowest - 0.04 > 0.08
    assert ball.position[2] - 0.04 == pytest.approx(0.1, abs=0.012)
    assert report.min_det_f > 0.9


def test_a_shell_plate_clamped_on_one_edge_sags_as_kirchhoffs_plate():
    # A 1 m square steel plate (h = 1 cm, nu = 0) clamped along x = -0.5 under its weight: the
    # tip deflection q L^4 / (8 D) within 2 % on an 8 x 8 mesh (1.6 % measured in C++), a static
    # solve by Backward Euler steps of 100 s.
    E, h, rho = 2e11, 0.01, 7800.0
    mesh = sd.make_rectangle_mesh([1.0, 1.0], [8, 8])
    assert mesh.num_vertices == 81 and mesh.num_faces == 128
    d = sd.ShellActorDesc("plate", mesh, sd.ShellMaterial(youngs_modulus=E, poisson_ratio=0.0,
                                                          density=rho, thickness=h))
    assert d.bending == sd.ShellBendingModel.Midedge
    x = mesh.vertices
    d.clamped_nodes = [int(i) for i in np.flatnonzero(x[:, 0] < -0.5 + 1e-12)]
    scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler))
    plate = scene.add_shell_actor(d)
    for _ in range(3):
        scene.step(100.0)
    q = rho * h * G
    expected = q / (8 * E * h**3 / 12)
    tip = -plate.node_positions[x[:, 0] > 0.5 - 1e-12, 2].mean()
    assert abs(tip / expected - 1) < 0.02
    assert not plate.is_soft and plate.node_velocities.shape == (81, 3)


def test_bad_shells_are_refused_naming_the_field():
    scene = sd.Scene()
    d = sd.ShellActorDesc("sheet", sd.make_rectangle_mesh([0.2, 0.2], [2, 2]))
    with pytest.raises(ValueError, match=r"^thickness: must be finite and > 0"):
        d.material.thickness = -1.0  # checked when set
    d = sd.ShellActorDesc("sheet", sd.TriangleMesh([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]]))
    with pytest.raises(ValueError, match=r"triangle 0 is degenerate"):
        scene.add_shell_actor(d)
    with pytest.raises(ValueError, match=r"^size: must be > 0"):
        sd.make_rectangle_mesh([0.0, 1.0], [2, 2])


def test_a_sheet_rests_on_a_pinned_sheet_through_their_point_clouds():
    # Two 10 cm sheets (PointCloud colliders, L_B = 1 cm): the lower pinned at z = 0, the upper
    # dropped from 2 cm. The upper comes to rest inside the spheres' band: its mean height
    # between L_B - eps (penalty depth at most the smoothing width) and L_B + delta, every step
    # converged. A ratio r <= 1 is refused naming the field.
    scene = sd.Scene(sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler))
    lower = sd.ShellActorDesc("lower", sd.make_rectangle_mesh([0.1, 0.1], [6, 6]))
    lower.constraints = [sd.NodeConstraint(list(range(lower.mesh.num_vertices)))]
    upper = sd.ShellActorDesc("upper", sd.make_rectangle_mesh([0.06, 0.06], [4, 4]))
    upper.position = [0, 0, 0.02]
    for d in (lower, upper):
        d.material.youngs_modulus = 1e7
        d.contact.penalty_coefficient = 1e6
        d.point_cloud.radius = 0.01
    scene.add_shell_actor(lower)
    sheet = scene.add_shell_actor(upper)
    for _ in range(150):
        report = scene.step(2e-3)
        assert report.status == "Converged"
    z = sheet.node_positions[:, 2].mean()
    assert 0.01 - 0.005 < z < 0.01 + 0.001
    assert np.linalg.norm(sheet.node_velocities, axis=1).max() < 0.05
    bad = sd.ShellActorDesc("bad", sd.make_rectangle_mesh([0.1, 0.1], [2, 2]))
    with pytest.raises(ValueError, match=r"^self_contact_exclusion_ratio: must be > 1, got 1"):
        bad.point_cloud.self_contact_exclusion_ratio = 1.0  # checked when set
    bad.collider_type = sd.ColliderType.Sdf
    with pytest.raises(ValueError, match=r"^collider_type: Sdf is not available for shell"):
        scene.add_shell_actor(bad)


def test_a_shell_plate_carries_a_tip_line_load_as_kirchhoffs_plate():
    # A 1 m square steel plate (h = 1 cm, nu = 0) clamped along x = -0.5 and loaded by 10 N
    # spread along its free edge (NodeLoad, lumped by the trapezoid rule), no gravity: the tip
    # deflection F L^3 / (3 D) within 3 % on 8 x 8 cells.
    E, h, F = 2e11, 0.01, 10.0
    mesh = sd.make_rectangle_mesh([1.0, 1.0], [8, 8])
    d = sd.ShellActorDesc("plate", mesh, sd.ShellMaterial(youngs_modulus=E, poisson_ratio=0.0,
                                                          density=7800.0, thickness=h))
    x = mesh.vertices
    d.clamped_nodes = [int(i) for i in np.flatnonzero(x[:, 0] < -0.5 + 1e-12)]
    tip = np.flatnonzero(x[:, 0] > 0.5 - 1e-12)
    ends = [int(i) for i in tip if abs(abs(x[i, 1]) - 0.5) < 1e-12]
    inner = [int(i) for i in tip if int(i) not in ends]
    d.loads = [sd.NodeLoad(inner, [(0.0, [0, 0, F / 8])]), sd.NodeLoad(ends, [(0.0, [0, 0, F / 16])])]
    assert len(d.loads) == 2 and d.loads[0].force[0][0] == 0.0
    settings = sd.SceneSettings(integrator=sd.IntegrationMethod.BackwardEuler)
    settings.gravity = [0, 0, 0]
    scene = sd.Scene(settings)
    plate = scene.add_shell_actor(d)
    for _ in range(3):
        scene.step(100.0)
    expected = F / (3 * E * h**3 / 12)
    w = plate.node_positions[tip, 2].mean()
    assert abs(w / expected - 1) < 0.03
    d.loads = [sd.NodeLoad([10**6], [(0.0, [0, 0, 1])])]
    with pytest.raises(ValueError, match=r"^loads\[0\]\.nodes: node 1000000 does not exist"):
        scene.add_shell_actor(d)


def test_disk_and_annulus_meshes():
    d = sd.make_disk_mesh(0.5, 3)
    assert d.num_vertices == 1 + 6 + 12 + 18 and d.num_faces == 54
    assert np.allclose(d.vertices[0], 0) and np.allclose(np.linalg.norm(d.vertices[-18:], axis=1), 0.5)
    a = sd.make_annulus_mesh(6.0, 10.0, [4, 32])
    assert a.num_vertices == 5 * 33 and a.num_faces == 256
    with pytest.raises(ValueError, match=r"^rings: must be in \[1, 500\]"):
        sd.make_disk_mesh(0.5, 0)
    with pytest.raises(ValueError, match=r"^radii: must be 0 < inner < outer"):
        sd.make_annulus_mesh(10.0, 6.0, [4, 32])
