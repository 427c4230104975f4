// text() takes a string: a number is refused with its place (OpenSCAD draws nothing).
// expect error: err_text.scad:4:24: text(): text must be a string, not 5
// expect no-openscad: OpenSCAD builds an empty model
linear_extrude(1) text(5);
