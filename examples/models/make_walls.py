#!/usr/bin/env python3
"""Writes the example model files of free-standing brick walls on a shake table (docs/model-file.md):

    wall.json         a 2.0 x 1.5 m one-brick wall in running bond (0.25 x 0.12 x 0.075 m units, joints included),
                      mortar joints of the paper's Table 1 on a 3 cm contact-point grid, on a table block;
    wall_window.json  the same wall with a 0.5 x 0.6 m window and a stone lintel over it.

Both are shaken out of plane (along y) by the record at a PGA of 0.3 g. Run from anywhere:
    python3 examples/models/make_walls.py
"""
import json
import os

LENGTH, WIDTH, HEIGHT = 0.25, 0.12, 0.075   # unit with its joints, m
UNITS, COURSES = 8, 20                       # 2.0 m long, 1.5 m high


def box(x0, y0, z0, x1, y1, z1):
    return [[x0, y0, z0], [x1, y1, z1]]


def wall(window=None):
    """Blocks of the wall; window = (x0, x1, z0, z1) leaves an opening, bridged by a lintel one course high."""
    blocks = []
    for c in range(COURSES):
        z0, z1 = c * HEIGHT, (c + 1) * HEIGHT
        cuts = [0.0]
        shift = 0.5 * LENGTH if c % 2 else 0.0
        cuts += [shift + u * LENGTH for u in range(UNITS) if shift + u * LENGTH > 0]
        cuts.append(UNITS * LENGTH)
        pieces = list(zip(cuts[:-1], cuts[1:]))
        if window:
            x0, x1, w0, w1 = window
            if w0 <= z0 and z1 <= w1:  # a course through the opening: units cut at its jambs
                cut = []
                for a, b in pieces:
                    if b <= x0 or a >= x1:
                        cut.append((a, b))
                    else:
                        if a < x0:
                            cut.append((a, x0))
                        if b > x1:
                            cut.append((x1, b))
                pieces = cut
            elif w1 <= z0 < w1 + HEIGHT:  # the lintel's course: one stone over the opening and a bearing each side
                bearing = 0.15
                cut, lintel = [], (x0 - bearing, x1 + bearing)
                for a, b in pieces:
                    if b <= lintel[0] or a >= lintel[1]:
                        cut.append((a, b))
                    else:
                        if a < lintel[0]:
                            cut.append((a, lintel[0]))
                        if b > lintel[1]:
                            cut.append((lintel[1], b))
                blocks.append({"name": "lintel", "group": "lintel", "material": "stone",
                               "box": box(lintel[0], 0, z0, lintel[1], WIDTH, z1)})
                pieces = cut
        for k, (a, b) in enumerate(pieces):
            if b - a > 1e-9:
                blocks.append({"name": f"unit c{c + 1}-{k + 1}", "group": "wall", "material": "brick",
                               "box": box(a, 0, z0, b, WIDTH, z1)})
    blocks.append({"name": "table", "group": "table", "material": "concrete", "motion": "base",
                   "box": box(-0.25, -0.3, -0.2, UNITS * LENGTH + 0.25, WIDTH + 0.3, 0)})
    return blocks


def model(name, window=None):
    mortar = {"law": "softening", "preset": "paper_table1", "contact_point_spacing": 0.03}
    joints = [dict(between=["wall", "wall"], **mortar), dict(between=["wall", "table"], **mortar)]
    monitors = [{"name": "top", "point": [0.5 * UNITS * LENGTH, 0.5 * WIDTH, COURSES * HEIGHT - 0.5 * HEIGHT]},
                {"name": "mid", "point": [0.5 * UNITS * LENGTH, 0.5 * WIDTH, 0.5 * COURSES * HEIGHT]}]
    materials = {"brick": {"density": 1800}, "concrete": {"density": 2400}}
    if window:
        materials["stone"] = {"density": 2500}
        joints += [dict(between=["lintel", "wall"], **mortar)]
        monitors.append({"name": "lintel", "block": "lintel"})
    return {
        "blockdem_model": 1,
        "name": name,
        "units": "SI",
        "gravity": [0, 0, -9.81],
        "materials": materials,
        "joints": joints,
        "contacts": {"kinds": "general"},
        "blocks": wall(window),
        "monitors": monitors,
        "table": "table",
        "excitation": {"record": "", "axis": "y", "pga_g": 0.3},
        "study": {"levels_percent": [50, 100], "rest_s": 1.0, "damping": {"scheme": "maxwell", "zeta": 0.03}},
    }


def write(path, data):
    with open(path, "w") as f:
        f.write("{\n")
        keys = list(data)
        for i, key in enumerate(keys):
            value = data[key]
            if key == "blocks":  # one block per line
                text = "[\n    " + ",\n    ".join(json.dumps(b) for b in value) + "\n  ]"
            else:
                text = json.dumps(value)
            f.write(f"  {json.dumps(key)}: {text}{',' if i + 1 < len(keys) else ''}\n")
        f.write("}\n")


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    write(os.path.join(here, "wall.json"), model("running-bond brick wall, 2.0 x 1.5 m"))
    write(os.path.join(here, "wall_window.json"),
          model("running-bond brick wall with a window and a lintel", window=(0.75, 1.25, 0.45, 1.05)))
