"""blockdem.Model: a block structure and its study, held as a model file (docs/model-file.md).

A Model is the model file's JSON document as a dict (`model.data`), built by its methods or loaded from a file.
blockdem reads it as the programs do whenever it is checked or run, so every error names the field of the file
(blocks[12].faces[3]) and the allowed range. Units are SI: m, kg, s, N, Pa (joint stiffnesses in Pa/m).
"""

import copy
import json
import os

import numpy as np

from . import _core

_FORMAT = 1


def _vector(value, what, length=3):
    v = np.asarray(value, dtype=float).reshape(-1)
    if v.size != length:
        raise ValueError("%s: expected %d numbers, got %d" % (what, length, v.size))
    return [float(x) for x in v]


def _set(target, key, value):
    if value is not None:
        target[key] = value


class Model:
    """A block structure and its study, as a model file (docs/model-file.md).

    Model(name, gravity=(0, 0, -9.81)) starts an empty one; blockdem.load(path) reads a file;
    blockdem.generate.wall(...) and its siblings make common typologies. Methods add materials, joint laws between
    groups, blocks, ties and monitor points, and set the table, the excitation and the study; check() reads the
    model as blockdem does and reports its blocks, contacts and problems; save(path) writes the file.
    """

    def __init__(self, name="structure", gravity=(0.0, 0.0, -9.81)):
        self.data = {"blockdem_model": _FORMAT, "name": str(name), "units": "SI",
                     "gravity": _vector(gravity, "gravity"), "materials": {}, "joints": [], "blocks": []}
        self.base_dir = os.getcwd()
        self.source = None
        self._text = None

    # -- reading and writing -----------------------------------------------------------------------------------

    @classmethod
    def from_dict(cls, data, base_dir=None, source=None):
        """A model from a model file's document (a dict, copied); relative paths in it are taken from base_dir."""
        if not isinstance(data, dict):
            raise TypeError("a model file's document is a dict, got %s" % type(data).__name__)
        model = cls.__new__(cls)
        model.data = copy.deepcopy(data)
        model.base_dir = os.path.abspath(base_dir) if base_dir else os.getcwd()
        model.source = source
        model._text = None
        return model

    @classmethod
    def from_json(cls, text, base_dir=None, source=None):
        """A model from a model file's JSON text."""
        return cls.from_dict(json.loads(text), base_dir, source)

    def to_json(self, indent=1):
        """The model file's JSON text."""
        return json.dumps(self.data, indent=indent)

    def save(self, path):
        """Writes the model file (JSON). A relative record or geometry path in it stays relative to the model's
        folder (base_dir), so save into that folder to keep them valid."""
        with open(path, "w") as f:
            f.write(self.to_json())
            f.write("\n")

    def copy(self):
        """An independent copy."""
        return Model.from_dict(self.data, self.base_dir, self.source)

    @property
    def name(self):
        return self.data.get("name", "structure")

    def _describe(self):
        """The source named in messages."""
        return self.source or "<model '%s' built in Python>" % self.name

    def _file(self):
        """The model as blockdem reads it (a ModelFile): every error names the field, and the line of the file as
        loaded while the model is as it was loaded."""
        text = getattr(self, "_text", None)
        if text is not None and json.loads(text) == self.data:
            return _core.parse_model(text, self._describe(), self.base_dir)
        source = self._describe() + (" (as changed in Python)" if self.source else "")
        return _core.parse_model(json.dumps(self.data, indent=1), source, self.base_dir)

    # -- building ----------------------------------------------------------------------------------------------

    def material(self, name, density, youngs_modulus=None, poisson_ratio=None):
        """Adds (or replaces) a material: density in kg/m^3; youngs_modulus (Pa) and poisson_ratio for deformable
        blocks. Returns the model."""
        m = {"density": float(density)}
        _set(m, "youngs_modulus", None if youngs_modulus is None else float(youngs_modulus))
        _set(m, "poisson_ratio", None if poisson_ratio is None else float(poisson_ratio))
        self.data["materials"][str(name)] = m
        return self

    def groups(self, *names):
        """Sets the order of the groups (optional: by default the order in which blocks name them)."""
        self.data["groups"] = [str(n) for n in names]
        return self

    def joint(self, group_a, group_b, law, contact_point_spacing=0.0, **parameters):
        """The joint law between the blocks of two groups ('*': any group), with the model file's keys as keyword
        arguments: law 'elastic' (normal_stiffness, shear_stiffness, Pa/m), 'mohr_coulomb' (also
        friction_angle_deg, tensile_strength and cohesion in Pa, residual_...) or 'softening' (preset='paper_table1'
        or the strengths, fracture energies in J/m^2, ...). contact_point_spacing (m): the grid of contact points on
        these joints, 0 for the corners of each overlap only. Returns the model."""
        entry = {"between": [str(group_a), str(group_b)], "law": str(law)}
        if contact_point_spacing:
            entry["contact_point_spacing"] = float(contact_point_spacing)
        entry.update(parameters)
        self.data["joints"].append(entry)
        return self

    def block(self, material, vertices=None, faces=None, box=None, name=None, group=None, motion="free", max_edge=None):
        """Adds a convex block and returns its index. Its shape: box=((x0, y0, z0), (x1, y1, z1)) in m, or vertices
        (an n x 3 array, m) and faces (lists of vertex indices, in either order around each face). motion: 'free',
        'fixed' or 'base' (moved by the record). max_edge (m): mesh it into constant-strain tetrahedra (its
        material then needs youngs_modulus)."""
        b = {}
        _set(b, "name", None if name is None else str(name))
        _set(b, "group", None if group is None else str(group))
        b["material"] = str(material)
        if motion != "free":
            b["motion"] = str(motion)
        if box is not None:
            if vertices is not None or faces is not None:
                raise ValueError("block: give box, or vertices and faces, not both")
            lo, hi = box
            b["box"] = [_vector(lo, "box[0]"), _vector(hi, "box[1]")]
        else:
            if vertices is None or faces is None:
                raise ValueError("block: give box=(lowest corner, highest corner), or vertices and faces")
            v = np.asarray(vertices, dtype=float)
            if v.ndim != 2 or v.shape[1] != 3:
                raise ValueError("block: vertices must be an n x 3 array, got shape %s" % (v.shape,))
            b["vertices"] = v.tolist()
            b["faces"] = [[int(i) for i in f] for f in faces]
        if max_edge is not None:
            b["deformable"] = {"max_edge": float(max_edge)}
        self.data["blocks"].append(b)
        return len(self.data["blocks"]) - 1

    def geometry(self, path, material, objects=None, group=None, motion="free", planarity_tolerance=None):
        """Adds the blocks of a geometry file (OBJ, a 3DEC deck, a COMPAS assembly; docs/geometry-import.md), a path
        relative to the model's folder; objects: a pattern of the names to take ('lintel*')."""
        b = {"geometry": str(path), "material": str(material)}
        _set(b, "objects", objects)
        _set(b, "group", group)
        if motion != "free":
            b["motion"] = str(motion)
        _set(b, "planarity_tolerance", planarity_tolerance)
        self.data["blocks"].append(b)
        return self

    def tie(self, end_a, end_b, area, youngs_modulus, density, pretension=0.0, name=None):
        """A steel tie (truss) between two points: each end (block name or index, (x, y, z) in m). area in m^2,
        youngs_modulus in Pa, density in kg/m^3, pretension in N (tension positive)."""
        def end(e):
            block, point = e
            return {"block": block, "point": _vector(point, "tie end")}
        t = {"ends": [end(end_a), end(end_b)], "area": float(area), "youngs_modulus": float(youngs_modulus),
             "density": float(density)}
        if pretension:
            t["pretension"] = float(pretension)
        _set(t, "name", name)
        self.data.setdefault("ties", []).append(t)
        return self

    def monitor(self, name, point=None, block=None):
        """A monitor point: its histories are the displacements relative to the table (<name>_ux, _uy, _uz, m) and
        the absolute accelerations (<name>_ax, ..., m/s^2). Give the point (x, y, z in m), the block (name or
        index: its centroid), or both."""
        m = {"name": str(name)}
        _set(m, "block", block)
        if point is not None:
            m["point"] = _vector(point, "monitor point")
        self.data.setdefault("monitors", []).append(m)
        return self

    def table(self, block):
        """The base block the outputs are relative to (by default the first block with motion 'base')."""
        self.data["table"] = block
        return self

    def contacts(self, kinds=None, tolerance=None):
        """How contacts are found: kinds 'general' (vertex, edge and face: blocks may rock and tumble) or 'faces'
        (face to face within 20 degrees); tolerance in m."""
        c = self.data.setdefault("contacts", {})
        _set(c, "kinds", kinds)
        _set(c, "tolerance", tolerance)
        return self

    def excitation(self, record=None, units=None, dt=None, axis=None, baseline=None, truncation=None, window=None,
                   record_level=None, pga_g=None, sa_g=None, sa_period=None):
        """The record and its scaling: record (a file, relative to the model's folder; '' for the built-in
        stand-in), units ('g', 'm/s2', 'cm/s2'), dt (s, one-column text), axis ('x', 'y', 'z'), baseline
        ('mean,highpass:0.1'), truncation ('window' or 'wavelet'), window ((start, end) in s), and one of
        record_level (%), pga_g or sa_g with sa_period (s): the intensity of the 100 % level (one given replaces
        the model's)."""
        e = self.data.setdefault("excitation", {})
        scales = ("record_level_percent", "pga_g", "sa_g", "sa_period_s")
        if record_level is not None or pga_g is not None or sa_g is not None:
            for key in scales:  # the intensity is given once: the new one replaces the old
                e.pop(key, None)
        for key, value in (("record", record), ("units", units), ("dt", dt), ("axis", axis), ("baseline", baseline),
                           ("truncation", truncation), ("record_level_percent", record_level), ("pga_g", pga_g),
                           ("sa_g", sa_g), ("sa_period_s", sa_period)):
            _set(e, key, value)
        if window is not None:
            e["window_s"] = _vector(window, "window", 2)
        return self

    def study(self, levels=None, rest=None, damping=None, zeta=None, frequency=None, band=None, branches=None,
              frame=None, target_dt=None, mass_increase=None, max_mass_increase=None, settling=None,
              settle_tolerance=None, settle_steps=None, history_dt=None, snapshots_every=None, collapse_displacement=None,
              runaway_displacement=None, max_speed=None, free_vibration=None):
        """The seismic study's options: levels (% of the record), rest (s), damping ('none', 'mass', 'stiffness',
        'rayleigh', 'maxwell') with zeta, frequency (Hz), band ((low, high) Hz), branches and frame ('table' or
        'absolute'); target_dt (s), mass_increase and max_mass_increase (%); settling ('auto', 'inertial',
        'local'), settle_tolerance, settle_steps;
        history_dt, snapshots_every (s); collapse_displacement, runaway_displacement (m), max_speed (m/s);
        free_vibration (bool). Unset ones keep the file's value or the default."""
        s = self.data.setdefault("study", {})
        if s.get("analysis") == "pushover" and levels is not None:
            raise ValueError("study: this model runs a pushover; call study(...) before pushover(...), or drop pushover")
        _set(s, "levels_percent", None if levels is None else [float(x) for x in np.atleast_1d(levels)])
        _set(s, "rest_s", rest)
        d = {}
        for key, value in (("scheme", damping), ("zeta", zeta), ("frequency_hz", frequency), ("branches", branches),
                           ("frame", frame)):
            _set(d, key, value)
        if band is not None:
            d["band_hz"] = _vector(band, "band", 2)
        if d:
            s.setdefault("damping", {}).update(d)
        t = {}
        for key, value in (("target_dt_s", target_dt), ("mass_increase_percent", mass_increase),
                           ("max_mass_increase_percent", max_mass_increase)):
            _set(t, key, value)
        if t:
            s.setdefault("timestep", {}).update(t)
        st = {}
        _set(st, "method", settling)
        _set(st, "tolerance", settle_tolerance)
        _set(st, "max_steps", settle_steps)
        if st:
            s.setdefault("settle", {}).update(st)
        out = {}
        _set(out, "history_dt_s", history_dt)
        _set(out, "snapshots_every_s", snapshots_every)
        if out:
            s.setdefault("outputs", {}).update(out)
        _set(s, "collapse_displacement_m", collapse_displacement)
        _set(s, "runaway_displacement_m", runaway_displacement)
        _set(s, "max_speed_m_s", max_speed)
        _set(s, "free_vibration", free_vibration)
        return self

    def pushover(self, axis="x", upper=None, resolution=None, collapse_displacement=None, tolerance=None,
                 max_steps=None):
        """Makes the study an equivalent-static pushover: lambda g along axis ('x', '-x', 'y', '-y'), bisected up to
        `upper` to within `resolution`; collapse_displacement (m, 0: 2 % of the height), tolerance (the
        unbalanced-force ratio of equilibrium), max_steps per trial."""
        s = self.data.setdefault("study", {})
        s.pop("levels_percent", None)
        s["analysis"] = "pushover"
        p = {"axis": str(axis)}
        for key, value in (("upper", upper), ("resolution", resolution), ("collapse_displacement_m",
                           collapse_displacement), ("tolerance", tolerance), ("max_steps", max_steps)):
            _set(p, key, value)
        s["pushover"] = p
        return self

    # -- what blockdem makes of it -----------------------------------------------------------------------------

    def check(self):
        """Reads the model as blockdem does and checks it as `blockdem check --json` does: a dict with its blocks,
        nodes and tetrahedra, groups, free mass (kg), contact points (also by pair of groups), monitor points,
        table, and 'issues' (each with 'severity' error, warning or note, 'block' and 'message'); 'errors' counts
        what makes blocks unusable. A malformed file raises ValueError naming the field."""
        return _core.check_model(self._file())

    @property
    def blocks(self):
        """The number of blocks (those of geometry files counted, as built)."""
        return self._file().blocks

    def __repr__(self):
        return "Model('%s': %d block entries, %d materials, %d joint laws)" % (
            self.name, len(self.data.get("blocks", [])), len(self.data.get("materials", {})),
            len(self.data.get("joints", [])))


def load(path):
    """Reads a model file (docs/model-file.md). A malformed file raises ValueError naming the file, line, column and
    field; a file that cannot be read raises blockdem.InputError."""
    path = os.fspath(path)
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise _core.InputError("%s: cannot read the model file: %s" % (path, e.strerror)) from None
    base_dir = os.path.dirname(os.path.abspath(path))
    _core.parse_model(text, path, base_dir)  # blockdem's own reading first: its messages name line and column
    model = Model.from_json(text, base_dir, path)
    model._text = text
    return model
