"""Run by pvbatch under Xvfb: trA of fields.xmf with the disks drawn as glyphs, saved as a PNG, the
way a user of ParaView's GUI draws it (docs/results.md, "fields.xmf in ParaView").

    DISPLAY=:N pvbatch paraview_screenshot.py FIELDS_XMF OUT_PNG OUT_JSON   (N: an X server, e.g. Xvfb)

Opens the file with the XDMF Reader, takes the block velocity_mesh (selected by its name) coloured
by trA and the block particles through a Glyph filter (a sphere of diameter 1 scaled by 2 radius: seen from +z the
disk), black (black under any lighting), at the last time step, in a 2D view of 300 x 600 pixels fitted to the domain; writes the
PNG and, to OUT_JSON, the disk's centre and radius and the display's point of the centre (so the
test can look at the pixel there).
"""

import json
import sys

from paraview import simple

path, png, out = sys.argv[1:4]

reader = simple.XDMFReader(FileNames=[path])
times = list(reader.TimestepValues)
view = simple.CreateRenderView()
view.ViewSize = [300, 600]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
view.ViewTime = times[-1]

field = simple.ExtractBlock(Input=reader, Selectors=["/Root/velocity_mesh"])
field.UpdatePipeline(times[-1])  # the colour range of the last time, not of t = 0 (trA = 2)
field_display = simple.Show(field, view)
field_display.SetRepresentationType("Surface")
simple.ColorBy(field_display, ("POINTS", "trA"))
field_display.RescaleTransferFunctionToDataRange(True, False)

disks = simple.ExtractBlock(Input=reader, Selectors=["/Root/particles"])
glyph = simple.Glyph(Input=disks, GlyphType="Sphere")
glyph.GlyphType.Radius = 0.5
glyph.GlyphType.ThetaResolution = 64
glyph.GlyphType.PhiResolution = 32
glyph.ScaleArray = ["POINTS", "radius"]
glyph.ScaleFactor = 2.0  # the sphere of diameter 1 scaled by 2 r: seen from +z, the disk
glyph.GlyphMode = "All Points"
glyph_display = simple.Show(glyph, view)
glyph_display.ColorArrayName = ["POINTS", ""]
glyph_display.AmbientColor = [0.0, 0.0, 0.0]  # black whatever the lighting
glyph_display.DiffuseColor = [0.0, 0.0, 0.0]
glyph_display.Specular = 0.0

view.InteractionMode = "2D"
simple.ResetCamera(view)
simple.Render(view)

disks.UpdatePipeline(times[-1])
points = disks.GetClientSideObject().GetOutputDataObject(0)
leaf = points.GetBlock(0) if points.IsA("vtkMultiBlockDataSet") else points
centre = list(leaf.GetPoint(0))
radius = leaf.GetPointData().GetArray("radius").GetValue(0)

renderer = view.GetRenderer()
renderer.SetWorldPoint(centre[0], centre[1], centre[2], 1.0)
renderer.WorldToDisplay()
display = list(renderer.GetDisplayPoint())
renderer.SetWorldPoint(centre[0] + radius, centre[1], centre[2], 1.0)
renderer.WorldToDisplay()
edge = list(renderer.GetDisplayPoint())

simple.SaveScreenshot(png, view, ImageResolution=[300, 600])
with open(out, "w") as f:
    json.dump({"time": times[-1], "centre": centre, "radius": radius, "display": display,
               "display_radius": abs(edge[0] - display[0]),
               "size": [300, 600]}, f)
