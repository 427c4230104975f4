// Two overlapping 2-squares: 4 + 4 - 1.
// expect volume: 7
linear_extrude(1) union() { square(2); translate([1, 1]) square(2); }
