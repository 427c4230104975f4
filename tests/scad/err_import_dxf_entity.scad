// A DXF entity the reader does not know is an error naming the file and line.
// expect error: ellipse.dxf:58: DXF entity ELLIPSE is not supported yet
// expect no-openscad: OpenSCAD skips the ellipse with a warning
linear_extrude(1) import("data/ellipse.dxf");
