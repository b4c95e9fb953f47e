# blockdem.Model: built in Python, loaded, generated, checked and saved, against `blockdem check` and
# `blockdem generate` on the same input.
import json
import os

import numpy as np
import pytest

import blockdem


def two_courses():
    """The two-course wall of docs/model-file.md, built with the methods."""
    m = blockdem.Model("two courses of a brick wall")
    m.material("brick", density=1800).material("concrete", density=2400)
    m.joint("wall", "wall", "softening", preset="paper_table1", contact_point_spacing=0.03)
    m.joint("wall", "table", "softening", preset="paper_table1", contact_point_spacing=0.03)
    m.contacts(kinds="general")
    for name, lo, hi in (("unit c1-1", (0, 0, 0), (0.25, 0.12, 0.075)), ("unit c1-2", (0.25, 0, 0), (0.5, 0.12, 0.075)),
                         ("unit c2-1", (0, 0, 0.075), (0.125, 0.12, 0.15)),
                         ("unit c2-2", (0.125, 0, 0.075), (0.375, 0.12, 0.15)),
                         ("unit c2-3", (0.375, 0, 0.075), (0.5, 0.12, 0.15))):
        m.block("brick", box=(lo, hi), name=name, group="wall")
    m.block("concrete", box=((-0.25, -0.3, -0.2), (0.75, 0.42, 0)), name="table", group="table", motion="base")
    m.monitor("top", point=(0.25, 0.06, 0.1125))
    m.table("table")
    m.excitation(axis="y", pga_g=0.3)
    m.study(levels=[50, 100], rest=1.0, damping="maxwell", zeta=0.03)
    return m


def test_built_model_checks_as_the_program_checks_its_file(tmp_path, run_program):
    m = two_courses()
    report = m.check()
    assert report["blocks"] == 6 and report["groups"] == ["wall", "table"] and report["errors"] == 0
    assert report["free_mass_kg"] == pytest.approx(1800 * 0.5 * 0.12 * 0.15, rel=1e-12)
    assert report["monitor_points"] == ["top"] and report["table"] == "table"
    path = tmp_path / "wall.json"
    m.save(path)
    program = json.loads(run_program("blockdem", "check", path, "--json"))
    assert report["contact_points"] == program["contact_points"] > 0
    assert report["contact_points_by_group_pair"] == program["contact_points_by_group_pair"]
    again = blockdem.load(path)
    assert again.data == m.data and again.check()["contact_points"] == report["contact_points"]


def test_blocks_from_numpy_vertices_and_faces():
    m = blockdem.Model("tetrahedra and a prism")
    m.material("stone", density=2500, youngs_modulus=1e10, poisson_ratio=0.2)
    m.joint("*", "*", "mohr_coulomb", normal_stiffness=1e10, shear_stiffness=5e9, friction_angle_deg=30)
    # A triangular prism from an array of corners; faces listed in either direction.
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [0, 1, 1]], dtype=float)
    faces = [[0, 1, 2], [3, 4, 5], [0, 1, 4, 3], [1, 2, 5, 4], [0, 3, 5, 2]]
    m.block("stone", vertices=v, faces=faces, name="prism")
    m.block("stone", vertices=v + [0, 0, 1], faces=faces, name="upper prism", max_edge=0.5)
    r = m.check()
    assert r["blocks"] == 2 and r["deformable_blocks"] == 1 and r["tetrahedra"] > 0 and r["nodes"] >= 6
    assert r["free_mass_kg"] == pytest.approx(2 * 2500 * 0.5, rel=1e-12)
    assert r["contact_points"] > 0
    assert m.blocks == 2


def test_generators_write_the_programs_model_files(run_program):
    assert blockdem.generate.wall(courses=6, openings=[(0.75, 1.25, 2, 5)]).data == json.loads(
        run_program("blockdem", "generate", "wall", "--courses", 6, "--opening", "0.75,1.25,2,5"))
    assert blockdem.generate.barrel_vault(rings=9, pushover=True).data == json.loads(
        run_program("blockdem", "generate", "barrel-vault", "--rings", 9, "--pushover"))
    assert blockdem.generate.arch(voussoirs=12).data == json.loads(run_program("blockdem", "generate", "arch", "--voussoirs", 12))
    vault = blockdem.generate.cross_vault()
    assert vault.data == json.loads(run_program("blockdem", "generate", "cross-vault"))
    assert vault.check()["contact_points"] == 14290  # the paper's vault, face-to-face contacts (docs/vault-study.md)


def test_errors_name_the_field_and_the_allowed_values(tmp_path):
    m = two_courses()
    m.data["blocks"][0]["material"] = "bricks"
    with pytest.raises(ValueError, match=r"blocks\[0\].material: no material \"bricks\" \(materials: brick, concrete\)"):
        m.check()
    m = two_courses()
    m.study(levels=[50])
    m.data["study"]["level_percent"] = [10]
    with pytest.raises(ValueError, match="study: unknown key \"level_percent\""):
        m.check()
    with pytest.raises(ValueError, match="give box, or vertices and faces, not both"):
        two_courses().block("brick", box=((0, 0, 0), (1, 1, 1)), vertices=np.zeros((4, 3)), faces=[])
    with pytest.raises(ValueError, match="vertices must be an n x 3 array"):
        two_courses().block("brick", vertices=np.zeros((4, 2)), faces=[[0, 1, 2]])
    bad = tmp_path / "bad.json"
    bad.write_text('{"blockdem_model": 1, "materials": {}, "joints": [], "blocks": [,]}')
    with pytest.raises(ValueError, match="bad.json:1:"):
        blockdem.load(bad)
    with pytest.raises(blockdem.InputError, match="cannot read the model file"):
        blockdem.load(tmp_path / "missing.json")


def test_check_reports_unusable_blocks():
    m = two_courses()
    m.block("brick", box=((0.1, 0.01, 0.01), (0.2, 0.11, 0.06)), name="inside", group="wall")  # overlaps unit c1-1
    r = m.check()
    assert r["errors"] > 0
    assert any(i["severity"] == "error" and "overlap" in i["message"] for i in r["issues"])
