# Run by ParaView's pvbatch (under xvfb-run: Debian's ParaView renders through X): opens data.xdmf with ParaView's XDMF reader, probes the
# fields at the points of POINTS.json and reads the values ParaView holds at the grid indices of
# INDICES (i, j, k) directly, writes both to PROBED.json, and renders the
# equatorial plane (the stored z = 0 face) coloured by rho and by alp to PNG files in OUTDIR.
#   xvfb-run -a pvbatch pv_probe.py DATA.xdmf POINTS.json PROBED.json OUTDIR
import json
import sys

from paraview.simple import (ColorBy, ExtractSubset, GetActiveViewOrCreate, ProbeLocation, Render, ResetCamera,
                             SaveScreenshot, Show, XDMFReader)
from paraview import servermanager

xdmf, points_file, probed_file, outdir = sys.argv[1:5]
fields = ["alp", "gxx", "betay", "kxy", "rho", "vel[1]", "w_lorentz"]
reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipeline()
available = list(reader.PointData.keys())
missing = [f for f in fields if f not in available]
if missing:
    sys.exit(f"pv_probe: {xdmf} lacks {missing}; it has {available}")

grid = servermanager.Fetch(reader)
dims = grid.GetDimensions()
stored = {"dimensions": list(dims), "types": {}, "at": []}
for name in fields:
    stored["types"][name] = grid.GetPointData().GetArray(name).GetDataTypeAsString()
for i, j, k in json.load(open(points_file))["indices"]:
    pid = i + dims[0] * (j + dims[1] * k)
    stored["at"].append({name: grid.GetPointData().GetArray(name).GetValue(pid) for name in fields})

probed = []
for point in json.load(open(points_file))["points"]:
    probe = ProbeLocation(Input=reader, ProbeType="Fixed Radius Point Source")
    probe.ProbeType.Center = point
    probe.UpdatePipeline()
    data = servermanager.Fetch(probe)
    values = {}
    for name in fields:
        array = data.GetPointData().GetArray(name)
        values[name] = array.GetValue(0) if array is not None else None
    probed.append({"point": point, "values": values})
json.dump({"probed": probed, "stored": stored}, open(probed_file, "w"), indent=1)

# The equatorial plane: the stored half's k = 0 layer (a slice exactly on the face would be empty),
# seen from +z.
plane = ExtractSubset(Input=reader)
plane.VOI = [0, dims[0] - 1, 0, dims[1] - 1, 0, 0]
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [800, 800]
view.OrientationAxesVisibility = 0
display = Show(plane, view)
for name in ["rho", "alp"]:
    display.SetScalarBarVisibility(view, False)
    ColorBy(display, ("POINTS", name))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    view.CameraPosition = [0.0, 0.0, 50.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    ResetCamera(view)
    Render(view)
    SaveScreenshot(f"{outdir}/equator_{name}.png", view, ImageResolution=[800, 800])
