// A 2D result of two overlapping squares: their union as sheet faces.
// expect area: 7
// expect no-openscad: OpenSCAD exports 2D results as DXF or SVG only
union() { square(2); translate([1, 1]) square(2); }
