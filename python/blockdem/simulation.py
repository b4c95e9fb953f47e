"""blockdem.Simulation: a model's simulation stepped from Python, for a loop of your own."""

from . import _core
from .model import Model, load


class Simulation(_core.Simulation):
    """A model's simulation, stepped from Python: the steps of blockdem.run, one call at a time.

    sim = blockdem.Simulation(model, damping="maxwell", zeta=0.03)   # the damping is chosen here, once
    sim.settle()                          # static equilibrium under gravity (local damping), as the study settles
    sim.set_record(level=100)             # the model's record moves the table from now (or a blockdem.Record)
    for k in range(300):
        sim.run(0.01)                     # 10 ms of simulated time, without the GIL
        u = sim.monitor_displacements()   # (points, 3) m, relative to the table
    sim.contacts()["normal_stress"]       # arrays of the contact points now

    model: a blockdem.Model or a model file's path. Options: those of blockdem.run that concern the run (damping,
    zeta, frequency, band, branches, damping_frame, target_dt, mass_increase, max_mass_increase, contacts,
    settling, settle_tolerance, settle_steps, max_speed, record, units, axis, record_level, truncate, window, baseline,
    progress). State: time, dt, steps, block_positions, block_velocities, block_angular_velocities,
    block_orientations, block_masses, node_positions, node_velocities, node_blocks, tetrahedra, element_stresses
    (numpy views of blockdem's storage, read-only, current as the run goes on), contacts(), energy(),
    monitor_displacements(), unbalanced_force_ratio; write_vtk(path).
    """

    def __init__(self, model, **options):
        if not isinstance(model, Model):
            model = load(model)
        self.model = model
        super().__init__(model._file(), model._describe(), options)

    def __repr__(self):
        return "Simulation('%s', t = %.6g s, %d steps, %s)" % (self.model.name, self.time, self.steps,
                                                             "dynamic" if self.dynamic else "settling")
