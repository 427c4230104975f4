// A faceting beyond a million segments per circle is refused, not attempted.
// expect error: err_segments.scad:4:1: sphere(): more than 10^6 segments per circle
// expect no-openscad: OpenSCAD would try to build it
sphere(1, $fn = 1e300);
