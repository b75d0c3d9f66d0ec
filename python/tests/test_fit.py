"""Sensitivities and fitting through the Python API."""
import os

import numpy as np
import pytest
import superdex as sd

SRC = os.environ.get("SUPERDEX_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
THROW = os.path.join(SRC, "scenes", "data", "fit_throw.json")


def synthetic(mu, cn):
    """The thrown box with the box at (mu, cn): times and centres of mass every 10 steps."""
    times, com = [], []
    s = sd.load_scene(THROW)
    steps = int(round(s.duration / s.dt))
    c = s.scene.actor("box").contact_params
    c.coulomb_friction_coefficient = mu
    c.normal_viscous_damping_coefficient = cn
    s.scene.actor("box").contact_params = c
    for n in range(1, steps + 1):
        s.scene.step(s.dt)
        if n % 10 == 0:
            times.append(s.scene.time)
            com.append(s.scene.actor("box").position)
    return np.array(times), np.array(com)


def test_fit_from_arrays_recovers_mu_and_cn():
    times, com = synthetic(0.4, 4.0)
    r = sd.fit(sd.load_scene(THROW), ["box.coulomb_friction_coefficient",
                                      "box.normal_viscous_damping_coefficient"],
               times=times, positions={"box": com})
    assert r.converged, r.message
    assert r.fitted == pytest.approx([0.4, 4.0], rel=1e-6)
    assert r.initial == pytest.approx([0.6, 1.0])


def test_fit_from_the_shipped_measurement():
    r = sd.fit(sd.load_scene(THROW), ["box.coulomb_friction_coefficient",
                                      "box.normal_viscous_damping_coefficient"],
               observed=os.path.join(SRC, "scenes", "data", "fit_throw_observed.jsonl"))
    assert r.converged
    # Made at (0.4, 4) with 1 mm noise: within three standard errors.
    assert abs(r.fitted[0] - 0.4) < 3 * r.standard_error[0]
    assert abs(r.fitted[1] - 4.0) < 3 * r.standard_error[1]
    assert 0.8e-3 < r.rms_residual < 1.2e-3


def test_sensitivity_matches_differences():
    def final_x(mu):
        f = sd.load_scene(THROW)
        c = f.scene.actor("box").contact_params
        c.coulomb_friction_coefficient = mu
        f.scene.actor("box").contact_params = c
        for _ in range(100):
            f.scene.step(f.dt)
        return f.scene.actor("box").position

    f = sd.load_scene(THROW)
    sens = sd.ForwardSensitivity(f.scene, ["box.coulomb_friction_coefficient"])
    for _ in range(100):
        sens.step(f.dt)
    J = sens.com_jacobian("box")
    assert J.shape == (3, 1)
    h = 1e-5 * 0.6
    fd = (final_x(0.6 + h) - final_x(0.6 - h)) / (2 * h)
    assert np.allclose(J[:, 0], fd, rtol=1e-4, atol=1e-6 * np.abs(fd).max())


def test_fit_errors():
    f = sd.load_scene(THROW)
    with pytest.raises(ValueError, match="unknown name 'grip'"):
        sd.fit(f, ["box.grip"], times=[0.02], positions={"box": [[0, 0, 0.1]]})
    with pytest.raises(ValueError, match="one row per time"):
        sd.fit(f, ["box.coulomb_friction_coefficient"], times=[0.02, 0.04], positions={"box": [[0, 0, 0.1]]})
    with pytest.raises(ValueError, match="give a trajectory file, or times and positions"):
        sd.fit(f, ["box.coulomb_friction_coefficient"])
    with pytest.raises(ValueError, match="no actor named"):
        sd.ForwardSensitivity(f.scene, ["crate.density"])


def test_adjoint_gradient_and_lbfgs_fit():
    times, com = synthetic(0.4, 4.0)
    names = ["box.coulomb_friction_coefficient", "box.velocity.x"]
    g = sd.trajectory_gradient(sd.load_scene(THROW), names, times=times, positions={"box": com})
    assert g.gradient.shape == (2,)
    assert g.values == pytest.approx([0.6, 2.0])
    # d cost / dμ against central differences of the cost (tests/scenes/test_fit.cpp states the
    # accuracy).
    h = 1e-5 * 0.6
    costs = []
    for sign in (1, -1):
        f = sd.load_scene(THROW)
        c = f.scene.actor("box").contact_params
        c.coulomb_friction_coefficient = 0.6 + sign * h
        f.scene.actor("box").contact_params = c
        costs.append(sd.trajectory_gradient(f, names, times=times, positions={"box": com}).cost)
    assert g.gradient[0] == pytest.approx((costs[0] - costs[1]) / (2 * h), rel=1e-4)
    assert g.gradient[1] != 0.0
    r = sd.fit(sd.load_scene(THROW), ["box.coulomb_friction_coefficient",
                                      "box.normal_viscous_damping_coefficient"],
               times=times, positions={"box": com}, method="lbfgs", max_iterations=100)
    assert r.converged, r.message
    assert r.fitted == pytest.approx([0.4, 4.0], rel=1e-2)
    with pytest.raises(ValueError, match="method: must be 'lm' or 'lbfgs'"):
        sd.fit(sd.load_scene(THROW), names, times=times, positions={"box": com}, method="newton")


def test_a_truncated_last_line_is_skipped_with_a_warning(tmp_path):
    # The trajectory of a killed writer ends in a partial line: reported and skipped.
    with open(os.path.join(SRC, "scenes", "data", "fit_throw_observed.jsonl")) as f:
        text = f.read()
    path = tmp_path / "killed.jsonl"
    path.write_text(text + '{"t": 0.42, "actors": [null, {"p": [0.3')
    with pytest.warns(UserWarning, match=r"killed\.jsonl:23: the last line is truncated"):
        g = sd.trajectory_gradient(sd.load_scene(THROW), ["box.coulomb_friction_coefficient"],
                                   observed=str(path))
    assert g.residuals == 63
