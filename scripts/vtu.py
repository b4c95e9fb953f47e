"""Reading the ASCII VTK unstructured grids that blockdem writes (io/vtk.hpp): the blocks' faces as polygons with
their cell arrays, for the rendering and plotting scripts."""

import xml.etree.ElementTree as ET

import numpy as np


def read_vtu(path):
    """Points, polygons (lists of point indices) and cell arrays of an ASCII VTK unstructured grid."""
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")

    def array(parent, name=None):
        for a in parent.iter("DataArray"):
            if name is None or a.get("Name") == name:
                return np.array(a.text.split(), dtype=float)
        raise KeyError(f"{path}: no DataArray {name}")

    points = array(piece.find("Points")).reshape(-1, 3)
    cells = piece.find("Cells")
    connectivity = array(cells, "connectivity").astype(int)
    offsets = array(cells, "offsets").astype(int)
    starts = np.concatenate(([0], offsets[:-1]))
    polygons = [connectivity[s:e] for s, e in zip(starts, offsets)]
    cell_data = {a.get("Name"): np.array(a.text.split(), dtype=float) for a in piece.find("CellData").iter("DataArray")}
    return points, polygons, cell_data
