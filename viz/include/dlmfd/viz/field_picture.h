// A picture of a scalar node field (trA, the speed, the vorticity, a component of A, the pressure)
// with axes in the domain's coordinates, a colour bar with ticks and a label, optional isolines
// and velocity arrows, and the particles drawn exactly: a frame of a results directory, a snapshot
// that a running job streams, or a frame of a movie.
//
// Discrete method: each pixel of the field panel takes the value of the field's own
// finite-element representation at the pixel centre: P1 on the triangles of its mesh (squares of
// side h cut by the SW-NE diagonal, paper section 3), so the picture shows exactly what the solver
// computed, with no smoothing across the diagonal. Colours (colour_scale.h): values map linearly
// from [min, max] of the finite node values to viridis, or, with log_colours, log10 of the value
// from [min, max] of the positive finite node values (a value <= 0 takes the bottom colour); the
// bar's ticks are then placed at their logarithm (axis_ticks.h: 1-2-5 multiples or decades), so a
// log scale shows as one. With `diverging` (a signed quantity: the vorticity, A12, the pressure)
// the range is [-m, m], m the largest finite |value|, on Moreland's cool to warm map, so zero is
// the neutral grey, negative values blue and positive ones red. A fixed range (the user's, or a
// movie's over all its frames) replaces the field's extremes as given; on a diverging scale zero
// stays neutral and the sign stays the hue (colour_scale.h). The colour bar draws the same scale
// from its bottom (min) to its top (max). A constant field takes the middle colour (no division
// by zero); NaN/Inf pixels are grey. A `percentile` below 100 takes the automatic range from the
// values' percentiles instead of their extremes: [P_(100-p), P_p] of the finite values, or on a
// diverging scale [-m, m] with m the p-th percentile of |value| (a single spike at a disk surface
// no longer sets the scale of the whole wake); values beyond the range take the end colours and the
// colour bar shows a triangle at each end that is exceeded.
// Isolines: the exact level sets of the P1 field (isolines.h) at `isolines` values evenly spaced
// inside the colour range (in log10 with log_colours), marked on the colour bar too: white over
// viridis, black over cool to warm (white would vanish in its light middle); with fill = false
// only the isolines are drawn, in black on white, as in the paper's figures ("isovalues of
// trA"). Arrows: the P1 velocity at the centres of a regular lattice of
// `arrows` columns, the longest arrow one lattice spacing; the key below the panel, right of the x
// title and clear of it, draws the largest round (1-2-5) speed not above the longest arrow's at its
// own length. Streamlines (streamlines.h) are drawn over the field as thin lines with an arrowhead
// at their middle. Particles: circles of their radius at their centres (the same scale on both
// axes), white with a black rim, with a radius drawn at their rotation angle (the angle the
// record's angular velocity integrates to, results_frame.h), clipped to the panel. CropField cuts a
// field down to the nodes of a window, for close-ups of particles. Layout: the panel keeps the
// domain's aspect ratio (to within one pixel) and is as large as fits in max_width x max_height
// with the caption above, the axes' labels and the colour bar; the image is no larger. Text in
// DejaVu Sans (canvas.h), font_size pixels (default: the picture's smaller side / 55, at least 9:
// text grows with the picture), lines in proportion to the text, so a figure drawn at size x dpi
// keeps its proportions at any resolution. Not supported: periodic images of particles that cross a
// periodic side.
#pragma once

#include <string>
#include <vector>

#include "dlmfd/core/grid.h"
#include "dlmfd/viz/axis_ticks.h"
#include "dlmfd/viz/canvas.h"

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
  double angle = 0.0;      // orientation, radians, counter-clockwise
  bool has_angle = false;  // draw the rotation mark
  // An ellipse: its semi-axes along the body's x and y axes (turned by angle); 0: a disk.
  double semi_a = 0.0, semi_b = 0.0;
};

// The velocity at the nodes, for arrows (u and v on the same grid).
struct NodeVelocity {
  NodeField u;
  NodeField v;
};

struct PictureOptions {
  int max_width = 1000;   // pixels, whole image
  int max_height = 1000;  // pixels, whole image
  // Drawn above the field when not empty; '\n' starts a paragraph, and lines wrap in the picture's
  // width (caption_lines.h).
  std::string caption;
  bool log_colours = false;  // colour by log10 of the value (see the header)
  bool diverging = false;    // cool to warm about zero, for signed quantities (not with log)
  std::string colour_label;  // the colour bar's label (default: the field's quantity)
  bool fixed_range = false;  // colour range [range_min, range_max] instead of the field's
  double range_min = 0.0;
  double range_max = 1.0;
  int isolines = 0;           // number of isovalues drawn (0: none)
  bool fill = true;           // false: isolines only, black on white
  int arrows = 0;             // columns of velocity arrows (0: none; needs a NodeVelocity)
  int exact_width = 0;        // > 0: the image is exactly this wide and high (movie frames),
  int exact_height = 0;       // the panel centred in the room it leaves
  double font_size = 0.0;     // text size in pixels (0: the picture's smaller side / 55, >= 9)
  double percentile = 100.0;  // automatic colour range from percentiles (see the header)
  std::string x_title = "x";  // axis titles (with units when the caller knows them)
  std::string y_title = "y";
  std::string speed_units;  // after the arrow key's speed ("cm s-1"), or ""
  int streamlines = 0;      // seed lattice columns of streamlines (0: none; needs a velocity)
};

struct FieldPicture {
  Canvas image{1, 1};
  int panel_left = 0;  // the field panel inside the image, pixels
  int panel_top = 0;
  int panel_width = 0;
  int panel_height = 0;
  int bar_left = 0;  // the colour bar
  int bar_top = 0;
  int bar_width = 0;
  int bar_height = 0;
  double value_min = 0.0;  // the colour range (the field's finite extremes unless fixed)
  double value_max = 0.0;
  std::vector<double> isovalues;
  AxisTicks x_ticks;  // of the axes, in domain coordinates
  AxisTicks y_ticks;
  AxisTicks bar_ticks;       // of the colour bar, in field values
  double arrow_speed = 0.0;  // the speed drawn as one lattice spacing
  double key_speed = 0.0;    // the round speed of the arrow key
  bool clipped_low = false;  // values below / above the colour range (the bar's end triangles)
  bool clipped_high = false;
  int streamlines_drawn = 0;
  Grid grid;
  // Image pixel coordinates (continuous, y down) of a point of the domain.
  double PixelX(double x) const;
  double PixelY(double y) const;
  // The row of the colour bar (continuous, y down) that shows `value`.
  double BarY(double value) const;
  bool log_colours = false;
  bool diverging = false;
};

// Throws InvalidParameter when the values do not match the grid, the size leaves no room, arrows
// are asked without a velocity, a fixed range is inverted or not finite, or diverging is asked
// with log_colours.
FieldPicture DrawFieldPicture(const NodeField& field, const std::vector<DiskOutline>& disks,
                              const PictureOptions& options = {},
                              const NodeVelocity* velocity = nullptr);
// The nodes of `field` inside [x_min, x_max] x [y_min, y_max], widened outwards to whole cells and
// clipped to the domain. Throws InvalidParameter when the window is empty, inverted, not finite or
// misses the domain.
NodeField CropField(const NodeField& field, double x_min, double y_min, double x_max, double y_max);
// The value of the P1 interpolant at (x, y); (x, y) is clamped into the domain.
double InterpolateP1(const NodeField& field, double x, double y);
// "%.4g" of a value, the form of the caption's numbers.
std::string FormatLabel(double value);

}  // namespace dlmfd
