#!/usr/bin/python3
"""Reads a ParaView collection (.pvd) as ParaView would, with VTK's own XML reader.

An independent reader for the test of `dynamesh-cli run --export` (issue 12): the .pvd is
parsed with Python's XML parser (VTK has no .pvd reader; ParaView's vtkXMLCollectionReader is
not part of VTK), and every dataset it names is read with vtkXMLPolyDataReader. Prints one
JSON object: {"frames": [{"time", "file", "points", "polys", "triangles_only",
"arrays": {name: [components, min, max]}, "bounds": [xmin, xmax, ...]}, ...]}.
Exits 1 with a message on stderr when VTK reports an error or a file does not read.
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader


class ErrorObserver:
    def __init__(self):
        self.messages = []

    def __call__(self, caller, event):
        self.messages.append(event)


def read_frame(path):
    reader = vtkXMLPolyDataReader()
    errors = ErrorObserver()
    reader.AddObserver(vtkCommand.ErrorEvent, errors)
    reader.GetExecutive().AddObserver(vtkCommand.ErrorEvent, errors)
    reader.SetFileName(path)
    reader.Update()
    if errors.messages or reader.GetErrorCode() != 0:
        sys.exit(f"{path}: VTK could not read it ({errors.messages}, code {reader.GetErrorCode()})")
    poly = reader.GetOutput()
    polys = poly.GetPolys()
    triangles_only = all(polys.GetCellSize(i) == 3 for i in range(polys.GetNumberOfCells()))
    arrays = {}
    point_data = poly.GetPointData()
    for i in range(point_data.GetNumberOfArrays()):
        a = point_data.GetArray(i)
        if a.GetNumberOfTuples() != poly.GetNumberOfPoints():
            sys.exit(f"{path}: array {a.GetName()} has {a.GetNumberOfTuples()} values")
        lo, hi = a.GetRange(-1 if a.GetNumberOfComponents() > 1 else 0)
        arrays[a.GetName()] = [a.GetNumberOfComponents(), lo, hi]
    return {
        "points": poly.GetNumberOfPoints(),
        "polys": poly.GetNumberOfPolys(),
        "triangles_only": triangles_only,
        "arrays": arrays,
        "bounds": list(poly.GetBounds()),
    }


def main():
    pvd = sys.argv[1]
    root = ET.parse(pvd).getroot()
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        sys.exit(f"{pvd}: not a VTK collection")
    frames = []
    for dataset in root.iter("DataSet"):
        path = os.path.join(os.path.dirname(pvd), dataset.get("file"))
        frame = read_frame(path)
        frame["time"] = float(dataset.get("timestep"))
        frame["file"] = dataset.get("file")
        frames.append(frame)
    print(json.dumps({"frames": frames}))


if __name__ == "__main__":
    main()
