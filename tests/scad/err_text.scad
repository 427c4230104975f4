// text() is not supported yet: an error with its place, never other geometry.
// expect error: err_text.scad:4:1: text() is not supported yet
// expect no-openscad: text() is not supported here
text("hi");
