// A twisted extrusion of a 2D union needs the 2D Boolean first.
// expect valid
linear_extrude(height = 1, twist = 30) union() { square(2); translate([1, 1]) square(2); }
