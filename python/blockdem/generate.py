"""Model files of common masonry typologies (docs/generators.md), as `blockdem generate` writes them: each returns a
blockdem.Model, ready to run or to change. Lengths in m, angles in degrees, stiffnesses in Pa/m."""

from . import _core
from .model import Model


def _model(text, what):
    return Model.from_json(text, source="<generated %s>" % what)


def wall(length=2.0, courses=20, thickness=0.12, unit_length=0.25, unit_height=0.075, openings=(), lintel_bearing=0.125,
         return_length=0.0, floor=False, unit="brick", lintel="stone", friction_angle=35.0, normal_stiffness=1e10,
         pushover=False):
    """A running-bond wall along x on a foundation (or a floor slab: floor=True), shaken out of plane (along y).
    openings: (x0, x1, sill_course, head_course) each, jambs in m from the left end; unit and lintel: 'brick'
    (1800 kg/m^3) or 'stone' (2200); return_length: return walls at both ends (m, 0: none). pushover=True: the
    equivalent-static pushover out of plane instead of the seismic levels."""
    return _model(_core.generate_wall(length, courses, thickness, unit_length, unit_height,
                                      [tuple(o) for o in openings], lintel_bearing, return_length, floor, unit, lintel,
                                      friction_angle, normal_stiffness, pushover), "wall")


def barrel_vault(span=2.0, thickness=0.24, length=1.0, rings=15, unit_length=0.25, straight_joints=False, unit="brick",
                 friction_angle=35.0, normal_stiffness=1e10, pushover=False):
    """A semicircular barrel vault on two abutments, shaken across its span (along x): span (clear), thickness
    (radial) and length (along y) in m, rings of voussoirs across the span, staggered unless straight_joints."""
    return _model(_core.generate_barrel_vault(span, thickness, length, rings, unit_length, straight_joints, unit,
                                              friction_angle, normal_stiffness, pushover), "barrel vault")


def arch(voussoirs=40, radius=1.0, thickness_ratio=0.15, depth=0.5, friction_angle=40.0):
    """The semicircular arch of the program `arch` on fixed springings, with its pushover along x: radius to the
    centreline and depth in m, thickness_ratio t/R."""
    return _model(_core.generate_arch(voussoirs, radius, thickness_ratio, depth, friction_angle), "arch")


def cross_vault():
    """The paper's cross vault (LNEC) on its shake table, rigid blocks, with the study of Sect. 5."""
    return _model(_core.generate_cross_vault(), "cross vault")
