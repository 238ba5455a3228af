// A picture of a scalar node field (trA, or the speed |u| of a Newtonian run) with the particles
// drawn as disks: a frame of a results directory, or a snapshot that a running job streams.
//
// Discrete method: each pixel takes the value of the field's own finite-element representation at
// the pixel centre: P1 on the triangles of the velocity mesh (squares of side h cut by the SW-NE
// diagonal, paper section 3), so the picture shows exactly what the solver computed, with no
// smoothing across the diagonal. Values map linearly from [min, max] of the finite node values to
// viridis, or, with log_colours, log10 of the value from [min, max] of the positive finite node
// values (a value <= 0 takes the bottom colour; the bar then also labels its middle, the geometric
// mean): trA spans decades near a particle, and a linear scale shows only the hottest spot. A
// constant field takes the middle colour (no division by zero); NaN/Inf pixels are grey.
// CropField cuts a field down to the nodes of a window, for close-ups of particles.
// Particles are filled white with a black rim. A colour bar on the right carries the max (top) and
// min (bottom) labels; an optional caption runs above the field.
// Layout: the field panel keeps the domain's aspect ratio (to within one pixel) and is as large as
// fits in max_width x max_height together with the bar and margins; the image is no larger.
// Not supported: periodic images of particles that cross a periodic side, vector arrows, contours.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/viz/raster_image.h"

namespace dlmfd {

// Node values (ny+1) x (nx+1), x fastest (the layout of the snapshot files, design.md 3.2).
struct NodeField {
  Grid grid;
  std::vector<double> values;
  std::string quantity = "trA";
};

struct DiskOutline {
  double x = 0.0;
  double y = 0.0;
  double radius = 0.0;
};

struct PictureOptions {
  int max_width = 1000;      // pixels, whole image
  int max_height = 1000;     // pixels, whole image
  std::string caption;       // drawn above the field when not empty
  bool log_colours = false;  // colour by log10 of the value (see the header)
};

struct FieldPicture {
  RasterImage image{1, 1};
  int panel_left = 0;  // the field panel inside the image, pixels
  int panel_top = 0;
  int panel_width = 0;
  int panel_height = 0;
  int bar_left = 0;  // the colour bar
  int bar_top = 0;
  int bar_width = 0;
  int bar_height = 0;
  double value_min = 0.0;  // the finite extremes that set the colour scale
  double value_max = 0.0;
  Grid grid;
  // Image pixel coordinates (continuous, y down) of a point of the domain.
  double PixelX(double x) const;
  double PixelY(double y) const;
};

// Throws InvalidParameter when the values do not match the grid or the size leaves no room.
FieldPicture DrawFieldPicture(const NodeField& field, const std::vector<DiskOutline>& disks,
                              const PictureOptions& options = {});
// The nodes of `field` inside [x_min, x_max] x [y_min, y_max], widened outwards to whole cells and
// clipped to the domain. Throws InvalidParameter when the window is empty, inverted, not finite or
// misses the domain.
NodeField CropField(const NodeField& field, double x_min, double y_min, double x_max, double y_max);
// The value of the P1 interpolant at (x, y); (x, y) is clamped into the domain.
double InterpolateP1(const NodeField& field, double x, double y);
// "%.4g" of a value, the form of the colour bar labels.
std::string FormatLabel(double value);

}  // namespace dlmfd
