"""Run by pvbatch (ParaView's Python): what one of ParaView's XDMF readers makes of fields.xmf.

    pvbatch paraview_probe.py READERS FIELDS_XMF NODE_INDEX PRESSURE_NODE_INDEX OUT_JSON

READERS: a comma-separated list of XDMFReader (XDMF2, "Xdmf Reader"), Xdmf3ReaderS, Xdmf3ReaderT
(one pvbatch for all: its start takes seconds). Writes, per reader and per time step of it, each
leaf block: its class, bounds, point count, arrays (name -> components), and the
coordinates and every array's tuple at the node index (NODE_INDEX on the block with "velocity",
PRESSURE_NODE_INDEX on the block with "p", 0 on the particles' block, the one with "radius") and
the block's name. paraview_test reads the JSON and compares with h5py.
"""

import json
import sys

from paraview import simple
from paraview.vtk import vtkCompositeDataSet, vtkDataObjectTreeIterator

reader_names, path, node, pressure_node, out = sys.argv[1:6]


def leaves(data):
    """(name, leaf) of each leaf block; the name from the block's metadata ("" without one)."""
    if not data.IsA("vtkCompositeDataSet"):
        yield "", data
        return
    it = vtkDataObjectTreeIterator()
    it.SetDataSet(data)
    it.VisitOnlyLeavesOn()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        meta = it.GetCurrentMetaData()
        name = meta.Get(vtkCompositeDataSet.NAME()) if meta.Has(vtkCompositeDataSet.NAME()) else ""
        yield name or "", it.GetCurrentDataObject()
        it.GoToNextItem()


def probe(reader_name):
    if reader_name == "XDMFReader":
        reader = simple.XDMFReader(FileNames=[path])
    else:
        reader = getattr(simple, reader_name)(FileName=[path])
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    steps = []
    for t in times:
        reader.UpdatePipeline(t)
        data = reader.GetClientSideObject().GetOutputDataObject(0)
        steps.append({"time": t, "blocks": [describe(name, leaf) for name, leaf in leaves(data)]})
    simple.Delete(reader)
    return {"times": times, "steps": steps}


def describe(name, leaf):
    pd = leaf.GetPointData()
    arrays = {pd.GetArrayName(i): pd.GetArray(i).GetNumberOfComponents()
              for i in range(pd.GetNumberOfArrays())}
    k = 0 if "radius" in arrays else int(node) if "velocity" in arrays else int(pressure_node)
    inside = k < leaf.GetNumberOfPoints()
    return {
        "name": name,
        "class": leaf.GetClassName(),
        "bounds": list(leaf.GetBounds()),
        "points": leaf.GetNumberOfPoints(),
        "arrays": arrays,
        "point": list(leaf.GetPoint(k)) if inside else None,
        "values": {name: list(pd.GetArray(name).GetTuple(k)) for name in arrays} if inside else {},
    }


with open(out, "w") as f:
    json.dump({name: probe(name) for name in reader_names.split(",")}, f)
