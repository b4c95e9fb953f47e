# blockdem.Simulation: the study's steps one call at a time, bit for bit the study's run; the state as numpy views;
# contact forces in equilibrium with the weight; the GIL released while it runs.
import threading
import time

import numpy as np
import pytest

import blockdem
from test_model import two_courses


def test_the_steps_of_the_study_give_the_studys_history_bit_for_bit(tmp_path):
    m = two_courses()
    study = blockdem.run(m, out=tmp_path, levels=[100], window=(2, 3), rest=0.5, progress=False)
    level = study.level(100)
    sim = blockdem.Simulation(m, window=(2, 3), progress=False)
    settled = sim.settle()
    assert settled["converged"] and settled["steps"] == study.report["settling"]["steps"]
    sim.set_record(level=100)
    assert sim.dt == study.report["timestep"]["dt_s"]
    t0, h = sim.time, 0.005
    uy = [sim.monitor_displacements()[0, 1]]
    k = 1
    while sim.time < t0 + level["duration_s"] - 0.5 * sim.dt:
        sim.run(min(t0 + k * h, t0 + level["duration_s"]) - sim.time)
        uy.append(sim.monitor_displacements()[0, 1])
        k += 1
    history = study.history(100)
    assert len(uy) == len(history["top_uy"])
    assert np.allclose(uy, history["top_uy"], rtol=1e-8, atol=1e-15)  # the file has 9 significant digits
    assert sim.steps == level["steps"]  # the dynamic run's
    assert sim.energy()["balance_error"] == level["energy"]["balance_error"]
    assert max(uy) == level["peaks"]["top_uy"]["max"]


def test_contacts_carry_the_weight_after_settling():
    m = two_courses()
    sim = blockdem.Simulation(m, progress=False)
    sim.settle()
    c = sim.contacts()
    n = len(c["area"])
    assert n == sim.contacts()["position"].shape[0] > 0
    for key in ("position", "normal", "force"):
        assert c[key].shape == (n, 3)
    assert np.allclose(np.linalg.norm(c["normal"], axis=1), 1)
    assert c["block_a"].dtype == np.int64 and c["cracked"].dtype == bool
    table = sim.block_names.index("table")
    on_table = np.where((c["block_b"] == table)[:, None], c["force"], -c["force"])[(c["block_a"] == table) | (c["block_b"] == table)]
    weight = 1800 * 0.5 * 0.12 * 0.15 * 9.81
    assert on_table[:, 2].sum() == pytest.approx(-weight, rel=1e-3)
    assert np.all(c["normal_stress"][(c["block_a"] == table) | (c["block_b"] == table)] > 0)  # compression positive
    assert c["area"].sum() > 0 and np.all(c["damage"] == 0)


def test_state_arrays_are_live_read_only_views():
    m = two_courses()
    sim = blockdem.Simulation(m, progress=False)
    p = sim.block_positions
    assert p.shape == (6, 3) and not p.flags.writeable and not p.flags.owndata
    with pytest.raises(ValueError):
        p[0, 0] = 1.0
    z0 = p[0, 2]
    sim.settle()
    sim.set_record(level=100)
    sim.run(0.3)
    assert p[0, 2] != z0  # the same view, current
    q = sim.block_orientations
    assert q.shape == (6, 4) and np.allclose(np.linalg.norm(q, axis=1), 1)
    assert sim.block_velocities.shape == sim.block_angular_velocities.shape == (6, 3)
    assert sim.block_masses[0] > 0 and sim.node_positions.shape == (0, 3)


def test_deformable_blocks_expose_nodes_and_element_stresses():
    m = blockdem.Model("a deformable block on a rigid base")
    m.material("stone", density=2500, youngs_modulus=1e9, poisson_ratio=0.2)
    m.joint("*", "*", "mohr_coulomb", normal_stiffness=1e11, shear_stiffness=5e10, friction_angle_deg=35)
    m.block("stone", box=((0, 0, -0.2), (1, 1, 0)), name="base", motion="base")
    m.block("stone", box=((0.2, 0.2, 0), (0.8, 0.8, 0.6)), name="pier", max_edge=0.3)
    sim = blockdem.Simulation(m, progress=False, settle_tolerance=1e-6)
    sim.settle()
    x, t, s = sim.node_positions, sim.tetrahedra, sim.element_stresses
    assert x.shape[1] == 3 and t.shape[1] == 4 and s.shape == (t.shape[0], 6)
    assert t.max() < x.shape[0] and np.all(sim.node_blocks == 1)
    # Under its own weight the pier's mean vertical stress is -rho g h / 2 (tension positive).
    assert s[:, 2].mean() == pytest.approx(-2500 * 9.81 * 0.6 / 2, rel=0.25)


def test_inertial_relaxation_and_local_damping_settle_to_one_rest():
    m = blockdem.Model("a deformable pier and a rigid block on it")
    m.material("stone", density=2500, youngs_modulus=1e9, poisson_ratio=0.2)
    m.joint("*", "*", "elastic", normal_stiffness=1e11, shear_stiffness=5e10)
    m.block("stone", box=((0, 0, -0.2), (1, 1, 0)), name="base", motion="base")
    m.block("stone", box=((0.2, 0.2, 0), (0.8, 0.8, 0.6)), name="pier", max_edge=0.3)
    m.block("stone", box=((0.5, 0.3, 0.6), (0.7, 0.7, 0.7)), name="cap")
    settled = {}
    for method in ("inertial", "local"):
        sim = blockdem.Simulation(m, progress=False, settle_tolerance=1e-9, settle_steps=200000, settling=method)
        assert sim.settle()["converged"]
        settled[method] = (np.array(sim.node_positions), np.array(sim.block_positions))
    sink = 2500 * 9.81 * 0.7 / 1e11 + 2500 * 9.81 * 0.3 / 1e9  # m: the joint's and the pier's share, for scale
    for a, b in zip(settled["inertial"], settled["local"]):
        assert np.abs(a - b).max() < 1e-4 * sink
    with pytest.raises(ValueError, match="settling must be one of 'auto', 'inertial', 'local', got 'viscous'"):
        blockdem.Simulation(m, progress=False, settling="viscous")


def test_runs_without_the_gil():
    sim = blockdem.Simulation(two_courses(), progress=False)
    sim.settle()
    sim.set_record(level=100)
    ticks = []
    worker = threading.Thread(target=sim.run, args=(3.0,))
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    assert len(ticks) > 20  # the interpreter went on while the run computed
    assert sim.time > 2.99


def test_bad_use_is_refused_with_a_reason():
    with pytest.raises(TypeError, match="out, resume and levels are options of blockdem.run"):
        blockdem.Simulation(two_courses(), levels=[50])
    with pytest.raises(ValueError, match="damping must be one of"):
        blockdem.Simulation(two_courses(), damping="viscous")
    sim = blockdem.Simulation(two_courses(), progress=False)
    with pytest.raises(ValueError, match="duration must be >= 0 s"):
        sim.run(-1)
    with pytest.raises(ValueError, match=r"level must be in \(0, 1000\] %"):
        sim.set_record(level=0)
    sim.run(0.001)
    with pytest.raises(ValueError, match="settling comes before"):
        sim.settle()
    free = blockdem.Model("no table")
    free.material("stone", density=2000)
    free.joint("*", "*", "elastic", normal_stiffness=1e9, shear_stiffness=1e9)
    free.block("stone", box=((0, 0, 0), (1, 1, 1)), motion="fixed")
    free.block("stone", box=((0, 0, 1), (1, 1, 2)))
    with pytest.raises(ValueError, match="has no base block"):
        blockdem.Simulation(free, progress=False).set_record()
