// An SVG construct the reader does not handle is an error naming the file and line.
// expect error: arc.svg:3: <path> path arcs (A) are not supported yet
// expect no-openscad: OpenSCAD draws the arc
linear_extrude(1) import("data/arc.svg");
